// LoadDriver: concurrent callers that cycle through RpcCases against one
// freeform::Client and tally every outcome per RPC; LoadSeconds, the
// duration of the load and fault runs (FREEFORM_LOAD_SECONDS, default 10:
// `FREEFORM_LOAD_SECONDS=60 ctest --preset release -L load` is the long
// run); and LoadSeed, the seed of the random requests.
#ifndef FREEFORM_TESTS_RELIABILITY_DRIVER_H_
#define FREEFORM_TESTS_RELIABILITY_DRIVER_H_

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "cases.h"

namespace freeform::reliability {

// LoadSeconds returns FREEFORM_LOAD_SECONDS (at least 1), or 10 when unset.
std::chrono::seconds LoadSeconds();

// LoadSeed returns FREEFORM_LOAD_SEED, or a fresh random seed when unset
// (each run draws other requests; a failure names the request it sent).
uint64_t LoadSeed();

// The outcomes of one RPC's calls.
struct Tally {
  int64_t calls = 0;
  // OK and every check held.
  int64_t answered = 0;
  int64_t checks = 0;
  // OK but a check failed: a wrong answer.
  int64_t wrong = 0;
  // RESOURCE_EXHAUSTED: refused by admission (memory budget, full queue).
  int64_t refused = 0;
  // UNAVAILABLE before any data arrived.
  int64_t unavailable = 0;
  // A stream that failed after some of its chunks had arrived.
  int64_t cut = 0;
  // Any other error.
  int64_t failed = 0;
  // The first wrong answer, cut stream or failure, with its request.
  std::string first_problem;
  // The first refusal's and the first UNAVAILABLE's messages.
  std::string first_refusal;
  std::string first_unavailable;

  void Add(const CallResult& result);
  void Merge(const Tally& other);
};

class LoadDriver {
 public:
  // `client` and `cases` must outlive the driver; caller c starts with
  // case c (so every RPC is called from the start) and draws its requests
  // from a generator seeded with seed + c.
  LoadDriver(Client* client, const std::vector<RpcCase>* cases, int callers,
             uint64_t seed);
  ~LoadDriver();
  LoadDriver(const LoadDriver&) = delete;
  LoadDriver& operator=(const LoadDriver&) = delete;

  struct Run {
    // No call starts after this.
    std::chrono::milliseconds duration{0};
    // A caller also stops after a call that ended UNAVAILABLE (its server
    // is gone).
    bool stop_on_unavailable = false;
    // A caller waits this long after a refusal (RESOURCE_EXHAUSTED: "retry
    // later") before its next call.
    std::chrono::milliseconds refusal_pause{0};
  };

  // Start starts the callers.
  void Start(const Run& run);
  // Join waits for every caller's last call.
  void Join();

  // Calls being made right now, and calls finished so far.
  int in_flight() const { return in_flight_.load(); }
  int64_t finished() const { return finished_.load(); }

  // After Join: the tallies, per case and in all.
  const std::vector<Tally>& tallies() const { return tallies_; }
  Tally Total() const;
  // A table of the tallies, one line per RPC and a total.
  std::string Report() const;

 private:
  void Caller(int index, std::chrono::steady_clock::time_point end,
              const Run& run, std::vector<Tally>* tallies);

  Client* const client_;
  const std::vector<RpcCase>* const cases_;
  const int callers_;
  const uint64_t seed_;
  std::atomic<int> in_flight_{0};
  std::atomic<int64_t> finished_{0};
  std::vector<std::thread> threads_;
  std::vector<std::vector<Tally>> per_caller_;
  std::vector<Tally> tallies_;
};

}  // namespace freeform::reliability

#endif  // FREEFORM_TESTS_RELIABILITY_DRIVER_H_
