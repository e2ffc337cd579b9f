#include "base/checked_chunks.h"

#include <atomic>

#include "freeform/core/points.h"

namespace freeform::internal {

absl::Status ParallelForInRange(absl::Span<const double> values, double lo,
                                double hi, absl::string_view field,
                                const ExecutionContext& context,
                                absl::FunctionRef<void(size_t, size_t)> body) {
  std::atomic<bool> outside{false};
  const absl::Status status =
      ParallelFor(values.size(), context, [&](size_t begin, size_t end) {
        if (outside.load(std::memory_order_relaxed)) return;
        if (!ValidateInRange(values.subspan(begin, end - begin), lo, hi, field)
                 .ok()) {
          outside.store(true, std::memory_order_relaxed);
          return;
        }
        body(begin, end);
      });
  if (outside.load(std::memory_order_relaxed)) {
    return ValidateInRange(values, lo, hi, field);
  }
  return status;
}

}  // namespace freeform::internal
