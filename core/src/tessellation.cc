#include "freeform/core/tessellation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "freeform/core/normals.h"
#include "freeform/core/rational.h"
#include "freeform/core/status.h"
#include "freeform/core/surface_output.h"

namespace freeform {
namespace {

// Curve subdivision stops after this many halvings (the parameter interval
// is then near the resolution of a double).
constexpr int kMaxDepth = 50;
// The smallest tolerance, relative to the control points' largest
// coordinate, that subdivision can meet in double precision.
constexpr double kResolution = 0x1p-48;
// The cancellation token is polled after this many subdivision steps.
constexpr size_t kCancelStride = 256;
// Grid cells per patch direction beyond this are refused (they would not
// fit the 32-bit vertex indices anyway).
constexpr double kMaxCells = 1 << 30;

absl::Status ValidateTolerance(double tolerance) {
  if (!std::isfinite(tolerance) || !(tolerance > 0.0)) {
    return InvalidFieldError("tolerance", "must be positive and finite");
  }
  return absl::OkStatus();
}

// CheckResolvable refuses a tolerance below what double precision resolves
// on geometry of the size of `coordinates`: no subdivision could meet it,
// and trying would only end at the size limit. Lines (degree < 2) are flat
// at any tolerance.
absl::Status CheckResolvable(double tolerance,
                             absl::Span<const double> coordinates, int degree) {
  if (degree < 2) return absl::OkStatus();
  double size = 0.0;
  for (const double c : coordinates) size = std::max(size, std::abs(c));
  if (tolerance >= kResolution * size) return absl::OkStatus();
  return InvalidFieldError(
      "tolerance", absl::StrCat(tolerance,
                                " is below what double precision resolves on "
                                "geometry of size ",
                                size, " (about ", kResolution * size, ")"));
}

// The tolerance is what makes a tessellation large, so the error names it.
absl::Status Exhausted(absl::string_view what, size_t limit) {
  return ExhaustedFieldError(
      "tolerance", absl::StrCat("the tessellation needs more than ", limit, " ",
                                what, " at this tolerance"));
}

// ---------------------------------------------------------------- curves --

// The layout of a Bezier piece's control points: degree + 1 points of
// `stride` values, the weight last when rational.
struct PieceShape {
  int degree = 0;
  int dimension = 0;
  bool rational = false;
  int stride() const { return dimension + (rational ? 1 : 0); }
  size_t size() const {
    return static_cast<size_t>(degree + 1) * static_cast<size_t>(stride());
  }
};

// DistanceToSegment returns the distance from p to the segment [a, b].
double DistanceToSegment(const double* p, const double* a, const double* b,
                         int dimension) {
  double ab2 = 0.0;
  double ap_ab = 0.0;
  for (int j = 0; j < dimension; ++j) {
    const double ab = b[j] - a[j];
    ab2 += ab * ab;
    ap_ab += (p[j] - a[j]) * ab;
  }
  const double s = ab2 > 0.0 ? std::clamp(ap_ab / ab2, 0.0, 1.0) : 0.0;
  double d2 = 0.0;
  for (int j = 0; j < dimension; ++j) {
    const double e = p[j] - (a[j] + s * (b[j] - a[j]));
    d2 += e * e;
  }
  return std::sqrt(d2);
}

// IsFlat reports whether every control point lies within `tolerance` of
// the chord (docs/references.md, 'Flatness test for curve tessellation').
// Rational pieces are projected first and are never flat while a weight is
// not positive (the convex hull property needs positive weights).
// `projected` is scratch.
bool IsFlat(const double* control, const PieceShape& shape, double tolerance,
            std::vector<double>& projected) {
  const int d = shape.dimension;
  if (shape.degree < 2) return true;
  const double* points = control;
  if (shape.rational) {
    projected.resize(static_cast<size_t>(shape.degree + 1) * d);
    for (int i = 0; i <= shape.degree; ++i) {
      const double* h = control + static_cast<size_t>(i) * shape.stride();
      if (!(h[d] > 0.0)) return false;
      for (int j = 0; j < d; ++j) projected[i * d + j] = h[j] / h[d];
    }
    points = projected.data();
  }
  const double* last = points + static_cast<size_t>(shape.degree) * d;
  for (int i = 1; i < shape.degree; ++i) {
    if (DistanceToSegment(points + static_cast<size_t>(i) * d, points, last,
                          d) > tolerance) {
      return false;
    }
  }
  return true;
}

// SplitInHalf writes the control points of the halves [0, 1/2] and
// [1/2, 1] of a (homogeneous) Bezier piece by de Casteljau.
void SplitInHalf(const double* control, const PieceShape& shape, double* left,
                 double* right, std::vector<double>& work) {
  const int n = shape.degree;
  const int s = shape.stride();
  work.assign(control, control + shape.size());
  for (int j = 0; j < s; ++j) {
    left[j] = work[j];
    right[static_cast<size_t>(n) * s + j] =
        work[static_cast<size_t>(n) * s + j];
  }
  for (int level = 1; level <= n; ++level) {
    for (int i = 0; i + level <= n; ++i) {
      for (int j = 0; j < s; ++j) {
        work[i * s + j] = 0.5 * (work[i * s + j] + work[(i + 1) * s + j]);
      }
    }
    for (int j = 0; j < s; ++j) {
      left[level * s + j] = work[j];
      right[(n - level) * s + j] = work[(n - level) * s + j];
    }
  }
}

// SubdivideBezierPiece appends to `parameters` the ends of the flat pieces
// of the Bezier piece `control` on the global interval [a, b], in order
// (a itself is not appended). Depth first, with a LIFO stack of control
// polygons in one buffer so nothing is allocated per piece.
absl::Status SubdivideBezierPiece(const double* control,
                                  const PieceShape& shape, double a, double b,
                                  double tolerance, size_t max_points,
                                  const CancellationToken* cancel,
                                  std::vector<double>& parameters) {
  struct Interval {
    double a;
    double b;
    int depth;
  };
  const size_t size = shape.size();
  std::vector<double> stack(control, control + size);
  std::vector<Interval> intervals = {{a, b, 0}};
  std::vector<double> projected, work, halves(2 * size);
  size_t steps = 0;
  while (!intervals.empty()) {
    if (++steps % kCancelStride == 0) {
      if (absl::Status status = CheckCancelled(cancel); !status.ok()) {
        return status;
      }
    }
    const Interval top = intervals.back();
    const double* piece = stack.data() + stack.size() - size;
    if (top.depth >= kMaxDepth || IsFlat(piece, shape, tolerance, projected)) {
      if (parameters.size() >= max_points)
        return Exhausted("points", max_points);
      parameters.push_back(top.b);
      intervals.pop_back();
      stack.resize(stack.size() - size);
      continue;
    }
    SplitInHalf(piece, shape, halves.data(), halves.data() + size, work);
    const double mid = 0.5 * (top.a + top.b);
    // Right half below the left one, so the left half is refined first.
    std::copy(halves.begin() + size, halves.end(), stack.end() - size);
    stack.insert(stack.end(), halves.begin(), halves.begin() + size);
    intervals.back() = {mid, top.b, top.depth + 1};
    intervals.push_back({top.a, mid, top.depth + 1});
  }
  return absl::OkStatus();
}

// ValidateCurveRequest checks the tolerance and that a polyline (two
// points at least) fits in max_points.
absl::Status ValidateCurveRequest(double tolerance, size_t max_points) {
  if (absl::Status status = ValidateTolerance(tolerance); !status.ok()) {
    return status;
  }
  if (max_points < 2) return Exhausted("points", max_points);
  return absl::OkStatus();
}

// PieceControl returns the control points to subdivide: homogeneous
// (w P, w) for a rational curve, the points themselves otherwise.
std::vector<double> PieceControl(const PointsView& points,
                                 absl::Span<const double> weights) {
  if (!weights.empty()) return HomogeneousPoints(points, weights);
  return std::vector<double>(points.coordinates.begin(),
                             points.coordinates.end());
}

// PolylineAt evaluates the points at `parameters` with `evaluate`.
template <typename Evaluate>
absl::StatusOr<Polyline> PolylineAt(int dimension,
                                    std::vector<double> parameters,
                                    Evaluate evaluate,
                                    const CancellationToken* cancel) {
  Polyline polyline;
  polyline.dimension = dimension;
  polyline.points.resize(parameters.size() * static_cast<size_t>(dimension));
  const std::vector<absl::Span<double>> output = {
      absl::MakeSpan(polyline.points)};
  ExecutionContext context;
  context.cancellation = cancel;
  if (absl::Status status = evaluate(parameters, output, context);
      !status.ok()) {
    return status;
  }
  polyline.parameters = std::move(parameters);
  return polyline;
}

// BlossomBezierPoints writes the Bezier control points of the non-empty
// span [u_s, u_{s+1}] of a B-spline with (homogeneous) control points
// `control` of `stride` values: point i is the blossom
// f(u_s^(p-i), u_{s+1}^i), by de Boor's algorithm with argument t_r at
// level r (The NURBS Book, section 5.1; de Boor, "A Practical Guide to
// Splines"). Works for clamped and unclamped knots.
void BlossomBezierPoints(const std::vector<double>& control, int stride, int p,
                         int s, absl::Span<const double> knots,
                         std::vector<double>& work, double* bezier) {
  for (int i = 0; i <= p; ++i) {
    work.assign(control.begin() + static_cast<size_t>(s - p) * stride,
                control.begin() + static_cast<size_t>(s + 1) * stride);
    for (int r = 1; r <= p; ++r) {
      const double t = r <= p - i ? knots[s] : knots[s + 1];
      for (int j = p; j >= r; --j) {
        const double lo = knots[s - p + j];
        const double alpha = (t - lo) / (knots[s + j - r + 1] - lo);
        for (int k = 0; k < stride; ++k) {
          work[j * stride + k] = (1.0 - alpha) * work[(j - 1) * stride + k] +
                                 alpha * work[j * stride + k];
        }
      }
    }
    std::copy(work.begin() + static_cast<size_t>(p) * stride, work.end(),
              bezier + static_cast<size_t>(i) * stride);
  }
}

// ----------------------------------------------------------- surfaces --

using Point3 = std::array<double, 3>;

// A place in one patch's parameter square and the vertex there.
struct Sample {
  uint32_t vertex = 0;
  double u = 0.0;
  double v = 0.0;
};

// Where a vertex was evaluated.
struct VertexSource {
  uint32_t patch = 0;
  double u = 0.0;
  double v = 0.0;
};

// One boundary curve shared by the patch sides with its control points.
struct Edge {
  int segments = 1;
  bool collapsed = false;
  // segments + 1 vertices in the canonical direction (created lazily).
  std::vector<uint32_t> vertices;
};

// A patch side: bottom (v = 0), right (u = 1), top (v = 1), left (u = 0);
// its curve runs in the direction of increasing parameter.
enum Side { kBottom = 0, kRight = 1, kTop = 2, kLeft = 3 };

struct PatchPlan {
  int grid_u = 2;  // interior grid cells
  int grid_v = 2;
  std::array<int, 4> edge = {};         // index into the edge list
  std::array<bool, 4> reversed = {};    // canonical direction is reversed
  std::array<uint32_t, 4> corner = {};  // (0,0), (1,0), (1,1), (0,1)
};

// SideControlPoints returns the control points of a patch side in the
// direction of increasing parameter.
std::vector<double> SideControlPoints(const ControlNetView& net, int side) {
  const int p = net.count_u - 1;
  const int q = net.count_v - 1;
  std::vector<double> points;
  const int count = side == kBottom || side == kTop ? p + 1 : q + 1;
  for (int k = 0; k < count; ++k) {
    const double* point = side == kBottom ? net.point(k, 0)
                          : side == kTop  ? net.point(k, q)
                          : side == kLeft ? net.point(0, k)
                                          : net.point(p, k);
    points.insert(points.end(), point, point + 3);
  }
  return points;
}

std::vector<double> Reversed(const std::vector<double>& points) {
  std::vector<double> result;
  for (size_t k = points.size(); k >= 3; k -= 3) {
    result.insert(result.end(), points.begin() + k - 3, points.begin() + k);
  }
  return result;
}

bool AllPointsEqual(const std::vector<double>& points) {
  for (size_t k = 3; k < points.size(); ++k) {
    if (points[k] != points[k % 3]) return false;
  }
  return true;
}

double Norm3(double x, double y, double z) {
  return std::sqrt(x * x + y * y + z * z);
}

// The bounds M_uu, M_uv, M_vv on the second partials of a polynomial patch
// from its control net (Filip, Magedson and Markot 1986).
struct SecondPartialBounds {
  double uu = 0.0;
  double uv = 0.0;
  double vv = 0.0;
};

SecondPartialBounds BoundSecondPartials(const ControlNetView& net) {
  const int p = net.count_u - 1;
  const int q = net.count_v - 1;
  SecondPartialBounds bounds;
  auto second = [](const double* a, const double* b, const double* c) {
    // (a + c) - 2b is symmetric in a and c, so reversed sides agree.
    return Norm3((a[0] + c[0]) - 2 * b[0], (a[1] + c[1]) - 2 * b[1],
                 (a[2] + c[2]) - 2 * b[2]);
  };
  for (int i = 0; i <= p; ++i) {
    for (int j = 0; j <= q; ++j) {
      if (i + 2 <= p) {
        bounds.uu = std::max(
            bounds.uu,
            second(net.point(i, j), net.point(i + 1, j), net.point(i + 2, j)));
      }
      if (j + 2 <= q) {
        bounds.vv = std::max(
            bounds.vv,
            second(net.point(i, j), net.point(i, j + 1), net.point(i, j + 2)));
      }
      if (i + 1 <= p && j + 1 <= q) {
        const double *a = net.point(i, j), *b = net.point(i + 1, j),
                     *c = net.point(i, j + 1), *d = net.point(i + 1, j + 1);
        bounds.uv = std::max(bounds.uv, Norm3(d[0] - b[0] - c[0] + a[0],
                                              d[1] - b[1] - c[1] + a[1],
                                              d[2] - b[2] - c[2] + a[2]));
      }
    }
  }
  bounds.uu *= p * (p - 1.0);
  bounds.vv *= q * (q - 1.0);
  bounds.uv *= static_cast<double>(p) * q;
  return bounds;
}

// NeededCells returns ceil(sqrt(m / (4 tolerance))), at least 1, as a
// double (it may be huge): with h = 1 / cells, h^2 m / 8 <= tolerance / 2.
double NeededCells(double m, double tolerance) {
  return std::max(1.0, std::ceil(std::sqrt(m / (4.0 * tolerance))));
}

absl::Status ValidatePatch(const BezierSurfaceView& patch, size_t index) {
  const std::string prefix = IndexedField("surfaces", index) + ".bezier";
  absl::Status status = ValidateBezierSurface(patch);
  if (!status.ok()) return PrefixFieldPath(status, prefix);
  if (patch.control_net.dimension != 3) {
    return InvalidFieldError(prefix + ".control_net.dimension",
                             "patches must be 3D to be meshed");
  }
  if (patch.rational()) {
    return InvalidFieldError(prefix + ".weights",
                             "rational patches are not supported");
  }
  return absl::OkStatus();
}

// The mesh under construction, before evaluation and welding.
class MeshBuilder {
 public:
  MeshBuilder(absl::Span<const BezierSurfaceView> patches, double tolerance)
      : patches_(patches), tolerance_(tolerance) {}

