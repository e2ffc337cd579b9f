// ThreadPool and ParallelFor: how the core spreads a big batch over cores.
//
// ThreadPool is a fixed set of worker threads with a bounded task queue.
// ParallelFor splits [0, count) into chunks of `grain` items that the calling
// thread and up to ExecutionContext::max_helpers pool workers (by default
// one per core the caller leaves free) run, so a batch uses every core when
// the pool is idle and degrades gracefully (the caller does more of the
// chunks itself) when it is busy or its queue is full. Each thread starts on
// a contiguous share of the chunks and, once its share is done, takes chunks
// from the end of the largest share left: a thread writes one stretch of the
// output, and a batch run again on the same threads finds most of its output
// in the caches it left it in. Each chunk checks the cancellation token
// first; a cancelled batch skips the chunks not yet started and returns
// CANCELLED or DEADLINE_EXCEEDED. A chunk that throws (the core does not
// throw, but an allocation can) ends no thread: the chunks not yet started
// are skipped and ParallelFor returns INTERNAL with the exception's text.
//
// Results do not depend on the number of threads: chunks write disjoint
// outputs, so a batch gives the same numbers serially and in parallel.
//
// Thread safety: every method of ThreadPool may be called from any thread.
//
// Example:
//   ThreadPool pool(4);
//   CancellationToken token;
//   ExecutionContext context{.pool = &pool, .cancellation = &token};
//   absl::Status status = ParallelFor(n, context, [&](size_t b, size_t e) {
//     for (size_t i = b; i < e; ++i) out[i] = f(in[i]);
//   });
#ifndef FREEFORM_CORE_THREAD_POOL_H_
#define FREEFORM_CORE_THREAD_POOL_H_

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

#include "absl/functional/any_invocable.h"
#include "absl/functional/function_ref.h"
#include "absl/status/status.h"
#include "freeform/core/cancellation.h"

namespace freeform {

class ThreadPool {
 public:
  // Starts `threads` workers (at least 1) with room for `max_queued` tasks.
  explicit ThreadPool(int threads, size_t max_queued = 4096);
  // Runs the tasks still queued, then joins the workers.
  ~ThreadPool();

  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  // size returns the number of worker threads.
  int size() const { return static_cast<int>(workers_.size()); }

  // TrySchedule queues `task`; returns false (and drops it) when the queue is
  // full or the pool is shutting down.
  bool TrySchedule(absl::AnyInvocable<void() &&> task);

  // queued returns the number of tasks waiting for a worker now.
  size_t queued() const;

 private:
  void WorkerLoop();

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<absl::AnyInvocable<void() &&>> queue_;
  const size_t max_queued_;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

// DefaultMaxHelpers returns the cores a ParallelFor caller leaves free (the
// machine's hardware threads less one): CPU-bound chunks gain nothing from
// more threads than cores, and lose each time two share one.
size_t DefaultMaxHelpers();

// Where and how a batch runs. The defaults run everything on the calling
// thread without cancellation.
struct ExecutionContext {
  // Pool for helpers; null runs every chunk on the calling thread.
  ThreadPool* pool = nullptr;
  // Checked before each chunk; may be null.
  const CancellationToken* cancellation = nullptr;
  // Items per chunk (at least 1). A batch of at most `grain` items runs
  // inline.
  size_t grain = 4096;
  // Most pool workers that join the caller on one batch.
  size_t max_helpers = DefaultMaxHelpers();
};

// ParallelFor calls body(begin, end) over disjoint chunks covering
// [0, count) and returns once every started chunk has finished. Returns OK,
// or the token's CANCELLED / DEADLINE_EXCEEDED when it stopped early (some
// chunks then never ran). `body` must be safe to call concurrently on
// different chunks.
absl::Status ParallelFor(size_t count, const ExecutionContext& context,
                         absl::FunctionRef<void(size_t, size_t)> body);

}  // namespace freeform

#endif  // FREEFORM_CORE_THREAD_POOL_H_
