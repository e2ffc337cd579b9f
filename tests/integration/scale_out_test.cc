// ScaleOut: freeformd replicas behind one DNS name, the way a Kubernetes
// headless Service puts pods behind one, on loopback. dnsmasq (dnsmasq.h)
// answers the name with 127.0.0.1, 127.0.0.2 and 127.0.0.3, each a replica
// listening on the same port; one freeform::Client resolves the name
// through it (`dns://127.0.0.1:DNSPORT/NAME:PORT`, gRPC's c-ares resolver
// with the DNS server named) and balances with round_robin, while callers
// keep calling. The replicas run with --max_connection_age, so the client
// reconnects and re-resolves every couple of seconds. Checked:
//   - the calls spread evenly over the three replicas;
//   - a fourth replica added to the name mid-load gets its share within
//     about one connection age (plus one resolution);
//   - a replica removed from the name and drained with SIGTERM costs no
//     failed call (the client health-checks each replica, and retries).
// Calls per replica come from each replica's Prometheus metrics. Each test
// prints its figures (shares, failed calls, time to traffic) on stderr.
// Skipped only when dnsmasq is not installed (scripts/setup.sh installs
// dnsmasq-base).
#include <gtest/gtest.h>
#include <signal.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/synchronization/mutex.h"
#include "dnsmasq.h"
#include "freeform/client.h"
#include "loopback_ports.h"
#include "metrics_scrape.h"
#include "sanitizers.h"
#include "server_process.h"

namespace freeform {
namespace {

using Clock = std::chrono::steady_clock;

constexpr char kName[] = "replicas.freeform.test";
// The replicas' --max_connection_age: a connection lives this long, plus or
// minus 10 %, before the server sends GOAWAY and the client re-resolves.
constexpr std::chrono::seconds kConnectionAge{2};
// The client's shortest time between two resolutions (gRPC's default, 30 s,
// would hold a new replica back for that long).
constexpr std::chrono::milliseconds kResolutionInterval{500};
// The calls on the way: four callers, each pausing 1 ms between calls, so
// that the load leaves room on a 2-core machine for the other tests.
constexpr int kCallers = 4;
constexpr std::chrono::milliseconds kCallerPause{1};
constexpr char kServedSeries[] =
    R"(freeform_calls_total{code="OK",method="CurveService.Evaluate",)"
    R"(transport="grpc"})";
constexpr char kRefusedWhileDrainingSeries[] =
    R"(freeform_admission_refusals_total{reason="draining"})";
// The most replicas a test runs: 127.0.0.1 to 127.0.0.4.
constexpr int kMostReplicas = 4;

std::string ReplicaHost(int index) {
  return absl::StrCat("127.0.0.", index + 1);
}

std::vector<std::string> ReplicaHosts(const std::vector<int>& indices) {
  std::vector<std::string> hosts;
  for (const int index : indices) hosts.push_back(ReplicaHost(index));
  return hosts;
}

double Seconds(Clock::duration duration) {
  return std::chrono::duration<double>(duration).count();
}

// CallLoad: callers that evaluate a line's midpoint through one client
// until stopped, counting the calls answered right and the others.
class CallLoad {
 public:
  CallLoad(Client* client, int callers) {
    for (int c = 0; c < callers; ++c) {
      threads_.emplace_back([this, client] { Call(client); });
    }
  }
  ~CallLoad() { Stop(); }
  CallLoad(const CallLoad&) = delete;
  CallLoad& operator=(const CallLoad&) = delete;

  void Stop() {
    stop_ = true;
    for (std::thread& thread : threads_) {
      if (thread.joinable()) thread.join();
    }
  }
  int64_t answered() const { return answered_.load(); }
  int64_t failed() const { return failed_.load(); }
  std::string first_failure() const {
    absl::MutexLock lock(&mutex_);
    return first_failure_;
  }

 private:
  void Call(Client* client) {
    while (!stop_) {
      // The midpoint of the line from 0 to 3 is 1.5.
      const absl::StatusOr<CurveSamples> answer =
          client->EvaluateBezier(1, {0.0, 3.0}, {0.5});
      if (answer.ok() && answer->count == 1 && answer->Point(0, 0)[0] == 1.5) {
        ++answered_;
      } else {
        Fail(answer.ok() ? "a wrong answer" : answer.status().ToString());
      }
      std::this_thread::sleep_for(kCallerPause);
    }
  }

  void Fail(const std::string& what) {
    ++failed_;
    absl::MutexLock lock(&mutex_);
    if (first_failure_.empty()) first_failure_ = what;
  }