  // Plan chooses grid and edge sample counts and bounds the vertices and
  // triangles they generate (planned_size), or returns RESOURCE_EXHAUSTED
  // beyond max_vertices.
  absl::Status Plan(size_t max_vertices);
  MeshSize planned_size() const { return planned_size_; }
  // Build creates the vertices and triangles of every patch.
  absl::Status Build(const CancellationToken* cancel);
  // Evaluate computes positions and normals on each vertex's patch.
  absl::Status Evaluate(const CancellationToken* cancel);
  // Finish welds coincident vertices and returns the mesh.
  Mesh Finish();

 private:
  uint32_t CornerVertex(uint32_t patch, int corner);
  uint32_t NewVertex(uint32_t patch, double u, double v);
  std::vector<Sample> SideSamples(uint32_t patch, int side);
  std::vector<std::pair<Sample, double>> OuterLoop(uint32_t patch);
  std::vector<std::pair<Sample, double>> InnerLoop(
      uint32_t patch, const std::vector<uint32_t>& grid);
  void AddTriangle(uint32_t patch, const Sample& a, const Sample& b,
                   const Sample& c);
  void ZipRing(uint32_t patch,
               const std::vector<std::pair<Sample, double>>& outer,
               const std::vector<std::pair<Sample, double>>& inner);
  void BuildPatch(uint32_t patch);
  size_t PlannedTriangles() const;

