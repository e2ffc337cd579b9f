#include "memory_trimmer.h"

#include <malloc.h>

namespace freeform::server {

MemoryTrimmer::MemoryTrimmer(const MemoryBudget* budget,
                             uint64_t threshold_bytes,
                             std::chrono::milliseconds period)
    : budget_(budget),
      threshold_bytes_(threshold_bytes),
      period_(period),
      thread_([this] { Run(); }) {}

MemoryTrimmer::~MemoryTrimmer() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

uint64_t MemoryTrimmer::trims() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return trims_;
}

void MemoryTrimmer::Run() {
  uint64_t released_at_last_trim = budget_->released();
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, period_, [this] { return stopping_; })) {
    const uint64_t released = budget_->released();
    if (budget_->in_use() != 0 ||
        released - released_at_last_trim < threshold_bytes_) {
      continue;
    }
    released_at_last_trim = released;
    lock.unlock();
    malloc_trim(0);
    lock.lock();
    ++trims_;
  }
}

}  // namespace freeform::server
