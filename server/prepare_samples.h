// The prepare step's samples: where a request evaluates its geometry, and
// the preparation of the evaluation requests themselves.
//
// A curve's parameters (ParameterSet: a list or a uniform range) and a
// surface's (u, v) samples (points or a grid) are resolved against the
// geometry's domain and the server's limits before any work. Each
// evaluation request prepares into one validated object: the geometry (see
// prepare.h), its resolved parameters or samples, and the orders wanted
// (PrepareCurveEvaluation, PrepareBasisEvaluation,
// PrepareSurfaceEvaluation); the handler then plans, runs the core and
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
// (PrepareSurfaceEvaluation). The surface's Curvature and the tensor
// basis's evaluation resolve their samples into one too (ResolveSamples).
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

// ResolvePairs returns the (u, v) pairs of `points` once they are pairs
// (an even, non-zero number of values) within the limits, with
// `values_per_point` numbers of answer each.
absl::StatusOr<absl::Span<const double>> ResolvePairs(
    const v1::SurfacePoints& points, uint64_t values_per_point,
    const ServiceLimits& limits);

// ResolveSamples resolves the (u, v) points or the grid into `plan`, after
// checking their number, with `values_per_point` numbers each, against the
// limits: nothing as large as the answer is made before that. `plan` holds
// the surface (or, for a basis, its domain) already.
absl::Status ResolveSamples(const v1::SurfaceParameters& parameters,
                            const ServiceLimits& limits,
                            uint64_t values_per_point, SurfacePlan& plan);

// PrepareSurfaceEvaluation checks the derivative order and the normals
// (a 3D surface), prepares the surface (PrepareSurface, "surface") and
// resolves its samples (ResolveSamples) for the answer's size.
absl::StatusOr<SurfacePlan> PrepareSurfaceEvaluation(
    const v1::EvaluateSurfaceRequest& request, const ServiceLimits& limits);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_PREPARE_SAMPLES_H_
