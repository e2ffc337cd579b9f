// SIGTERM against the real freeformd: with --grace_period=3s the process
// exits with status 0 within the grace period plus one second, while a
// client is still reading a long stream slowly or keeps an idle channel
// open; and health watchers are told NOT_SERVING once the signal arrives.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "freeform/client.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "server_process.h"

namespace freeform {
namespace {

using std::chrono::milliseconds;
using HealthStatus = grpc::health::v1::HealthCheckResponse;

constexpr auto kGrace = std::chrono::seconds(3);
constexpr auto kExitLimit = kGrace + std::chrono::seconds(1);

// A cubic Bezier curve in 1-D at `count` parameters.
v1::EvaluateCurveRequest CubicAt(uint32_t count) {
  v1::EvaluateCurveRequest request;
  v1::Points* points =
      request.mutable_curve()->mutable_bezier()->mutable_control_points();
  points->set_dimension(1);
  for (double value : {0.0, 1.0, -1.0, 0.5}) points->add_coordinates(value);
  request.mutable_parameters()->mutable_range()->set_count(count);
  return request;
}

class ShutdownTest : public ::testing::Test {
 protected:
  ShutdownTest() : server_({"--grace_period=3s"}) {}

  void SetUp() override {
    ASSERT_GT(server_.port(), 0) << "freeformd did not report its port";
    client_ = NewClient(std::chrono::seconds(60));
    ASSERT_NE(client_, nullptr);
  }

  std::unique_ptr<Client> NewClient(milliseconds timeout) const {
    ClientOptions options;
    options.target = server_.address();
    options.timeout = timeout;
    options.retry_unavailable = false;
    absl::StatusOr<std::unique_ptr<Client>> client = Client::Create(options);
    EXPECT_TRUE(client.ok()) << client.status();
    return client.ok() ? *std::move(client) : nullptr;
  }

  // ExpectExitWithinLimit sends SIGTERM and checks that the process exits
  // with status 0 within kExitLimit of the signal; returns how long it took.
  milliseconds ExpectExitWithinLimit() {
    const auto signalled = std::chrono::steady_clock::now();
    server_.Signal(SIGTERM);
    std::optional<int> status = server_.WaitForExit(kExitLimit);
    const auto took = std::chrono::duration_cast<milliseconds>(
        std::chrono::steady_clock::now() - signalled);
    EXPECT_TRUE(status.has_value())
        << "still running " << took.count() << " ms after SIGTERM";
    if (!status.has_value()) status = server_.WaitForExit(kGrace * 5);
    EXPECT_EQ(status, 0);
    std::fprintf(stderr, "freeformd exited %lld ms after SIGTERM\n",
                 static_cast<long long>(took.count()));
    return took;
  }

  ServerProcess server_;
  std::unique_ptr<Client> client_;
};

// A client reads a stream of 10^7 points (153 chunks) with 100 ms between
// reads, about 15 s in all, and is still reading when the signal comes.
TEST_F(ShutdownTest, ExitsWithinGraceWhileAClientStreamsSlowly) {
  constexpr uint32_t kPoints = 10'000'000;
  std::atomic<int> chunks{0};
  std::atomic<uint64_t> points{0};
  grpc::Status finished;
  std::unique_ptr<grpc::ClientContext> context = client_->NewContext();
  std::thread reader([&] {
    auto stream =
        client_->curves().EvaluateStream(context.get(), CubicAt(kPoints));
    v1::EvaluateCurveResponse chunk;
    while (stream->Read(&chunk)) {
      points += chunk.count();
      ++chunks;
      std::this_thread::sleep_for(milliseconds(100));
    }
    finished = stream->Finish();
  });
  while (chunks < 2) std::this_thread::sleep_for(milliseconds(10));

  ExpectExitWithinLimit();
  reader.join();
  EXPECT_LT(points, kPoints) << "the stream was not cut short";
  EXPECT_FALSE(finished.ok());
}

// A channel stays connected and idle after its stream has finished. gRPC's
// own shutdown would wait out the whole grace period for that connection;
// with no call in flight there is nothing to wait for, so freeformd exits
// at once (measured here: about 50 ms).
TEST_F(ShutdownTest, ExitsAtOnceWithAnIdleChannelOpen) {
  absl::StatusOr<CurveSamples> samples =
      client_->EvaluateCurveStreamed(CubicAt(100'000));
  ASSERT_TRUE(samples.ok()) << samples.status();
  EXPECT_EQ(samples->count, 100'000u);
  ASSERT_EQ(client_->channel()->GetState(/*try_to_connect=*/false),
            GRPC_CHANNEL_READY);

  EXPECT_LT(ExpectExitWithinLimit(), kGrace / 2);
}

// A Health.Watch opened before the signal sees SERVING, then NOT_SERVING
// after it, before the process exits. A Check cannot observe this reliably:
// the listener closes right after health turns NOT_SERVING, so a Check sent
// after the signal mostly finds no server; it must never find SERVING.
TEST_F(ShutdownTest, HealthTurnsNotServingOnTheSignal) {
  auto health = grpc::health::v1::Health::NewStub(client_->channel());
  std::unique_ptr<grpc::ClientContext> context = client_->NewContext();
  auto watch = health->Watch(context.get(), {});
  HealthStatus status;
  ASSERT_TRUE(watch->Read(&status));
  EXPECT_EQ(status.status(), HealthStatus::SERVING);

  const auto signalled = std::chrono::steady_clock::now();
  server_.Signal(SIGTERM);
  ASSERT_TRUE(watch->Read(&status));
  EXPECT_EQ(status.status(), HealthStatus::NOT_SERVING);
  std::unique_ptr<Client> late = NewClient(milliseconds(1000));
  ASSERT_NE(late, nullptr);
  EXPECT_FALSE(late->CheckHealth().ok());

  EXPECT_EQ(server_.WaitForExit(std::chrono::duration_cast<milliseconds>(
                kExitLimit - (std::chrono::steady_clock::now() - signalled))),
            0);
  context->TryCancel();
}

}  // namespace
}  // namespace freeform
