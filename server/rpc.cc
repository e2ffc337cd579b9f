#include "rpc.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/reflection.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "absl/base/casts.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "errors.h"
#include "freeform/core/status.h"
#include "grpc_handoff.h"
#include "spdlog/spdlog.h"

namespace freeform::server {
namespace {

// The call's deadline on the steady clock (gRPC reports it on the system
// clock; an infinite deadline comes back as a far-future time point).
std::optional<CancellationToken::Clock::time_point> SteadyDeadline(
    const grpc::CallbackServerContext& context) {
  const auto deadline = context.deadline();
  if (deadline == std::chrono::system_clock::time_point::max()) {
    return std::nullopt;
  }
  const auto remaining = deadline - std::chrono::system_clock::now();
  if (remaining > std::chrono::hours(24 * 365)) return std::nullopt;
  return CancellationToken::Clock::now() +
         std::chrono::duration_cast<CancellationToken::Clock::duration>(
             remaining);
}

// RetryAttempt returns the attempt number of a call that gRPC's retry
// policy sent again (its grpc-previous-rpc-attempts header counts the
// attempts before it), or 0 for a first attempt.
int RetryAttempt(const grpc::CallbackServerContext& context) {
  const auto& metadata = context.client_metadata();
  const auto header = metadata.find("grpc-previous-rpc-attempts");
  int previous = 0;
  if (header == metadata.end() ||
      !absl::SimpleAtoi(
          absl::string_view(header->second.data(), header->second.size()),
          &previous) ||
      previous < 1) {
    return 0;
  }
  return previous + 1;
}

// LogLevel is the access-log level of a call that ends with `status`.
spdlog::level::level_enum LogLevel(const absl::Status& status) {
  return status.code() == absl::StatusCode::kInternal ? spdlog::level::err
                                                      : spdlog::level::info;
}

// Responses larger than this are freed before their call's reservation.
constexpr size_t kFreeResponseBytes = 1 << 20;

// FreeMessage empties `message` and gives back the memory of its fields
// (Clear keeps their capacity).
void FreeMessage(google::protobuf::Message& message) {
  std::unique_ptr<google::protobuf::Message> empty(message.New());
  message.GetReflection()->Swap(&message, empty.get());
}

// A unary call: plan, reserve, run (inline or on the pool), answer.
class UnaryCall final : public grpc::ServerUnaryReactor {
 public:
  UnaryCall(RpcFrame* frame, absl::string_view method,
            grpc::CallbackServerContext* context,
            const google::protobuf::Message* request,
            google::protobuf::Message* response, UnaryPlanner planner,
            Planning planning)
      : record_(frame, method, context, request, planning),
        response_(response),
        planner_(std::move(planner)) {}

  void Start() {
    if (absl::Status status = record_.CheckNotDraining(); !status.ok()) {
      return Answer(status);
    }
    if (record_.PlanOnPool()) {
      if (!record_.Schedule([this] { PlanAndRun(/*on_pool=*/true); })) {
        Answer(QueueFullError());
      }
      return;
    }
    PlanAndRun(/*on_pool=*/false);
  }

  void OnCancel() override {
    TakeBackFromGrpc(this);
    record_.Cancel();
  }
  void OnDone() override {
    TakeBackFromGrpc(this);
    record_.Done(status_, response_bytes_);
    // gRPC frees the response only after OnDone; free a large one now, so
    // its memory is gone before the reservation is (with this call).
    if (response_bytes_ > kFreeResponseBytes) FreeMessage(*response_);
    delete this;
  }

 private:
  void PlanAndRun(bool on_pool) {
    if (record_.token().IsCancelled()) return Answer(record_.token().status());
    absl::StatusOr<UnaryWork> work =
        record_.Contain([this] { return std::move(planner_)(); });
    if (!work.ok()) return Answer(work.status());
    if (absl::Status status = record_.Reserve(work->plan); !status.ok()) {
      return Answer(status);
    }
    run_ = std::move(work->run);
    if (work->plan.heavy && !on_pool) {
      if (!record_.Schedule([this] { Run(); })) Answer(QueueFullError());
      return;
    }
    Run();
  }

  void Run() {
    Answer(record_.Contain(
        [this] { return std::move(run_)(record_.execution()); }));
  }

  void Answer(absl::Status status) {
    if (status.ok()) status = record_.CheckAnswer(*response_);
    if (status.ok()) response_bytes_ = response_->ByteSizeLong();
    status_ = status;
    HandOffToGrpc(this);  // to OnDone
    Finish(AnswerStatus(status));
  }

