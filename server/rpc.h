// RpcFrame: the frame every freeformd RPC runs in, on gRPC's callback API.
//
// A handler only plans: from its request it returns the call's plan (the
// memory its answer and work need, whether the work is heavy) and the work
// itself. The frame does the rest, the same way for every RPC:
//   1. plans on the gRPC thread, or on the pool for a large request;
//   2. reserves the planned memory from the server's one MemoryBudget
//      (RESOURCE_EXHAUSTED at once when it does not fit);
//   3. runs light work inline and heavy work on the thread pool, under a
//      CancellationToken that carries the deadline and client cancellation;
//   4. streams chunk after chunk with compute and transfer overlapped: one
//      chunk per pool thread is computed while an earlier one is written
//      (chunks_in_flight);
//   5. answers with the status (field paths as google.rpc.BadRequest), and
//      writes one access-log line: method, transport (grpc, or http for a
//      call of the HTTP gateway, transport.h), peer, sizes, status,
//      microseconds, and `attempt=N` for a call gRPC's retry policy sent
//      again;
//   6. reports the call and admission's refusals to the server's
//      CallObserver, when it has one (call_observer.h: the metrics).
// Every OK answer (each streamed message too) is checked to be finite: a
// value that overflowed double precision turns the answer into
// INVALID_ARGUMENT on the request's geometry. Debug and sanitizer builds
// also check that the answer fits the memory its plan reserved.
// Thread-safe: one frame serves every call.
#ifndef FREEFORM_SERVER_RPC_H_
#define FREEFORM_SERVER_RPC_H_

#include <google/protobuf/message.h>
#include <grpcpp/server_context.h>
#include <grpcpp/support/server_callback.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/functional/any_invocable.h"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "admission.h"
#include "call_observer.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/thread_pool.h"
#include "grpc_handoff.h"
#include "service_limits.h"
#include "transport.h"

namespace freeform::server {

// What a call needs, decided from its request before any work starts.
struct CallPlan {
  // Peak memory of the call: its answer (counted twice, the message and its
  // serialized copy) plus its working memory.
  uint64_t memory_bytes = 0;
  // Large work runs on the thread pool, small work on the gRPC thread.
  bool heavy = false;
};

// A planned unary call: run() fills the response.
struct UnaryWork {
  CallPlan plan;
  absl::AnyInvocable<absl::Status(const ExecutionContext&) &&> run;
};

// A planned streaming call: prepare() runs once first when set and returns
// the number of chunks (an answer made before it is cut, such as a mesh);
// otherwise there are chunk_count chunks. fill(k, response) writes chunk k
// into a cleared message; fills of different chunks may run at once.
template <typename Response>
struct StreamWork {
  CallPlan plan;
  size_t chunk_count = 0;
  absl::AnyInvocable<absl::StatusOr<size_t>(const ExecutionContext&)> prepare;
  absl::AnyInvocable<absl::Status(size_t, Response&, const ExecutionContext&)>
      fill;
};

// EvenChunks returns the work of a stream of `count` items cut into chunks
// of `chunk`: fill_range(first, last, response, execution) fills items
// [first, last) into one message.
template <typename Response, typename FillRange>
StreamWork<Response> EvenChunks(const CallPlan& plan, size_t count,
                                size_t chunk, FillRange fill_range) {
  return {.plan = plan,
          .chunk_count = (count + chunk - 1) / chunk,
          .prepare = {},
          .fill = [count, chunk, fill_range = std::move(fill_range)](
                      size_t k, Response& response,
                      const ExecutionContext& execution) {
            const size_t first = k * chunk;
            return fill_range(first, std::min(count, first + chunk), response,
                              execution);
          }};
}

using UnaryPlanner = absl::AnyInvocable<absl::StatusOr<UnaryWork>() &&>;
template <typename Response>
using StreamPlanner =
    absl::AnyInvocable<absl::StatusOr<StreamWork<Response>>() &&>;

// Chunks of one stream computed or written at once: one per pool thread
// and one being written, within these bounds.
inline constexpr size_t kMinChunksInFlight = 2;
inline constexpr size_t kMaxChunksInFlight = 17;

class RpcFrame;

// Where a call's planner runs. A planner is cheap (a pass over the request)
// unless the request says otherwise: kByRequestSize plans small requests on
// the gRPC thread and larger ones on the pool; kOnPool always plans on the
// pool, for planners whose work grows with the answer (a mesh within a
// normal-angle limit).
enum class Planning { kByRequestSize, kOnPool };

// The bookkeeping every call shares: token, timing, reservation, log line.
class CallRecord {
 public:
  CallRecord(RpcFrame* frame, absl::string_view method,
             grpc::CallbackServerContext* context,
             const google::protobuf::Message* request, Planning planning);
  ~CallRecord();
  CallRecord(const CallRecord&) = delete;
  CallRecord& operator=(const CallRecord&) = delete;

