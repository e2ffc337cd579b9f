// Drain: SIGTERM reaches freeformd while 64 callers are each in
// a call (every RPC, with evaluation streams of 10^5 to 3 10^5 points so
// the calls take a while). Every call either completes whole, its answer
// checked, or gets UNAVAILABLE before any data; no stream is cut after some
// chunks, no call fails otherwise; freeformd exits 0 within its grace
// period. Each caller stops at its first UNAVAILABLE: the server is gone.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <thread>

#include "../integration/server_process.h"
#include "driver.h"

namespace freeform::reliability {
namespace {

constexpr int kCallers = 64;
constexpr auto kGrace = std::chrono::seconds(30);

TEST(Drain, SigtermFinishesEveryCallInFlightAndRefusesTheRest) {
  ServerProcess server({"--grace_period=30s", "--log_level=warn"});
  ASSERT_GT(server.port(), 0) << "freeformd did not report its port";
  ClientOptions options;
  options.target = server.address();
  options.timeout = std::chrono::seconds(120);
  options.retry_unavailable = false;
  absl::StatusOr<std::unique_ptr<Client>> client = Client::Create(options);
  ASSERT_TRUE(client.ok()) << client.status();

  const std::vector<RpcCase> cases =
      AllCases({.min_points = 100'000, .max_points = 300'000});
  LoadDriver driver(client->get(), &cases, kCallers, LoadSeed());
  // Far longer than the test: the callers end at the server's exit.
  driver.Start(
      {.duration = std::chrono::minutes(5), .stop_on_unavailable = true});

  // Signal once every caller is in a call, after each has made a few.
  const auto give_up =
      std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while ((driver.finished() < 2 * kCallers || driver.in_flight() < kCallers) &&
         std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  const int in_flight = driver.in_flight();
  const int64_t finished_before = driver.finished();
  const auto signalled = std::chrono::steady_clock::now();
  server.Signal(SIGTERM);
  const std::optional<int> status =
      server.WaitForExit(kGrace + std::chrono::seconds(1));
  const auto took = std::chrono::duration_cast<std::chrono::milliseconds>(
      std::chrono::steady_clock::now() - signalled);
  driver.Join();

  const Tally total = driver.Total();
  std::fprintf(stderr,
               "drain: SIGTERM with %d calls in flight (%lld finished "
               "before); %lld calls after it: %lld completed, %lld "
               "UNAVAILABLE; freeformd exited %d after %lld ms\n%s",
               in_flight, static_cast<long long>(finished_before),
               static_cast<long long>(total.calls - finished_before),
               static_cast<long long>(total.answered - finished_before),
               static_cast<long long>(total.unavailable), status.value_or(-1),
               static_cast<long long>(took.count()), driver.Report().c_str());
  EXPECT_EQ(in_flight, kCallers);
  EXPECT_EQ(status, 0);
  EXPECT_EQ(total.cut, 0) << total.first_problem;
  EXPECT_EQ(total.failed, 0) << total.first_problem;
  EXPECT_EQ(total.wrong, 0) << total.first_problem;
  EXPECT_EQ(total.refused, 0);
  EXPECT_EQ(total.answered + total.unavailable, total.calls);
  EXPECT_EQ(total.unavailable, kCallers) << "one per caller, at the end";
  EXPECT_GT(total.answered, finished_before)
      << "no call in flight at the signal completed";
}

}  // namespace
}  // namespace freeform::reliability
