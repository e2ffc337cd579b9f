#include "freeform/core/section.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "absl/functional/function_ref.h"
#include "absl/strings/str_cat.h"
#include "base/scaled.h"
#include "base/tessellation_checks.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "queries/bezier_net.h"

namespace freeform {
namespace {

using internal::Net;
using internal::NetEvaluator;
using internal::Pieces;

// Coefficients of g within this many rounding errors of the magnitude of
// their terms (RoundingOf) are zero: the surface lies in the plane there.
constexpr double kZeroRounding = 64 * std::numeric_limits<double>::epsilon();
// Two evaluations of a piece at nearly the same parameters may differ by
// this fraction of its largest coordinate by rounding alone.
constexpr double kEvaluationRounding =
    64 * std::numeric_limits<double>::epsilon();
// The most evaluations of g one root takes (Slicer::Root).
constexpr int kRootSteps = 200;

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

// RoundingOf returns kZeroRounding times the largest sum of the magnitudes
// of the terms of a coefficient of g: coefficients below it are zero within
// rounding (they are computed from such terms, and halving only averages
// them).
double RoundingOf(const Net& net, absl::Span<const double> normal,
                  double offset) {
  double largest = 0.0;
  for (int i = 0; i < net.count_u; ++i) {
    for (int j = 0; j < net.count_v; ++j) {
      const double* p = net.at(i, j);
      const double w = net.rational ? p[net.dimension] : 1.0;
      double sum = std::abs(offset * w);
      for (int x = 0; x < net.dimension; ++x) sum += std::abs(normal[x] * p[x]);
      largest = std::max(largest, sum);
    }
  }
  return kZeroRounding * largest;
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

// The edges of a piece's parameter square: u = 0, u = 1, v = 0, v = 1.
// Edge e fixes axis e / 2 at e % 2.
constexpr int kEdges = 4;

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

// An edge of a piece by the surface parameters of its ends (in order), so
// that the edge two pieces share has one key.
using EdgeKey = std::array<double, 4>;

// The work (SectionOptions::max_work) charged for a cell and for an
// evaluation of g.
uint64_t CellCost(const Net& net) { return 8 * net.values.size() + 16; }
uint64_t ValueCost(const Net& net) {
  return 2 * net.values.size() + static_cast<uint64_t>(net.count_u) +
         static_cast<uint64_t>(net.count_v) + 16;
}

// Slicer traces the section of the (scaled) pieces by the plane
// n . x = offset (n a unit vector) to `tolerance` (in the pieces' units).
class Slicer {
 public:
  // The pieces are in units of 2^exponent, of largest coordinate `largest`.
  Slicer(const Pieces& pieces, absl::Span<const double> normal, double offset,
         double tolerance, int exponent, double largest,
         const SectionOptions& options, const CancellationToken* cancel)
      : pieces_(pieces),
        normal_(normal.begin(), normal.end()),
        offset_(offset),
        tolerance_(tolerance),
        exponent_(exponent),
        rounding_(kEvaluationRounding * largest),
        options_(options),
        cancel_(cancel),
        budget_(options.max_work, "max_work", "the section's quadtree", cancel),
        partials_(6 * static_cast<size_t>(pieces.dimension)) {
    for (const Net& net : pieces.nets) {
      scalars_.push_back(ScalarNet(net, normal, offset));
      zeros_.push_back(RoundingOf(net, normal, offset));
    }
  }

  absl::Status Run();
  std::vector<std::vector<Vertex>>& arcs() { return arcs_; }
  // The pieces that lie in the plane, in order.
  const std::vector<size_t>& regions() const { return regions_; }

 private:
  bool InPlane(size_t piece) const;
  bool EdgeInPlane(size_t piece, int edge) const;
  // Key returns the key of edge `edge` of `piece`, or nullopt for an edge
  // collapsed to a point.
  std::optional<EdgeKey> Key(size_t piece, int edge) const;
  absl::Status Piece(size_t piece);
  absl::Status Edges(size_t piece);
  // OneSign returns true when the coefficients of `cell` have one sign (0
  // positive), those on its sides that are edges of the piece in the plane
  // left out.
  bool OneSign(size_t piece, const Cell& cell) const;
  // G returns g at (s, t) of a piece, and in `magnitude` the sum its
  // rounding is relative to (NetEvaluator::Value), charging the work to
  // max_work when `quadtree` (a vertex's work is bounded by max_points
  // instead).
  double G(size_t piece, double s, double t, bool quadtree, double& magnitude);
  // Root returns where g changes sign on the line where coordinate
  // `fixed_axis` is `fixed`, between lo and hi of the other coordinate.
  double Root(size_t piece, int fixed_axis, double fixed, double lo, double hi,
              bool quadtree);
  void EdgeRoots(size_t piece, int fixed_axis, double fixed,
                 std::vector<double> coefficients, double lo, double hi,
                 int depth, std::vector<double>& roots);
  absl::Status Leaf(size_t piece, const Cell& cell, int along);
  absl::Status Arc(size_t piece, int along, double c0, double c1,
                   absl::FunctionRef<double(double)> locate);
  absl::StatusOr<Vertex> MakeVertex(size_t piece, int along, double c,
                                    double a);
  absl::Status CheckResolved(const Vertex& vertex);
  absl::Status CountVertex();

  const Pieces& pieces_;
  const std::vector<double> normal_;
  const double offset_;
  const double tolerance_;
  const int exponent_;
  const double rounding_;
  const SectionOptions& options_;
  const CancellationToken* cancel_;
  internal::WorkBudget budget_;
  CancellationPoll poll_{cancel_};
  std::vector<Net> scalars_;
  std::vector<double> zeros_;
  NetEvaluator evaluator_;
  std::vector<double> partials_;
  std::vector<std::vector<Vertex>> arcs_;
  std::vector<size_t> regions_;
  std::vector<bool> in_plane_;
  // The edges in the plane traced already, or bounding a region.
  std::set<EdgeKey> edges_;
  size_t vertices_ = 0;
};

bool Slicer::InPlane(size_t piece) const {
  for (const double g : scalars_[piece].values) {
    if (std::abs(g) > zeros_[piece]) return false;
  }
  return true;
}

bool Slicer::EdgeInPlane(size_t piece, int edge) const {
  const Net& net = scalars_[piece];
  const int axis = edge / 2;
  const int count = axis == 0 ? net.count_v : net.count_u;
  const int row =
      edge % 2 == 0 ? 0 : (axis == 0 ? net.count_u : net.count_v) - 1;
  for (int k = 0; k < count; ++k) {
    const double g = axis == 0 ? net.at(row, k)[0] : net.at(k, row)[0];
    if (std::abs(g) > zeros_[piece]) return false;
  }
  return true;
}

std::optional<EdgeKey> Slicer::Key(size_t piece, int edge) const {
  const int axis = edge / 2;
  const double fixed = edge % 2;
  double ends[2][2];
  for (int end = 0; end < 2; ++end) {
    const double s = axis == 0 ? fixed : end;
    const double t = axis == 0 ? end : fixed;
    pieces_.parameters(piece, s, t, ends[end]);
  }
  if (ends[0][0] == ends[1][0] && ends[0][1] == ends[1][1]) {
    return std::nullopt;
  }
  const bool ordered = std::make_pair(ends[0][0], ends[0][1]) <
                       std::make_pair(ends[1][0], ends[1][1]);
  const double(&a)[2] = ordered ? ends[0] : ends[1];
  const double(&b)[2] = ordered ? ends[1] : ends[0];
  return EdgeKey{a[0], a[1], b[0], b[1]};
}

double Slicer::G(size_t piece, double s, double t, bool quadtree,
                 double& magnitude) {
  if (quadtree) budget_.Add(ValueCost(scalars_[piece]));
  return evaluator_.Value(scalars_[piece], s, t, magnitude);
}

// Root runs false position with the Illinois modification, bisecting where
// two steps did not halve the bracket, on the bracket [lo, hi] (g of different
// signs at its ends) until g is within one rounding error of the magnitude of
// its terms there or the bracket is two neighbouring doubles, at most
// kRootSteps evaluations.
double Slicer::Root(size_t piece, int fixed_axis, double fixed, double lo,
                    double hi, bool quadtree) {
  double magnitude = 0.0;
  auto at = [&](double x) {
    return fixed_axis == 0 ? G(piece, fixed, x, quadtree, magnitude)
                           : G(piece, x, fixed, quadtree, magnitude);
  };
  double g_lo = at(lo);
  double g_hi = at(hi);
  const bool negative_lo = Negative(g_lo);
  int kept = 0;  // the side kept by the last step: -1 lo, 1 hi
  double width = hi - lo;
  for (int k = 0; k < kRootSteps; ++k) {
    double x = lo - g_lo * (hi - lo) / (g_hi - g_lo);
    // Bisect when the last two steps did not halve the bracket.
    if (k % 2 == 1) {
      if (hi - lo > 0.5 * width) x = 0.5 * (lo + hi);
      width = hi - lo;
    }
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    if (x <= lo || x >= hi) break;
    const double g = at(x);
    if (std::abs(g) <= std::numeric_limits<double>::epsilon() * magnitude) {
      return x;
    }
    if (Negative(g) == negative_lo) {
      lo = x;
      g_lo = g;
      if (kept == 1) g_hi *= 0.5;
      kept = 1;
    } else {
      hi = x;
      g_hi = g;
      if (kept == -1) g_lo *= 0.5;
      kept = -1;
    }
  }
  return 0.5 * (lo + hi);
}

// EdgeRoots isolates the sign changes of the 1D Bezier `coefficients` of g
// on [lo, hi] of the edge (coordinate fixed_axis = fixed) by halving until
// each part has one variation, then finds the root on the piece's function.
void Slicer::EdgeRoots(size_t piece, int fixed_axis, double fixed,
                       std::vector<double> coefficients, double lo, double hi,
                       int depth, std::vector<double>& roots) {
  budget_.Add(4 * coefficients.size() * coefficients.size() + 16);
  const int changes = SignChanges(coefficients);
  if (changes == 0) return;
  if (changes == 1 || depth >= kMaxSectionDepth) {
    if (Negative(coefficients.front()) != Negative(coefficients.back())) {
      roots.push_back(Root(piece, fixed_axis, fixed, lo, hi, true));
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

// CountVertex counts one more vertex against options.max_points (a bound
// of those returned: Chain drops one where two arcs meet, at most one per
// arc but the first) and polls the token.
absl::Status Slicer::CountVertex() {
  ++vertices_;
  if (vertices_ > options_.max_points + arcs_.size()) {
    return ExhaustedFieldError("max_points",
                               absl::StrCat("the sections need more than ",
                                            options_.max_points, " points"));
  }
  return poll_.Done(64 * 16);
}

// MakeVertex returns the vertex at (c across, a along) of a piece, once it
// is checked to lie within the tolerance of the plane (double precision
// cannot place it so where the surface moves by more than the tolerance
// between neighbouring parameters, as extreme weights make it).
absl::StatusOr<Vertex> Slicer::MakeVertex(size_t piece, int along, double c,
                                          double a) {
  RETURN_IF_ERROR(CountVertex());
  Vertex vertex{.piece = piece};
  vertex.x[along] = a;
  vertex.x[1 - along] = c;
  evaluator_.Evaluate(pieces_.nets[piece], vertex.x[0], vertex.x[1],
                      partials_.data());
  vertex.point.assign(partials_.begin(), partials_.begin() + pieces_.dimension);
  double distance = -offset_;
  for (int x = 0; x < pieces_.dimension; ++x) {
    distance += normal_[x] * vertex.point[x];
  }
  if (!(std::abs(distance) <= tolerance_)) {
    double uv[2];
    pieces_.parameters(piece, vertex.x[0], vertex.x[1], uv);
    return InvalidFieldError(
        "surface",
        absl::StrCat("double precision cannot place a section vertex within "
                     "the tolerance of the plane near (u, v) = (",
                     uv[0], ", ", uv[1],
                     "): the surface moves farther than that between "
                     "neighbouring parameter values there (weights too far "
                     "apart)"));
  }
  RETURN_IF_ERROR(CheckResolved(vertex));
  return vertex;
}

// CheckResolved checks that the surface at the vertex's parameters as the
// answer reports them, rounded to doubles and mapped back onto its piece,
// is within the tolerance of the vertex (where a knot span is a few ulps of
// its position, spans of 0.25 at 2e15, the nearest double lies on another
// span): else UnresolvedError, naming "surface".
absl::Status Slicer::CheckResolved(const Vertex& vertex) {
  double uv[2];
  pieces_.parameters(vertex.piece, vertex.x[0], vertex.x[1], uv);
  double st[2];
  pieces_.locals(vertex.piece, uv, st);
  if (st[0] == vertex.x[0] && st[1] == vertex.x[1]) return absl::OkStatus();
  evaluator_.Evaluate(pieces_.nets[vertex.piece], st[0], st[1],
                      partials_.data());
  const double moved = internal::ScaledDistanceOf(
      partials_.data(), vertex.point.data(), pieces_.dimension);
  if (moved <= tolerance_ + rounding_) return absl::OkStatus();
  return internal::UnresolvedError("surface", uv, std::ldexp(moved, exponent_));
}

// Arc adds the arc from c0 to c1 (c across; `locate` gives the coordinate
// along at each c) with vertices inserted at midpoints of c until each
// middle vertex is within tolerance of its chord.
absl::Status Slicer::Arc(size_t piece, int along, double c0, double c1,
                         absl::FunctionRef<double(double)> locate) {
  const int dim = pieces_.dimension;
  absl::StatusOr<Vertex> first = MakeVertex(piece, along, c0, locate(c0));
  if (!first.ok()) return first.status();
  absl::StatusOr<Vertex> last = MakeVertex(piece, along, c1, locate(c1));
  if (!last.ok()) return last.status();
  std::vector<Vertex> done = {*std::move(first)};
  std::vector<std::pair<Vertex, int>> pending = {{*std::move(last), 0}};
  while (!pending.empty()) {
    const Vertex& from = done.back();
    const Vertex& to = pending.back().first;
    const int depth = pending.back().second;
    const double c = 0.5 * (from.x[1 - along] + to.x[1 - along]);
    absl::StatusOr<Vertex> middle = MakeVertex(piece, along, c, locate(c));
    if (!middle.ok()) return middle.status();
    double deviation = 0.0;
    for (int x = 0; x < dim; ++x) {
      const double d = middle->point[x] - 0.5 * (from.point[x] + to.point[x]);
      deviation += d * d;
    }
    if (std::sqrt(deviation) <= tolerance_ || depth >= kMaxSectionDepth) {
      done.push_back(*std::move(middle));
      done.push_back(std::move(pending.back().first));
      pending.pop_back();
      continue;
    }
    pending.back().second = depth + 1;
    pending.emplace_back(*std::move(middle), depth + 1);
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
      ends.emplace_back(
          c, Root(piece, across, c, cell.lo[along], cell.hi[along], true));
    }
  }
  std::sort(ends.begin(), ends.end());
  for (size_t k = 0; k + 1 < ends.size(); k += 2) {
    // Named copies, not structured bindings: a lambda may not capture
    // those before C++20's P1091 (clang 14).
    const double c0 = ends[k].first, a0 = ends[k].second;
    const double c1 = ends[k + 1].first, a1 = ends[k + 1].second;
    auto locate = [&](double c) {
      if (c == c0) return a0;
      if (c == c1) return a1;
      return Root(piece, across, c, cell.lo[along], cell.hi[along], false);
    };
    RETURN_IF_ERROR(Arc(piece, along, c0, c1, locate));
  }
  return absl::OkStatus();
}

bool Slicer::OneSign(size_t piece, const Cell& cell) const {
  const Net& net = cell.net;
  // Rows (axis 0) and columns (axis 1) on an edge of the piece in the
  // plane: Edges traces those.
  bool skip[kEdges];
  for (int edge = 0; edge < kEdges; ++edge) {
    const int axis = edge / 2;
    const bool on = edge % 2 == 0 ? cell.lo[axis] == 0.0 : cell.hi[axis] == 1.0;
    skip[edge] = on && EdgeInPlane(piece, edge);
  }
  bool negative = false;
  bool positive = false;
  for (int i = 0; i < net.count_u; ++i) {
    if ((i == 0 && skip[0]) || (i == net.count_u - 1 && skip[1])) continue;
    for (int j = 0; j < net.count_v; ++j) {
      if ((j == 0 && skip[2]) || (j == net.count_v - 1 && skip[3])) continue;
      (Negative(net.at(i, j)[0]) ? negative : positive) = true;
    }
  }
  return !(negative && positive);
}

absl::Status Slicer::Piece(size_t piece) {
  std::vector<Cell> stack = {Cell{.net = scalars_[piece]}};
  while (!stack.empty()) {
    Cell cell = std::move(stack.back());
    stack.pop_back();
    budget_.Add(CellCost(cell.net));
    RETURN_IF_ERROR(budget_.Check());
    if (OneSign(piece, cell)) continue;
    const int along =
        Monotone(cell.net, 0) ? 0 : (Monotone(cell.net, 1) ? 1 : -1);
    if (along >= 0) {
      RETURN_IF_ERROR(Leaf(piece, cell, along));
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

// Edges traces the edges of a piece that lie in the plane, each once: not
// those of a region, nor one a neighbouring piece traced.
absl::Status Slicer::Edges(size_t piece) {
  for (int edge = 0; edge < kEdges; ++edge) {
    if (!EdgeInPlane(piece, edge)) continue;
    const std::optional<EdgeKey> key = Key(piece, edge);
    if (!key.has_value() || !edges_.insert(*key).second) continue;
    const int axis = edge / 2;
    const double fixed = edge % 2;
    if (absl::Status status =
            Arc(piece, axis, 0.0, 1.0, [fixed](double) { return fixed; });
        !status.ok()) {
      return status;
    }
  }
  return absl::OkStatus();
}

absl::Status Slicer::Run() {
  RETURN_IF_ERROR(CheckCancelled(cancel_));
  // Regions first, so that their edges are not traced.
  for (size_t piece = 0; piece < scalars_.size(); ++piece) {
    if (!InPlane(piece)) continue;
    regions_.push_back(piece);
    for (int edge = 0; edge < kEdges; ++edge) {
      if (const std::optional<EdgeKey> key = Key(piece, edge)) {
        edges_.insert(*key);
      }
    }
  }
  for (size_t piece = 0; piece < scalars_.size(); ++piece) {
    if (InPlane(piece)) continue;
    RETURN_IF_ERROR(Edges(piece));
    RETURN_IF_ERROR(Piece(piece));
  }
  return budget_.Check();
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
  if (closed) {
    // The last vertex is the first one's partner, within the slack: a
    // closed polyline repeats its first vertex exactly (the proto's
    // promise), so its last vertex is the first's, point and parameters.
    const size_t d = static_cast<size_t>(dimension_);
    const size_t first = sections.offsets.back();
    std::copy_n(sections.points.begin() + first * d, d,
                sections.points.end() - d);
    std::copy_n(sections.parameters.begin() + first * 2, 2,
                sections.parameters.end() - 2);
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
    RETURN_IF_ERROR(ValidateFinite(values, name));
  }
  if (std::all_of(normal.begin(), normal.end(),
                  [](double n) { return n == 0.0; })) {
    return InvalidFieldError("plane_normal", "must not be the zero vector");
  }
  return absl::OkStatus();
}

// UnitNormal returns the normal divided by its length, computed after
// dividing by its largest magnitude, so that neither huge nor tiny normals
// overflow or underflow.
std::vector<double> UnitNormal(absl::Span<const double> normal) {
  double largest = 0.0;
  for (const double n : normal) largest = std::max(largest, std::abs(n));
  std::vector<double> unit(normal.begin(), normal.end());
  double length = 0.0;
  for (double& n : unit) {
    n /= largest;
    length += n * n;
  }
  length = std::sqrt(length);
  for (double& n : unit) n /= length;
  return unit;
}

// ScaledOffset returns n . point in units of 2^exponent, computed without
// overflow: infinite when it lies beyond the range of doubles there.
double ScaledOffset(absl::Span<const double> unit,
                    absl::Span<const double> point, int exponent) {
  double largest = 0.0;
  for (const double p : point) largest = std::max(largest, std::abs(p));
  if (largest == 0.0) return 0.0;
  double sum = 0.0;
  for (size_t x = 0; x < point.size(); ++x)
    sum += unit[x] * (point[x] / largest);
  if (sum == 0.0) return 0.0;
  // largest * 2^-exponent, by exponents, so that it saturates to infinity.
  const int e = std::ilogb(largest);
  return sum * std::ldexp(std::ldexp(largest, -e), e - exponent);
}

// Regions writes the parameter corners of the pieces lying in the plane.
void WriteRegions(const std::vector<size_t>& regions, const Pieces& pieces,
                  Sections& sections) {
  for (const size_t piece : regions) {
    const double corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    std::vector<double> uv;
    for (const auto& corner : corners) {
      double p[2];
      pieces.parameters(piece, corner[0], corner[1], p);
      const size_t n = uv.size();
      if (n >= 2 && uv[n - 2] == p[0] && uv[n - 1] == p[1]) continue;
      if (n >= 2 && uv[0] == p[0] && uv[1] == p[1]) continue;
      uv.insert(uv.end(), {p[0], p[1]});
    }
    sections.region_corners.insert(sections.region_corners.end(), uv.begin(),
                                   uv.end());
    sections.region_offsets.push_back(sections.region_corners.size() / 2);
  }
}

// FitError is the failure of the fit of polyline k: the approximation's
// refusals name its own inputs (parameters, points), which are not fields
// of the request, so they name fit_tolerance, the option that asked for it;
// a stop by the token passes as it is.
absl::Status FitError(const absl::Status& status, size_t k) {
  if (status.code() != absl::StatusCode::kInvalidArgument) return status;
  return InvalidFieldError(
      "fit_tolerance",
      absl::StrCat("polyline ", k,
                   " cannot be fitted within it: ", status.message()));
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
  // Least squares with ever more control points; with one per vertex, the
  // interpolant (averaged knots, which meet the Schoenberg-Whitney
  // condition).
  for (int controls = std::min(count, 2 * (degree + 1)); controls < count;
       controls = std::min(count, 2 * controls)) {
    absl::StatusOr<CurveApproximation> fit = ApproximateCurve(
        points, degree, controls, Parameterization::kChordLength, {}, cancel);
    // Least squares with nearly a control per vertex can place a knot span
    // without a vertex (singular): the interpolant below cannot.
    if (!fit.ok() &&
        fit.status().code() != absl::StatusCode::kInvalidArgument) {
      return fit.status();
    }
    if (!fit.ok()) break;
    if (fit->max_residual <= tolerance) return std::move(fit->curve);
  }
  absl::StatusOr<CurveInterpolation> fit = InterpolateCurve(
      points, {.degree = degree,
               .parameterization = Parameterization::kChordLength,
               .cancel = cancel});
  if (!fit.ok()) return FitError(fit.status(), k);
  if (!(fit->max_residual <= tolerance)) {
    return InvalidFieldError(
        "fit_tolerance", absl::StrCat("polyline ", k,
                                      " cannot be fitted within it: its "
                                      "interpolant is still ",
                                      fit->max_residual, " off at a vertex"));
  }
  return std::move(fit->curve);
}

}  // namespace

absl::StatusOr<Sections> IntersectSurfacePlane(
    const Surface& surface, absl::Span<const double> plane_point,
    absl::Span<const double> plane_normal, const SectionOptions& options,
    const CancellationToken* cancel) {
  const int dimension = DimensionOf(surface);
  RETURN_IF_ERROR(CheckPlane(plane_point, plane_normal, dimension));
  if (!std::isfinite(options.tolerance) || options.tolerance <= 0.0) {
    return InvalidFieldError("tolerance", "must be positive and finite");
  }
  if (!std::isfinite(options.fit_tolerance) || options.fit_tolerance < 0.0) {
    return InvalidFieldError("fit_tolerance", "must be finite and >= 0");
  }
  absl::StatusOr<Pieces> pieces = internal::LiftPieces(surface, cancel);
  if (!pieces.ok()) return pieces.status();
  Pieces* const all[] = {&*pieces};
  const absl::StatusOr<internal::QueryScale> scale =
      internal::ScaleForQuery(options.tolerance, all);
  if (!scale.ok()) return scale.status();
  const int exponent = scale->exponent;
  if (options.fit_tolerance > 0.0) {
    RETURN_IF_ERROR(internal::CheckResolvableAt(
        options.fit_tolerance, std::ldexp(scale->largest, exponent),
        "fit_tolerance"));
  }
  const std::vector<double> normal = UnitNormal(plane_normal);
  const double offset = ScaledOffset(normal, plane_point, exponent);
  Sections sections{.dimension = dimension};
  if (!std::isfinite(offset)) return sections;  // far beyond the surface
  Slicer slicer(*pieces, normal, offset,
                std::ldexp(options.tolerance, -exponent), exponent,
                scale->largest, options, cancel);
  RETURN_IF_ERROR(slicer.Run());
  // Ends closer than this are one point: 1e-9 of the geometry's size, at
  // most the tolerance, so a joined end stays within it of the other.
  const double slack =
      std::min(1e-9 * scale->largest, std::ldexp(options.tolerance, -exponent));
  Chain chain(slicer.arcs(), dimension, slack);
  chain.Write(*pieces, sections);
  for (double& x : sections.points) x = std::ldexp(x, exponent);
  WriteRegions(slicer.regions(), *pieces, sections);
  const size_t count = sections.points.size() / static_cast<size_t>(dimension) +
                       sections.region_corners.size() / 2;
  if (count > options.max_points) {
    return ExhaustedFieldError(
        "max_points", absl::StrCat("the sections need ", count,
                                   " points, more than ", options.max_points));
  }
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
