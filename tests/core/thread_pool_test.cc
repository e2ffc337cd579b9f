#include "freeform/core/thread_pool.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <mutex>
#include <new>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "absl/strings/match.h"

namespace freeform {
namespace {

TEST(ParallelForTest, CoversEveryIndexExactlyOnce) {
  ThreadPool pool(3);
  for (size_t count : {0u, 1u, 7u, 100u, 10'007u}) {
    for (size_t grain : {1u, 3u, 64u, 100'000u}) {
      std::vector<std::atomic<int>> hits(count);
      const absl::Status status = ParallelFor(
          count,
          ExecutionContext{.pool = &pool, .grain = grain, .max_helpers = 3},
          [&](size_t begin, size_t end) {
            ASSERT_LE(end - begin, grain);
            for (size_t i = begin; i < end; ++i) hits[i].fetch_add(1);
          });
      ASSERT_TRUE(status.ok());
      for (size_t i = 0; i < count; ++i) ASSERT_EQ(hits[i].load(), 1) << i;
    }
  }
}

TEST(ParallelForTest, RunsInlineWithoutPool) {
  std::set<std::thread::id> threads;
  ASSERT_TRUE(
      ParallelFor(1000, ExecutionContext{.grain = 10}, [&](size_t, size_t) {
        threads.insert(std::this_thread::get_id());
      }).ok());
  EXPECT_EQ(threads, std::set<std::thread::id>{std::this_thread::get_id()});
}

TEST(ParallelForTest, UsesEveryPoolThread) {
  constexpr int kThreads = 4;
  ThreadPool pool(kThreads);
  std::mutex mutex;
  std::set<std::thread::id> threads;
  std::atomic<int> arrived{0};
  // Each of the first kThreads + 1 chunks waits until that many chunks have
  // started, so the batch can only finish if every worker and the caller
  // took one.
  ASSERT_TRUE(
      ParallelFor(
          kThreads + 1,
          ExecutionContext{.pool = &pool, .grain = 1, .max_helpers = kThreads},
          [&](size_t, size_t) {
            {
              std::lock_guard<std::mutex> lock(mutex);
              threads.insert(std::this_thread::get_id());
            }
            arrived.fetch_add(1);
            while (arrived.load() < kThreads + 1) {
              std::this_thread::yield();
            }
          })
          .ok());
  EXPECT_EQ(threads.size(), static_cast<size_t>(kThreads + 1));
}

TEST(ParallelForTest, DefaultHelpersAreTheCoresBesideTheCaller) {
  const size_t cores = std::max(1u, std::thread::hardware_concurrency());
  EXPECT_EQ(DefaultMaxHelpers(), cores - 1);
  EXPECT_EQ(ExecutionContext{}.max_helpers, cores - 1);
}

// With the default context a batch runs on the caller and one helper per
// core the caller leaves free, however many workers the pool has. Each of
// the first `expected` chunks waits until that many have started, so the
// batch can only finish if every helper it may have took one.
TEST(ParallelForTest, DefaultContextUsesOneThreadPerCore) {
  constexpr size_t kWorkers = 4;
  ThreadPool pool(static_cast<int>(kWorkers));
  const size_t expected = std::min(kWorkers, DefaultMaxHelpers()) + 1;
  std::mutex mutex;
  std::set<std::thread::id> threads;
  std::atomic<size_t> arrived{0};
  ASSERT_TRUE(
      ParallelFor(64, ExecutionContext{.pool = &pool, .grain = 1},
                  [&](size_t, size_t) {
                    {
                      std::lock_guard<std::mutex> lock(mutex);
                      if (!threads.insert(std::this_thread::get_id()).second) {
                        return;
                      }
                    }
                    arrived.fetch_add(1);
                    while (arrived.load() < expected) {
                      std::this_thread::yield();
                    }
                  })
          .ok());
  EXPECT_EQ(threads.size(), expected);
}

// Four threads on 64 chunks: each starts at the front of its own quarter.
TEST(ParallelForTest, EachThreadStartsOnItsOwnShare) {
  constexpr size_t kHelpers = 3;
  ThreadPool pool(static_cast<int>(kHelpers));
  std::mutex mutex;
  std::map<std::thread::id, size_t> first_chunk;
  std::atomic<size_t> arrived{0};
  ASSERT_TRUE(
      ParallelFor(
          64,
          ExecutionContext{.pool = &pool, .grain = 1, .max_helpers = kHelpers},
          [&](size_t begin, size_t) {
            {
              std::lock_guard<std::mutex> lock(mutex);
              if (!first_chunk.emplace(std::this_thread::get_id(), begin)
                       .second) {
                return;
              }
            }
            arrived.fetch_add(1);
            while (arrived.load() < kHelpers + 1) {
              std::this_thread::yield();
            }
          })
          .ok());
  std::set<size_t> firsts;
  for (const auto& [thread, chunk] : first_chunk) firsts.insert(chunk);
  EXPECT_EQ(firsts, (std::set<size_t>{0, 16, 32, 48}));
  EXPECT_EQ(first_chunk.at(std::this_thread::get_id()), 0u);
}

// A helper that cannot start leaves its share to the caller, who finishes
// its own share first and then takes the helper's from the back: the caller
// runs 0..31 in order, then 63 down to 32.
TEST(ParallelForTest, CallerTakesALateHelpersShareFromTheBack) {
  ThreadPool pool(1);
  std::atomic<bool> started{false}, release{false};
  ASSERT_TRUE(pool.TrySchedule([&] {
    started.store(true);
    while (!release.load()) std::this_thread::yield();
  }));
  while (!started.load()) std::this_thread::yield();
  std::vector<size_t> order;
  ASSERT_TRUE(
      ParallelFor(64,
                  ExecutionContext{.pool = &pool, .grain = 1, .max_helpers = 1},
                  [&](size_t begin, size_t) { order.push_back(begin); })
          .ok());
  release.store(true);
  std::vector<size_t> expected;
  for (size_t chunk = 0; chunk < 32; ++chunk) expected.push_back(chunk);
  for (size_t chunk = 64; chunk-- > 32;) expected.push_back(chunk);
  EXPECT_EQ(order, expected);
}

TEST(ParallelForTest, CancellationSkipsRemainingChunks) {
  ThreadPool pool(2);
  CancellationToken token;
  std::atomic<size_t> ran{0};
  const absl::Status status = ParallelFor(
      1000, ExecutionContext{.pool = &pool, .cancellation = &token, .grain = 1},
      [&](size_t, size_t) {
        if (ran.fetch_add(1) == 10) token.Cancel();
      });
  EXPECT_EQ(status.code(), absl::StatusCode::kCancelled);
  EXPECT_LT(ran.load(), 1000u);
}

TEST(ParallelForTest, ChunkThatThrowsFailsTheLoopAndNoThread) {
  // Chunks on the caller and on every helper throw (the exception types an
  // allocation and a vector's size check raise); the loop returns INTERNAL
  // with the text, skips what is left, and the pool still serves.
  ThreadPool pool(3);
  for (const size_t thrower : {0u, 5u, 99u}) {
    std::atomic<size_t> ran{0};
    const absl::Status status = ParallelFor(
        100, ExecutionContext{.pool = &pool, .grain = 1, .max_helpers = 3},
        [&](size_t begin, size_t) {
          ran.fetch_add(1);
          if (begin == thrower)
            throw std::length_error("vector::_M_default_append");
          if (begin == thrower + 1) throw std::bad_alloc();
        });
    EXPECT_EQ(status.code(), absl::StatusCode::kInternal) << status;
    EXPECT_TRUE(absl::StrContains(status.message(), "vector::") ||
                absl::StrContains(status.message(), "bad_alloc"))
        << status;
    EXPECT_LE(ran.load(), 100u);
  }
  std::atomic<size_t> ran{0};
  ASSERT_TRUE(
      ParallelFor(1000,
                  ExecutionContext{.pool = &pool, .grain = 1, .max_helpers = 3},
                  [&](size_t, size_t) { ran.fetch_add(1); })
          .ok());
  EXPECT_EQ(ran.load(), 1000u);
}

TEST(ParallelForTest, PassedDeadlineReportsDeadlineExceeded) {
  CancellationToken token;
  token.SetDeadline(CancellationToken::Clock::now() -
                    std::chrono::milliseconds(1));
  size_t ran = 0;
  const absl::Status status =
      ParallelFor(100, ExecutionContext{.cancellation = &token, .grain = 1},
                  [&](size_t, size_t) { ++ran; });
  EXPECT_EQ(status.code(), absl::StatusCode::kDeadlineExceeded);
  EXPECT_EQ(ran, 0u);
}

TEST(ParallelForTest, FinishedBatchIsOkEvenIfTheDeadlinePassesLater) {
  CancellationToken token;
  token.SetDeadline(CancellationToken::Clock::now() +
                    std::chrono::milliseconds(50));
  ASSERT_TRUE(ParallelFor(10, ExecutionContext{.cancellation = &token},
                          [](size_t, size_t) {})
                  .ok());
}

TEST(ThreadPoolTest, FullQueueRefusesAndParallelForStillFinishes) {
  ThreadPool pool(1, /*max_queued=*/1);
  std::atomic<bool> release{false};
  ASSERT_TRUE(pool.TrySchedule([&] {
    while (!release.load()) std::this_thread::yield();
  }));
  // The worker is busy; one slot in the queue.
  while (!pool.TrySchedule([] {})) std::this_thread::yield();
  EXPECT_FALSE(pool.TrySchedule([] {}));
  // ParallelFor cannot get helpers but the caller does all the chunks.
  std::atomic<size_t> sum{0};
  ASSERT_TRUE(
      ParallelFor(100,
                  ExecutionContext{.pool = &pool, .grain = 7, .max_helpers = 1},
                  [&](size_t begin, size_t end) { sum.fetch_add(end - begin); })
          .ok());
  EXPECT_EQ(sum.load(), 100u);
  release.store(true);
}

TEST(ThreadPoolTest, QueuedCountsTheTasksWaitingForAWorker) {
  ThreadPool pool(1);
  EXPECT_EQ(pool.queued(), 0u);
  std::atomic<bool> started{false}, release{false};
  ASSERT_TRUE(pool.TrySchedule([&] {
    started.store(true);
    while (!release.load()) std::this_thread::yield();
  }));
  while (!started.load()) std::this_thread::yield();
  // The one worker is busy: what comes next waits in the queue.
  std::atomic<int> ran{0};
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(pool.TrySchedule([&] { ran.fetch_add(1); }));
  }
  EXPECT_EQ(pool.queued(), 3u);
  release.store(true);
  while (ran.load() < 3) std::this_thread::yield();
  EXPECT_EQ(pool.queued(), 0u);
}

TEST(ThreadPoolTest, DestructorRunsQueuedTasks) {
  std::atomic<int> ran{0};
  {
    ThreadPool pool(2);
    for (int i = 0; i < 50; ++i) {
      ASSERT_TRUE(pool.TrySchedule([&] { ran.fetch_add(1); }));
    }
  }
  EXPECT_EQ(ran.load(), 50);
}

}  // namespace
}  // namespace freeform
