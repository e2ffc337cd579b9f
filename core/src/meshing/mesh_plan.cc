// PlanMesh of mesh.h: every surface as a tensor net with knots, the grid of
// each span rectangle from bounds on the derivatives of the net, and the
// sides the pieces share; with a normal-angle limit, then the refinement of
// mesh_angle.cc.
#include "meshing/mesh_plan.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "base/tessellation_checks.h"
#include "freeform/core/mesh.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "geometry/variant_dispatch.h"
#include "meshing/piece_bounds.h"

namespace freeform {
namespace {

using internal::BoundPiece;
using internal::EdgePlan;
using internal::kBottom;
using internal::kLeft;
using internal::kRight;
using internal::kTop;
using internal::NeededCells;
using internal::NonEmptySpans;
using internal::PieceBounds;
using internal::PiecePlan;
using internal::TensorForm;
using internal::TensorFormOf;
using internal::WeightIndex;

// The cancellation token is polled after this many pieces.
constexpr size_t kPiecesPerCancelCheck = 64;

// CheckMeshable checks that a surface is 3D with positive weights, naming
// the field of its kind.
absl::Status CheckMeshable(const Surface& surface, size_t index) {
  const std::string prefix = IndexedField("surfaces", index);
  return std::visit(
      [&](const auto& kind) -> absl::Status {
        using Kind = std::decay_t<decltype(kind)>;
        constexpr bool kTriangular = std::is_same_v<Kind, TriangularPatch>;
        const std::string field = absl::StrCat(
            prefix, kTriangular ? ".triangular_bezier"
                    : std::is_same_v<Kind, BSplineSurface> ? ".bspline"
                                                           : ".bezier");
        if (kind.dimension() != 3) {
          return InvalidFieldError(
              absl::StrCat(field, kTriangular ? ".control_points.dimension"
                                              : ".control_net.dimension"),
              "surfaces must be 3D to be meshed");
        }
        const absl::Span<const double> weights = kind.view().weights;
        for (size_t k = 0; k < weights.size(); ++k) {
          if (!(weights[k] > 0.0)) {
            return InvalidFieldError(
                absl::StrCat(field, ".weights[", k, "]"),
                "weights must be positive to be meshed (a rational surface "
                "with a zero or negative weight has no bounded piece)");
          }
        }
        return absl::OkStatus();
      },
      surface);
}

// CellsFor returns the cells a piece direction needs for the tolerance
// (second partials `second`) and the longest edge (first partial `first`:
// an edge spans at most one cell each way, so h_u M_u + h_v M_v <= L when
// each term is at most L / 2).
// `by_tolerance` is what the tolerance alone needs.
struct Cells {
  double cells = 1.0;
  double by_tolerance = 1.0;
};

Cells CellsFor(double second, double first, const MeshOptions& options) {
  Cells cells;
  cells.by_tolerance = NeededCells(second, options.tolerance);
  cells.cells = cells.by_tolerance;
  if (options.max_edge_length > 0.0) {
    cells.cells =
        std::max(cells.cells, std::ceil(2.0 * first / options.max_edge_length));
  }
  return cells;
}

// PieceVertices is the bound on a piece's vertices that a grid of
// cells_u x cells_v cells plans: its interior grid nodes and the corners.
double PieceVertices(double cells_u, double cells_v) {
  return (std::max(2.0, cells_u) - 1.0) * (std::max(2.0, cells_v) - 1.0) + 4.0;
}

// Clamped reports whether the knot vector repeats its end value degree + 1
// times at the start (at_end = false) or at the end.
bool Clamped(absl::Span<const double> knots, int degree, bool at_end) {
  const size_t n = knots.size();
  for (int k = 1; k <= degree; ++k) {
    const size_t a = at_end ? n - 1 : 0;
    const size_t b =
        at_end ? n - 1 - static_cast<size_t>(k) : static_cast<size_t>(k);
    if (knots[b] != knots[a]) return false;
  }
  return true;
}

// The sides of all pieces, identified so that shared sides are one edge.
class EdgeTable {
 public:
  // Add returns the first of `count` new edges.
  int Add(size_t count) {
    const int first = static_cast<int>(edges_.size());
    edges_.resize(edges_.size() + count);
    return first;
  }
  // ByContent returns the edge of a boundary side with Bezier control
  // points `points` ((x, y, z, w) each, in the direction of increasing
  // parameter) and whether it runs against its canonical direction.
  std::pair<int, bool> ByContent(const std::vector<double>& points) {
    std::vector<double> backward;
    for (size_t k = points.size(); k >= 4; k -= 4) {
      backward.insert(backward.end(), points.begin() + (k - 4),
                      points.begin() + k);
    }
    const bool reversed = backward < points;
    const std::vector<double>& key = reversed ? backward : points;
    auto [it, inserted] =
        by_content_.emplace(key, static_cast<int>(edges_.size()));
    if (inserted)
      edges_.push_back({.segments = 1, .collapsed = Collapsed(key)});
    return {it->second, reversed};
  }
  std::vector<EdgePlan>& edges() { return edges_; }

