// The prepare step's samples: where a request evaluates its geometry, and
// the preparation of the evaluation requests themselves.
//
// A curve's parameters (ParameterSet: a list or a uniform range; an
// interval, PrepareInterval) and a surface's (u, v) samples (points or a
// grid) are resolved against the geometry's domain and the server's limits
// before any work. Each evaluation request prepares into one validated
// object: the geometry (see prepare.h), its resolved parameters or samples,
// and the orders wanted (PrepareCurveEvaluation, PrepareBasisEvaluation,
// PrepareSurfaceEvaluation, PrepareTensorBasisEvaluation,
// PrepareSurfaceCurvature); the handler then plans, runs the core and
// writes the response. Field paths are the request's
// ("parameters.range.count", "derivative_order"). The prepared objects view
// the request's arrays, so they must not outlive it. Thread-compatible.
#ifndef FREEFORM_SERVER_PREPARE_SAMPLES_H_
#define FREEFORM_SERVER_PREPARE_SAMPLES_H_

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "freeform/core/basis.h"
#include "freeform/core/curve.h"
#include "freeform/core/surface.h"
#include "freeform/v1/curve_service.pb.h"
#include "freeform/v1/geometry.pb.h"
#include "freeform/v1/surface_service.pb.h"
#include "service_limits.h"

namespace freeform::server {

// Room for generated parameters, reused from chunk to chunk.
struct ParameterStorage {
  std::unique_ptr<double[]> values;
  size_t capacity = 0;
};

// A resolved set of curve parameters: an explicit list (a view into the
// request) or a uniform range generated on demand, chunk by chunk.
class ParameterSet {
 public:
  // Resolve checks `parameters` against the domain [lo, hi] and the count
  // limit. Field paths are relative to the Parameters message
  // ("list.values[3]", "range.count"); an empty message is an error naming "".
  static absl::StatusOr<ParameterSet> Resolve(const v1::Parameters& parameters,
                                              double lo, double hi,
                                              size_t max_count);

  size_t size() const { return count_; }

  // Values returns parameters [begin, end): a view of the list, or range
  // values generated into `storage` (grown as needed, never zero-filled).
  absl::Span<const double> Values(size_t begin, size_t end,
                                  ParameterStorage& storage) const;

 private:
  absl::Span<const double> list_;
  bool is_range_ = false;
  double start_ = 0;
  double end_ = 0;
  size_t count_ = 0;
};

// PrepareInterval resolves an interval of `curve`'s parameters, an omitted
// end being that end of the domain, and checks it as the arc-length
// queries do (ValidateArcLengthInterval: finite, within the domain, start
// <= end): errors name "<field>.start" or "<field>.end".
absl::StatusOr<ParameterDomain> PrepareInterval(
    const v1::ParameterInterval& interval, const Curve& curve,
    absl::string_view field);

// PrepareArcLengthStart resolves ParametersAtArcLength's `start` (default:
// the domain's start), checked as PrepareInterval checks an interval's
// start (errors name "start").
absl::StatusOr<double> PrepareArcLengthStart(
    const v1::ParametersAtArcLengthRequest& request, const Curve& curve);

// ResolveParameters resolves the `parameters` field of an evaluation-like
// request against `curve`'s domain and the parameter limit, and copies them
// once; errors are under "parameters".
absl::StatusOr<std::vector<double>> ResolveParameters(
    const v1::Parameters& parameters, const Curve& curve,
    const ServiceLimits& limits);

// What a curve or basis evaluation request resolves to before any math
// runs: the curve or the basis, the parameters, and the orders wanted.
template <typename Geometry>
struct Evaluation {
  Geometry geometry;
  ParameterSet parameters;
  size_t orders = 1;  // derivative orders 0..orders-1
  int dimension = 0;  // values per point and order (a basis: its functions)

  uint64_t ValuesPerParameter() const {
    return orders * static_cast<uint64_t>(dimension);
  }
  uint64_t Values() const { return parameters.size() * ValuesPerParameter(); }
};

// PrepareCurveEvaluation checks the derivative order and the Bezier
// algorithm, prepares the curve (PrepareCurveToEvaluate, "curve"), resolves
// the parameters against its domain ("parameters") and checks the answer's
// size against the output limit. The message limit is the caller's: a
// stream's chunks are smaller than its answer.
absl::StatusOr<Evaluation<Curve>> PrepareCurveEvaluation(
    const v1::EvaluateCurveRequest& request, const ServiceLimits& limits);

// PrepareBasisEvaluation is PrepareCurveEvaluation for blending functions
// (PrepareBasis, "basis").
absl::StatusOr<Evaluation<CurveBasis>> PrepareBasisEvaluation(
    const v1::EvaluateBasisRequest& request, const ServiceLimits& limits);

// Everything a surface evaluation request resolves to before any math runs
// (PrepareSurfaceEvaluation). The surface's Curvature
// (PrepareSurfaceCurvature) and the tensor basis's evaluation
// (PrepareTensorBasisEvaluation) resolve their samples into one too.
struct SurfacePlan {
  // The surface (absent for a basis) and where its samples must lie.
  std::optional<Surface> surface;
  int dimension = 0;
  SurfaceDomain domain;
  bool triangular = false;
  // (u, v) pairs (a view into the request), or a grid.
  absl::Span<const double> uv;
  bool grid = false;
  std::vector<double> u;
  std::vector<double> v;
  // Partials returned, and partials computed (normals need order 2 for
  // the limit at degenerate points).
  int order = 0;
  int evaluated_order = 0;
  bool normals = false;

