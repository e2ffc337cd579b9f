#include "freeform/core/thread_pool.h"

#include <algorithm>
#include <atomic>
#include <memory>
#include <utility>

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

namespace {

// Shared by the caller and its helpers. Helpers that start after every chunk
// was claimed touch only this state (kept alive by shared_ptr), never the
// caller's body, which may be gone by then.
struct ParallelForState {
  ParallelForState(size_t item_count, size_t chunk_size,
                   const CancellationToken* cancellation,
                   absl::FunctionRef<void(size_t, size_t)> chunk_body)
      : count(item_count),
        grain(chunk_size),
        chunks((item_count + chunk_size - 1) / chunk_size),
        token(cancellation),
        body(chunk_body) {}

  // Claims and runs chunks until none is left.
  void Work() {
    while (true) {
      const size_t chunk = next.fetch_add(1, std::memory_order_relaxed);
      if (chunk >= chunks) return;
      if (token != nullptr && token->IsCancelled()) {
        skipped.store(true, std::memory_order_relaxed);
      } else {
        const size_t begin = chunk * grain;
        body(begin, std::min(count, begin + grain));
      }
      if (done.fetch_add(1, std::memory_order_acq_rel) + 1 == chunks) {
        std::lock_guard<std::mutex> lock(mutex);
        finished.notify_all();
      }
    }
  }

  void WaitUntilDone() {
    std::unique_lock<std::mutex> lock(mutex);
    finished.wait(lock, [this] {
      return done.load(std::memory_order_acquire) == chunks;
    });
  }

  const size_t count;
  const size_t grain;
  const size_t chunks;
  const CancellationToken* const token;
  const absl::FunctionRef<void(size_t, size_t)> body;
  std::atomic<size_t> next{0};
  std::atomic<size_t> done{0};
  std::atomic<bool> skipped{false};
  std::mutex mutex;
  std::condition_variable finished;
};

}  // namespace

absl::Status ParallelFor(size_t count, const ExecutionContext& context,
                         absl::FunctionRef<void(size_t, size_t)> body) {
  if (count == 0) return absl::OkStatus();
  const size_t grain = std::max<size_t>(context.grain, 1);
  auto state = std::make_shared<ParallelForState>(count, grain,
                                                  context.cancellation, body);
  if (context.pool != nullptr && state->chunks > 1) {
    const size_t helpers = std::min<size_t>(
        static_cast<size_t>(context.pool->size()), state->chunks - 1);
    for (size_t i = 0; i < helpers; ++i) {
      if (!context.pool->TrySchedule([state] { state->Work(); })) break;
    }
  }
  state->Work();
  state->WaitUntilDone();
  if (state->skipped.load(std::memory_order_relaxed)) {
    return context.cancellation->status();
  }
  return absl::OkStatus();
}

}  // namespace freeform
