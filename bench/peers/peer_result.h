// Timing and the one output format of the workload peer programs
// (occt_workloads_bench, eigen_workloads_bench; scipy_workloads.py prints
// the same), which scripts/performance.sh parses:
//
//   RESULT <workload> <implementation> <value> <unit> checksum=<x>
//
// with unit points_per_s (a rate: higher is better) or seconds (the time of
// one call: lower is better), and the checksum that shows which geometry was
// computed (the sum of x + y + z over every output for W1-W4).
#ifndef FREEFORM_BENCH_PEERS_PEER_RESULT_H_
#define FREEFORM_BENCH_PEERS_PEER_RESULT_H_

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace freeform::bench {

// Runs is how many times each workload runs; the best wall time counts.
// The peer programs take it as their first argument (default 3).
inline int RunsFromArguments(int argc, char** argv) {
  const int runs = argc > 1 ? std::atoi(argv[1]) : 3;
  return std::max(1, runs);
}

// BestSeconds returns the shortest wall time of `runs` calls of `work`.
template <typename Work>
double BestSeconds(int runs, Work&& work) {
  double best = std::numeric_limits<double>::infinity();
  for (int run = 0; run < runs; ++run) {
    const auto start = std::chrono::steady_clock::now();
    work();
    const std::chrono::duration<double> elapsed =
        std::chrono::steady_clock::now() - start;
    best = std::min(best, elapsed.count());
  }
  return best;
}

// PrintRate prints `points` evaluated in `seconds` as points_per_s.
inline void PrintRate(const char* workload, const char* implementation,
                      double points, double seconds, double checksum) {
  std::printf("RESULT %s %s %.6e points_per_s checksum=%.12g\n", workload,
              implementation, points / seconds, checksum);
  std::fflush(stdout);
}

// PrintSeconds prints the time of one call.
inline void PrintSeconds(const char* workload, const char* implementation,
                         double seconds, double checksum) {
  std::printf("RESULT %s %s %.6e seconds checksum=%.12g\n", workload,
              implementation, seconds, checksum);
  std::fflush(stdout);
}

}  // namespace freeform::bench

#endif  // FREEFORM_BENCH_PEERS_PEER_RESULT_H_