  size_t size() const { return grid ? u.size() * v.size() : uv.size() / 2; }

  // Samples of points [first, last) of a grid that start at point
  // `offset` of the range.
  struct Piece {
    size_t offset = 0;
    SurfaceSamples samples;
  };

  // Pieces returns the samples of points [first, last): one piece for (u,
  // v) pairs; for a grid (u-major) up to three grids, the end of the first
  // row, the whole rows and the start of the last, so a chunk may cut a
  // row anywhere.
  std::vector<Piece> Pieces(size_t first, size_t last) const;

  // All returns every sample.
  SurfaceSamples All() const {
    return grid ? SurfaceSamples::Grid(u, v) : SurfaceSamples::Pairs(uv);
  }

  size_t ValuesPerPoint() const {
    return PartialCount(order) * static_cast<size_t>(dimension) +
           (normals ? 3 : 0);
  }
};

// The surface requests resolve their `parameters` the same way: (u, v)
// points (an even, non-zero number of values, within the domain or the
// triangle) or a grid (two parameter sets over the domain; a triangular
// patch takes points), their number checked with the answer's numbers per
// point against the parameter and output limits before anything as large
// as the answer is made. Errors name "parameters.points.uv",
// "parameters.grid.u.range.count" and so on.

// PrepareSurfaceEvaluation checks the derivative order and the normals
// (a 3D surface), prepares the surface (PrepareSurface, "surface") and
// resolves its samples for the answer's size.
absl::StatusOr<SurfacePlan> PrepareSurfaceEvaluation(
    const v1::EvaluateSurfaceRequest& request, const ServiceLimits& limits);

// PrepareEvaluationOf is PrepareSurfaceEvaluation for a surface already
// prepared (a face's), from the request's parameters, derivative order and
// normals flag, the samples checked for answers of
// `extra_values_per_point` numbers per point besides the evaluation's.
absl::StatusOr<SurfacePlan> PrepareEvaluationOf(
    Surface surface, const v1::SurfaceParameters& parameters,
    uint32_t derivative_order, bool normals, uint64_t extra_values_per_point,
    const ServiceLimits& limits);

// PrepareSamplesOn resolves `parameters` against a surface already
// prepared, for answers of `values_per_point` numbers per point.
absl::StatusOr<SurfacePlan> PrepareSamplesOn(
    Surface surface, const v1::SurfaceParameters& parameters,
    uint64_t values_per_point, const ServiceLimits& limits);

// PrepareSurfaceCurvature prepares the surface of a Curvature request
// (PrepareSurface, "surface"; curvatures need it 3D) and resolves its
// samples for answers of `values_per_point` numbers each (the planner's,
// from CurvatureSizes).
absl::StatusOr<SurfacePlan> PrepareSurfaceCurvature(
    const v1::SurfaceCurvatureRequest& request, uint64_t values_per_point,
    const ServiceLimits& limits);

// What a tensor basis evaluation request resolves to: the bases in u and
// in v, and the samples over their domains (a plan without a surface).
struct TensorBasisEvaluation {
  CurveBasis u;
  CurveBasis v;
  SurfacePlan samples;

  // Values per sample: the products of the two bases' functions.
  uint64_t FunctionCount() const {
    return static_cast<uint64_t>(FunctionCountOf(u)) *
           static_cast<uint64_t>(FunctionCountOf(v));
  }
};

// PrepareTensorBasisEvaluation prepares the two bases of the request's
// `tensor` (PrepareBasis, "tensor.u" and "tensor.v") and resolves the
// samples over their domains, with FunctionCount() numbers each.
absl::StatusOr<TensorBasisEvaluation> PrepareTensorBasisEvaluation(
    const v1::EvaluateSurfaceBasisRequest& request,
    const ServiceLimits& limits);

// What a triangular basis evaluation request resolves to: the degree of
// its Bernstein polynomials and the (u, v) pairs (a view into the request).
struct TriangularBasisEvaluation {
  int degree = 0;
  absl::Span<const double> uv;

  size_t size() const { return uv.size() / 2; }
  // Values per sample: the (degree + 1)(degree + 2) / 2 polynomials.
  uint64_t FunctionCount() const;
};

// PrepareTriangularBasisEvaluation checks `triangular_degree` against the
// degree limit and resolves the request's (u, v) points (a grid is refused
// naming "parameters.points"), with FunctionCount() numbers each; whether
// they lie in the triangle is the core's check.
absl::StatusOr<TriangularBasisEvaluation> PrepareTriangularBasisEvaluation(
    const v1::EvaluateSurfaceBasisRequest& request,
    const ServiceLimits& limits);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_PREPARE_SAMPLES_H_
