// The geometry of a request as the query oracles (query_oracles.h) see it:
// prepared by the server's own PrepareCurve / PrepareSurface, evaluated by
// the core's evaluators (not by the query code under test), with the two
// measures the oracles' margins are made of:
//   - scale: the largest |coordinate| of the geometry's Bezier pieces'
//     control points (DecomposeCurve / DecomposeSurface, the form every
//     query works on), so that a Lagrange curve whose Bezier form cancels
//     or a Hermite curve with long tangents gets its real size;
//   - slack: how far the geometry moves when a parameter the answer gives
//     is off by its rounding. A query finds a parameter on a Bezier piece
//     [a, b] and reports a + s (b - a), rounded by a few ulps of
//     |a| + |t|; the point there moves by the derivative times that, which
//     is large where the parametrization is ill-conditioned (a span of
//     1e-12 at 1, a weight of 1e10 at a corner). The slack of a point is
//     kParameterRounding * |derivative| * (|t| + 2 |a|) per parameter.
// Geometry with a degree-0 (piecewise constant) direction jumps at its
// knots there; the value at a knot is the right-hand limit, and an answer
// may give the left-hand one, so such geometry is evaluated on both sides
// (Evaluation). An evaluation that overflows is not judged.
// Views point into the request, which must outlive them.
// Thread-compatible.
#ifndef FREEFORM_TESTS_FUZZ_ORACLE_GEOMETRY_H_
#define FREEFORM_TESTS_FUZZ_ORACLE_GEOMETRY_H_

#include <cstddef>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "freeform/core/curve.h"
#include "freeform/core/surface.h"
#include "freeform/v1/geometry.pb.h"
#include "service_limits.h"

namespace freeform::fuzz {

// The relative rounding of a parameter an answer reports: the piece's
// affine map and a Newton step round by a few ulps (2^-52 = 2.2e-16 each);
// 1e-12 is over 4000 of them.
inline constexpr double kParameterRounding = 1e-12;

// Distance returns |a - b| for points of `dimension`, without overflow or
// underflow of the squares (scaled by the largest difference, and halved
// first so that differences of numbers near DBL_MAX stay finite).
double Distance(const double* a, const double* b, int dimension);

// Norm returns |a|, computed like Distance.
double Norm(const double* a, int dimension);

// LargestMagnitude returns max |v| over the finite values of `values`.
double LargestMagnitude(absl::Span<const double> values);

// AllFinite is true when every value is finite.
bool AllFinite(absl::Span<const double> values);

// The geometry at a set of parameters: its values there (side 0) and, for
// geometry that jumps at its knots, its left-hand limits (more sides), with
// each point's slack.
class Evaluation {
 public:
  Evaluation(int dimension, std::vector<std::vector<double>> sides,
             std::vector<double> slack)
      : dimension_(dimension),
        sides_(std::move(sides)),
        slack_(std::move(slack)) {}

  // Point k's value (the evaluator's, the right-hand limit).
  absl::Span<const double> Point(size_t k) const { return Side(0, k); }
  // How far point k moves when its parameters are off by their rounding
  // (infinite when its derivatives overflow: nothing is judged there).
  double Slack(size_t k) const { return slack_[k]; }
  // DistanceTo returns the smallest distance from `x` to point k over the
  // sides whose coordinates are finite; NaN when none is (every comparison
  // with it is false, so nothing is judged).
  double DistanceTo(size_t k, absl::Span<const double> x) const;
  // Gap returns the smallest distance between point k of this and point
  // `other_k` of `other` over their finite sides; NaN when there is none.
  double Gap(size_t k, const Evaluation& other, size_t other_k) const;

 private:
  absl::Span<const double> Side(size_t side, size_t k) const {
    return absl::MakeConstSpan(sides_[side])
        .subspan(k * static_cast<size_t>(dimension_),
                 static_cast<size_t>(dimension_));
  }

  int dimension_;
  std::vector<std::vector<double>> sides_;
  std::vector<double> slack_;
};

class OracleCurve {
 public:
  // Create prepares `message` as the server does (`field` as in its error
  // paths).
  static absl::StatusOr<OracleCurve> Create(const v1::Curve& message,
                                            const server::ServiceLimits& limits,
                                            absl::string_view field);