  RpcFrame& frame() { return *frame_; }
  const CancellationToken& token() const { return token_; }
  ExecutionContext execution() const;
  // The context of one stream chunk: computed on its own pool thread,
  // since the chunks in flight already keep the pool busy.
  ExecutionContext chunk_execution() const;
  size_t request_bytes() const { return request_bytes_; }
  // PlanOnPool says whether the planner runs on the pool.
  bool PlanOnPool() const;
  // Reserve takes the plan's memory from the budget.
  absl::Status Reserve(const CallPlan& plan);
  // CheckAnswer returns INVALID_ARGUMENT on the request's geometry when
  // `answer` holds a NaN or an infinity (OverflowError), and, in debug and
  // sanitizer builds, INTERNAL when it is larger than the reserved plan.
  absl::Status CheckAnswer(const google::protobuf::Message& answer) const;
  // Schedule runs `task` on the pool; false (a refusal) when its queue is
  // full.
  template <typename Task>
  bool Schedule(Task task);
  // CheckNotDraining returns DrainingError (a refusal) when the server
  // drains.
  absl::Status CheckNotDraining();
  void Cancel() { token_.Cancel(); }
  // Contain runs `step` (a planner, a run, a prepare or a fill) and returns
  // its result, or INTERNAL when it throws: an exception never leaves the
  // frame, so the call still answers, leaves the in-flight count and
  // releases its reservation, and the server stays up. The access log
  // names the method and the exception (HandlerThrew).
  template <typename Step>
  auto Contain(Step&& step) const -> decltype(std::forward<Step>(step)());
  // Done reports the call's final status to the observer and writes the
  // access-log line. The reservation is held until the record is
  // destroyed, after the call's messages (declare the record first in a
  // reactor, so it goes last).
  void Done(const absl::Status& status, size_t response_bytes);

 private:
  // Refuse reports the call's refusal, once, to the frame's observer.
  void Refuse(Refusal reason);
  void Log(const absl::Status& status, size_t response_bytes,
           std::chrono::steady_clock::duration elapsed) const;

  RpcFrame* const frame_;
  const absl::string_view method_;
  grpc::CallbackServerContext* const context_;
  const google::protobuf::Message* const request_;
  const size_t request_bytes_;
  const Planning planning_;
  uint64_t planned_bytes_ = 0;
  const std::chrono::steady_clock::time_point started_;
  // The call's transport and the peer the access log names (transport.h).
  const CallOrigin origin_;
  // The method's observer, or null when the frame has none.
  MethodObserver* const observer_;
  std::atomic<bool> refused_{false};
  CancellationToken token_;
  MemoryBudget::Reservation reservation_;
};

class RpcFrame {
 public:
  // `pool`, `budget` and `observer` (null: calls are not reported) must
  // outlive the frame.
  RpcFrame(ThreadPool* pool, MemoryBudget* budget, const ServiceLimits& limits,
           CallObserver* observer = nullptr)
      : pool_(pool), budget_(budget), limits_(limits), observer_(observer) {}

  const ServiceLimits& limits() const { return limits_; }
  ThreadPool* pool() const { return pool_; }
  // chunks_in_flight is how many chunks of one stream exist at once; a
  // stream's plan counts that many chunk messages.
  size_t chunks_in_flight() const;
  // calls_in_flight counts the calls started and not yet done;
  // calls_started every call ever started.
  int64_t calls_in_flight() const {
    return calls_in_flight_.load(std::memory_order_acquire);
  }
  int64_t calls_started() const {
    return calls_started_.load(std::memory_order_acquire);
  }
  // Schedule runs `task` on the pool; false (`task` dropped) when the
  // pool's queue is full.
  template <typename Task>
  bool Schedule(Task task);
  // BeginDrain makes every call that starts from now on fail at once with
  // UNAVAILABLE (DrainingError), before any work: a client retries it on
  // another replica, while the calls already running finish.
  void BeginDrain() { draining_.store(true, std::memory_order_release); }
  bool draining() const { return draining_.load(std::memory_order_acquire); }
  MemoryBudget& budget() const { return *budget_; }

  // Unary serves a unary call whose handler is `planner`.
  grpc::ServerUnaryReactor* Unary(absl::string_view method,
                                  grpc::CallbackServerContext* context,
                                  const google::protobuf::Message* request,
                                  google::protobuf::Message* response,
                                  UnaryPlanner planner,
                                  Planning planning = Planning::kByRequestSize);

  // Stream serves a server-streaming call whose handler is `planner`.
  template <typename Response>
  grpc::ServerWriteReactor<Response>* Stream(
      absl::string_view method, grpc::CallbackServerContext* context,
      const google::protobuf::Message* request, StreamPlanner<Response> planner,
      Planning planning = Planning::kByRequestSize);

