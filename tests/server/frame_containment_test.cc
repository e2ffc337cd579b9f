// The RpcFrame contains whatever a handler's step throws: a unary planner
// or run, a stream's planner, prepare or fill, inline on gRPC's thread or on
// the pool. Each such call answers INTERNAL, leaves the in-flight count,
// gives its reservation back, and the server goes on serving. A test
// CurveService whose steps throw on request (the request's derivative order
// says which) runs on a real gRPC server with the real frame.
#include <grpcpp/create_channel.h>
#include <grpcpp/security/credentials.h>
#include <grpcpp/security/server_credentials.h>
#include <grpcpp/server_builder.h>
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "admission.h"
#include "freeform/core/thread_pool.h"
#include "freeform/v1/curve_service.grpc.pb.h"
#include "rpc.h"

namespace freeform::server {
namespace {

// Which step throws, as the request's derivative_order.
enum Thrower : uint32_t {
  kNone = 0,
  kPlanner = 1,
  kRun = 2,
  kPrepare = 3,
  kFill = 4,
  kRunInParallelLoop = 5,
};

constexpr uint64_t kPlannedBytes = 1 << 20;

void MaybeThrow(const v1::EvaluateCurveRequest& request, Thrower at) {
  if (request.derivative_order() != at) return;
  // The exceptions the standard library raises: a vector's size check and
  // a failed allocation.
  if (request.parameters().list().values_size() == 0) {
    throw std::length_error("vector::_M_default_append");
  }
  throw std::bad_alloc();
}

class ThrowingCurveService final : public v1::CurveService::CallbackService {
 public:
  explicit ThrowingCurveService(RpcFrame* frame) : frame_(frame) {}

  grpc::ServerUnaryReactor* Evaluate(
      grpc::CallbackServerContext* context,
      const v1::EvaluateCurveRequest* request,
      v1::EvaluateCurveResponse* response) override {
    return frame_->Unary(
        "CurveService.Evaluate", context, request, response,
        [request, response]() -> absl::StatusOr<UnaryWork> {
          MaybeThrow(*request, kPlanner);
          return UnaryWork{
              .plan = {.memory_bytes = kPlannedBytes,
                       .heavy = request->parameters().list().values_size() > 1},
              .run = [request, response](const ExecutionContext& execution) {
                MaybeThrow(*request, kRun);
                if (request->derivative_order() == kRunInParallelLoop) {
                  // A chunk that throws on a helper thread of the pool.
                  absl::Status status =
                      ParallelFor(64, {.pool = execution.pool, .grain = 1},
                                  [](size_t begin, size_t) {
                                    if (begin == 63) throw std::bad_alloc();
                                  });
                  if (!status.ok()) return status;
                }
                response->set_dimension(1);
                return absl::OkStatus();
              }};
        });
  }

  grpc::ServerWriteReactor<v1::EvaluateCurveResponse>* EvaluateStream(
      grpc::CallbackServerContext* context,
      const v1::EvaluateCurveRequest* request) override {
    return frame_->Stream<v1::EvaluateCurveResponse>(
        "CurveService.EvaluateStream", context, request,
        [request]() -> absl::StatusOr<StreamWork<v1::EvaluateCurveResponse>> {
          MaybeThrow(*request, kPlanner);
          StreamWork<v1::EvaluateCurveResponse> work{
              .plan = {.memory_bytes = kPlannedBytes, .heavy = true},
              .chunk_count = 4};
          if (request->derivative_order() == kPrepare) {
            work.prepare =
                [request](const ExecutionContext&) -> absl::StatusOr<size_t> {
              MaybeThrow(*request, kPrepare);
              return 4;
            };
          }
          work.fill = [request](size_t chunk, v1::EvaluateCurveResponse& out,
                                const ExecutionContext&) {
            if (chunk == 2) MaybeThrow(*request, kFill);
            out.set_dimension(1);
            return absl::OkStatus();
          };
          return work;
        });
  }

 private:
  RpcFrame* const frame_;
};

class FrameContainmentTest : public ::testing::Test {
 protected:
  void SetUp() override {
    service_ = std::make_unique<ThrowingCurveService>(&frame_);
    grpc::ServerBuilder builder;
    int port = 0;
    builder.AddListeningPort("127.0.0.1:0", grpc::InsecureServerCredentials(),
                             &port);
    builder.RegisterService(service_.get());
    server_ = builder.BuildAndStart();
    ASSERT_NE(server_, nullptr);
    stub_ = v1::CurveService::NewStub(
        grpc::CreateChannel("127.0.0.1:" + std::to_string(port),
                            grpc::InsecureChannelCredentials()));
  }

