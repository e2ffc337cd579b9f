// What limits a batch on two threads (docs/performance_profile.md, W7):
//
//   build/release/bench/thread_bench --benchmark_repetitions=5
//
// BM_CacheLineRoundTrip: one cache line passed back and forth between a
// thread on CPU 0 and one on CPU 1; about 100 ns a round trip between cores
// that share an L3, several hundred between cores that do not.
// BM_HelperStartDelay: from the start of a ParallelFor until its helper (a
// sleeping pool worker) starts its first chunk.
// BM_W7_ChunkTrace: W1 on every thread, timed chunk by chunk: how many
// chunks each thread ran, how long each took against the same chunks on
// one thread, and when the helper started.
#include <benchmark/benchmark.h>
#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include "core_workloads.h"
#include "freeform/core/bspline.h"
#include "freeform/core/thread_pool.h"
#include "workloads.h"

namespace {

using Clock = std::chrono::steady_clock;

bool PinToCpu(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  return pthread_setaffinity_np(pthread_self(), sizeof(set), &set) == 0;
}

double MicrosecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::micro>(Clock::now() - start)
      .count();
}

void BM_CacheLineRoundTrip(benchmark::State& state) {
  cpu_set_t allowed;
  if (pthread_getaffinity_np(pthread_self(), sizeof(allowed), &allowed) != 0 ||
      !CPU_ISSET(0, &allowed) || !CPU_ISSET(1, &allowed) || !PinToCpu(0)) {
    state.SkipWithError("needs CPUs 0 and 1");
    return;
  }
  alignas(64) std::atomic<uint64_t> ball{0};
  std::atomic<bool> stop{false};
  std::thread partner([&] {
    PinToCpu(1);
    uint64_t seen = 0;
    while (!stop.load(std::memory_order_relaxed)) {
      const uint64_t value = ball.load(std::memory_order_acquire);
      if (value != seen && value % 2 == 1) {
        seen = value + 1;
        ball.store(seen, std::memory_order_release);
      }
    }
  });
  uint64_t value = 0;
  for (auto _ : state) {
    ball.store(++value, std::memory_order_release);
    while (ball.load(std::memory_order_acquire) != value + 1) {
    }
    ++value;
  }
  stop.store(true);
  partner.join();
  // Threads started later (pool workers) inherit the caller's CPUs.
  pthread_setaffinity_np(pthread_self(), sizeof(allowed), &allowed);
}
BENCHMARK(BM_CacheLineRoundTrip)->Unit(benchmark::kNanosecond);

void BM_HelperStartDelay(benchmark::State& state) {
  freeform::ThreadPool pool(
      static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  if (freeform::DefaultMaxHelpers() == 0) {
    state.SkipWithError("one core: a batch has no helper");
    return;
  }
  const freeform::ExecutionContext context{
      .pool = &pool, .grain = 1, .max_helpers = 1};
  for (auto _ : state) {
    const Clock::time_point start = Clock::now();
    std::atomic<double> delay{-1};
    // Chunk 0 is the caller's share, chunk 1 the helper's: the caller waits
    // in its chunk until the helper has started, so it never takes chunk 1.
    const absl::Status status =
        freeform::ParallelFor(2, context, [&](size_t begin, size_t) {
          if (begin == 1) {
            delay.store(MicrosecondsSince(start));
            return;
          }
          while (delay.load() < 0) std::this_thread::yield();
        });
    if (!status.ok()) state.SkipWithError(status.ToString().c_str());
    state.SetIterationTime(delay.load() * 1e-6);
    // Let the worker go back to sleep, as between a server's calls.
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}
BENCHMARK(BM_HelperStartDelay)->UseManualTime()->Unit(benchmark::kMicrosecond);

// One W1 batch (10^6 parameters) in chunks of the default grain, the chunks
// timed one by one.
class ChunkTrace {
 public:
  ChunkTrace()
      : curve_(freeform::bench::W1Curve()),
        parameters_(freeform::bench::UniformParameters(1'000'000)),
        output_(parameters_.size() * 3) {}

  size_t size() const { return parameters_.size(); }
  size_t chunks() const { return (size() + kGrain - 1) / kGrain; }

  // Evaluates the chunk [begin, end) on the calling thread.
  void Evaluate(size_t begin, size_t end) {
    absl::Span<double> points(output_.data() + 3 * begin, 3 * (end - begin));
    const absl::Status status = freeform::EvaluateBSplineCurve(
        curve_.view(),
        absl::MakeConstSpan(parameters_).subspan(begin, end - begin),
        absl::MakeSpan(&points, 1), {});
    benchmark::DoNotOptimize(status.ok());
  }

  // ExecutionContext's default grain.
  inline static const size_t kGrain = freeform::ExecutionContext{}.grain;

 private:
  freeform::BSplineCurveData curve_;
  std::vector<double> parameters_;
  std::vector<double> output_;
};

void BM_W7_ChunkTrace(benchmark::State& state) {
  freeform::ThreadPool pool(
      static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  ChunkTrace trace;
  const size_t count = trace.size();
  double alone_us = 0;
  double caller_us = 0;
  double helper_us = 0;
  double caller_chunks = 0;
  double helper_chunks = 0;
  double helper_start_us = 0;
  // The same chunks on the calling thread alone, before the runs on two
  // threads (between them, they would bring every output line into this
  // thread's caches and slow the helper's next run).
  constexpr int kAloneRuns = 20;
  for (int run = 0; run <= kAloneRuns; ++run) {
    const Clock::time_point start = Clock::now();
    for (size_t begin = 0; begin < count; begin += ChunkTrace::kGrain) {
      trace.Evaluate(begin, std::min(count, begin + ChunkTrace::kGrain));
    }
    if (run > 0) alone_us += MicrosecondsSince(start);  // run 0 warms up
  }
  for (auto _ : state) {
    const std::thread::id caller = std::this_thread::get_id();
    std::atomic<double> first_helper_chunk{1e300};
    const Clock::time_point start = Clock::now();
    const absl::Status status = freeform::ParallelFor(
        count, {.pool = &pool, .max_helpers = 1},
        [&](size_t begin, size_t end) {
          const double started = MicrosecondsSince(start);
          trace.Evaluate(begin, end);
          const double took = MicrosecondsSince(start) - started;
          if (std::this_thread::get_id() == caller) {
            caller_us += took;
            caller_chunks += 1;
            return;
          }
          double first = first_helper_chunk.load();
          while (started < first &&
                 !first_helper_chunk.compare_exchange_weak(first, started)) {
          }
          // The one helper (max_helpers): these sums are its own.
          helper_us += took;
          helper_chunks += 1;
        });
    if (!status.ok()) state.SkipWithError(status.ToString().c_str());
    if (first_helper_chunk.load() < 1e300) {
      helper_start_us += first_helper_chunk.load();
    }
  }
  const double runs = static_cast<double>(state.iterations());
  state.counters["alone_us_per_chunk"] =
      alone_us / (kAloneRuns * static_cast<double>(trace.chunks()));
  state.counters["caller_chunks"] = caller_chunks / runs;
  state.counters["caller_us_per_chunk"] =
      caller_chunks > 0 ? caller_us / caller_chunks : 0;
  state.counters["helper_chunks"] = helper_chunks / runs;
  state.counters["helper_us_per_chunk"] =
      helper_chunks > 0 ? helper_us / helper_chunks : 0;
  state.counters["helper_start_us"] = helper_start_us / runs;
}
BENCHMARK(BM_W7_ChunkTrace)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
