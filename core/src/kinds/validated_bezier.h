// Evaluation of Bezier curves that have already passed their Validate*
// function (the classes of curve.h, basis.h and surface.h call it, so the
// geometry is validated once and then evaluated chunk after chunk). Each
// still checks its batch: parameters in the domain and output sizes.
// Internal to the core; thread-safe like the public evaluators.
#ifndef FREEFORM_CORE_SRC_KINDS_VALIDATED_BEZIER_H_
#define FREEFORM_CORE_SRC_KINDS_VALIDATED_BEZIER_H_

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/bezier.h"
#include "freeform/core/curve_output.h"
#include "freeform/core/thread_pool.h"

namespace freeform::internal {

absl::Status EvaluateValidBezierCurve(const BezierCurveView& curve,
                                      absl::Span<const double> parameters,
                                      CurveOutput output,
                                      const ExecutionContext& context,
                                      BezierAlgorithm algorithm);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_KINDS_VALIDATED_BEZIER_H_
