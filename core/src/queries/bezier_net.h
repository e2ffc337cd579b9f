// Bezier nets in homogeneous form for the subdivision queries (closest
// points, intersections, sections): halving by de Casteljau, hull bounds,
// evaluation of the partials up to order 2, and a small box-constrained
// Newton minimizer. A curve is a net with one column (count_v == 1).
// Internal to the core; thread-safe (values and const functions).
#ifndef FREEFORM_CORE_SRC_QUERIES_BEZIER_NET_H_
#define FREEFORM_CORE_SRC_QUERIES_BEZIER_NET_H_

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "absl/functional/function_ref.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/curve.h"
#include "freeform/core/geometry_data.h"
#include "freeform/core/surface.h"

namespace freeform::internal {

// A (count_u x count_v) Bezier net, point (i, j) at
// values[(i * count_v + j) * stride()], homogeneous (w P, w) when rational.
struct Net {
  int dimension = 0;
  bool rational = false;
  int count_u = 1;
  int count_v = 1;
  std::vector<double> values;

  int stride() const { return dimension + (rational ? 1 : 0); }
  const double* at(int i, int j) const {
    return values.data() + (static_cast<size_t>(i) * count_v + j) *
                               static_cast<size_t>(stride());
  }
  double* at(int i, int j) {
    return values.data() + (static_cast<size_t>(i) * count_v + j) *
                               static_cast<size_t>(stride());
  }
};

// LiftCurve and LiftSurface return the homogeneous net of a Bezier piece.
Net LiftCurve(const BezierCurveData& curve);
Net LiftSurface(const SurfaceData& surface);

// A geometry's Bezier pieces (DecomposeCurve, DecomposeSurface), lifted, and
// the map from a piece's (s, t) in [0, 1]^2 to the geometry's parameters (one
// for a curve, whose t is ignored; two for a surface).
struct Pieces {
  int dimension = 0;
  int parameter_count = 1;
  std::vector<Net> nets;
  std::function<void(size_t, double, double, double*)> parameters;
  // locals(k, global, st) maps the geometry's parameters `global` back to
  // piece k's (s, t), clamped to [0, 1]^2 (t = 0 for a curve): where an
  // answer's parameters, rounded to doubles, lie on the piece that found
  // them.
  std::function<void(size_t, const double*, double*)> locals;
};

// LiftPieces returns the pieces of a valid curve or surface; it fails only
// with the token's status.
absl::StatusOr<Pieces> LiftPieces(const Curve& curve,
                                  const CancellationToken* cancel);
absl::StatusOr<Pieces> LiftPieces(const Surface& surface,
                                  const CancellationToken* cancel);

// An answer found on a piece at (s, t) reports the geometry's parameters
// there, rounded to doubles. Where a piece spans only a few ulps of its
// parameters (knot spans of 0.25 at 2e15) or the geometry moves far between
// neighbouring doubles (extreme weights), the point at the rounded
// parameters (Pieces::locals) is not the answer's: the queries check it
// and refuse such an answer. UnresolvedError is that refusal, naming
// `field`: at the doubles nearest `near` (one or two parameters) the inputs
// lie `apart` (in their units), beyond the tolerance.
absl::Status UnresolvedError(absl::string_view field,
                             absl::Span<const double> near, double apart);

// Halve writes the halves [0, 1/2] and [1/2, 1] of `net` in u (in_u) or v
// (reusing the memory `low` and `high` hold).
void Halve(const Net& net, bool in_u, Net& low, Net& high);

// Project writes the Cartesian control points (dimension values each) and
// returns false when a weight is not positive (the hull property then does
// not hold).
bool Project(const Net& net, std::vector<double>& points);

// Point writes the Cartesian point (i, j); returns false at a weight <= 0.
bool Point(const Net& net, int i, int j, double* point);

// CheckTolerances checks the options the queries share: a positive finite
// "tolerance" and a finite "separation" >= 0.
absl::Status CheckTolerances(double tolerance, double separation);

// LargestNetCoordinate returns the largest magnitude of a coordinate of the
// net's projected control points of positive weight (0 for none).
double LargestNetCoordinate(const Net& net);

// LargestCoordinate returns the largest magnitude of a coordinate of the
// Cartesian control points (those of positive weight) of all `pieces`: the
// scale that rounding is relative to.
double LargestCoordinate(absl::Span<const Pieces* const> pieces);

// The scale the subdivision queries work at: their pieces divided by
// 2^exponent (exact), so that squared distances neither overflow nor
// underflow; `largest` is their largest coordinate then (in [1, 2), or 0).
struct QueryScale {
  int exponent = 0;
  double largest = 0.0;
};

// ScaleForQuery checks `tolerance` against what double precision resolves
// on all `pieces` (CheckResolvableAt, naming "tolerance"), then divides the
// spatial parts (w P) of their control points by 2^k for k the exponent of
// their largest coordinate (LargestCoordinate); the weights are kept.
absl::StatusOr<QueryScale> ScaleForQuery(double tolerance,
                                         absl::Span<Pieces* const> pieces);

// WorkBudget counts the work of a search in units of about one
// multiply-add on a double against a limit fixed before it starts, and
// polls the cancellation token on the way. Not thread-safe.
class WorkBudget {
 public:
  // `field` names the limit in the RESOURCE_EXHAUSTED status; `what` says
  // what ran out of it.
  WorkBudget(uint64_t limit, absl::string_view field, absl::string_view what,
             const CancellationToken* cancel)
      : limit_(limit), field_(field), what_(what), poll_(cancel) {}