 private:
  friend class CallRecord;

  ThreadPool* const pool_;
  MemoryBudget* const budget_;
  const ServiceLimits limits_;
  CallObserver* const observer_;
  std::atomic<int64_t> calls_in_flight_{0};
  std::atomic<int64_t> calls_started_{0};
  std::atomic<bool> draining_{false};
};

// Requests larger than this are planned on the pool, not the gRPC thread.
inline constexpr size_t kInlinePlanningBytes = 64 * 1024;

// WatchCall makes `token` stop at the call's deadline and when the client
// cancels, as every call's own token does: for a planner that does real
// work before the call's token is at hand (PlanMesh with a normal-angle
// limit evaluates the surfaces). The deadline is the client's, or
// `max_call_time` from now when that comes first (ServiceLimits).
void WatchCall(grpc::CallbackServerContext& context,
               absl::Duration max_call_time, CancellationToken& token);

// QueueFullError is the answer to a call whose work the pool's full queue
// refused.
absl::Status QueueFullError();

// DrainingError is the answer to a call that starts while the server
// drains before it stops.
absl::Status DrainingError();

// GeometryFieldOf returns the path of the geometry a request describes: its
// field number 1 (curve, surface, basis, points, polygon, surfaces), with
// the kind chosen in its oneof ("curve.bezier").
std::string GeometryFieldOf(const google::protobuf::Message& request);

// OverflowError is the answer to a request whose result is not finite in
// double precision, on the request's geometry.
absl::Status OverflowError(const google::protobuf::Message& request);

// AllFinite returns true when every double of `message` and of its
// submessages is finite.
bool AllFinite(const google::protobuf::Message& message);

// Debug and sanitizer builds check every OK answer's size against its plan.
#ifdef NDEBUG
inline constexpr bool kCheckAnswers = false;
#else
inline constexpr bool kCheckAnswers = true;
#endif

// AnswerStatus converts a call's final status for the wire, with field-path
// details (errors.h).
grpc::Status AnswerStatus(const absl::Status& status);

// HandlerThrew logs that a step of `method` threw `what` and returns the
// INTERNAL answer of the call.
absl::Status HandlerThrew(absl::string_view method, absl::string_view what);

template <typename Step>
auto CallRecord::Contain(Step&& step) const
    -> decltype(std::forward<Step>(step)()) {
  try {
    return std::forward<Step>(step)();
  } catch (const std::exception& exception) {
    return HandlerThrew(method_, exception.what());
  } catch (...) {
    return HandlerThrew(method_, "an exception of unknown type");
  }
}

template <typename Task>
bool RpcFrame::Schedule(Task task) {
  return pool_->TrySchedule(std::move(task));
}

template <typename Task>
bool CallRecord::Schedule(Task task) {
  if (frame_->Schedule(std::move(task))) return true;
  Refuse(Refusal::kQueueFull);
  return false;
}

// A server-streaming call: compute on the pool overlapped with writes.
template <typename Response>
class StreamCall final : public grpc::ServerWriteReactor<Response> {
 public:
  StreamCall(RpcFrame* frame, absl::string_view method,
             grpc::CallbackServerContext* context,
             const google::protobuf::Message* request,
             StreamPlanner<Response> planner, Planning planning)
      : record_(frame, method, context, request, planning),
        planner_(std::move(planner)),
        slots_(frame->chunks_in_flight()) {}

  void Start() {
    if (absl::Status status = record_.CheckNotDraining(); !status.ok()) {
      return Fail(status);
    }
    if (record_.PlanOnPool()) {
      if (!record_.Schedule([this] { Plan(); })) Fail(QueueFullError());
      return;
    }
    Plan();
  }

  void OnCancel() override {
    TakeBackFromGrpc(this);
    record_.Cancel();
  }
  void OnWriteDone(bool ok) override {
    TakeBackFromGrpc(this);
    std::vector<Action> actions;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      writing_ = false;
      slots_[next_write_ % slots_.size()].state = SlotState::kFree;
      ++next_write_;
      if (!ok && error_.ok()) {
        error_ = absl::CancelledError("the client stopped reading");
      }
      actions = PumpLocked();
    }
    if (!actions.empty()) Execute(std::move(actions));
  }
  void OnDone() override {
    TakeBackFromGrpc(this);
    record_.Done(final_status_, streamed_bytes_);
    delete this;
  }

 private:
  enum class SlotState { kFree, kComputing, kReady };
  struct Slot {
    SlotState state = SlotState::kFree;
    size_t chunk = 0;
    Response message;
  };
  // What to do once the lock is released.
  struct Action {
    enum Kind { kCompute, kWrite, kFinish } kind;
    size_t slot = 0;
  };

