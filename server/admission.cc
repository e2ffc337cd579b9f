#include "admission.h"

#include <utility>

#include "absl/strings/str_cat.h"

namespace freeform::server {
namespace {

std::string Megabytes(uint64_t bytes) {
  return absl::StrCat(bytes / 1'000'000, ".", (bytes % 1'000'000) / 100'000,
                      " MB");
}

}  // namespace

MemoryBudget::Reservation::Reservation(Reservation&& other) noexcept
    : budget_(std::exchange(other.budget_, nullptr)),
      bytes_(std::exchange(other.bytes_, 0)) {}

MemoryBudget::Reservation& MemoryBudget::Reservation::operator=(
    Reservation&& other) noexcept {
  if (this != &other) {
    Release();
    budget_ = std::exchange(other.budget_, nullptr);
    bytes_ = std::exchange(other.bytes_, 0);
  }
  return *this;
}

void MemoryBudget::Reservation::Release() {
  if (budget_ != nullptr) {
    budget_->released_.fetch_add(bytes_, std::memory_order_relaxed);
    budget_->in_use_.fetch_sub(bytes_, std::memory_order_relaxed);
    budget_ = nullptr;
    bytes_ = 0;
  }
}

absl::StatusOr<MemoryBudget::Reservation> MemoryBudget::Reserve(
    uint64_t bytes, absl::string_view what) {
  uint64_t used = in_use_.load(std::memory_order_relaxed);
  while (true) {
    if (bytes > capacity_ || used > capacity_ - bytes) {
      refusals_.fetch_add(1, std::memory_order_relaxed);
      return absl::ResourceExhaustedError(absl::StrCat(
          what, " needs about ", Megabytes(bytes), " and only ",
          Megabytes(used < capacity_ ? capacity_ - used : 0), " of the ",
          Megabytes(capacity_), " that calls may use of the ",
          Megabytes(budget_),
          " memory budget (--memory_budget) is free now; retry later",
          bytes > capacity_ ? " with a smaller request" : ""));
    }
    if (in_use_.compare_exchange_weak(used, used + bytes,
                                      std::memory_order_relaxed)) {
      return Reservation(this, bytes);
    }
  }
}

}  // namespace freeform::server
