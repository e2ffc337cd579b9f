#include "freeform/core/bounding_box.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <variant>
#include <vector>

#include "freeform/core/elevation.h"
#include "freeform/core/geometry_data.h"
#include "freeform/core/status.h"
#include "freeform/core/subdivision.h"
#include "freeform/core/triangular.h"

namespace freeform {
namespace {

// The box is widened by this fraction of the largest control coordinate.
constexpr double kMargin = 0x1p-44;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A Bezier piece (a SurfaceData net, a curve being a net of one column, or
// a TriangularPatchData) waiting in the branch and bound, with its upper
// bound and the state of its splitting rule: the direction of the next
// halving of a tensor net, the newest vertex of a triangular patch.
template <typename Net>
struct Piece {
  Net net;
  double bound = 0.0;
  int depth = 0;
  int next = 0;
};

template <typename Net>
bool LowerBound(const Piece<Net>& a, const Piece<Net>& b) {
  return a.bound < b.bound;
}

// Coordinate j of control point k, times `sign`.
template <typename Net>
double Signed(const Net& net, size_t k, int j, double sign) {
  return sign * net.coordinates[k * static_cast<size_t>(net.dimension) +
                                static_cast<size_t>(j)];
}

// HullBound returns the largest signed coordinate j of the control points,
// which bounds the piece when every weight is positive, else infinity.
template <typename Net>
double HullBound(const Net& net, int j, double sign) {
  double bound = -kInfinity;
  const size_t count = net.coordinates.size() / net.dimension;
  for (size_t k = 0; k < count; ++k) {
    if (!net.weights.empty() && !(net.weights[k] > 0.0)) return kInfinity;
    bound = std::max(bound, Signed(net, k, j, sign));
  }
  return bound;
}

// Corners returns the control points that lie on the geometry: the four
// corners of a net, the three of a triangular patch.
std::array<size_t, 4> Corners(const SurfaceData& net) {
  const size_t row = static_cast<size_t>(net.count_v);
  const size_t last_row = static_cast<size_t>(net.count_u - 1) * row;
  return {0, row - 1, last_row, last_row + row - 1};
}

std::array<size_t, 3> Corners(const TriangularPatchData& patch) {
  return {TriangularIndex(patch.degree, patch.degree, 0),
          TriangularIndex(patch.degree, 0, patch.degree),
          TriangularIndex(patch.degree, 0, 0)};
}

// Attained returns the largest signed coordinate j of the corners.
template <typename Net>
double Attained(const Net& net, int j, double sign) {
  double best = -kInfinity;
  for (const size_t k : Corners(net)) {
    best = std::max(best, Signed(net, k, j, sign));
  }
  return best;
}

// Halves splits a net in the direction `next` (u when 0) and returns the
// halves with the direction after; a net of one column or row is always
// split along its length.
absl::StatusOr<std::vector<std::pair<SurfaceData, int>>> Halves(
    const SurfaceData& net, int next) {
  const bool in_u = net.count_v == 1 || (net.count_u > 1 && next == 0);
  absl::StatusOr<std::vector<SurfaceData>> halves =
      SplitBezierSurface(net.bezier_view(), in_u, 0.5);
  if (!halves.ok()) return halves.status();
  std::vector<std::pair<SurfaceData, int>> result;
  for (SurfaceData& half : *halves) {
    result.emplace_back(std::move(half), in_u ? 1 : 0);
  }
  return result;
}

// Halves bisects the edge opposite the newest vertex `next`; in each half
// the midpoint is the newest vertex.
absl::StatusOr<std::vector<std::pair<TriangularPatchData, int>>> Halves(
    const TriangularPatchData& patch, int next) {
  absl::StatusOr<std::vector<TriangularPatchData>> halves =
      BisectTriangularPatch(patch.view(), next);
  if (!halves.ok()) return halves.status();
  const std::array<int, 2> newest = next == 0   ? std::array{1, 2}
                                    : next == 1 ? std::array{0, 2}
                                                : std::array{0, 1};
  std::vector<std::pair<TriangularPatchData, int>> result;
  for (size_t h = 0; h < 2; ++h) {
    result.emplace_back(std::move((*halves)[h]), newest[h]);
  }
  return result;
}

// HalvingWork bounds what halving `net` costs: its control values times the
// points of its longest side (de Casteljau's work per value is the points
// along the split).
size_t HalvingWork(const SurfaceData& net) {
  return net.coordinates.size() *
         static_cast<size_t>(std::max(net.count_u, net.count_v));
}

size_t HalvingWork(const TriangularPatchData& patch) {
  return patch.coordinates.size() * static_cast<size_t>(patch.degree + 1);
}

// CornerWeightsPositive tells whether the corners, which lie on the
// geometry, have positive weights. A corner of weight zero (given, or
// rounded to zero by the halvings) is a point at infinity or undefined, so
// no halving can bound the piece.
template <typename Net>
bool CornerWeightsPositive(const Net& net) {
  if (net.weights.empty()) return true;
  for (const size_t k : Corners(net)) {
    if (!(net.weights[k] > 0.0)) return false;
  }
  return true;
}

// Extreme returns an upper bound of the signed coordinate j over the pieces
// within `tolerance` of a value the geometry attains (see bounding_box.h),
// or a non-finite value when the geometry has none: a corner at infinity,
// or a bound that is NaN.
template <typename Net>
absl::StatusOr<double> Extreme(const std::vector<Net>& nets, int j, double sign,
                               double tolerance, CancellationPoll& poll) {
  std::vector<Piece<Net>> heap;
  double best = -kInfinity;
  for (const Net& net : nets) {
    best = std::max(best, Attained(net, j, sign));
    heap.push_back({net, HullBound(net, j, sign), 0, 0});
  }
  std::make_heap(heap.begin(), heap.end(), LowerBound<Net>);
  size_t work = 0;
  for (int halvings = 0;; ++halvings) {
    std::pop_heap(heap.begin(), heap.end(), LowerBound<Net>);
    Piece<Net> top = std::move(heap.back());
    heap.pop_back();
    if (std::isnan(top.bound) ||
        (top.bound == kInfinity && !CornerWeightsPositive(top.net))) {
      return top.bound;
    }
    // A piece unbounded by a zero weight inside is halved whatever the
    // work so far (a halving or two in each direction bounds it); only the
    // count of halvings limits that.
    const bool bounded = top.bound < kInfinity;
    if (top.bound - best <= tolerance || top.depth >= kMaxBoxDepth ||
        halvings >= kMaxBoxHalvings ||
        (bounded && work >= kMaxBoxHalvingWork)) {
      return top.bound;
    }
    if (bounded) work += HalvingWork(top.net);
    auto halves = Halves(top.net, top.next);
    if (!halves.ok()) return halves.status();
    for (auto& [half, next] : *halves) {
      best = std::max(best, Attained(half, j, sign));
      const double bound = HullBound(half, j, sign);
      heap.push_back({std::move(half), bound, top.depth + 1, next});
      std::push_heap(heap.begin(), heap.end(), LowerBound<Net>);
    }
    if (absl::Status status = poll.Done(4 * top.net.coordinates.size());
        !status.ok()) {
      return status;
    }
  }
}

// BoxOf returns the box of the geometry made of the Bezier pieces `nets`.
template <typename Net>
absl::StatusOr<BoundingBox> BoxOf(const std::vector<Net>& nets,
                                  double tolerance,
                                  const CancellationToken* cancel) {
  const int dimension = nets.front().dimension;
  double scale = 0.0;
  for (const Net& net : nets) {
    for (const double c : net.coordinates) scale = std::max(scale, std::abs(c));
  }
  const double margin = kMargin * scale;
  const double reachable = std::max(tolerance, margin);
  BoundingBox box{.lower = std::vector<double>(dimension),
                  .upper = std::vector<double>(dimension)};
  CancellationPoll poll(cancel);
  for (int j = 0; j < dimension; ++j) {
    absl::StatusOr<double> upper = Extreme(nets, j, 1.0, reachable, poll);
    if (!upper.ok()) return upper.status();
    absl::StatusOr<double> lower = Extreme(nets, j, -1.0, reachable, poll);
    if (!lower.ok()) return lower.status();
    box.upper[j] = *upper + margin;
    box.lower[j] = -*lower - margin;
  }
  return box;
}

// A Bezier curve as a net of one column.
SurfaceData ColumnOf(BezierCurveData curve) {
  const int count =
      static_cast<int>(curve.coordinates.size()) / std::max(curve.dimension, 1);
  return {.degree_u = count - 1,
          .degree_v = 0,
          .dimension = curve.dimension,
          .count_u = count,
          .count_v = 1,
          .coordinates = std::move(curve.coordinates),
          .knots_u = {},
          .knots_v = {},
          .weights = std::move(curve.weights)};
}

// A triangular patch's own control points (its domain triangle does not
// change its points).
TriangularPatchData PatchOf(const TriangularPatchView& view) {
  return {.degree = view.degree,
          .dimension = view.control_points.dimension,
          .coordinates = {view.control_points.coordinates.begin(),
                          view.control_points.coordinates.end()},
          .weights = {view.weights.begin(), view.weights.end()},
          .domain_triangle = {}};
}

}  // namespace

absl::StatusOr<BoundingBox> CurveBoundingBox(const Curve& curve,
                                             double tolerance,
                                             const CancellationToken* cancel) {
  if (absl::Status status = ValidatePositive(tolerance, "tolerance");
      !status.ok()) {
    return status;
  }
  absl::StatusOr<BezierDecomposition> pieces = DecomposeCurve(curve, cancel);
  if (!pieces.ok()) return pieces.status();
  std::vector<SurfaceData> nets;
  for (BezierCurveData& segment : pieces->segments) {
    nets.push_back(ColumnOf(std::move(segment)));
  }
  return BoxOf(nets, tolerance, cancel);
}

absl::StatusOr<BoundingBox> SurfaceBoundingBox(
    const Surface& surface, double tolerance, const CancellationToken* cancel) {
  if (absl::Status status = ValidatePositive(tolerance, "tolerance");
      !status.ok()) {
    return status;
  }
  // A triangular patch is halved as a triangle (BisectTriangularPatch), a
  // tensor surface as its Bezier pieces.
  if (const auto* patch = std::get_if<TriangularPatch>(&surface)) {
    return BoxOf(std::vector<TriangularPatchData>{PatchOf(patch->view())},
                 tolerance, cancel);
  }
  absl::StatusOr<SurfaceDecomposition> pieces =
      DecomposeSurface(surface, cancel);
  if (!pieces.ok()) return pieces.status();
  return BoxOf(pieces->pieces.patches, tolerance, cancel);
}

}  // namespace freeform