  void TearDown() override {
    server_->Shutdown();
    server_->Wait();
  }

  static v1::EvaluateCurveRequest Request(Thrower thrower, int values) {
    v1::EvaluateCurveRequest request;
    request.set_derivative_order(thrower);
    for (int i = 0; i < values; ++i)
      request.mutable_parameters()->mutable_list()->add_values(i);
    return request;
  }

  grpc::Status CallUnary(const v1::EvaluateCurveRequest& request) {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() +
                         std::chrono::seconds(30));
    v1::EvaluateCurveResponse response;
    return stub_->Evaluate(&context, request, &response);
  }

  grpc::Status CallStream(const v1::EvaluateCurveRequest& request,
                          int* messages) {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() +
                         std::chrono::seconds(30));
    auto reader = stub_->EvaluateStream(&context, request);
    v1::EvaluateCurveResponse response;
    *messages = 0;
    while (reader->Read(&response)) ++*messages;
    return reader->Finish();
  }

  // The frame's counters settle once the calls' OnDone ran, just after the
  // client saw their status.
  void ExpectSettled() {
    const auto give_up =
        std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while ((frame_.calls_in_flight() != 0 || budget_.in_use() != 0) &&
           std::chrono::steady_clock::now() < give_up) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    EXPECT_EQ(frame_.calls_in_flight(), 0);
    EXPECT_EQ(budget_.in_use(), 0u);
  }

  ThreadPool pool_{2};
  MemoryBudget budget_{uint64_t{1} << 30};
  RpcFrame frame_{&pool_, &budget_, ServiceLimits{}};
  std::unique_ptr<ThrowingCurveService> service_;
  std::unique_ptr<grpc::Server> server_;
  std::unique_ptr<v1::CurveService::Stub> stub_;
};

TEST_F(FrameContainmentTest, UnaryStepsThatThrowAnswerInternal) {
  // One value plans and runs inline on gRPC's thread, two run on the pool;
  // a large request (over kInlinePlanningBytes) plans on the pool.
  const int large = static_cast<int>(kInlinePlanningBytes / 8) + 1;
  for (const int values : {0, 1, 2, large}) {
    for (const Thrower thrower : {kPlanner, kRun, kRunInParallelLoop}) {
      const grpc::Status status = CallUnary(Request(thrower, values));
      EXPECT_EQ(status.error_code(), grpc::StatusCode::INTERNAL)
          << "thrower " << thrower << ", " << values
          << " values: " << status.error_message();
      EXPECT_NE(status.error_message().find("bug: please report"),
                std::string::npos)
          << status.error_message();
      ExpectSettled();
    }
  }
  EXPECT_TRUE(CallUnary(Request(kNone, 2)).ok());
  ExpectSettled();
}

TEST_F(FrameContainmentTest, StreamStepsThatThrowAnswerInternal) {
  for (const Thrower thrower : {kPlanner, kPrepare, kFill}) {
    for (const int values : {0, 1}) {
      int messages = 0;
      const grpc::Status status =
          CallStream(Request(thrower, values), &messages);
      EXPECT_EQ(status.error_code(), grpc::StatusCode::INTERNAL)
          << "thrower " << thrower << ": " << status.error_message();
      // Chunks before the one that threw may have been written, not after.
      EXPECT_LE(messages, 2);
      ExpectSettled();
    }
  }
  int messages = 0;
  EXPECT_TRUE(CallStream(Request(kNone, 1), &messages).ok());
  EXPECT_EQ(messages, 4);
  ExpectSettled();
}

TEST_F(FrameContainmentTest, ManyThrowingCallsLeakNothing) {
  // Each would keep 1 MiB and its in-flight slot if the frame leaked it;
  // 2,000 of them are twice the budget.
  for (int i = 0; i < 2000; ++i) {
    const Thrower thrower = i % 2 == 0 ? kPlanner : kRun;
    ASSERT_EQ(CallUnary(Request(thrower, i % 3)).error_code(),
              grpc::StatusCode::INTERNAL);
  }
  ExpectSettled();
  EXPECT_EQ(budget_.refusals(), 0u);
  EXPECT_TRUE(CallUnary(Request(kNone, 1)).ok());
}

}  // namespace
}  // namespace freeform::server