 private:
  static bool Collapsed(const std::vector<double>& points) {
    for (size_t k = 4; k < points.size(); ++k) {
      if (k % 4 != 3 && points[k] != points[k % 4]) return false;
    }
    return true;
  }

  std::map<std::vector<double>, int> by_content_;
  std::vector<EdgePlan> edges_;
};

// BoundaryPieces returns the Bezier control points ((x, y, z, w) each) of
// the pieces of a boundary curve of `surface`: row u = start (side kLeft),
// u = end (kRight), v = start (kBottom) or v = end (kTop), which is the
// boundary when the knots across it are clamped; one entry per non-empty
// span along it, empty when not clamped.
absl::StatusOr<std::vector<std::vector<double>>> BoundaryPieces(
    const BSplineSurfaceView& surface, int side,
    const CancellationToken* cancel) {
  const bool along_u = side == kBottom || side == kTop;
  const bool at_end = side == kRight || side == kTop;
  const int across_degree = along_u ? surface.degree_v : surface.degree_u;
  if (!Clamped(along_u ? surface.knots_v : surface.knots_u, across_degree,
               at_end)) {
    return std::vector<std::vector<double>>{};
  }
  const ControlNetView& net = surface.control_net;
  const int count = along_u ? net.count_u : net.count_v;
  const int fixed = at_end ? (along_u ? net.count_v : net.count_u) - 1 : 0;
  BSplineCurveData row{.degree = along_u ? surface.degree_u : surface.degree_v,
                       .dimension = 3};
  for (int k = 0; k < count; ++k) {
    const int i = along_u ? k : fixed, j = along_u ? fixed : k;
    const double* point = net.point(i, j);
    row.coordinates.insert(row.coordinates.end(), point, point + 3);
    if (surface.rational()) {
      row.weights.push_back(surface.weights[WeightIndex(net, i, j)]);
    }
  }
  const absl::Span<const double> knots =
      along_u ? surface.knots_u : surface.knots_v;
  row.knots.assign(knots.begin(), knots.end());
  absl::StatusOr<BezierDecomposition> pieces =
      DecomposeBSplineCurve(row.view(), cancel);
  if (!pieces.ok()) return pieces.status();
  std::vector<std::vector<double>> result;
  for (const BezierCurveData& segment : pieces->segments) {
    std::vector<double> points;
    for (size_t k = 0; k * 3 < segment.coordinates.size(); ++k) {
      points.insert(points.end(), segment.coordinates.begin() + 3 * k,
                    segment.coordinates.begin() + 3 * k + 3);
      points.push_back(segment.weights.empty() ? 1.0 : segment.weights[k]);
    }
    result.push_back(std::move(points));
  }
  return result;
}

// PlannedTriangles returns the triangles the pieces make at most: the
// zipped ring (one per sample of the outer and the inner loop) and two per
// interior grid cell.
size_t PlannedTriangles(const MeshPlan& plan) {
  size_t triangles = 0;
  for (const PiecePlan& piece : plan.pieces) {
    const size_t nu = static_cast<size_t>(piece.grid_u);
    const size_t nv = static_cast<size_t>(piece.grid_v);
    for (int side = 0; side < 4; ++side) {
      const EdgePlan& edge = plan.edges[static_cast<size_t>(piece.edge[side])];
      const bool along_u = side == kBottom || side == kTop;
      triangles += 1 + (edge.collapsed ? (along_u ? nu : nv)
                                       : static_cast<size_t>(edge.segments));
    }
    triangles += 2 * std::max<size_t>(2, nu - 1) +
                 2 * std::max<size_t>(2, nv - 1) + 2 * (nu - 2) * (nv - 2);
  }
  return triangles;
}

// Planner builds the plan surface by surface.
class Planner {
 public:
  Planner(absl::Span<const Surface> surfaces, const MeshOptions& options,
          const CancellationToken* cancel)
      : options_(options), cancel_(cancel) {
    plan_.surfaces = surfaces;
  }

  absl::Status AddSurface(uint32_t index, const TensorForm& form);
  absl::StatusOr<std::shared_ptr<const MeshPlan>> Finish();