  // Add counts `units` of work.
  void Add(uint64_t units) {
    spent_ += units;
    pending_ += units;
  }
  bool exhausted() const { return spent_ > limit_; }
  uint64_t spent() const { return spent_; }

  // Check returns RESOURCE_EXHAUSTED naming the field once more than the
  // limit was spent, the token's status when it stopped, else OK.
  absl::Status Check();

 private:
  const uint64_t limit_;
  const std::string field_;
  const std::string what_;
  CancellationPoll poll_;
  uint64_t spent_ = 0;
  uint64_t pending_ = 0;
};

// BoxDistance returns the distance from `query` to the bounding box of
// `points` (count points of `dimension` values).
double BoxDistance(absl::Span<const double> points, int dimension,
                   const double* query);

// BoxDiameter returns the diagonal of the bounding box of `points`.
double BoxDiameter(absl::Span<const double> points, int dimension);

// DirectionalBound returns a lower bound of the distance from `query` to
// the convex hull of `points`: with e the unit vector from `toward` to the
// query, the hull lies where e . (query - x) >= min_i e . (query - P_i).
// Taken towards a point near the nearest point of a small piece, it is
// exact to second order, where the bounding box is only first order
// (docs/references.md, 'Closest points by branch and bound').
double DirectionalBound(absl::Span<const double> points, int dimension,
                        const double* query, const double* toward);

// PolygonLengths returns the largest control-polygon length along u and
// along v of the projected points (count_u x count_v of `dimension`).
void PolygonLengths(absl::Span<const double> points, int dimension, int count_u,
                    int count_v, double& along_u, double& along_v);

// NetEvaluator evaluates a net's partials S, S_u, S_v, S_uu, S_uv, S_vv at
// (s, t) in [0, 1]^2 (PartialIndex order, dimension values each; those in v
// are zero for a curve). It holds only scratch memory, so one serves every
// net. Not thread-safe: one per thread.
class NetEvaluator {
 public:
  // Evaluate writes the 6 partials of `net` into partials[6 * dimension].
  void Evaluate(const Net& net, double s, double t, double* partials);

  // Value returns the value at (s, t) of a scalar net (dimension 1, not
  // rational), without its partials, and in `magnitude` the same sum of
  // the coefficients' magnitudes (what its rounding is relative to).
  double Value(const Net& scalar, double s, double t, double& magnitude);

 private:
  void EvaluateCurve(const Net& net, double s, double* partials);

  std::vector<double> basis_u_;
  std::vector<double> basis_v_;
  std::vector<double> homogeneous_;
};

// The value, gradient and Hessian (row-major) of a function of up to 3
// variables.
struct LocalModel {
  double value = 0.0;
  double gradient[3] = {0, 0, 0};
  double hessian[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
};

// DistanceModel evaluates |S(x) - query|^2 / 2 with its gradient and
// Hessian (full Newton: the second partials included) for `net` of
// `parameter_count` parameters; `partials` is scratch of 6 * dimension.
void DistanceModel(NetEvaluator& evaluator, const Net& net, int parameter_count,
                   const double* query, const double* x, double* partials,
                   LocalModel& model);

// MinimizeInBox runs projected Newton from `x` (count <= 3 variables,
// updated in place) on the box [lower, upper]: variables at a bound with the
// gradient pointing out are held, the others take the Newton step (the
// Hessian shifted until positive definite), halved until the value
// decreases (or, once the value changes by rounding only, until the
// projected gradient shrinks); it stops when no step decreases, or when the
// step is within rounding of x. Returns the value at the final x.
double MinimizeInBox(int count, const double* lower, const double* upper,
                     double* x,
                     absl::FunctionRef<void(const double*, LocalModel&)> model,
                     int max_iterations = 60);

// NormalizeWeights divides the homogeneous values of a rational net by
// the power of two at or above its largest weight (the same net, with
// weights at most 1); a polynomial net is left as it is.
void NormalizeWeights(Net& net);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_QUERIES_BEZIER_NET_H_
