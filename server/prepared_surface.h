// PrepareSurface: from a request's surface message to a validated,
// ready-to-run core evaluation, with full field paths ("surface.bspline.
// knots_u[3]") in its errors. Interpolating and Hermite patches become the
// Bezier nets of the same surfaces. The prepared surface refers to the
// request's arrays or to its own converted copy, so it must not outlive the
// request. Thread-compatible.
#ifndef FREEFORM_SERVER_PREPARED_SURFACE_H_
#define FREEFORM_SERVER_PREPARED_SURFACE_H_

#include <functional>

#include "absl/status/statusor.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/tensor_surface.h"
#include "freeform/core/thread_pool.h"
#include "freeform/core/triangular.h"
#include "freeform/v1/geometry.pb.h"
#include "service_limits.h"

namespace freeform::server {

using SurfaceEvaluator = std::function<absl::Status(
    const SurfaceSamples&, SurfaceOutput, const ExecutionContext&)>;

struct PreparedSurface {
  int dimension = 0;
  // The parameter rectangle of tensor-product surfaces.
  double u_start = 0.0;
  double u_end = 1.0;
  double v_start = 0.0;
  double v_end = 1.0;
  // Triangular patches take (u, v) pairs only and check them themselves.
  bool triangular = false;
  SurfaceEvaluator evaluate;
};

// Validated* check a message against the core rules and `limits` and return
// its view; field paths are relative to the message.
absl::StatusOr<ControlNetView> ValidatedNet(const v1::ControlNet& net,
                                            const ServiceLimits& limits,
                                            absl::string_view field);
absl::StatusOr<BezierSurfaceView> ValidatedBezierSurface(
    const v1::BezierSurface& message, const ServiceLimits& limits);
absl::StatusOr<BSplineSurfaceView> ValidatedBSplineSurface(
    const v1::BSplineSurface& message, const ServiceLimits& limits);
absl::StatusOr<TriangularPatchView> ValidatedTriangularPatch(
    const v1::TriangularBezierPatch& message, const ServiceLimits& limits);

// PrepareSurface validates `surface` (the request's field "surface").
absl::StatusOr<PreparedSurface> PrepareSurface(const v1::Surface& surface,
                                               const ServiceLimits& limits);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_PREPARED_SURFACE_H_