  CallRecord record_;
  google::protobuf::Message* const response_;
  UnaryPlanner planner_;
  absl::AnyInvocable<absl::Status(const ExecutionContext&) &&> run_;
  absl::Status status_;
  size_t response_bytes_ = 0;
};

// True when no value of `values` is a NaN or an infinity: an exponent of all
// ones. A branch-free loop the compiler vectorizes.
bool FiniteValues(const double* values, size_t count) {
  constexpr uint64_t kExponent = 0x7ff0000000000000ull;
  uint64_t non_finite = 0;
  for (size_t i = 0; i < count; ++i) {
    const uint64_t bits = absl::bit_cast<uint64_t>(values[i]);
    non_finite |= static_cast<uint64_t>((bits & kExponent) == kExponent);
  }
  return non_finite == 0;
}

// The values of a repeated double field, read without a virtual call per
// value (RepeatedFieldRef has one).
const google::protobuf::RepeatedField<double>& RepeatedDoubles(
    const google::protobuf::Message& message,
    const google::protobuf::FieldDescriptor* field) {
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
  return message.GetReflection()->GetRepeatedField<double>(message, field);
#pragma GCC diagnostic pop
}

}  // namespace

bool AllFinite(const google::protobuf::Message& message) {
  using google::protobuf::FieldDescriptor;
  const google::protobuf::Reflection* reflection = message.GetReflection();
  std::vector<const FieldDescriptor*> fields;
  reflection->ListFields(message, &fields);
  for (const FieldDescriptor* field : fields) {
    if (field->cpp_type() == FieldDescriptor::CPPTYPE_DOUBLE) {
      if (field->is_repeated()) {
        const google::protobuf::RepeatedField<double>& values =
            RepeatedDoubles(message, field);
        if (!FiniteValues(values.data(), values.size())) return false;
      } else if (!std::isfinite(reflection->GetDouble(message, field))) {
        return false;
      }
    } else if (field->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE) {
      if (field->is_repeated()) {
        const int size = reflection->FieldSize(message, field);
        for (int i = 0; i < size; ++i) {
          if (!AllFinite(reflection->GetRepeatedMessage(message, field, i))) {
            return false;
          }
        }
      } else if (!AllFinite(reflection->GetMessage(message, field))) {
        return false;
      }
    }
  }
  return true;
}

CallRecord::CallRecord(RpcFrame* frame, absl::string_view method,
                       grpc::CallbackServerContext* context,
                       const google::protobuf::Message* request,
                       Planning planning)
    : frame_(frame),
      method_(method),
      context_(context),
      request_(request),
      request_bytes_(request->ByteSizeLong()),
      planning_(planning),
      started_(std::chrono::steady_clock::now()),
      origin_(OriginOf(*context)),
      observer_(frame->observer_ == nullptr
                    ? nullptr
                    : &frame->observer_->ForMethod(method, origin_.transport)) {
  WatchCall(*context, frame->limits().max_call_time, token_);
  frame_->calls_in_flight_.fetch_add(1, std::memory_order_acq_rel);
  frame_->calls_started_.fetch_add(1, std::memory_order_acq_rel);
}

CallRecord::~CallRecord() {
  frame_->calls_in_flight_.fetch_sub(1, std::memory_order_acq_rel);
}

ExecutionContext CallRecord::execution() const {
  return {.pool = frame_->pool(),
          .cancellation = &token_,
          .grain = frame_->limits().grain};
}

ExecutionContext CallRecord::chunk_execution() const {
  return {.pool = nullptr,
          .cancellation = &token_,
          .grain = frame_->limits().grain};
}

absl::Status CallRecord::Reserve(const CallPlan& plan) {
  // The request stays in memory for the whole call too, as parsed: its
  // arrays' capacity (parsing grows them by doubling) and its submessages.
  absl::StatusOr<MemoryBudget::Reservation> reservation =
      frame_->budget().Reserve(plan.memory_bytes + request_->SpaceUsedLong(),
                               method_);
  if (!reservation.ok()) {
    Refuse(Refusal::kMemoryBudget);
    return reservation.status();
  }
  reservation_ = *std::move(reservation);
  planned_bytes_ = plan.memory_bytes;
  return absl::OkStatus();
}

absl::Status CallRecord::CheckAnswer(
    const google::protobuf::Message& answer) const {
  if (!AllFinite(answer)) return OverflowError(*request_);
  if (kCheckAnswers) {
    const size_t bytes = answer.ByteSizeLong();
    if (bytes > planned_bytes_) {
      return absl::InternalError(absl::StrCat(
          "the answer of ", bytes, " bytes exceeds the ", planned_bytes_,
          " bytes its plan reserved (a server bug: please report the "
          "request)"));
    }
  }
  return absl::OkStatus();
}

bool CallRecord::PlanOnPool() const {
  return planning_ == Planning::kOnPool ||
         request_bytes_ > kInlinePlanningBytes;
}

absl::Status CallRecord::CheckNotDraining() {
  if (!frame_->draining()) return absl::OkStatus();
  Refuse(Refusal::kDraining);
  return DrainingError();
}

void CallRecord::Refuse(Refusal reason) {
  if (frame_->observer_ != nullptr && !refused_.exchange(true)) {
    frame_->observer_->Refused(reason);
  }
}

void CallRecord::Done(const absl::Status& status, size_t response_bytes) {
  const bool log = spdlog::should_log(LogLevel(status));
  if (observer_ == nullptr && !log) return;
  const auto elapsed = std::chrono::steady_clock::now() - started_;
  if (observer_ != nullptr) {
    observer_->CallDone(status.code(), elapsed, request_bytes_, response_bytes);
  }
  if (log) Log(status, response_bytes, elapsed);
}

void CallRecord::Log(const absl::Status& status, size_t response_bytes,
                     std::chrono::steady_clock::duration elapsed) const {
  const bool failed = !status.ok();
  const auto micros =
      std::chrono::duration_cast<std::chrono::microseconds>(elapsed).count();
  const int attempt = RetryAttempt(*context_);
  spdlog::log(LogLevel(status),
              "rpc method={} transport={} peer={} request_bytes={} "
              "response_bytes={} status={} micros={}{}{}{}{}",
              std::string(method_),
              std::string(TransportName(origin_.transport)), origin_.peer,
              request_bytes_, response_bytes,
              absl::StatusCodeToString(status.code()), micros,
              attempt > 0 ? absl::StrCat(" attempt=", attempt) : "",
              failed ? " error=\"" : "",
              failed ? std::string(status.message()) : std::string(),
              failed ? "\"" : "");
}

size_t RpcFrame::chunks_in_flight() const {
  return std::clamp<size_t>(static_cast<size_t>(pool_->size()) + 1,
                            kMinChunksInFlight, kMaxChunksInFlight);
}

grpc::ServerUnaryReactor* RpcFrame::Unary(
    absl::string_view method, grpc::CallbackServerContext* context,
    const google::protobuf::Message* request,
    google::protobuf::Message* response, UnaryPlanner planner,
    Planning planning) {
  HandOffToGrpc(this);  // to the server's teardown (~FreeformServer)
  auto* call = new UnaryCall(this, method, context, request, response,
                             std::move(planner), planning);
  HandOffToGrpc(call);  // to OnCancel
  call->Start();
  return call;
}

void WatchCall(grpc::CallbackServerContext& context,
               absl::Duration max_call_time, CancellationToken& token) {
  const std::optional<CancellationToken::Clock::time_point> client =
      SteadyDeadline(context);
  if (max_call_time > absl::ZeroDuration()) {
    const auto server = CancellationToken::Clock::now() +
                        absl::ToChronoNanoseconds(max_call_time);
    if (!client.has_value() || server < *client) {
      token.SetDeadline(
          server, absl::StrCat("the call ran for the server's longest call "
                               "time (--max_call_time=",
                               absl::FormatDuration(max_call_time),
                               ") before its work finished; split the "
                               "request, or ask for a higher limit"));
    } else {
      token.SetDeadline(*client);
    }
  } else if (client.has_value()) {
    token.SetDeadline(*client);
  }
  token.SetPoll([&context] { return context.IsCancelled(); });
}

absl::Status HandlerThrew(absl::string_view method, absl::string_view what) {
  spdlog::error(
      "rpc method={} threw: {} (a server bug: the call answers "
      "INTERNAL)",
      std::string(method), std::string(what));
  return absl::InternalError(
      "the server failed on this request (a server bug: please report the "
      "request)");
}

absl::Status DrainingError() {
  return absl::UnavailableError(
      "the server is shutting down; retry on another replica");
}

absl::Status QueueFullError() {
  return absl::ResourceExhaustedError(
      "the server's work queue is full; retry later");
}

std::string GeometryFieldOf(const google::protobuf::Message& request) {
  const google::protobuf::FieldDescriptor* field =
      request.GetDescriptor()->FindFieldByNumber(1);
  if (field == nullptr) return "";
  std::string path = field->name();
  if (field->cpp_type() != google::protobuf::FieldDescriptor::CPPTYPE_MESSAGE ||
      field->is_repeated()) {
    return path;
  }
  const google::protobuf::Message& geometry =
      request.GetReflection()->GetMessage(request, field);
  const google::protobuf::Descriptor* type = geometry.GetDescriptor();
  for (int i = 0; i < type->oneof_decl_count(); ++i) {
    const google::protobuf::FieldDescriptor* kind =
        geometry.GetReflection()->GetOneofFieldDescriptor(geometry,
                                                          type->oneof_decl(i));
    if (kind != nullptr) return absl::StrCat(path, ".", kind->name());
  }
  return path;
}

absl::Status OverflowError(const google::protobuf::Message& request) {
  return InvalidFieldError(
      GeometryFieldOf(request),
      "the answer is not finite in double precision: the values (coordinates, "
      "weights, knot spacing, parameters) are too extreme for this request; "
      "scale the geometry");
}

grpc::Status AnswerStatus(const absl::Status& status) {
  return ToGrpcStatus(status);
}

}  // namespace freeform::server
