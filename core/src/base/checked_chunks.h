// Range checks of a batch's parameters done chunk by chunk, on the threads
// that evaluate the chunks, just before each chunk: the check of a large
// batch is then not a serial step ahead of the parallel evaluation (it was
// 11% of a cubic B-spline batch, which capped two threads at 1.44x).
// Internal to the core.
#ifndef FREEFORM_CORE_SRC_BASE_CHECKED_CHUNKS_H_
#define FREEFORM_CORE_SRC_BASE_CHECKED_CHUNKS_H_

#include <cstddef>

#include "absl/functional/function_ref.h"
#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "freeform/core/thread_pool.h"

namespace freeform::internal {

// ParallelForInRange is ParallelFor over the indices of `values` that checks
// each chunk's values lie in [lo, hi] just before running `body` on it, and
// runs no body once a chunk fails. It returns what ValidateInRange(values,
// lo, hi, field) returns (naming the first offender) when a value is NaN,
// infinite or outside, else ParallelFor's status. After a failure, chunks
// that passed may have been evaluated.
absl::Status ParallelForInRange(absl::Span<const double> values, double lo,
                                double hi, absl::string_view field,
                                const ExecutionContext& context,
                                absl::FunctionRef<void(size_t, size_t)> body);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_BASE_CHECKED_CHUNKS_H_