  absl::Span<const BezierSurfaceView> patches_;
  double tolerance_;
  std::vector<PatchPlan> plans_;
  std::vector<Edge> edges_;
  MeshSize planned_size_;
  std::map<Point3, uint32_t> corners_;
  std::vector<VertexSource> sources_;
  std::vector<double> positions_;
  std::vector<double> normals_;
  std::vector<uint32_t> triangles_;
  std::vector<uint32_t> triangle_patch_;
  std::vector<double> corner_uv_;
};

absl::Status MeshBuilder::Plan(size_t max_vertices) {
  std::map<std::vector<double>, int> edge_index;
  double vertex_count = 0.0;
  const double limit = static_cast<double>(max_vertices);
  plans_.resize(patches_.size());
  for (size_t i = 0; i < patches_.size(); ++i) {
    const ControlNetView& net = patches_[i].control_net;
    const SecondPartialBounds m = BoundSecondPartials(net);
    const double cells_u = NeededCells(m.uu + m.uv, tolerance_);
    const double cells_v = NeededCells(m.vv + m.uv, tolerance_);
    if (cells_u * cells_v > limit || cells_u > kMaxCells ||
        cells_v > kMaxCells) {
      return Exhausted("vertices", max_vertices);
    }
    PatchPlan& plan = plans_[i];
    plan.grid_u = std::max(2, static_cast<int>(cells_u));
    plan.grid_v = std::max(2, static_cast<int>(cells_v));
    vertex_count += (plan.grid_u - 1.0) * (plan.grid_v - 1.0);
    for (int side = 0; side < 4; ++side) {
      const std::vector<double> forward = SideControlPoints(net, side);
      const std::vector<double> backward = Reversed(forward);
      plan.reversed[side] = backward < forward;
      const std::vector<double>& key = plan.reversed[side] ? backward : forward;
      auto [it, inserted] =
          edge_index.emplace(key, static_cast<int>(edges_.size()));
      if (inserted) {
        edges_.push_back(
            {.segments = 1, .collapsed = AllPointsEqual(key), .vertices = {}});
      }
      plan.edge[side] = it->second;
      Edge& edge = edges_[it->second];
      const double cells = side == kBottom || side == kTop ? cells_u : cells_v;
      if (!edge.collapsed && cells > edge.segments) {
        vertex_count += cells - edge.segments;
        edge.segments = static_cast<int>(cells);
      }
    }
    vertex_count += 4;  // corners, an upper bound
    if (vertex_count > limit || vertex_count >= UINT32_MAX) {
      return Exhausted("vertices", max_vertices);
    }
  }
  planned_size_ = {.vertices = static_cast<size_t>(vertex_count),
                   .triangles = PlannedTriangles()};
  return absl::OkStatus();
}

// The triangles BuildPatch makes at most: the zipped ring (one per sample
// of the outer and the inner loop) and two per interior grid cell.
size_t MeshBuilder::PlannedTriangles() const {
  size_t triangles = 0;
  for (const PatchPlan& plan : plans_) {
    const size_t nu = static_cast<size_t>(plan.grid_u);
    const size_t nv = static_cast<size_t>(plan.grid_v);
    for (int side = 0; side < 4; ++side) {
      const Edge& edge = edges_[plan.edge[side]];
      const bool along_u = side == kBottom || side == kTop;
      triangles += 1 + (edge.collapsed ? (along_u ? nu : nv)
                                       : static_cast<size_t>(edge.segments));
    }
    triangles += 2 * std::max<size_t>(2, nu - 1) +
                 2 * std::max<size_t>(2, nv - 1) + 2 * (nu - 2) * (nv - 2);
  }
  return triangles;
}

uint32_t MeshBuilder::NewVertex(uint32_t patch, double u, double v) {
  sources_.push_back({patch, u, v});
  return static_cast<uint32_t>(sources_.size() - 1);
}

uint32_t MeshBuilder::CornerVertex(uint32_t patch, int corner) {
  const ControlNetView& net = patches_[patch].control_net;
  const int i = corner == 1 || corner == 2 ? net.count_u - 1 : 0;
  const int j = corner >= 2 ? net.count_v - 1 : 0;
  const double* p = net.point(i, j);
  auto [it, inserted] = corners_.emplace(
      Point3{p[0], p[1], p[2]}, static_cast<uint32_t>(sources_.size()));
  if (inserted) NewVertex(patch, i == 0 ? 0.0 : 1.0, j == 0 ? 0.0 : 1.0);
  return it->second;
}

// SideSamples returns the samples of a side at t = m / n, m = 0..n, in the
// direction of increasing parameter. The vertices belong to the side's
// edge, numbered in its canonical direction, so patches that share the
// edge share them. A collapsed side is one vertex sampled as densely as
// the patch grid, which keeps the fan triangles at its apex small in
// parameter space.
std::vector<Sample> MeshBuilder::SideSamples(uint32_t patch, int side) {
  const PatchPlan& plan = plans_[patch];
  Edge& edge = edges_[plan.edge[side]];
  const bool along_u = side == kBottom || side == kTop;
  const int start_corner = side == kBottom  ? 0
                           : side == kRight ? 1
                           : side == kTop   ? 3
                                            : 0;
  const int end_corner = side == kBottom  ? 1
                         : side == kRight ? 2
                         : side == kTop   ? 2
                                          : 3;
  const int n =
      edge.collapsed ? (along_u ? plan.grid_u : plan.grid_v) : edge.segments;
  if (edge.vertices.empty() && !edge.collapsed) {
    edge.vertices.resize(static_cast<size_t>(n) + 1);
    const uint32_t first = plan.corner[start_corner];
    const uint32_t last = plan.corner[end_corner];
    edge.vertices.front() = plan.reversed[side] ? last : first;
    edge.vertices.back() = plan.reversed[side] ? first : last;
    for (int k = 1; k < n; ++k) {
      const int m = plan.reversed[side] ? n - k : k;
      const double t = static_cast<double>(m) / n;
      const double fixed = side == kRight || side == kTop ? 1.0 : 0.0;
      edge.vertices[k] =
          along_u ? NewVertex(patch, t, fixed) : NewVertex(patch, fixed, t);
    }
  }
  std::vector<Sample> samples(static_cast<size_t>(n) + 1);
  for (int m = 0; m <= n; ++m) {
    const double t = static_cast<double>(m) / n;
    const double fixed = side == kRight || side == kTop ? 1.0 : 0.0;
    const uint32_t vertex =
        edge.collapsed ? plan.corner[start_corner]
                       : edge.vertices[plan.reversed[side] ? n - m : m];
    samples[m] = along_u ? Sample{vertex, t, fixed} : Sample{vertex, fixed, t};
  }
  return samples;
}

// OuterLoop returns the boundary samples counter-clockwise from (0, 0),
// each with its perimeter coordinate theta in [0, 4] (side k covers
// [k, k + 1]); corners appear at the end of one side and the start of the
// next.
std::vector<std::pair<Sample, double>> MeshBuilder::OuterLoop(uint32_t patch) {
  std::vector<std::pair<Sample, double>> loop;
  for (int side = 0; side < 4; ++side) {
    std::vector<Sample> samples = SideSamples(patch, side);
    const size_t n = samples.size() - 1;
    const bool backward = side == kTop || side == kLeft;
    for (size_t m = 0; m <= n; ++m) {
      const Sample& s = samples[backward ? n - m : m];
      const double along = side == kBottom  ? s.u
                           : side == kRight ? s.v
                           : side == kTop   ? 1.0 - s.u
                                            : 1.0 - s.v;
      loop.push_back({s, side + along});
    }
  }
  return loop;
}

// InnerLoop returns the boundary of the interior grid (nodes 1..grid-1 each
// way) counter-clockwise, each node with the perimeter coordinate of the
// outer loop's side it faces (its u or v along that side), so the zipper
// pairs samples that are at most one spacing apart in u and in v, also at
// the corners (where the inner corner appears once for each side).
std::vector<std::pair<Sample, double>> MeshBuilder::InnerLoop(
    uint32_t patch, const std::vector<uint32_t>& grid) {
  const int nu = plans_[patch].grid_u;
  const int nv = plans_[patch].grid_v;
  auto node = [&](int i, int j) {
    return Sample{grid[static_cast<size_t>(i - 1) * (nv - 1) + (j - 1)],
                  static_cast<double>(i) / nu, static_cast<double>(j) / nv};
  };
  std::vector<std::pair<Sample, double>> loop;
  auto add_side = [&](int side, int count, auto at) {
    for (int k = 0; k < count; ++k) {
      const Sample s = at(k);
      const double along = side == kBottom  ? s.u
                           : side == kRight ? s.v
                           : side == kTop   ? 1.0 - s.u
                                            : 1.0 - s.v;
      loop.push_back({s, side + along});
    }
  };
  // Each side from its start corner to its end corner; a single node is
  // both (count 2 then repeats it).
  add_side(kBottom, std::max(2, nu - 1),
           [&](int k) { return node(std::min(1 + k, nu - 1), 1); });
  add_side(kRight, std::max(2, nv - 1),
           [&](int k) { return node(nu - 1, std::min(1 + k, nv - 1)); });
  add_side(kTop, std::max(2, nu - 1),
           [&](int k) { return node(std::max(nu - 1 - k, 1), nv - 1); });
  add_side(kLeft, std::max(2, nv - 1),
           [&](int k) { return node(1, std::max(nv - 1 - k, 1)); });
  return loop;
}

void MeshBuilder::AddTriangle(uint32_t patch, const Sample& a, const Sample& b,
                              const Sample& c) {
  if (a.vertex == b.vertex || b.vertex == c.vertex || a.vertex == c.vertex) {
    return;
  }
  for (const Sample* s : {&a, &b, &c}) {
    triangles_.push_back(s->vertex);
    corner_uv_.push_back(s->u);
    corner_uv_.push_back(s->v);
  }
  triangle_patch_.push_back(patch);
}

// ZipRing triangulates the ring between the outer and inner loops by
// merging them in order of theta (a "zipper"): each step advances the loop
// whose next sample comes first, so every triangle spans at most about one
// sample spacing of each loop.
void MeshBuilder::ZipRing(uint32_t patch,
                          const std::vector<std::pair<Sample, double>>& outer,
                          const std::vector<std::pair<Sample, double>>& inner) {
  size_t i = 0;
  size_t j = 0;
  while (i + 1 < outer.size() || j + 1 < inner.size()) {
    const bool advance_outer =
        j + 1 == inner.size() ||
        (i + 1 < outer.size() && outer[i + 1].second <= inner[j + 1].second);
    if (advance_outer) {
      AddTriangle(patch, outer[i].first, outer[i + 1].first, inner[j].first);
      ++i;
    } else {
      AddTriangle(patch, outer[i].first, inner[j + 1].first, inner[j].first);
      ++j;
    }
  }
}

void MeshBuilder::BuildPatch(uint32_t patch) {
  PatchPlan& plan = plans_[patch];
  for (int corner = 0; corner < 4; ++corner) {
    plan.corner[corner] = CornerVertex(patch, corner);
  }
  const int nu = plan.grid_u;
  const int nv = plan.grid_v;
  std::vector<uint32_t> grid;
  grid.reserve(static_cast<size_t>(nu - 1) * (nv - 1));
  for (int i = 1; i < nu; ++i) {
    for (int j = 1; j < nv; ++j) {
      grid.push_back(NewVertex(patch, static_cast<double>(i) / nu,
                               static_cast<double>(j) / nv));
    }
  }
  ZipRing(patch, OuterLoop(patch), InnerLoop(patch, grid));
  auto node = [&](int i, int j) {
    return Sample{grid[static_cast<size_t>(i - 1) * (nv - 1) + (j - 1)],
                  static_cast<double>(i) / nu, static_cast<double>(j) / nv};
  };
  for (int i = 1; i + 1 < nu; ++i) {
    for (int j = 1; j + 1 < nv; ++j) {
      AddTriangle(patch, node(i, j), node(i + 1, j), node(i + 1, j + 1));
      AddTriangle(patch, node(i, j), node(i + 1, j + 1), node(i, j + 1));
    }
  }
}

absl::Status MeshBuilder::Build(const CancellationToken* cancel) {
  for (uint32_t patch = 0; patch < patches_.size(); ++patch) {
    if (absl::Status status = CheckCancelled(cancel); !status.ok())
      return status;
    BuildPatch(patch);
  }
  return absl::OkStatus();
}

absl::Status MeshBuilder::Evaluate(const CancellationToken* cancel) {
  std::vector<std::vector<uint32_t>> owned(patches_.size());
  for (uint32_t r = 0; r < sources_.size(); ++r) {
    owned[sources_[r].patch].push_back(r);
  }
  positions_.resize(3 * sources_.size());
  normals_.resize(3 * sources_.size());
  constexpr int kOrder = 2;  // second partials for degenerate normals
  std::vector<double> uv;
  std::vector<std::vector<double>> buffers(PartialCount(kOrder));
  std::vector<double> normals;
  for (size_t patch = 0; patch < patches_.size(); ++patch) {
    if (absl::Status status = CheckCancelled(cancel); !status.ok())
      return status;
    const std::vector<uint32_t>& vertices = owned[patch];
    if (vertices.empty()) continue;
    uv.clear();
    for (uint32_t r : vertices) {
      uv.push_back(sources_[r].u);
      uv.push_back(sources_[r].v);
    }
    std::vector<absl::Span<double>> output;
    for (std::vector<double>& buffer : buffers) {
      buffer.resize(3 * vertices.size());
      output.push_back(absl::MakeSpan(buffer));
    }
    const SurfaceSamples samples = SurfaceSamples::Pairs(uv);
    absl::Status status =
        EvaluateBezierSurface(patches_[patch], samples, output);
    normals.resize(3 * vertices.size());
    if (status.ok()) {
      status = ComputeUnitNormals(output, samples, BezierSurfaceDomain(),
                                  absl::MakeSpan(normals));
    }
    if (!status.ok()) return status;
    for (size_t k = 0; k < vertices.size(); ++k) {
      for (int x = 0; x < 3; ++x) {
        positions_[3 * vertices[k] + x] = buffers[0][3 * k + x];
        normals_[3 * vertices[k] + x] = normals[3 * k + x];
      }
    }
  }
  return absl::OkStatus();
}

// WeldMap returns, for every vertex, the first vertex within `epsilon` of
// it (itself when none), found by hashing into cells of size epsilon and
// searching the 27 neighbouring cells.
std::vector<uint32_t> WeldMap(const std::vector<double>& positions,
                              double epsilon) {
  const size_t count = positions.size() / 3;
  std::vector<uint32_t> target(count);
  using Cell = std::array<int64_t, 3>;
  struct CellHash {
    size_t operator()(const Cell& c) const {
      return static_cast<size_t>(static_cast<uint64_t>(c[0]) * 73856093u ^
                                 static_cast<uint64_t>(c[1]) * 19349663u ^
                                 static_cast<uint64_t>(c[2]) * 83492791u);
    }
  };
  std::unordered_map<Cell, std::vector<uint32_t>, CellHash> cells;
  auto cell_of = [&](size_t r) {
    std::array<int64_t, 3> cell;
    for (int x = 0; x < 3; ++x) {
      cell[x] =
          static_cast<int64_t>(std::floor(positions[3 * r + x] / epsilon));
    }
    return cell;
  };
  for (size_t r = 0; r < count; ++r) {
    target[r] = static_cast<uint32_t>(r);
    const std::array<int64_t, 3> cell = cell_of(r);
    bool found = false;
    for (int dx = -1; dx <= 1 && !found; ++dx) {
      for (int dy = -1; dy <= 1 && !found; ++dy) {
        for (int dz = -1; dz <= 1 && !found; ++dz) {
          auto it = cells.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
          if (it == cells.end()) continue;
          for (uint32_t other : it->second) {
            if (Norm3(positions[3 * r] - positions[3 * other],
                      positions[3 * r + 1] - positions[3 * other + 1],
                      positions[3 * r + 2] - positions[3 * other + 2]) <=
                epsilon) {
              target[r] = other;
              found = true;
              break;
            }
          }
        }
      }
    }
    if (!found) cells[cell].push_back(static_cast<uint32_t>(r));
  }
  return target;
}

Mesh MeshBuilder::Finish() {
  double scale = 0.0;
  for (const BezierSurfaceView& patch : patches_) {
    for (double c : patch.control_net.coordinates) {
      scale = std::max(scale, std::abs(c));
    }
  }
  const double epsilon = std::max(1e-12 * scale, 1e-300);
  const std::vector<uint32_t> target = WeldMap(positions_, epsilon);
  Mesh mesh;
  std::vector<uint32_t> index(target.size());
  for (size_t r = 0; r < target.size(); ++r) {
    if (target[r] != r) continue;
    index[r] = static_cast<uint32_t>(mesh.patch.size());
    mesh.vertices.insert(mesh.vertices.end(), positions_.begin() + 3 * r,
                         positions_.begin() + 3 * r + 3);
    mesh.normals.insert(mesh.normals.end(), normals_.begin() + 3 * r,
                        normals_.begin() + 3 * r + 3);
    mesh.patch.push_back(sources_[r].patch);
    mesh.uv.push_back(sources_[r].u);
    mesh.uv.push_back(sources_[r].v);
  }
  for (size_t t = 0; t < triangle_patch_.size(); ++t) {
    std::array<uint32_t, 3> corners;
    for (int k = 0; k < 3; ++k)
      corners[k] = index[target[triangles_[3 * t + k]]];
    if (corners[0] == corners[1] || corners[1] == corners[2] ||
        corners[0] == corners[2]) {
      continue;  // collapsed by welding
    }
    mesh.triangles.insert(mesh.triangles.end(), corners.begin(), corners.end());
    mesh.triangle_patch.push_back(triangle_patch_[t]);
    mesh.corner_uv.insert(mesh.corner_uv.end(), corner_uv_.begin() + 6 * t,
                          corner_uv_.begin() + 6 * t + 6);
  }
  return mesh;
}

}  // namespace

absl::StatusOr<Polyline> TessellateBezierCurve(
    const BezierCurveView& curve, double tolerance, size_t max_points,
    const CancellationToken* cancel) {
  if (absl::Status status = ValidateBezierCurve(curve); !status.ok()) {
    return status;
  }
  if (absl::Status status = ValidateCurveRequest(tolerance, max_points);
      !status.ok()) {
    return status;
  }
  if (absl::Status status = CheckResolvable(
          tolerance, curve.control_points.coordinates, curve.degree());
      !status.ok()) {
    return status;
  }
  const PieceShape shape{.degree = curve.degree(),
                         .dimension = curve.control_points.dimension,
                         .rational = curve.rational()};
  const std::vector<double> control =
      PieceControl(curve.control_points, curve.weights);
  std::vector<double> parameters = {0.0};
  if (absl::Status status =
          SubdivideBezierPiece(control.data(), shape, 0.0, 1.0, tolerance,
                               max_points, cancel, parameters);
      !status.ok()) {
    return status;
  }
  return PolylineAt(
      shape.dimension, std::move(parameters),
      [&](absl::Span<const double> t, CurveOutput output,
          const ExecutionContext& context) {
        return EvaluateBezierCurve(curve, t, output, context);
      },
      cancel);
}

absl::StatusOr<Polyline> TessellateBSplineCurve(
    const BSplineCurveView& curve, double tolerance, size_t max_points,
    const CancellationToken* cancel) {
  if (absl::Status status = ValidateBSplineCurve(curve); !status.ok()) {
    return status;
  }
  if (absl::Status status = ValidateCurveRequest(tolerance, max_points);
      !status.ok()) {
    return status;
  }
  if (absl::Status status = CheckResolvable(
          tolerance, curve.control_points.coordinates, curve.degree);
      !status.ok()) {
    return status;
  }
  const int p = curve.degree;
  const PieceShape shape{.degree = p,
                         .dimension = curve.control_points.dimension,
                         .rational = curve.rational()};
  const std::vector<double> control =
      PieceControl(curve.control_points, curve.weights);
  const int n = static_cast<int>(curve.control_points.size()) - 1;
  std::vector<double> parameters = {curve.knots[p]};
  std::vector<double> bezier(shape.size()), work;
  for (int s = p; s <= n; ++s) {
    if (!(curve.knots[s] < curve.knots[s + 1])) continue;
    if (absl::Status status = CheckCancelled(cancel); !status.ok())
      return status;
    BlossomBezierPoints(control, shape.stride(), p, s, curve.knots, work,
                        bezier.data());
    if (absl::Status status = SubdivideBezierPiece(
            bezier.data(), shape, curve.knots[s], curve.knots[s + 1], tolerance,
            max_points, cancel, parameters);
        !status.ok()) {
      return status;
    }
  }
  return PolylineAt(
      shape.dimension, std::move(parameters),
      [&](absl::Span<const double> t, CurveOutput output,
          const ExecutionContext& context) {
        return EvaluateBSplineCurve(curve, t, output, context);
      },
      cancel);
}

namespace {

absl::Status ValidateMeshRequest(absl::Span<const BezierSurfaceView> patches,
                                 double tolerance, size_t max_vertices) {
  for (size_t i = 0; i < patches.size(); ++i) {
    if (absl::Status status = ValidatePatch(patches[i], i); !status.ok()) {
      return status;
    }
  }
  if (absl::Status status = ValidateTolerance(tolerance); !status.ok()) {
    return status;
  }
  for (const BezierSurfaceView& patch : patches) {
    const ControlNetView& net = patch.control_net;
    if (absl::Status status = CheckResolvable(
            tolerance, net.coordinates, std::max(net.count_u, net.count_v) - 1);
        !status.ok()) {
      return status;
    }
  }
  if (patches.size() >= UINT32_MAX) return Exhausted("vertices", max_vertices);
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<MeshSize> BezierPatchesMeshBound(
    absl::Span<const BezierSurfaceView> patches, double tolerance,
    size_t max_vertices) {
  if (absl::Status status =
          ValidateMeshRequest(patches, tolerance, max_vertices);
      !status.ok()) {
    return status;
  }
  MeshBuilder builder(patches, tolerance);
  if (absl::Status status = builder.Plan(max_vertices); !status.ok()) {
    return status;
  }
  return builder.planned_size();
}

absl::StatusOr<Mesh> TessellateBezierPatches(
    absl::Span<const BezierSurfaceView> patches, double tolerance,
    size_t max_vertices, const CancellationToken* cancel) {
  if (absl::Status status =
          ValidateMeshRequest(patches, tolerance, max_vertices);
      !status.ok()) {
    return status;
  }
  MeshBuilder builder(patches, tolerance);
  absl::Status status = builder.Plan(max_vertices);
  if (status.ok()) status = builder.Build(cancel);
  if (status.ok()) status = builder.Evaluate(cancel);
  if (!status.ok()) return status;
  return builder.Finish();
}

}  // namespace freeform
