#include "freeform/core/thread_pool.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "absl/strings/str_cat.h"

namespace freeform {

ThreadPool::ThreadPool(int threads, size_t max_queued)
    : max_queued_(std::max<size_t>(max_queued, 1)) {
  const int count = std::max(threads, 1);
  workers_.reserve(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    workers_.emplace_back([this] { WorkerLoop(); });
  }
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

bool ThreadPool::TrySchedule(absl::AnyInvocable<void() &&> task) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_ || queue_.size() >= max_queued_) return false;
    queue_.push_back(std::move(task));
  }
  wake_.notify_one();
  return true;
}

size_t ThreadPool::queued() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return queue_.size();
}

void ThreadPool::WorkerLoop() {
  while (true) {
    absl::AnyInvocable<void() &&> task;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping and drained
      task = std::move(queue_.front());
      queue_.pop_front();
    }
    std::move(task)();
  }
}

size_t DefaultMaxHelpers() {
  static const size_t helpers =
      std::max<size_t>(std::thread::hardware_concurrency(), 1) - 1;
  return helpers;
}

namespace {

// One thread's share of a batch's chunks, [front, back), packed in one word
// so that its owner (taking from the front) and a thief (taking from the
// back) claim with one compare-and-swap each. Alone on its cache line.
class alignas(64) ChunkShare {
 public:
  void Assign(uint32_t front, uint32_t back) {
    bounds_.store(Pack(front, back), std::memory_order_relaxed);
  }

  // Chunks not yet claimed.
  uint32_t Left() const {
    const uint64_t bounds = bounds_.load(std::memory_order_relaxed);
    return Back(bounds) - Front(bounds);
  }

  // TakeFront and TakeBack claim the first or last chunk left; nullopt when
  // none is.
  std::optional<uint32_t> TakeFront() { return Take(/*from_back=*/false); }
  std::optional<uint32_t> TakeBack() { return Take(/*from_back=*/true); }

 private:
  static uint64_t Pack(uint32_t front, uint32_t back) {
    return uint64_t{front} << 32 | back;
  }
  static uint32_t Front(uint64_t bounds) {
    return static_cast<uint32_t>(bounds >> 32);
  }
  static uint32_t Back(uint64_t bounds) {
    return static_cast<uint32_t>(bounds);
  }

  std::optional<uint32_t> Take(bool from_back) {
    uint64_t bounds = bounds_.load(std::memory_order_relaxed);
    while (true) {
      const uint32_t front = Front(bounds);
      const uint32_t back = Back(bounds);
      if (front >= back) return std::nullopt;
      const uint64_t taken =
          from_back ? Pack(front, back - 1) : Pack(front + 1, back);
      if (bounds_.compare_exchange_weak(bounds, taken,
                                        std::memory_order_relaxed)) {
        return from_back ? back - 1 : front;
      }
    }
  }

  std::atomic<uint64_t> bounds_{0};
};

// How a batch of `count` items is cut: chunks of `grain` items (the
// context's grain, raised where needed so that a batch has fewer than 2^32
// chunks, which ChunkShare counts in 32 bits), `chunks` of them.
struct Chunking {
  Chunking(size_t count, size_t requested_grain)
      : grain(
            std::max({requested_grain, size_t{1},
                      (count - 1) / std::numeric_limits<uint32_t>::max() + 1})),
        chunks(static_cast<uint32_t>((count - 1) / grain + 1)) {}

  const size_t grain;
  const uint32_t chunks;
};

// Shared by the caller and its helpers. Helpers that start after every chunk
// was claimed touch only this state (kept alive by shared_ptr), never the
// caller's body, which may be gone by then.
struct ParallelForState {
  ParallelForState(size_t item_count, const Chunking& chunking, size_t threads,
                   const CancellationToken* cancellation,
                   absl::FunctionRef<void(size_t, size_t)> chunk_body)
      : count(item_count),
        grain(chunking.grain),
        chunks(chunking.chunks),
        share_count(threads),
        shares(std::make_unique<ChunkShare[]>(threads)),
        token(cancellation),
        body(chunk_body) {
    // Share s is [s * chunks / threads, (s + 1) * chunks / threads).
    for (size_t s = 0; s < threads; ++s) {
      shares[s].Assign(static_cast<uint32_t>(s * chunks / threads),
                       static_cast<uint32_t>((s + 1) * chunks / threads));
    }
  }

