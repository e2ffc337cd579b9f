#include "freeform/core/section.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "bezier_net.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/status.h"

namespace freeform {
namespace {

using internal::Net;
using internal::NetEvaluator;
using internal::Pieces;

// The sign convention of the quadtree: 0 counts as positive, so a root is
// where the sign flips and neighbouring cells agree on it.
bool Negative(double value) { return value < 0.0; }

// ScalarNet returns the coefficients of g = n . (w P) - offset w of a
// lifted net, as a net of dimension 1.
Net ScalarNet(const Net& net, absl::Span<const double> normal, double offset) {
  Net scalar{.dimension = 1,
             .rational = false,
             .count_u = net.count_u,
             .count_v = net.count_v};
  for (int i = 0; i < net.count_u; ++i) {
    for (int j = 0; j < net.count_v; ++j) {
      const double* p = net.at(i, j);
      const double w = net.rational ? p[net.dimension] : 1.0;
      double g = -offset * w;
      for (int x = 0; x < net.dimension; ++x) g += normal[x] * p[x];
      scalar.values.push_back(g);
    }
  }
  return scalar;
}

// Monotone returns true when the coefficients strictly rise or strictly
// fall along u (axis 0) or v (axis 1).
bool Monotone(const Net& cell, int axis) {
  const int nu = cell.count_u;
  const int nv = cell.count_v;
  if ((axis == 0 ? nu : nv) < 2) return false;
  bool rising = true;
  bool falling = true;
  for (int i = 0; i + (axis == 0 ? 1 : 0) < nu; ++i) {
    for (int j = 0; j + (axis == 1 ? 1 : 0) < nv; ++j) {
      const double d = axis == 0 ? cell.at(i + 1, j)[0] - cell.at(i, j)[0]
                                 : cell.at(i, j + 1)[0] - cell.at(i, j)[0];
      rising &= d > 0.0;
      falling &= d < 0.0;
    }
  }
  return rising || falling;
}

int SignChanges(const std::vector<double>& values) {
  int changes = 0;
  for (size_t k = 1; k < values.size(); ++k) {
    changes += Negative(values[k]) != Negative(values[k - 1]) ? 1 : 0;
  }
  return changes;
}

// A vertex of a section: piece, (s, t) in it, point.
struct Vertex {
  size_t piece = 0;
  double x[2] = {0.0, 0.0};
  std::vector<double> point;
};

// A quadtree cell: the scalar coefficients over [lo, hi] of a piece.
struct Cell {
  double lo[2] = {0.0, 0.0};
  double hi[2] = {1.0, 1.0};
  Net net;
  int depth = 0;
};

class Slicer {
 public:
  Slicer(const Pieces& pieces, absl::Span<const double> normal, double offset,
         const SectionOptions& options, const CancellationToken* cancel)
      : pieces_(pieces),
        options_(options),
        poll_(cancel),
        cancel_(cancel),
        partials_(6 * static_cast<size_t>(pieces.dimension)),
        scalar_partials_(6) {
    for (const Net& net : pieces.nets) {
      scalars_.push_back(ScalarNet(net, normal, offset));
    }
  }

  absl::Status Run();
  std::vector<std::vector<Vertex>>& arcs() { return arcs_; }

 private:
  absl::Status Piece(size_t piece);
  double G(size_t piece, double s, double t);
  // Root returns where g changes sign on the line where coordinate
  // `fixed_axis` is `fixed`, between lo and hi of the other coordinate.
  double Root(size_t piece, int fixed_axis, double fixed, double lo, double hi);
  void EdgeRoots(size_t piece, int fixed_axis, double fixed,
                 std::vector<double> coefficients, double lo, double hi,
                 int depth, std::vector<double>& roots);
  absl::Status Leaf(size_t piece, const Cell& cell, int along);
  absl::Status Arc(size_t piece, int along, double c0, double a0, double c1,
                   double a1, const Cell& cell);
  Vertex MakeVertex(size_t piece, int along, double c, double a);

