// Evaluation entry points for geometry that has already passed its
// Validate* function (the classes of curve.h, basis.h and surface.h call
// them, so a curve is validated once and then evaluated chunk after chunk).
// Each still checks its batch: parameters in the domain and output sizes.
// Internal to the core; thread-safe like the public evaluators.
#ifndef FREEFORM_CORE_SRC_VALIDATED_H_
#define FREEFORM_CORE_SRC_VALIDATED_H_

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/bezier.h"
#include "freeform/core/bspline.h"
#include "freeform/core/curve_output.h"
#include "freeform/core/hermite.h"
#include "freeform/core/lagrange.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/tensor_surface.h"
#include "freeform/core/thread_pool.h"
#include "freeform/core/triangular.h"

namespace freeform::internal {

absl::Status EvaluateValidBezierCurve(const BezierCurveView& curve,
                                      absl::Span<const double> parameters,
                                      CurveOutput output,
                                      const ExecutionContext& context,
                                      BezierAlgorithm algorithm);

absl::Status EvaluateValidBSplineCurve(const BSplineCurveView& curve,
                                       absl::Span<const double> parameters,
                                       CurveOutput output,
                                       const ExecutionContext& context);

absl::Status EvaluateValidBSplineBasis(int degree,
                                       absl::Span<const double> knots,
                                       absl::Span<const double> weights,
                                       absl::Span<const double> parameters,
                                       CurveOutput output,
                                       const ExecutionContext& context);

absl::Status EvaluateValidLagrangeCurve(const LagrangeCurveView& curve,
                                        absl::Span<const double> parameters,
                                        CurveOutput output,
                                        const ExecutionContext& context);

absl::Status EvaluateValidLagrangeBasis(absl::Span<const double> nodes,
                                        absl::Span<const double> parameters,
                                        CurveOutput output,
                                        const ExecutionContext& context);

absl::Status EvaluateValidHermiteCurve(const HermiteCurveView& curve,
                                       absl::Span<const double> parameters,
                                       CurveOutput output,
                                       const ExecutionContext& context);

absl::Status EvaluateValidBezierSurface(const BezierSurfaceView& surface,
                                        const SurfaceSamples& samples,
                                        SurfaceOutput output,
                                        const ExecutionContext& context);

absl::Status EvaluateValidBSplineSurface(const BSplineSurfaceView& surface,
                                         const SurfaceSamples& samples,
                                         SurfaceOutput output,
                                         const ExecutionContext& context);

absl::Status EvaluateValidTriangularPatch(const TriangularPatchView& patch,
                                          absl::Span<const double> uv,
                                          SurfaceOutput output,
                                          const ExecutionContext& context);

// ValidateTriangularPairs checks the (u, v) pairs EvaluateTriangularPatch
// would take from a valid patch ("uv", "uv[i]").
absl::Status ValidateTriangularPairs(const TriangularPatchView& patch,
                                     absl::Span<const double> uv);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_VALIDATED_H_
