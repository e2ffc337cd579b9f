// MemoryBudget: the one admission controller of the whole server.
//
// Every call reserves the memory its answer and its work will need,
// estimated from the request before any work starts, and holds the
// reservation until its answer has been sent. A call that does not fit in
// what is left of the budget gets RESOURCE_EXHAUSTED at once, naming the
// budget, so a burst of large calls is refused instead of driving the
// process out of memory. Thread-safe.
#ifndef FREEFORM_SERVER_ADMISSION_H_
#define FREEFORM_SERVER_ADMISSION_H_

#include <atomic>
#include <cstdint>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace freeform::server {

class MemoryBudget {
 public:
  // Memory held until destroyed (or moved from).
  class Reservation {
   public:
    Reservation() = default;
    Reservation(Reservation&& other) noexcept;
    Reservation& operator=(Reservation&& other) noexcept;
    Reservation(const Reservation&) = delete;
    Reservation& operator=(const Reservation&) = delete;
    ~Reservation() { Release(); }

    uint64_t bytes() const { return bytes_; }

   private:
    friend class MemoryBudget;
    Reservation(MemoryBudget* budget, uint64_t bytes)
        : budget_(budget), bytes_(bytes) {}
    void Release();

    MemoryBudget* budget_ = nullptr;
    uint64_t bytes_ = 0;
  };

  // `budget_bytes` bounds the process's memory; calls may reserve 3/4 of
  // it together. The rest is for the process itself: its code and idle
  // state, gRPC's buffers, and the memory the allocator keeps in its
  // per-thread arenas between calls (measured with 64 concurrent maximal
  // calls: up to about a fifth of what the calls reserve).
  explicit MemoryBudget(uint64_t budget_bytes)
      : budget_(budget_bytes), capacity_(budget_bytes / 4 * 3) {}

  // Reserve returns a reservation of `bytes`, or RESOURCE_EXHAUSTED when
  // they do not fit next to the reservations held now (`what` names the
  // call in the message).
  absl::StatusOr<Reservation> Reserve(uint64_t bytes, absl::string_view what);

  uint64_t budget() const { return budget_; }
  // capacity is what calls may reserve together.
  uint64_t capacity() const { return capacity_; }
  uint64_t in_use() const { return in_use_.load(std::memory_order_relaxed); }
  // released counts the bytes of every reservation released so far.
  uint64_t released() const {
    return released_.load(std::memory_order_relaxed);
  }
  // refusals counts the calls refused so far.
  uint64_t refusals() const {
    return refusals_.load(std::memory_order_relaxed);
  }

 private:
  const uint64_t budget_;
  const uint64_t capacity_;
  std::atomic<uint64_t> in_use_{0};
  std::atomic<uint64_t> released_{0};
  std::atomic<uint64_t> refusals_{0};
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_ADMISSION_H_