  const Pieces& pieces_;
  const SectionOptions& options_;
  CancellationPoll poll_;
  const CancellationToken* cancel_;
  std::vector<Net> scalars_;
  NetEvaluator evaluator_;
  std::vector<double> partials_;
  std::vector<double> scalar_partials_;
  std::vector<std::vector<Vertex>> arcs_;
  size_t cells_ = 0;
  size_t vertices_ = 0;
};

double Slicer::G(size_t piece, double s, double t) {
  evaluator_.Evaluate(scalars_[piece], s, t, scalar_partials_.data());
  return scalar_partials_[0];
}

double Slicer::Root(size_t piece, int fixed_axis, double fixed, double lo,
                    double hi) {
  auto at = [&](double x) {
    return fixed_axis == 0 ? G(piece, fixed, x) : G(piece, x, fixed);
  };
  const bool negative_lo = Negative(at(lo));
  for (int k = 0; k < 64; ++k) {
    const double middle = 0.5 * (lo + hi);
    if (middle <= lo || middle >= hi) break;
    (Negative(at(middle)) == negative_lo ? lo : hi) = middle;
  }
  return 0.5 * (lo + hi);
}

// EdgeRoots isolates the sign changes of the 1D Bezier `coefficients` of g
// on [lo, hi] of the edge (coordinate fixed_axis = fixed) by halving until
// each part has one variation, then bisects on the piece's function.
void Slicer::EdgeRoots(size_t piece, int fixed_axis, double fixed,
                       std::vector<double> coefficients, double lo, double hi,
                       int depth, std::vector<double>& roots) {
  const int changes = SignChanges(coefficients);
  if (changes == 0) return;
  if (changes == 1 || depth >= kMaxSectionDepth) {
    if (Negative(coefficients.front()) != Negative(coefficients.back())) {
      roots.push_back(Root(piece, fixed_axis, fixed, lo, hi));
    }
    return;
  }
  Net line{.dimension = 1,
           .count_u = static_cast<int>(coefficients.size()),
           .values = std::move(coefficients)};
  Net low, high;
  internal::Halve(line, true, low, high);
  const double middle = 0.5 * (lo + hi);
  EdgeRoots(piece, fixed_axis, fixed, std::move(low.values), lo, middle,
            depth + 1, roots);
  EdgeRoots(piece, fixed_axis, fixed, std::move(high.values), middle, hi,
            depth + 1, roots);
}

Vertex Slicer::MakeVertex(size_t piece, int along, double c, double a) {
  Vertex vertex{.piece = piece};
  vertex.x[along] = a;
  vertex.x[1 - along] = c;
  evaluator_.Evaluate(pieces_.nets[piece], vertex.x[0], vertex.x[1],
                      partials_.data());
  vertex.point.assign(partials_.begin(), partials_.begin() + pieces_.dimension);
  return vertex;
}

// Arc adds the arc from (c0, a0) to (c1, a1) (c across, a along) with
// vertices inserted at midpoints of c until each middle vertex is within
// tolerance of its chord.
absl::Status Slicer::Arc(size_t piece, int along, double c0, double a0,
                         double c1, double a1, const Cell& cell) {
  const int dim = pieces_.dimension;
  std::vector<Vertex> done = {MakeVertex(piece, along, c0, a0)};
  std::vector<std::pair<Vertex, int>> pending = {
      {MakeVertex(piece, along, c1, a1), 0}};
  while (!pending.empty()) {
    if (++vertices_ > options_.max_points) {
      return ExhaustedFieldError("max_points",
                                 absl::StrCat("the sections need more than ",
                                              options_.max_points, " points"));
    }
    if (absl::Status status = poll_.Done(64 * scalars_[piece].values.size());
        !status.ok()) {
      return status;
    }
    const Vertex& from = done.back();
    const Vertex& to = pending.back().first;
    const int depth = pending.back().second;
    const double c = 0.5 * (from.x[1 - along] + to.x[1 - along]);
    const double a = Root(piece, 1 - along, c, cell.lo[along], cell.hi[along]);
    Vertex middle = MakeVertex(piece, along, c, a);
    double deviation = 0.0;
    for (int x = 0; x < dim; ++x) {
      const double d = middle.point[x] - 0.5 * (from.point[x] + to.point[x]);
      deviation += d * d;
    }
    if (std::sqrt(deviation) <= options_.tolerance ||
        depth >= kMaxSectionDepth) {
      done.push_back(std::move(middle));
      done.push_back(std::move(pending.back().first));
      pending.pop_back();
      continue;
    }
    pending.back().second = depth + 1;
    pending.emplace_back(std::move(middle), depth + 1);
  }
  arcs_.push_back(std::move(done));
  return absl::OkStatus();
}

// Leaf traces a cell where g is monotone along axis `along`.
absl::Status Slicer::Leaf(size_t piece, const Cell& cell, int along) {
  const int across = 1 - along;
  const Net& net = cell.net;
  const int n_along = along == 0 ? net.count_u : net.count_v;
  const int n_across = along == 0 ? net.count_v : net.count_u;
  auto coefficient = [&](int k_along, int k_across) {
    return along == 0 ? net.at(k_along, k_across)[0]
                      : net.at(k_across, k_along)[0];
  };
  // Boundary points (across, along).
  std::vector<std::pair<double, double>> ends;
  for (int side = 0; side < 2; ++side) {
    const int k = side == 0 ? 0 : n_along - 1;
    const double a = side == 0 ? cell.lo[along] : cell.hi[along];
    std::vector<double> edge;
    for (int m = 0; m < n_across; ++m) edge.push_back(coefficient(k, m));
    std::vector<double> roots;
    EdgeRoots(piece, along, a, std::move(edge), cell.lo[across],
              cell.hi[across], 0, roots);
    for (double c : roots) ends.emplace_back(c, a);
  }
  for (int side = 0; side < 2; ++side) {
    const int m = side == 0 ? 0 : n_across - 1;
    const double c = side == 0 ? cell.lo[across] : cell.hi[across];
    if (Negative(coefficient(0, m)) != Negative(coefficient(n_along - 1, m))) {
      ends.emplace_back(c,
                        Root(piece, across, c, cell.lo[along], cell.hi[along]));
    }
  }
  std::sort(ends.begin(), ends.end());
  for (size_t k = 0; k + 1 < ends.size(); k += 2) {
    if (absl::Status status = Arc(piece, along, ends[k].first, ends[k].second,
                                  ends[k + 1].first, ends[k + 1].second, cell);
        !status.ok()) {
      return status;
    }
  }
  return absl::OkStatus();
}

absl::Status Slicer::Piece(size_t piece) {
  double scale = 0.0;
  for (double g : scalars_[piece].values) scale = std::max(scale, std::abs(g));
  const double zero = 64.0 * std::numeric_limits<double>::epsilon() * scale;
  std::vector<Cell> stack = {Cell{.net = scalars_[piece]}};
  while (!stack.empty()) {
    Cell cell = std::move(stack.back());
    stack.pop_back();
    if (++cells_ > options_.max_cells) {
      return ExhaustedFieldError("max_cells",
                                 absl::StrCat("the sections need more than ",
                                              options_.max_cells, " cells"));
    }
    if (absl::Status status = poll_.Done(8 * cell.net.values.size());
        !status.ok()) {
      return status;
    }
    const auto [lo, hi] =
        std::minmax_element(cell.net.values.begin(), cell.net.values.end());
    if (*lo >= 0.0 || *hi < 0.0) continue;      // one sign (0 positive)
    if (*hi <= zero && -*lo <= zero) continue;  // in the plane
    const int along =
        Monotone(cell.net, 0) ? 0 : (Monotone(cell.net, 1) ? 1 : -1);
    if (along >= 0) {
      if (absl::Status status = Leaf(piece, cell, along); !status.ok()) {
        return status;
      }
      continue;
    }
    if (cell.depth < kMaxSectionDepth) {
      const bool in_u = cell.net.count_v < 2 ||
                        (cell.net.count_u >= 2 &&
                         cell.hi[0] - cell.lo[0] >= cell.hi[1] - cell.lo[1]);
      const int axis = in_u ? 0 : 1;
      const double middle = 0.5 * (cell.lo[axis] + cell.hi[axis]);
      Cell low{.lo = {cell.lo[0], cell.lo[1]},
               .hi = {cell.hi[0], cell.hi[1]},
               .depth = cell.depth + 1};
      Cell high = low;
      low.hi[axis] = middle;
      high.lo[axis] = middle;
      internal::Halve(cell.net, in_u, low.net, high.net);
      stack.push_back(std::move(low));
      stack.push_back(std::move(high));
    }
  }
  return absl::OkStatus();
}

absl::Status Slicer::Run() {
  if (absl::Status status = CheckCancelled(cancel_); !status.ok()) {
    return status;
  }
  for (size_t piece = 0; piece < scalars_.size(); ++piece) {
    if (absl::Status status = Piece(piece); !status.ok()) return status;
  }
  return absl::OkStatus();
}

// Chain joins arcs whose end points coincide into polylines.
class Chain {
 public:
  Chain(std::vector<std::vector<Vertex>>& arcs, int dimension, double slack)
      : arcs_(arcs), dimension_(dimension), slack_(slack) {
    Match();
  }