  std::atomic<bool> stop_{false};
  std::atomic<int64_t> answered_{0};
  std::atomic<int64_t> failed_{0};
  mutable absl::Mutex mutex_;
  std::string first_failure_ ABSL_GUARDED_BY(mutex_);
  std::vector<std::thread> threads_;
};

class ScaleOutTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (Dnsmasq::Binary().empty()) {
      GTEST_SKIP() << "dnsmasq is not installed (scripts/setup.sh installs "
                      "dnsmasq-base)";
    }
    absl::StatusOr<int> port =
        FreePortOnEvery(ReplicaHosts({0, 1, 2, 3}), {SOCK_STREAM});
    ASSERT_TRUE(port.ok()) << port.status();
    port_ = *port;
    for (int r = 0; r < 3; ++r) ASSERT_NO_FATAL_FAILURE(StartReplica(r));
    absl::StatusOr<std::unique_ptr<Dnsmasq>> dns =
        Dnsmasq::Start(kName, ReplicaHosts({0, 1, 2}));
    ASSERT_TRUE(dns.ok()) << dns.status();
    dns_ = *std::move(dns);
    ASSERT_NO_FATAL_FAILURE(StartLoad());
  }

  // StartLoad starts the client and its callers, and returns once every
  // replica of the name has answered a call.
  void StartLoad() {
    absl::StatusOr<std::unique_ptr<Client>> client =
        Client::Create({.target = absl::StrCat("dns://127.0.0.1:", dns_->port(),
                                               "/", kName, ":", port_),
                        .round_robin = true,
                        .min_time_between_resolutions = kResolutionInterval,
                        .timeout = std::chrono::seconds(20)});
    ASSERT_TRUE(client.ok()) << client.status();
    client_ = *std::move(client);
    load_ = std::make_unique<CallLoad>(client_.get(), kCallers);
    for (int r = 0; r < 3; ++r) {
      ASSERT_TRUE(WaitUntilServing(r, Scaled(std::chrono::seconds(10))))
          << ReplicaHost(r) << " got no call";
    }
  }

  void TearDown() override {
    if (load_ != nullptr) load_->Stop();
  }

  // StartReplica starts replica `index` on its own address and the shared
  // port, with its metrics on a port of its own.
  void StartReplica(int index) {
    replicas_[index] = std::make_unique<ServerProcess>(std::vector<std::string>{
        absl::StrCat("--listen=", ReplicaHost(index), ":", port_),
        "--metrics_listen=127.0.0.1:0",
        absl::StrCat("--max_connection_age=", kConnectionAge.count(), "s"),
        "--max_connection_age_grace=5s", "--grace_period=5s",
        "--log_level=warn"});
    ASSERT_EQ(replicas_[index]->port(), port_)
        << ReplicaHost(index) << " did not start";
    ASSERT_GT(replicas_[index]->metrics_port(), 0);
  }

  // What a replica's metrics count.
  struct Counts {
    // Calls answered OK.
    double served = 0;
    // Calls answered UNAVAILABLE because it was draining.
    double refused_while_draining = 0;
  };

  // Scrape returns replica `index`'s counts now, or the last ones read
  // once it no longer answers.
  const Counts& Scrape(int index) {
    if (replicas_[index] != nullptr) {
      absl::StatusOr<std::string> metrics =
          HttpGet(replicas_[index]->metrics_port(), "/metrics");
      if (metrics.ok()) {
        counts_[index] = {
            .served = MetricValue(*metrics, kServedSeries).value_or(0),
            .refused_while_draining =
                MetricValue(*metrics, kRefusedWhileDrainingSeries).value_or(0)};
      }
    }
    return counts_[index];
  }

  double Served(int index) { return Scrape(index).served; }

