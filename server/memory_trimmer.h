// MemoryTrimmer: gives the memory of large answers back to the system once
// the server is idle.
//
// glibc keeps freed memory in its arenas so the next call reuses it without
// page faults (mapping each large answer afresh tripled the cost of a
// streamed answer). After a burst of large calls that memory would stay
// resident; the trimmer returns it (malloc_trim) when no call holds a
// reservation and at least `threshold_bytes` have been released since the
// last trim. It checks every `period` on a thread of its own.
#ifndef FREEFORM_SERVER_MEMORY_TRIMMER_H_
#define FREEFORM_SERVER_MEMORY_TRIMMER_H_

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

#include "admission.h"

namespace freeform::server {

class MemoryTrimmer {
 public:
  // `budget` must outlive the trimmer.
  MemoryTrimmer(const MemoryBudget* budget, uint64_t threshold_bytes,
                std::chrono::milliseconds period);
  ~MemoryTrimmer();
  MemoryTrimmer(const MemoryTrimmer&) = delete;
  MemoryTrimmer& operator=(const MemoryTrimmer&) = delete;

  // trims counts the times memory was handed back.
  uint64_t trims() const;

 private:
  void Run();

  const MemoryBudget* const budget_;
  const uint64_t threshold_bytes_;
  const std::chrono::milliseconds period_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  uint64_t trims_ = 0;
  std::thread thread_;
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_MEMORY_TRIMMER_H_
