#include "freeform/core/bounding_box.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <variant>
#include <vector>

#include "freeform/core/elevation.h"
#include "freeform/core/geometry_data.h"
#include "freeform/core/rational.h"
#include "freeform/core/saturating.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/subdivision.h"
#include "freeform/core/triangular.h"
#include "geometry/scaled_geometry.h"
#include "geometry/variant_dispatch.h"
#include "refine/bezier_halving.h"

namespace freeform {
namespace {

// Each side of the box is widened by this fraction of the largest control
// coordinate on its axis.
constexpr double kMargin = 0x1p-44;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The shape of a tensor piece, count_u x count_v points (a curve is a net
// of one column), and of a triangular one.
struct NetShape {
  int count_u = 0;
  int count_v = 0;
};
struct TriangleShape {
  int degree = 0;
};

NetShape ShapeOf(const SurfaceData& net) { return {net.count_u, net.count_v}; }
TriangleShape ShapeOf(const TriangularPatchData& patch) {
  return {patch.degree};
}

size_t PointCount(NetShape shape) {
  return static_cast<size_t>(shape.count_u) *
         static_cast<size_t>(shape.count_v);
}
size_t PointCount(TriangleShape shape) {
  return TriangularPointCount(shape.degree);
}

// Corners returns the control points that lie on the geometry: the four
// corners of a net, the three of a triangular patch.
std::array<size_t, 4> Corners(NetShape shape) {
  const size_t row = static_cast<size_t>(shape.count_v);
  const size_t last_row = static_cast<size_t>(shape.count_u - 1) * row;
  return {0, row - 1, last_row, last_row + row - 1};
}
std::array<size_t, 3> Corners(TriangleShape shape) {
  return {TriangularIndex(shape.degree, shape.degree, 0),
          TriangularIndex(shape.degree, 0, shape.degree),
          TriangularIndex(shape.degree, 0, 0)};
}

// HalvingWork bounds what halving a piece costs: its control values times
// the points of its longest side (de Casteljau's work per value is the
// points along the split).
size_t HalvingWork(NetShape shape, int dimension) {
  return PointCount(shape) * static_cast<size_t>(dimension) *
         static_cast<size_t>(std::max(shape.count_u, shape.count_v));
}
size_t HalvingWork(TriangleShape shape, int dimension) {
  return PointCount(shape) * static_cast<size_t>(dimension) *
         static_cast<size_t>(shape.degree + 1);
}

// Halve splits the piece `values` by its splitting rule `next` into `first`
// and `second`, and returns their rules. A net is halved in the direction
// `next` (u when 0), then the other; a net of one column or row always
// along its length. A triangle is bisected at the midpoint of the edge
// opposite its newest vertex `next`; in each half the midpoint is the
// newest vertex.
std::array<int, 2> Halve(NetShape shape, int next, const double* values,
                         int width, double* first, double* second,
                         std::vector<double>&) {
  const bool in_u = shape.count_v == 1 || (shape.count_u > 1 && next == 0);
  internal::HalveNet(values, shape.count_u, shape.count_v, width, in_u, first,
                     second);
  const int after = in_u ? 1 : 0;
  return {after, after};
}
std::array<int, 2> Halve(TriangleShape shape, int next, const double* values,
                         int width, double* first, double* second,
                         std::vector<double>& scratch) {
  internal::BisectTriangle(values, shape.degree, width, next, first, second,
                           scratch);
  return next == 0   ? std::array{1, 2}
         : next == 1 ? std::array{0, 2}
                     : std::array{0, 1};
}

// The geometry's pieces for the search, lifted: point k of a piece is
// `width` values, its coordinates (times its weight when rational) and then
// its weight when rational. Every piece takes a block of `block` values;
// the first `initial` blocks are the geometry's pieces, the ones after them
// the halves made by one side's search, reused by the next side.
template <typename Shape>
struct LiftedPieces {
  int dimension = 0;
  int width = 0;
  bool rational = false;
  size_t block = 0;
  size_t initial = 0;
  // The most halvings of one side's search (BoxHalvings).
  size_t halvings = 0;
  std::vector<Shape> shapes;  // of the initial pieces
  std::vector<double> values;
};

// A piece unbounded by a zero weight inside is halved whatever the work of
// the bounded ones (a halving or two in each direction bounds it), up to
// this multiple of their budget.
constexpr size_t kUnboundedWorkFactor = 4;

// BoxHalvings returns the most halvings one side's search makes of pieces
// of `shape`: kMaxBoxHalvings, or fewer when the work budgets of bounded and
// unbounded pieces (Extreme) run out first.
template <typename Shape>
size_t BoxHalvings(Shape shape, int dimension) {
  const size_t work = std::max<size_t>(1, HalvingWork(shape, dimension));
  return std::min<size_t>(
      kMaxBoxHalvings,
      (1 + kUnboundedWorkFactor) * kMaxBoxHalvingWork / work + 2);
}

// Lift frees every net once it is copied, so the pieces exist once at a
// time. `pieces.values` keeps room for the halves the searches make.
template <typename Net>
auto Lift(std::vector<Net>& nets) {
  using Shape = decltype(ShapeOf(nets.front()));
  LiftedPieces<Shape> pieces;
  pieces.dimension = nets.front().dimension;
  for (const Net& net : nets) {
    pieces.rational = pieces.rational || !net.weights.empty();
  }
  pieces.width = pieces.dimension + (pieces.rational ? 1 : 0);
  const size_t width = static_cast<size_t>(pieces.width);
  for (const Net& net : nets) {
    pieces.block = std::max(pieces.block, PointCount(ShapeOf(net)) * width);
    pieces.halvings =
        std::max(pieces.halvings, BoxHalvings(ShapeOf(net), pieces.dimension));
  }
  pieces.initial = nets.size();
  pieces.shapes.reserve(nets.size());
  pieces.values.reserve((pieces.initial + 2 * pieces.halvings) * pieces.block);
  pieces.values.resize(pieces.initial * pieces.block);
  for (size_t n = 0; n < nets.size(); ++n) {
    Net& net = nets[n];
    pieces.shapes.push_back(ShapeOf(net));
    const auto block =
        pieces.values.begin() + static_cast<std::ptrdiff_t>(n * pieces.block);
    if (!pieces.rational) {
      std::copy(net.coordinates.begin(), net.coordinates.end(), block);
    } else {
      // HomogeneousPoints keeps the point of a zero weight as a direction.
      const PointsView points{net.dimension, net.coordinates};
      const std::vector<double> lifted = HomogeneousPoints(
          points, net.weights.empty() ? std::vector<double>(points.size(), 1.0)
                                      : net.weights);
      std::copy(lifted.begin(), lifted.end(), block);
    }
    net = {};
  }
  std::vector<Net>().swap(nets);
  return pieces;
}

// Coordinate j of point k of a lifted piece times `sign`, and whether its
// weight is positive (a point of weight zero is at infinity or undefined).
struct SignedCoordinate {
  double value = 0.0;
  bool finite_weight = true;
};

template <typename Shape>
SignedCoordinate Coordinate(const LiftedPieces<Shape>& pieces,
                            const double* values, size_t k, int j,
                            double sign) {
  const double* point = values + k * static_cast<size_t>(pieces.width);
  if (!pieces.rational) return {sign * point[j], true};
  const double weight = point[pieces.dimension];
  if (!(weight > 0.0)) return {0.0, false};
  return {sign * (point[j] / weight), true};
}

// HullBound returns the largest signed coordinate j of the control points,
// which bounds the piece when every weight is positive, else infinity.
template <typename Shape>
double HullBound(const LiftedPieces<Shape>& pieces, Shape shape,
                 const double* values, int j, double sign) {
  double bound = -kInfinity;
  const size_t count = PointCount(shape);
  for (size_t k = 0; k < count; ++k) {
    const SignedCoordinate x = Coordinate(pieces, values, k, j, sign);
    if (!x.finite_weight) return kInfinity;
    bound = std::max(bound, x.value);
  }
  return bound;
}

// Attained returns the largest signed coordinate j of the corners (those of
// positive weight), values of the geometry.
template <typename Shape>
double Attained(const LiftedPieces<Shape>& pieces, Shape shape,
                const double* values, int j, double sign) {
  double best = -kInfinity;
  for (const size_t k : Corners(shape)) {
    const SignedCoordinate x = Coordinate(pieces, values, k, j, sign);
    if (x.finite_weight) best = std::max(best, x.value);
  }
  return best;
}

// CornerWeightsPositive tells whether the corners, which lie on the
// geometry, have positive weights. A corner of weight zero (given, or
// rounded to zero by the halvings) is a point at infinity or undefined, so
// no halving can bound the piece.
template <typename Shape>
bool CornerWeightsPositive(const LiftedPieces<Shape>& pieces, Shape shape,
                           const double* values) {
  for (const size_t k : Corners(shape)) {
    if (!Coordinate(pieces, values, k, 0, 1.0).finite_weight) return false;
  }
  return true;
}

// A piece waiting in the branch and bound: its upper bound, its block, its
// shape and the state of its splitting rule (Halve).
template <typename Shape>
struct Piece {
  double bound = 0.0;
  size_t block = 0;
  Shape shape;
  int depth = 0;
  int next = 0;
};

template <typename Shape>
bool LowerBound(const Piece<Shape>& a, const Piece<Shape>& b) {
  return a.bound < b.bound;
}

// Extreme returns an upper bound of the signed coordinate j over the pieces
// within `tolerance` of a value the geometry attains (see bounding_box.h),
// or a non-finite value when the geometry has none: a corner at infinity,
// or a bound that is NaN. The halves live in `pieces.values` after the
// initial blocks; `scratch` is the halvings' scratch.
template <typename Shape>
absl::StatusOr<double> Extreme(LiftedPieces<Shape>& pieces, int j, double sign,
                               double tolerance, CancellationPoll& poll,
                               std::vector<double>& scratch) {
  pieces.values.resize(pieces.initial * pieces.block);
  std::vector<size_t> free_blocks;
  free_blocks.reserve(pieces.halvings);
  auto allocate = [&]() {
    if (!free_blocks.empty()) {
      const size_t block = free_blocks.back();
      free_blocks.pop_back();
      return block;
    }
    const size_t block = pieces.values.size() / pieces.block;
    pieces.values.resize(pieces.values.size() + pieces.block);
    return block;
  };
  auto values_of = [&](size_t block) {
    return pieces.values.data() + block * pieces.block;
  };
  std::vector<Piece<Shape>> heap;
  heap.reserve(pieces.initial + pieces.halvings + 1);
  double best = -kInfinity;
  for (size_t n = 0; n < pieces.initial; ++n) {
    const Shape shape = pieces.shapes[n];
    best = std::max(best, Attained(pieces, shape, values_of(n), j, sign));
    heap.push_back({.bound = HullBound(pieces, shape, values_of(n), j, sign),
                    .block = n,
                    .shape = shape});
  }
  std::make_heap(heap.begin(), heap.end(), LowerBound<Shape>);
  size_t bounded_work = 0;
  size_t unbounded_work = 0;
  for (int halvings = 0;; ++halvings) {
    std::pop_heap(heap.begin(), heap.end(), LowerBound<Shape>);
    const Piece<Shape> top = heap.back();
    heap.pop_back();
    if (std::isnan(top.bound) ||
        (top.bound == kInfinity &&
         !CornerWeightsPositive(pieces, top.shape, values_of(top.block)))) {
      return top.bound;
    }
    const bool bounded = top.bound < kInfinity;
    size_t& work = bounded ? bounded_work : unbounded_work;
    const size_t budget = bounded ? kMaxBoxHalvingWork
                                  : kUnboundedWorkFactor * kMaxBoxHalvingWork;
    if (top.bound - best <= tolerance || top.depth >= kMaxBoxDepth ||
        halvings >= kMaxBoxHalvings || work >= budget) {
      return top.bound;
    }
    work += HalvingWork(top.shape, pieces.dimension);
    const size_t first = allocate();
    const size_t second = allocate();
    const std::array<int, 2> next =
        Halve(top.shape, top.next, values_of(top.block), pieces.width,
              values_of(first), values_of(second), scratch);
    if (top.block >= pieces.initial) free_blocks.push_back(top.block);
    const std::array<size_t, 2> halves{first, second};
    for (size_t h = 0; h < 2; ++h) {
      const double* values = values_of(halves[h]);
      best = std::max(best, Attained(pieces, top.shape, values, j, sign));
      heap.push_back({.bound = HullBound(pieces, top.shape, values, j, sign),
                      .block = halves[h],
                      .shape = top.shape,
                      .depth = top.depth + 1,
                      .next = next[h]});
      std::push_heap(heap.begin(), heap.end(), LowerBound<Shape>);
    }
    RETURN_IF_ERROR(poll.Done(4 * PointCount(top.shape) *
                              static_cast<size_t>(pieces.dimension)));
  }
}

// AxisScales returns, for each axis, the largest |coordinate| of the
// pieces' control points on it: a coordinate's rounding is relative to its
// own axis, so a huge x widens neither y nor z.
template <typename Net>
std::vector<double> AxisScales(const std::vector<Net>& nets) {
  const size_t dimension = static_cast<size_t>(nets.front().dimension);
  std::vector<double> scales(dimension, 0.0);
  for (const Net& net : nets) {
    for (size_t c = 0; c < net.coordinates.size(); ++c) {
      double& scale = scales[c % dimension];
      scale = std::max(scale, std::abs(net.coordinates[c]));
    }
  }
  return scales;
}

// BoxOf returns the box of the geometry made of the Bezier pieces `nets`,
// each axis j within tolerances[j].
template <typename Net>
absl::StatusOr<BoundingBox> BoxOf(std::vector<Net> nets,
                                  const std::vector<double>& tolerances,
                                  const CancellationToken* cancel) {
  const int dimension = nets.front().dimension;
  const std::vector<double> scales = AxisScales(nets);
  // A side that is not finite makes the box unbounded: the sides not yet
  // searched are left infinite, which still contains the geometry.
  BoundingBox box{.lower = std::vector<double>(dimension, -kInfinity),
                  .upper = std::vector<double>(dimension, kInfinity)};
  CancellationPoll poll(cancel);
  auto pieces = Lift(nets);
  std::vector<double> scratch;
  for (int j = 0; j < dimension; ++j) {
    const double margin = kMargin * scales[static_cast<size_t>(j)];
    const double reachable =
        std::max(tolerances[static_cast<size_t>(j)], margin);
    for (const double sign : {1.0, -1.0}) {
      absl::StatusOr<double> extreme =
          Extreme(pieces, j, sign, reachable, poll, scratch);
      if (!extreme.ok()) return extreme.status();
      (sign > 0 ? box.upper[j] : box.lower[j]) = sign * (*extreme + margin);
      if (!std::isfinite(*extreme)) return box;
    }
  }
  return box;
}

// AxisTolerances returns `tolerance` in the units of each axis of a copy
// scaled per axis (scaled_geometry.h), at most the largest double.
std::vector<double> AxisTolerances(double tolerance, int dimension,
                                   const internal::ScaledValues& scale) {
  std::vector<double> tolerances(static_cast<size_t>(dimension));
  for (size_t j = 0; j < tolerances.size(); ++j) {
    tolerances[j] = std::min(std::ldexp(tolerance, -scale.AxisExponent(j)),
                             std::numeric_limits<double>::max());
  }
  return tolerances;
}

// Unscaled returns the box of a copy scaled per axis in the geometry's own
// units (exact: powers of two; a side beyond the largest double is
// infinite, which still holds the geometry).
absl::StatusOr<BoundingBox> Unscaled(absl::StatusOr<BoundingBox> box,
                                     const internal::ScaledValues& scale) {
  if (!box.ok()) return box;
  for (std::vector<double>* sides : {&box->lower, &box->upper}) {
    for (size_t j = 0; j < sides->size(); ++j) {
      (*sides)[j] = std::ldexp((*sides)[j], scale.AxisExponent(j));
    }
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

// What one heap block costs beyond its bytes: glibc's header and rounding.
constexpr uint64_t kBlockOverhead = 32;

// BoxBytes bounds the memory of the box of `pieces` pieces of `shape`, each
// piece kept as `records` bytes of records besides its values: cutting the
// geometry holds its knot-refined control points beside the pieces (at
// most three times their values); the search then holds the lifted blocks
// with room for the halves (the pieces being freed as they are lifted),
// the shapes, the heap and the free blocks. Saturates.
template <typename Shape>
uint64_t BoxBytes(uint64_t pieces, Shape shape, int dimension, bool rational,
                  uint64_t records) {
  const uint64_t block =
      PointCount(shape) * static_cast<uint64_t>(dimension + (rational ? 1 : 0));
  const uint64_t halvings = BoxHalvings(shape, dimension);
  if (pieces > (uint64_t{1} << 40) / std::max<uint64_t>(block, records)) {
    return UINT64_MAX;
  }
  return 8 * std::max(3 * pieces * block,
                      2 * pieces * block + 2 * halvings * block) +
         pieces * (records + sizeof(Shape)) +
         (pieces + halvings + 1) * sizeof(Piece<Shape>) +
         halvings * sizeof(size_t);
}

// A curve's pieces are kept as BezierCurveData, then SurfaceData columns.
constexpr uint64_t kCurvePieceRecords =
    sizeof(BezierCurveData) + sizeof(SurfaceData) + 2 * kBlockOverhead;
constexpr uint64_t kSurfacePieceRecords =
    sizeof(SurfaceData) + 2 * kBlockOverhead;

NetShape Column(size_t points) { return {static_cast<int>(points), 1}; }

}  // namespace

namespace {

// PiecesBoxBytes bounds the memory of the box of a geometry's pieces
// (BoxBytes), without its scaled copy.
uint64_t PiecesBoxBytes(const Curve& curve) {
  const int dimension = DimensionOf(curve);
  return std::visit(
      internal::Overloaded{
          [&](const BezierCurve& bezier) {
            return BoxBytes(1, Column(bezier.view().control_points.size()),
                            dimension, bezier.view().rational(),
                            kCurvePieceRecords);
          },
          [&](const BSplineCurve& bspline) {
            const BSplineCurveView& view = bspline.view();
            return BoxBytes(
                view.control_points.size() - static_cast<size_t>(view.degree),
                Column(static_cast<size_t>(view.degree) + 1), dimension,
                view.rational(), kCurvePieceRecords);
          },
          [&](const LagrangeCurve& lagrange) {
            return BoxBytes(1, Column(lagrange.view().points.size()), dimension,
                            false, kCurvePieceRecords);
          },
          [&](const HermiteCurve& hermite) {
            return BoxBytes(hermite.view().points.size() - 1, Column(4),
                            dimension, false, kCurvePieceRecords);
          }},
      curve);
}

uint64_t PiecesBoxBytes(const Surface& surface) {
  return std::visit(
      internal::Overloaded{
          [](const BezierSurface& bezier) {
            const BezierSurfaceView& view = bezier.view();
            return BoxBytes(
                1, NetShape{view.control_net.count_u, view.control_net.count_v},
                view.control_net.dimension, view.rational(),
                kSurfacePieceRecords);
          },
          [](const BSplineSurface& bspline) {
            const BSplineSurfaceView& view = bspline.view();
            const uint64_t pieces =
                static_cast<uint64_t>(view.control_net.count_u -
                                      view.degree_u) *
                static_cast<uint64_t>(view.control_net.count_v - view.degree_v);
            return BoxBytes(pieces,
                            NetShape{view.degree_u + 1, view.degree_v + 1},
                            view.control_net.dimension, view.rational(),
                            kSurfacePieceRecords);
          },
          [](const TriangularPatch& patch) {
            const TriangularPatchView& view = patch.view();
            return BoxBytes(1, TriangleShape{view.degree},
                            view.control_points.dimension, view.rational(),
                            sizeof(TriangularPatchData) + 2 * kBlockOverhead);
          }},
      surface);
}

}  // namespace

uint64_t CurveBoundingBoxBytes(const Curve& curve) {
  return SaturatingSum(internal::ScaledCopyBytes(curve), PiecesBoxBytes(curve));
}

uint64_t SurfaceBoundingBoxBytes(const Surface& surface) {
  return SaturatingSum(internal::ScaledCopyBytes(surface),
                       PiecesBoxBytes(surface));
}

absl::StatusOr<BoundingBox> CurveBoundingBox(const Curve& curve,
                                             double tolerance,
                                             const CancellationToken* cancel) {
  RETURN_IF_ERROR(ValidatePositive(tolerance, "tolerance"));
  // Each axis is scaled on its own: a box is affine-invariant per axis.
  const internal::ScaledCurve scaled = internal::ScaledCurve::OfAxes(curve);
  absl::StatusOr<BezierDecomposition> pieces =
      DecomposeCurve(scaled.curve(), cancel);
  if (!pieces.ok()) return pieces.status();
  std::vector<SurfaceData> nets;
  nets.reserve(pieces->segments.size());
  for (BezierCurveData& segment : pieces->segments) {
    nets.push_back(ColumnOf(std::move(segment)));
  }
  std::vector<BezierCurveData>().swap(pieces->segments);
  return Unscaled(
      BoxOf(std::move(nets),
            AxisTolerances(tolerance, DimensionOf(curve), scaled.scale()),
            cancel),
      scaled.scale());
}

absl::StatusOr<BoundingBox> SurfaceBoundingBox(
    const Surface& surface, double tolerance, const CancellationToken* cancel) {
  RETURN_IF_ERROR(ValidatePositive(tolerance, "tolerance"));
  // A triangular patch is halved as a triangle (BisectTriangularPatch), a
  // tensor surface as its Bezier pieces.
  // Each axis is scaled on its own: a box is affine-invariant per axis.
  const internal::ScaledSurface scaled =
      internal::ScaledSurface::OfAxes(surface);
  const std::vector<double> scaled_tolerance =
      AxisTolerances(tolerance, DimensionOf(surface), scaled.scale());
  const auto tensor = [&]() -> absl::StatusOr<BoundingBox> {
    ASSIGN_OR_RETURN(SurfaceDecomposition pieces,
                     DecomposeSurface(scaled.surface(), cancel));
    return BoxOf(std::move(pieces.pieces.patches), scaled_tolerance, cancel);
  };
  return Unscaled(
      std::visit(internal::Overloaded{
                     [&](const BezierSurface&) { return tensor(); },
                     [&](const BSplineSurface&) { return tensor(); },
                     [&](const TriangularPatch& patch) {
                       return BoxOf(std::vector<TriangularPatchData>{PatchOf(
                                        patch.view())},
                                    scaled_tolerance, cancel);
                     }},
                 scaled.surface()),
      scaled.scale());
}

}  // namespace freeform