  // WaitUntilServing polls replica `index` until it has answered a call;
  // false after `limit`.
  bool WaitUntilServing(int index, Clock::duration limit) {
    const Clock::time_point give_up = Clock::now() + limit;
    while (Served(index) == 0) {
      if (Clock::now() >= give_up) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return true;
  }

  // SharesOver returns each replica's share of the calls `indices` answered
  // over the next `window`, in the order of `indices`, and prints them.
  std::vector<double> SharesOver(const std::vector<int>& indices,
                                 std::chrono::milliseconds window,
                                 const std::string& label) {
    std::vector<double> before;
    for (const int index : indices) before.push_back(Served(index));
    std::this_thread::sleep_for(window);
    std::vector<double> calls;
    double total = 0;
    for (size_t i = 0; i < indices.size(); ++i) {
      calls.push_back(Served(indices[i]) - before[i]);
      total += calls.back();
    }
    std::vector<double> shares;
    std::vector<std::string> report;
    for (size_t i = 0; i < indices.size(); ++i) {
      shares.push_back(total > 0 ? calls[i] / total : 0);
      report.push_back(absl::StrCat(ReplicaHost(indices[i]), " ",
                                    std::lround(100 * shares.back()), "% (",
                                    calls[i], ")"));
    }
    std::fprintf(stderr, "scale-out: %s, %g calls in %.1f s: %s\n",
                 label.c_str(), total, Seconds(window),
                 absl::StrJoin(report, ", ").c_str());
    EXPECT_GE(total, 200) << "too few calls to measure shares";
    return shares;
  }

  // ExpectEvenShares expects every share within 10 points of an even split.
  static void ExpectEvenShares(const std::vector<double>& shares) {
    const double even = 1.0 / static_cast<double>(shares.size());
    for (size_t i = 0; i < shares.size(); ++i) {
      EXPECT_NEAR(shares[i], even, 0.10) << "replica " << i;
    }
  }

  void ExpectNoFailedCall() const {
    std::fprintf(stderr, "scale-out: %lld calls answered, %lld failed\n",
                 static_cast<long long>(load_->answered()),
                 static_cast<long long>(load_->failed()));
    EXPECT_EQ(load_->failed(), 0) << load_->first_failure();
  }

  int port_ = 0;
  std::array<std::unique_ptr<ServerProcess>, kMostReplicas> replicas_;
  std::array<Counts, kMostReplicas> counts_;
  std::unique_ptr<Dnsmasq> dns_;
  std::unique_ptr<Client> client_;
  std::unique_ptr<CallLoad> load_;
};

TEST_F(ScaleOutTest, CallsSpreadEvenlyOverThreeReplicas) {
  ExpectEvenShares(
      SharesOver({0, 1, 2}, std::chrono::seconds(3), "three replicas"));
  ExpectNoFailedCall();
}

// The client learns of the new address only when it resolves the name
// again: after the first connection to reach its age (at most 1.1 times
// kConnectionAge after it opened) and at least kResolutionInterval after
// the last resolution. Two seconds more (times FREEFORM_TEST_TIME_SCALE)
// absorb a loaded machine.
TEST_F(ScaleOutTest, AReplicaAddedMidLoadGetsItsShareWithinTheConnectionAge) {
  ASSERT_NO_FATAL_FAILURE(StartReplica(3));
  ASSERT_TRUE(dns_->SetAddresses(ReplicaHosts({0, 1, 2, 3})).ok());
  const Clock::time_point added = Clock::now();
  const Clock::duration limit = kConnectionAge * 11 / 10 + kResolutionInterval +
                                Scaled(std::chrono::seconds(2));
  ASSERT_TRUE(WaitUntilServing(3, limit + std::chrono::seconds(10)))
      << "the new replica got no call";
  const Clock::duration to_traffic = Clock::now() - added;
  std::fprintf(stderr,
               "scale-out: the new replica got its first call %.2f s after "
               "its address was added (connection age %lld s)\n",
               Seconds(to_traffic),
               static_cast<long long>(kConnectionAge.count()));
  EXPECT_LE(to_traffic, limit);
  ExpectEvenShares(SharesOver({0, 1, 2, 3}, std::chrono::seconds(3),
                              "after a fourth replica joined"));
  ExpectNoFailedCall();
}

// The replica's address leaves the name and SIGTERM reaches it at the same
// moment, as when Kubernetes ends a pod (without preStop's pause). Its
// health turns NOT_SERVING, which the client's health check sees, so it
// stops picking the replica; a call that reaches it still is refused
// UNAVAILABLE and retried on another by the client's retry policy.
TEST_F(ScaleOutTest, AReplicaRemovedMidLoadCostsNoFailedCall) {
  const int64_t answered_before = load_->answered();
  ASSERT_TRUE(dns_->SetAddresses(ReplicaHosts({0, 1})).ok());
  const Clock::time_point removed = Clock::now();
  replicas_[2]->Signal(SIGTERM);
  // Scraped until it exits: the calls it refused while draining, each
  // retried on another replica.
  std::optional<int> exit_status;
  while (!(exit_status =
               replicas_[2]->WaitForExit(std::chrono::milliseconds(20))) &&
         Clock::now() - removed < Scaled(std::chrono::seconds(10))) {
    Scrape(2);
  }
  EXPECT_EQ(exit_status, 0);
  const Clock::duration drain = Clock::now() - removed;
  replicas_[2].reset();
  std::fprintf(stderr,
               "scale-out: the removed replica drained in %.2f s, refusing "
               "%g calls (UNAVAILABLE, retried elsewhere)\n",
               Seconds(drain), counts_[2].refused_while_draining);
  ExpectEvenShares(
      SharesOver({0, 1}, std::chrono::seconds(2), "after one was removed"));
  load_->Stop();
  EXPECT_GT(load_->answered() - answered_before, 200);
  ExpectNoFailedCall();
}

}  // namespace
}  // namespace freeform