  // Write appends every polyline to `sections`.
  void Write(const Pieces& pieces, Sections& sections);

 private:
  // End e is arc e / 2, its first vertex when e is even.
  const Vertex& EndVertex(size_t e) const {
    const std::vector<Vertex>& arc = arcs_[e / 2];
    return e % 2 == 0 ? arc.front() : arc.back();
  }
  void Match();
  void Walk(size_t start_end, const Pieces& pieces, Sections& sections);

  std::vector<std::vector<Vertex>>& arcs_;
  const int dimension_;
  const double slack_;
  std::vector<size_t> partner_;
  std::vector<bool> used_;
};

void Chain::Match() {
  const size_t ends = 2 * arcs_.size();
  partner_.assign(ends, SIZE_MAX);
  std::vector<size_t> order(ends);
  for (size_t e = 0; e < ends; ++e) order[e] = e;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return EndVertex(a).point[0] < EndVertex(b).point[0];
  });
  for (size_t k = 0; k < ends; ++k) {
    const size_t a = order[k];
    if (partner_[a] != SIZE_MAX) continue;
    for (size_t m = k + 1; m < ends; ++m) {
      const size_t b = order[m];
      const std::vector<double>& pa = EndVertex(a).point;
      const std::vector<double>& pb = EndVertex(b).point;
      if (pb[0] - pa[0] > slack_) break;
      if (partner_[b] != SIZE_MAX || b / 2 == a / 2) continue;
      double d = 0.0;
      for (int x = 0; x < dimension_; ++x)
        d += (pa[x] - pb[x]) * (pa[x] - pb[x]);
      if (std::sqrt(d) > slack_) continue;
      partner_[a] = b;
      partner_[b] = a;
      break;
    }
  }
}