  // Runs the chunks of share `own`, then those left in the other shares,
  // until none is left.
  void Work(size_t own) {
    while (const std::optional<uint32_t> chunk = Claim(own)) Run(*chunk);
  }

  // The next chunk of share `own`, else the last one of the share with the
  // most left.
  std::optional<uint32_t> Claim(size_t own) {
    if (std::optional<uint32_t> chunk = shares[own].TakeFront()) return chunk;
    while (true) {
      size_t victim = own;
      uint32_t most_left = 0;
      for (size_t s = 0; s < share_count; ++s) {
        const uint32_t left = shares[s].Left();
        if (left > most_left) {
          most_left = left;
          victim = s;
        }
      }
      if (most_left == 0) return std::nullopt;
      if (std::optional<uint32_t> chunk = shares[victim].TakeBack()) {
        return chunk;
      }
    }
  }

  void Run(uint32_t chunk) {
    if (token != nullptr && token->IsCancelled()) {
      skipped.store(true, std::memory_order_relaxed);
    } else if (!failed.load(std::memory_order_relaxed)) {
      RunBody(chunk);
    }
    if (done.fetch_add(1, std::memory_order_acq_rel) + 1 == chunks) {
      std::lock_guard<std::mutex> lock(mutex);
      finished.notify_all();
    }
  }

  // RunBody runs one chunk's body. An exception it throws (an allocation
  // that failed, a library precondition) must not end a helper's thread:
  // it is kept as the loop's failure, and the chunks not yet run are
  // skipped.
  void RunBody(uint32_t chunk) {
    const size_t begin = chunk * grain;
    try {
      body(begin, std::min(count, begin + grain));
    } catch (const std::exception& exception) {
      Fail(exception.what());
    } catch (...) {
      Fail("an exception of unknown type");
    }
  }

  void Fail(const char* what) {
    std::lock_guard<std::mutex> lock(mutex);
    if (failed.exchange(true, std::memory_order_relaxed)) return;
    failure = what;
  }

  void WaitUntilDone() {
    std::unique_lock<std::mutex> lock(mutex);
    finished.wait(lock, [this] {
      return done.load(std::memory_order_acquire) == chunks;
    });
  }

  const size_t count;
  const size_t grain;
  const uint32_t chunks;
  const size_t share_count;
  const std::unique_ptr<ChunkShare[]> shares;
  const CancellationToken* const token;
  const absl::FunctionRef<void(size_t, size_t)> body;
  // The next helper's share; the caller's is 0.
  std::atomic<size_t> next_share{1};
  std::atomic<uint32_t> done{0};
  std::atomic<bool> skipped{false};
  std::atomic<bool> failed{false};
  std::string failure;  // guarded by mutex
  std::mutex mutex;
  std::condition_variable finished;
};

}  // namespace

absl::Status ParallelFor(size_t count, const ExecutionContext& context,
                         absl::FunctionRef<void(size_t, size_t)> body) {
  if (count == 0) return absl::OkStatus();
  const Chunking chunking(count, context.grain);
  const size_t helpers =
      context.pool == nullptr
          ? 0
          : std::min({static_cast<size_t>(context.pool->size()),
                      context.max_helpers, size_t{chunking.chunks} - 1});
  auto state = std::make_shared<ParallelForState>(count, chunking, helpers + 1,
                                                  context.cancellation, body);
  for (size_t i = 0; i < helpers; ++i) {
    if (!context.pool->TrySchedule([state] {
          state->Work(
              state->next_share.fetch_add(1, std::memory_order_relaxed));
        })) {
      break;
    }
  }
  state->Work(0);
  state->WaitUntilDone();
  if (state->failed.load(std::memory_order_relaxed)) {
    std::lock_guard<std::mutex> lock(state->mutex);
    return absl::InternalError(
        absl::StrCat("a parallel loop failed on an exception (a bug: please "
                     "report the request): ",
                     state->failure));
  }
  if (state->skipped.load(std::memory_order_relaxed)) {
    return context.cancellation->status();
  }
  return absl::OkStatus();
}

}  // namespace freeform
