// The geometry of a request as the query oracles (query_oracles.h) see it:
// prepared by the server's own PrepareCurve / PrepareSurface, evaluated by
// the core's evaluators (not by the query code under test), with the
// measures of size the oracles' margins are made of:
//   - scale: the largest |coordinate| of the geometry's Bezier pieces'
//     control points (DecomposeCurve / DecomposeSurface, the form every
//     query works on), so that a Lagrange curve whose Bezier form cancels
//     or a Hermite curve with long tangents gets its real size;
//   - conditioning: how many ulps of a parameter one ulp of the geometry
//     is worth, max(1, max(|a|, |b|) / (b - a)) over the spans [a, b]
//     between breakpoints: a span of 1e-12 at 1 gives 1e12, since
//     rounding a parameter there moves the point by up to that many ulps
//     of the span's own size.
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

// Distance returns |a - b| for points of `dimension`, without overflow or
// underflow of the squares (scaled by the largest difference, and halved
// first so that differences of numbers near DBL_MAX stay finite).
double Distance(const double* a, const double* b, int dimension);

// Norm returns |a|, computed like Distance.
double Norm(const double* a, int dimension);

// LargestMagnitude returns max |v| over the finite values of `values`.
double LargestMagnitude(absl::Span<const double> values);

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
  double conditioning() const { return conditioning_; }
  // True when every piece has positive weights (or none): the curve then
  // lies in the convex hull of its pieces' control points.
  bool positive_weights() const { return positive_weights_; }
  // True when no piece is rational with unequal weights: a piece's length
  // is then at most its control polygon's.
  bool polynomial() const { return polynomial_; }

  // Evaluate returns the points at `parameters` (dimension values each),
  // or the evaluator's error (a parameter outside the domain).
  absl::StatusOr<std::vector<double>> Evaluate(
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

 private:
  explicit OracleCurve(Curve curve) : curve_(std::move(curve)) {}

  Curve curve_;
  BezierDecomposition pieces_;
  double scale_ = 0.0;
  double conditioning_ = 1.0;
  bool positive_weights_ = true;
  bool polynomial_ = true;
  std::vector<double> hull_lower_, hull_upper_;
};

class OracleSurface {
 public:
  static absl::StatusOr<OracleSurface> Create(
      const v1::Surface& message, const server::ServiceLimits& limits,
      absl::string_view field);

  int dimension() const { return DimensionOf(surface_); }
  double scale() const { return scale_; }
  double conditioning() const { return conditioning_; }
  bool positive_weights() const { return positive_weights_; }

  // Evaluate returns the points at the (u, v) pairs `uv`, or the
  // evaluator's error.
  absl::StatusOr<std::vector<double>> Evaluate(
      absl::Span<const double> uv) const;
  // Samples returns (u, v) pairs spread over the domain: a 17 x 17 grid of
  // a tensor-product surface, the barycentric lattice of step 1/16 of a
  // triangular one (mapped to its domain triangle when it has one).
  std::vector<double> Samples() const;
  double HullLower(int j) const { return hull_lower_[static_cast<size_t>(j)]; }
  double HullUpper(int j) const { return hull_upper_[static_cast<size_t>(j)]; }

 private:
  explicit OracleSurface(Surface surface) : surface_(std::move(surface)) {}

  Surface surface_;
  double scale_ = 0.0;
  double conditioning_ = 1.0;
  bool positive_weights_ = true;
  std::vector<double> hull_lower_, hull_upper_;
};

}  // namespace freeform::fuzz

#endif  // FREEFORM_TESTS_FUZZ_ORACLE_GEOMETRY_H_