void AppendVertex(const Vertex& vertex, const Pieces& pieces,
                  Sections& sections) {
  sections.points.insert(sections.points.end(), vertex.point.begin(),
                         vertex.point.end());
  double uv[2];
  pieces.parameters(vertex.piece, vertex.x[0], vertex.x[1], uv);
  sections.parameters.insert(sections.parameters.end(), {uv[0], uv[1]});
}

// Walk writes the polyline that leaves through end `start_end`'s arc.
void Chain::Walk(size_t start_end, const Pieces& pieces, Sections& sections) {
  size_t end = start_end;
  bool closed = false;
  for (bool first = true;; first = false) {
    used_[end / 2] = true;
    const std::vector<Vertex>& arc = arcs_[end / 2];
    const bool forward = end % 2 == 0;
    for (size_t k = first ? 0 : 1; k < arc.size(); ++k) {
      AppendVertex(arc[forward ? k : arc.size() - 1 - k], pieces, sections);
    }
    const size_t next = partner_[end ^ 1];
    if (next == SIZE_MAX) break;
    if (used_[next / 2]) {
      closed = next == start_end;
      break;
    }
    end = next;
  }
  sections.closed.push_back(closed ? 1 : 0);
  sections.offsets.push_back(sections.points.size() /
                             static_cast<size_t>(dimension_));
}

void Chain::Write(const Pieces& pieces, Sections& sections) {
  used_.assign(arcs_.size(), false);
  // Open polylines first, from an end without a partner.
  for (size_t e = 0; e < partner_.size(); ++e) {
    if (partner_[e] == SIZE_MAX && !used_[e / 2]) Walk(e, pieces, sections);
  }
  for (size_t e = 0; e < partner_.size(); e += 2) {
    if (!used_[e / 2]) Walk(e, pieces, sections);
  }
}

absl::Status CheckPlane(absl::Span<const double> point,
                        absl::Span<const double> normal, int dimension) {
  for (const auto& [values, name] :
       {std::pair{point, "plane_point"}, std::pair{normal, "plane_normal"}}) {
    if (values.size() != static_cast<size_t>(dimension)) {
      return InvalidFieldError(
          name, absl::StrCat("needs the surface's dimension ", dimension,
                             " values, got ", values.size()));
    }
    if (absl::Status status = ValidateFinite(values, name); !status.ok()) {
      return status;
    }
  }
  double length = 0.0;
  for (double n : normal) length += n * n;
  if (!(length > 0.0)) {
    return InvalidFieldError("plane_normal", "must not be the zero vector");
  }
  return absl::OkStatus();
}