  int dimension() const { return DimensionOf(curve_); }
  ParameterDomain domain() const { return DomainOf(curve_); }
  double scale() const { return scale_; }
  // The largest coordinate of a control point whose homogeneous value
  // w x underflows (below 2^-970): the evaluator may lose all of it, so its
  // points are only that accurate there (0 when none does).
  double underflow() const { return underflow_; }
  // True when every piece has positive weights (or none): the curve then
  // lies in the convex hull of its pieces' control points.
  bool positive_weights() const { return positive_weights_; }
  // True when no piece is rational with unequal weights: a piece's length
  // is then at most its control polygon's.
  bool polynomial() const { return polynomial_; }
  // False for a B-spline of degree 0, which jumps at its knots.
  bool continuous() const { return continuous_; }

  // Evaluate returns the points at `parameters` (dimension values each),
  // or the evaluator's error (a parameter outside the domain).
  absl::StatusOr<std::vector<double>> Evaluate(
      absl::Span<const double> parameters) const;
  // EvaluateSides returns the points at `parameters` with their slack and,
  // when the curve is not continuous, the points one ulp before them (the
  // left-hand limits at its knots).
  absl::StatusOr<Evaluation> EvaluateSides(
      absl::Span<const double> parameters) const;
  // Samples returns `count` >= 2 evenly spaced parameters over [a, b],
  // and with `breakpoints` the breakpoints inside, sorted.
  std::vector<double> Samples(double a, double b, size_t count,
                              bool breakpoints) const;
  // PolygonLength returns the summed control polygon lengths of the
  // pieces that meet [a, b]: an upper bound of the length over [a, b] of
  // a polynomial curve.
  double PolygonLength(double a, double b) const;
  // The smallest and largest coordinate j of the pieces' control points.
  double HullLower(int j) const { return hull_lower_[static_cast<size_t>(j)]; }
  double HullUpper(int j) const { return hull_upper_[static_cast<size_t>(j)]; }
  // AxisScale is the largest |coordinate| on axis j of the control points
  // the core's BoundingBox works on (bounding_box.h: its margin on that
  // axis is 2^-44 of it).
  double AxisScale(int j) const { return axis_scale_[static_cast<size_t>(j)]; }

 private:
  explicit OracleCurve(Curve curve) : curve_(std::move(curve)) {}

  Curve curve_;
  BezierDecomposition pieces_;
  double scale_ = 0.0;
  double underflow_ = 0.0;
  bool positive_weights_ = true;
  bool polynomial_ = true;
  bool continuous_ = true;
  std::vector<double> hull_lower_, hull_upper_;
  std::vector<double> axis_scale_;
};

class OracleSurface {
 public:
  static absl::StatusOr<OracleSurface> Create(
      const v1::Surface& message, const server::ServiceLimits& limits,
      absl::string_view field);

  int dimension() const { return DimensionOf(surface_); }
  double scale() const { return scale_; }
  double underflow() const { return underflow_; }  // as OracleCurve's
  bool positive_weights() const { return positive_weights_; }

  // Evaluate returns the points at the (u, v) pairs `uv`, or the
  // evaluator's error.
  absl::StatusOr<std::vector<double>> Evaluate(
      absl::Span<const double> uv) const;
  // EvaluateSides returns the points at `uv` with their slack and, in each
  // degree-0 direction of a B-spline surface, the points one ulp before.
  absl::StatusOr<Evaluation> EvaluateSides(absl::Span<const double> uv) const;
  // Samples returns (u, v) pairs spread over the domain: a 17 x 17 grid of
  // a tensor-product surface, the barycentric lattice of step 1/16 of a
  // triangular one (mapped to its domain triangle when it has one).
  std::vector<double> Samples() const;
  double HullLower(int j) const { return hull_lower_[static_cast<size_t>(j)]; }
  double HullUpper(int j) const { return hull_upper_[static_cast<size_t>(j)]; }
  // AxisScale is the largest |coordinate| on axis j of the control points
  // the core's BoundingBox works on (bounding_box.h: its margin on that
  // axis is 2^-44 of it).
  double AxisScale(int j) const { return axis_scale_[static_cast<size_t>(j)]; }

 private:
  explicit OracleSurface(Surface surface) : surface_(std::move(surface)) {}

  // The magnitude a parameter of `axis` (0: u, 1: v) is rounded against:
  // |x| + 2 |start of its piece| (of the domain triangle's corners).
  double ParameterMagnitude(int axis, double x) const;

  Surface surface_;
  double scale_ = 0.0;
  double underflow_ = 0.0;
  bool positive_weights_ = true;
  std::vector<double> breakpoints_[2];
  double triangle_magnitude_ = 0.0;
  std::vector<double> hull_lower_, hull_upper_;
  std::vector<double> axis_scale_;
};

}  // namespace freeform::fuzz

#endif  // FREEFORM_TESTS_FUZZ_ORACLE_GEOMETRY_H_
