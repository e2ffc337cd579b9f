// Evaluation of triangular Bezier patches that have already passed their
// Validate* function (the classes of curve.h, basis.h and surface.h call it, so
// the geometry is validated once and then evaluated chunk after chunk). Each
// still checks its batch: parameters in the domain and output sizes.
// Internal to the core; thread-safe like the public evaluators.
#ifndef FREEFORM_CORE_SRC_KINDS_VALIDATED_TRIANGULAR_H_
#define FREEFORM_CORE_SRC_KINDS_VALIDATED_TRIANGULAR_H_

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/thread_pool.h"
#include "freeform/core/triangular.h"

namespace freeform::internal {

absl::Status EvaluateValidTriangularPatch(const TriangularPatchView& patch,
                                          absl::Span<const double> uv,
                                          SurfaceOutput output,
                                          const ExecutionContext& context);

// ValidateTriangularPairs checks the (u, v) pairs EvaluateTriangularPatch
// would take from a valid patch ("uv", "uv[i]").
absl::Status ValidateTriangularPairs(const TriangularPatchView& patch,
                                     absl::Span<const double> uv);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_KINDS_VALIDATED_TRIANGULAR_H_