// FitPolyline returns the B-spline of polyline k within `tolerance` of its
// vertices (see SectionOptions::fit_tolerance).
absl::StatusOr<BSplineCurveData> FitPolyline(const Sections& sections, size_t k,
                                             double tolerance,
                                             const CancellationToken* cancel) {
  const size_t dim = static_cast<size_t>(sections.dimension);
  // The vertices, a repeated one (which chord lengths cannot place) once.
  std::vector<double> vertices;
  for (size_t r = sections.offsets[k]; r < sections.offsets[k + 1]; ++r) {
    const auto point = sections.points.begin() + r * dim;
    if (vertices.empty() ||
        !std::equal(point, point + dim, vertices.end() - dim)) {
      vertices.insert(vertices.end(), point, point + dim);
    }
  }
  const int count = static_cast<int>(vertices.size() / dim);
  if (count == 1) {  // a point: a line of length 0
    vertices.insert(vertices.end(), vertices.begin(), vertices.end());
    return BSplineCurveData{.degree = 1,
                            .dimension = sections.dimension,
                            .coordinates = vertices,
                            .knots = {0, 0, 1, 1},
                            .weights = {}};
  }
  const PointsView points{sections.dimension, vertices};
  const int degree = std::min(3, count - 1);
  absl::StatusOr<CurveApproximation> fit;
  for (int controls = std::min(count, 2 * (degree + 1));;
       controls = std::min(count, 2 * controls)) {
    fit = ApproximateCurve(points, degree, controls,
                           Parameterization::kChordLength, {}, cancel);
    if (!fit.ok()) return fit.status();
    if (fit->max_residual <= tolerance || controls == count) break;
  }
  return std::move(fit->curve);
}

}  // namespace

absl::StatusOr<Sections> IntersectSurfacePlane(
    const Surface& surface, absl::Span<const double> plane_point,
    absl::Span<const double> plane_normal, const SectionOptions& options,
    const CancellationToken* cancel) {
  const int dimension = DimensionOf(surface);
  if (absl::Status status = CheckPlane(plane_point, plane_normal, dimension);
      !status.ok()) {
    return status;
  }
  if (!std::isfinite(options.tolerance) || options.tolerance <= 0.0) {
    return InvalidFieldError("tolerance", "must be positive and finite");
  }
  if (!std::isfinite(options.fit_tolerance) || options.fit_tolerance < 0.0) {
    return InvalidFieldError("fit_tolerance", "must be finite and >= 0");
  }
  absl::StatusOr<Pieces> pieces = internal::LiftPieces(surface, cancel);
  if (!pieces.ok()) return pieces.status();
  std::vector<double> normal(plane_normal.begin(), plane_normal.end());
  double length = 0.0;
  for (double n : normal) length += n * n;
  length = std::sqrt(length);
  double offset = 0.0;
  for (int x = 0; x < dimension; ++x) {
    normal[x] /= length;
    offset += normal[x] * plane_point[x];
  }
  Slicer slicer(*pieces, normal, offset, options, cancel);
  if (absl::Status status = slicer.Run(); !status.ok()) return status;
  double extent = 0.0;
  std::vector<double> point(static_cast<size_t>(dimension));
  for (const Net& net : pieces->nets) {
    for (int i = 0; i < net.count_u; ++i) {
      for (int j = 0; j < net.count_v; ++j) {
        if (!internal::Point(net, i, j, point.data())) continue;
        for (double x : point) extent = std::max(extent, std::abs(x));
      }
    }
  }
  Sections sections{.dimension = dimension};
  Chain chain(slicer.arcs(), dimension, 1e-9 * std::max(extent, 1e-300));
  chain.Write(*pieces, sections);
  if (options.fit_tolerance > 0.0) {
    for (size_t k = 0; k + 1 < sections.offsets.size(); ++k) {
      absl::StatusOr<BSplineCurveData> curve =
          FitPolyline(sections, k, options.fit_tolerance, cancel);
      if (!curve.ok()) return curve.status();
      sections.curves.push_back(*std::move(curve));
    }
  }
  return sections;
}

}  // namespace freeform
