// MemoryTrimmer: gives the memory of large answers back to the system once
// the server is idle.
//
// glibc keeps freed memory in its arenas so the next call reuses it without
// page faults (mapping each large answer afresh tripled the cost of a
// streamed answer). After a burst of large calls that memory would stay
// resident; the trimmer returns it (malloc_trim) once the server is quiet:
// no call holds a reservation, none was released during the last `period`
// (gRPC frees an answer only after sending it, after its call released its
// reservation), and at least `threshold_bytes` have been released since the
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

// ConfigureAllocatorForTrimming sets glibc malloc up so that the trimmer
// can return everything a burst left behind; call it first thing in main,
// before any thread starts. malloc_trim returns the free memory of every
// arena but the top chunk of the main arena's only: a per-thread arena
// keeps its top, up to the dynamic trim threshold (64 MiB), after a burst of
// answers of a few MiB. So it asks for one arena (MALLOC_ARENA_MAX=1; small
// allocations stay per thread in tcache) and fixes the thresholds where the
// dynamic ones end: blocks over 32 MiB are mapped and unmapped per use, and
// the arena trims itself only beyond 512 MiB, so large answers reuse warm
// pages while the server is busy. An operator's MALLOC_ARENA_MAX,
// MALLOC_TRIM_THRESHOLD_, MALLOC_MMAP_THRESHOLD_ or GLIBC_TUNABLES take
// precedence: then nothing is changed. Returns whether it changed them.
bool ConfigureAllocatorForTrimming();

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