 private:
  // AddVertices counts a piece's planned vertices, and those it would need
  // for the tolerance alone.
  absl::Status AddVertices(double count, double by_tolerance);
  // TooLarge is the refusal of a mesh over max_vertices, on the option
  // that made it so: max_edge_length when the tolerance alone would fit.
  absl::Status TooLarge(bool fits_by_tolerance) const;
  absl::Status RefineNormalAngles();
  void UseSide(PiecePlan& piece, int side, std::pair<int, bool> edge,
               double cells);

  const MeshOptions& options_;
  const CancellationToken* cancel_;
  MeshPlan plan_;
  EdgeTable edges_;
  double vertex_count_ = 0.0;
  double vertex_count_by_tolerance_ = 0.0;
};

// RefineNormalAngles cuts the surfaces into their pieces, which the plan
// then keeps for TessellatePlanned, and refines the plan for the normal
// angle.
absl::Status Planner::RefineNormalAngles() {
  plan_.decompositions.reserve(plan_.surfaces.size());
  for (const Surface& surface : plan_.surfaces) {
    absl::StatusOr<SurfaceDecomposition> decomposition =
        DecomposeSurface(surface, cancel_);
    if (!decomposition.ok()) return decomposition.status();
    plan_.decompositions.push_back(*std::move(decomposition));
  }
  return internal::RefineNormalAngles(plan_, options_, vertex_count_, cancel_);
}

absl::Status Planner::AddVertices(double count, double by_tolerance) {
  vertex_count_ += count;
  vertex_count_by_tolerance_ += by_tolerance;
  const double cap =
      std::min(static_cast<double>(options_.max_vertices), UINT32_MAX - 1.0);
  if (vertex_count_ > cap) return TooLarge(vertex_count_by_tolerance_ <= cap);
  return absl::OkStatus();
}

absl::Status Planner::TooLarge(bool fits_by_tolerance) const {
  const bool by_edges = fits_by_tolerance && options_.max_edge_length > 0.0;
  return internal::TessellationTooLarge(
      by_edges ? "max_edge_length" : "tolerance", "vertices",
      options_.max_vertices);
}

void Planner::UseSide(PiecePlan& piece, int side, std::pair<int, bool> edge,
                      double cells) {
  piece.edge[side] = edge.first;
  piece.reversed[side] = edge.second;
  EdgePlan& plan = edges_.edges()[static_cast<size_t>(edge.first)];
  if (!plan.collapsed && cells > plan.segments) {
    vertex_count_ += cells - plan.segments;
    plan.segments = static_cast<int>(cells);
  }
}

absl::Status Planner::AddSurface(uint32_t index, const TensorForm& form) {
  const BSplineSurfaceView surface = form.view();
  const ControlNetView& net = surface.control_net;
  RETURN_IF_ERROR(
      internal::CheckResolvable(options_.tolerance, net.coordinates,
                                std::max(surface.degree_u, surface.degree_v)));
  for (const double c : net.coordinates) {
    plan_.scale = std::max(plan_.scale, std::abs(c));
  }
  const std::vector<int> spans_u =
      NonEmptySpans(surface.knots_u, surface.degree_u, net.count_u);
  const std::vector<int> spans_v =
      NonEmptySpans(surface.knots_v, surface.degree_v, net.count_v);
  std::array<std::vector<std::vector<double>>, 4> boundary;
  for (int side = 0; side < 4; ++side) {
    absl::StatusOr<std::vector<std::vector<double>>> pieces =
        BoundaryPieces(surface, side, cancel_);
    if (!pieces.ok()) return pieces.status();
    boundary[side] = *std::move(pieces);
  }
  const int last_u = static_cast<int>(spans_u.size()) - 1;
  const int last_v = static_cast<int>(spans_v.size()) - 1;
  const size_t pieces_u = spans_u.size(), pieces_v = spans_v.size();
  // The inner knot lines' sides: u lines 1..last_u (pieces_v sides each),
  // then v lines 1..last_v (pieces_u sides each).
  const int inner_u = edges_.Add(static_cast<size_t>(last_u) * pieces_v);
  const int inner_v = edges_.Add(static_cast<size_t>(last_v) * pieces_u);
  // The edge of side `side` of piece (i, j).
  auto side_edge = [&](int i, int j, int side) -> std::pair<int, bool> {
    const bool along_u = side == kBottom || side == kTop;
    const int span = along_u ? i : j;
    const int line = side == kBottom ? j
                     : side == kTop  ? j + 1
                     : side == kLeft ? i
                                     : i + 1;
    const int lines = along_u ? last_v + 1 : last_u + 1;
    if (line > 0 && line < lines) {
      return {along_u
                  ? inner_v + (line - 1) * static_cast<int>(pieces_u) + span
                  : inner_u + (line - 1) * static_cast<int>(pieces_v) + span,
              false};
    }
    if (!boundary[side].empty()) {
      return edges_.ByContent(boundary[side][static_cast<size_t>(span)]);
    }
    return {edges_.Add(1), false};
  };
  for (int i = 0; i <= last_u; ++i) {
    for (int j = 0; j <= last_v; ++j) {
      if (plan_.pieces.size() % kPiecesPerCancelCheck == 0) {
        RETURN_IF_ERROR(CheckCancelled(cancel_));
      }
      const PieceBounds bounds =
          BoundPiece(surface, spans_u[static_cast<size_t>(i)],
                     spans_v[static_cast<size_t>(j)]);
      const Cells needed_u =
          CellsFor(bounds.uu + bounds.uv, bounds.u, options_);
      const Cells needed_v =
          CellsFor(bounds.vv + bounds.uv, bounds.v, options_);
      const double cells_u = needed_u.cells;
      const double cells_v = needed_v.cells;
      const auto fits = [&](double u, double v) {
        return u * v <= static_cast<double>(options_.max_vertices) &&
               u <= internal::kMaxMeshCells && v <= internal::kMaxMeshCells;
      };
      if (!fits(cells_u, cells_v)) {
        return TooLarge(fits(needed_u.by_tolerance, needed_v.by_tolerance));
      }
      PiecePlan piece{.surface = index,
                      .piece = static_cast<uint32_t>(i * (last_v + 1) + j),
                      .grid_u = std::max(2, static_cast<int>(cells_u)),
                      .grid_v = std::max(2, static_cast<int>(cells_v))};
      for (int side = 0; side < 4; ++side) {
        const bool along_u = side == kBottom || side == kTop;
        UseSide(piece, side, side_edge(i, j, side),
                along_u ? cells_u : cells_v);
      }
      plan_.pieces.push_back(piece);
      // Interior grid nodes and the corners (an upper bound).
      RETURN_IF_ERROR(AddVertices(
          PieceVertices(piece.grid_u, piece.grid_v),
          PieceVertices(needed_u.by_tolerance, needed_v.by_tolerance)));
    }
  }
  return absl::OkStatus();
}

absl::StatusOr<std::shared_ptr<const MeshPlan>> Planner::Finish() {
  plan_.edges = std::move(edges_.edges());
  if (options_.max_normal_angle > 0.0) {
    RETURN_IF_ERROR(RefineNormalAngles());
  }
  plan_.size = {.vertices = static_cast<size_t>(vertex_count_),
                .triangles = PlannedTriangles(plan_)};
  for (const Surface& surface : plan_.surfaces) {
    const uint64_t values = SurfacePieceValues(surface);
    plan_.piece_values = values > UINT64_MAX - plan_.piece_values
                             ? UINT64_MAX
                             : plan_.piece_values + values;
  }
  return std::make_shared<const MeshPlan>(std::move(plan_));
}

absl::Status ValidateOptions(const MeshOptions& options) {
  RETURN_IF_ERROR(internal::ValidateTolerance(options.tolerance));
  if (options.max_edge_length != 0.0) {
    RETURN_IF_ERROR(
        ValidatePositive(options.max_edge_length, "max_edge_length"));
  }
  if (options.max_normal_angle != 0.0 &&
      !(options.max_normal_angle > 0.0 &&
        options.max_normal_angle < std::numbers::pi)) {
    return InvalidFieldError("max_normal_angle",
                             "must be above 0 and below pi (radians)");
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<std::shared_ptr<const MeshPlan>> PlanMesh(
    absl::Span<const Surface> surfaces, const MeshOptions& options,
    const CancellationToken* cancel) {
  for (size_t i = 0; i < surfaces.size(); ++i) {
    RETURN_IF_ERROR(CheckMeshable(surfaces[i], i));
  }
  RETURN_IF_ERROR(ValidateOptions(options));
  if (surfaces.size() >= UINT32_MAX) {
    return internal::TessellationTooLarge("tolerance", "vertices",
                                          options.max_vertices);
  }
  Planner planner(surfaces, options, cancel);
  for (size_t i = 0; i < surfaces.size(); ++i) {
    absl::StatusOr<TensorForm> form = TensorFormOf(surfaces[i]);
    if (!form.ok()) return form.status();
    RETURN_IF_ERROR(planner.AddSurface(static_cast<uint32_t>(i), *form));
  }
  return planner.Finish();
}

MeshSize PlannedMeshSize(const MeshPlan& plan) { return plan.size; }

uint64_t PlannedPieceValues(const MeshPlan& plan) { return plan.piece_values; }

}  // namespace freeform
