// Evaluation of B-spline curves and their basis functions that have already
// passed their Validate* function (the classes of curve.h, basis.h and
// surface.h call it, so the geometry is validated once and then evaluated chunk
// after chunk). Each still checks its batch: parameters in the domain and
// output sizes. Internal to the core; thread-safe like the public evaluators.
#ifndef FREEFORM_CORE_SRC_KINDS_VALIDATED_BSPLINE_H_
#define FREEFORM_CORE_SRC_KINDS_VALIDATED_BSPLINE_H_

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/bspline.h"
#include "freeform/core/curve_output.h"
#include "freeform/core/thread_pool.h"

namespace freeform::internal {

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

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_KINDS_VALIDATED_BSPLINE_H_
