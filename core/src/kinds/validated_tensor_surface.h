// Evaluation of Bezier and B-spline tensor-product surfaces that have already
// passed their Validate* function (the classes of curve.h, basis.h and
// surface.h call it, so the geometry is validated once and then evaluated chunk
// after chunk). Each still checks its batch: parameters in the domain and
// output sizes. Internal to the core; thread-safe like the public evaluators.
#ifndef FREEFORM_CORE_SRC_KINDS_VALIDATED_TENSOR_SURFACE_H_
#define FREEFORM_CORE_SRC_KINDS_VALIDATED_TENSOR_SURFACE_H_

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/tensor_surface.h"
#include "freeform/core/thread_pool.h"

namespace freeform::internal {

absl::Status EvaluateValidBezierSurface(const BezierSurfaceView& surface,
                                        const SurfaceSamples& samples,
                                        SurfaceOutput output,
                                        const ExecutionContext& context);

absl::Status EvaluateValidBSplineSurface(const BSplineSurfaceView& surface,
                                         const SurfaceSamples& samples,
                                         SurfaceOutput output,
                                         const ExecutionContext& context);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_KINDS_VALIDATED_TENSOR_SURFACE_H_