  void Plan() {
    absl::StatusOr<StreamWork<Response>> work =
        record_.Contain([this] { return std::move(planner_)(); });
    if (!work.ok()) return Fail(work.status());
    if (absl::Status status = record_.Reserve(work->plan); !status.ok()) {
      return Fail(status);
    }
    work_ = *std::move(work);
    if (!work_.prepare) return Begin();
    if (!record_.Schedule([this] {
          absl::StatusOr<size_t> chunks = record_.Contain(
              [this] { return work_.prepare(record_.execution()); });
          if (!chunks.ok()) return Fail(chunks.status());
          {
            std::lock_guard<std::mutex> lock(mutex_);
            work_.chunk_count = *chunks;
          }
          Begin();
        })) {
      Fail(QueueFullError());
    }
  }

  void Begin() {
    std::vector<Action> actions;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      actions = PumpLocked();
    }
    if (!actions.empty()) Execute(std::move(actions));
  }

  void Fail(const absl::Status& status) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = status;
    }
    Begin();
  }

  // Decides the next steps under the lock.
  std::vector<Action> PumpLocked() {
    std::vector<Action> actions;
    if (finished_) return actions;
    if (error_.ok() && record_.token().IsCancelled()) {
      error_ = record_.token().status();
    }
    while (error_.ok() && next_compute_ < work_.chunk_count &&
           next_compute_ < next_write_ + slots_.size()) {
      const size_t slot = next_compute_ % slots_.size();
      slots_[slot].state = SlotState::kComputing;
      slots_[slot].chunk = next_compute_++;
      ++computing_;
      actions.push_back({Action::kCompute, slot});
    }
    const size_t slot = next_write_ % slots_.size();
    if (error_.ok() && !writing_ && next_write_ < work_.chunk_count &&
        slots_[slot].state == SlotState::kReady &&
        slots_[slot].chunk == next_write_) {
      writing_ = true;
      actions.push_back({Action::kWrite, slot});
    }
    const bool all_written = next_write_ == work_.chunk_count;
    if (!writing_ && computing_ == 0 && (all_written || !error_.ok())) {
      finished_ = true;
      final_status_ = error_;
      actions.push_back({Action::kFinish, 0});
    }
    return actions;
  }

  // Callers run Execute only with actions: once the lock is released,
  // another thread may finish the call and delete it, unless this caller
  // holds a compute or a write (which keep it alive until they complete)
  // or the finish (the last action).
  void Execute(std::vector<Action> actions) {
    for (const Action& action : actions) {
      switch (action.kind) {
        case Action::kCompute:
          if (!record_.Schedule(
                  [this, slot = action.slot] { Compute(slot); })) {
            Computed(action.slot, QueueFullError());
          }
          break;
        case Action::kWrite:
          streamed_bytes_ += slots_[action.slot].message.ByteSizeLong();
          HandOffToGrpc(this);  // to OnWriteDone
          this->StartWrite(&slots_[action.slot].message);
          break;
        case Action::kFinish:
          HandOffToGrpc(this);  // to OnDone
          this->Finish(AnswerStatus(final_status_));
          break;
      }
    }
  }

  void Compute(size_t slot) {
    Response& message = slots_[slot].message;
    message.Clear();
    absl::Status status = record_.Contain([&] {
      return work_.fill(slots_[slot].chunk, message, record_.chunk_execution());
    });
    if (status.ok()) status = record_.CheckAnswer(message);
    Computed(slot, status);
  }

  void Computed(size_t slot, const absl::Status& status) {
    std::vector<Action> actions;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      --computing_;
      if (status.ok()) {
        slots_[slot].state = SlotState::kReady;
      } else if (error_.ok()) {
        error_ = status;
      }
      actions = PumpLocked();
    }
    if (!actions.empty()) Execute(std::move(actions));
  }

  CallRecord record_;
  StreamPlanner<Response> planner_;
  StreamWork<Response> work_;
  std::mutex mutex_;
  std::vector<Slot> slots_;
  size_t next_compute_ = 0;
  size_t next_write_ = 0;
  size_t computing_ = 0;
  bool writing_ = false;
  bool finished_ = false;
  absl::Status error_;
  absl::Status final_status_;
  size_t streamed_bytes_ = 0;
};

template <typename Response>
grpc::ServerWriteReactor<Response>* RpcFrame::Stream(
    absl::string_view method, grpc::CallbackServerContext* context,
    const google::protobuf::Message* request, StreamPlanner<Response> planner,
    Planning planning) {
  HandOffToGrpc(this);  // to the server's teardown (~FreeformServer)
  auto* call = new StreamCall<Response>(this, method, context, request,
                                        std::move(planner), planning);
  HandOffToGrpc(call);  // to OnCancel
  call->Start();
  return call;
}

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_RPC_H_
