// The samples of a surface query: (u, v) points or a grid, resolved
// against the surface's domain and the server's limits before any work, and
// cut into pieces for chunked answers. Shared by the evaluation and the
// query RPCs of SurfaceService. Thread-compatible.
#ifndef FREEFORM_SERVER_PREPARE_SAMPLES_H_
#define FREEFORM_SERVER_PREPARE_SAMPLES_H_

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/surface.h"
#include "freeform/v1/geometry.pb.h"
#include "service_limits.h"

namespace freeform::server {

// Everything a surface evaluation request resolves to before any math runs.
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

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_PREPARE_SAMPLES_H_
