#include "freeform/core/cancellation.h"

namespace freeform {

void CancellationToken::Stop(State reason) const {
  int expected = kRunning;
  state_.compare_exchange_strong(expected, reason, std::memory_order_relaxed);
}

bool CancellationToken::IsCancelled() const {
  if (state_.load(std::memory_order_relaxed) != kRunning) return true;
  if (deadline_.has_value() && Clock::now() >= *deadline_) {
    Stop(kDeadlineExceeded);
    return true;
  }
  if (poll_ && poll_()) {
    Stop(kCancelled);
    return true;
  }
  return false;
}

absl::Status CancellationToken::status() const {
  IsCancelled();
  switch (state_.load(std::memory_order_relaxed)) {
    case kCancelled:
      return absl::CancelledError("the request was cancelled");
    case kDeadlineExceeded:
      return absl::DeadlineExceededError(
          deadline_why_.empty() ? "the deadline passed before the work finished"
                                : deadline_why_);
    default:
      return absl::OkStatus();
  }
}

absl::Status CheckCancelled(const CancellationToken* cancel) {
  if (cancel != nullptr && cancel->IsCancelled()) return cancel->status();
  return absl::OkStatus();
}

}  // namespace freeform
