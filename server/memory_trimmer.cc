#include "memory_trimmer.h"

#include <malloc.h>

#include <cstdlib>

namespace freeform::server {

bool ConfigureAllocatorForTrimming() {
  for (const char* variable : {"MALLOC_ARENA_MAX", "MALLOC_TRIM_THRESHOLD_",
                               "MALLOC_MMAP_THRESHOLD_", "GLIBC_TUNABLES"}) {
    if (std::getenv(variable) != nullptr) return false;
  }
  constexpr int kMmapThreshold = 32 << 20;  // glibc's dynamic maximum
  constexpr int kTrimThreshold = 512 << 20;
  return mallopt(M_ARENA_MAX, 1) == 1 &&
         mallopt(M_MMAP_THRESHOLD, kMmapThreshold) == 1 &&
         mallopt(M_TRIM_THRESHOLD, kTrimThreshold) == 1;
}

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
  uint64_t released_at_last_check = released_at_last_trim;
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, period_, [this] { return stopping_; })) {
    const uint64_t released = budget_->released();
    // Quiet: no call released memory during the last period, so gRPC has
    // also freed the answers it was still sending when their calls ended.
    const bool quiet = released == released_at_last_check;
    released_at_last_check = released;
    if (!quiet || budget_->in_use() != 0 ||
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
