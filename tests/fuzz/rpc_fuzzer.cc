// The libFuzzer harness of every RPC fuzzer: it sends the input bytes, as
// they are, as the serialized request of one method to an in-process
// FreeformServer with small limits, reads
// the whole answer (every message of a stream) and aborts, so libFuzzer
// records the input, when the answer breaks a promise of the service:
// - the status is OK, INVALID_ARGUMENT or RESOURCE_EXHAUSTED, never
//   INTERNAL, UNKNOWN, DEADLINE_EXCEEDED, ...;
// - bytes that are not a valid request get INVALID_ARGUMENT "request is not
//   a valid freeform.v1.<Request>[: ...]" (and valid ones never do);
// - every other INVALID_ARGUMENT and RESOURCE_EXHAUSTED carries a
//   google.rpc.BadRequest whose field violations name a field;
// - an OK answer is one message (a stream: any number) of the response
//   type holding only finite numbers;
// - an OK answer of a query passes its oracle (query_oracles.h): a closest
//   point at its distance, intersection points on both inputs, section
//   vertices on the plane, lengths between a polyline's and the control
//   polygons', ...
// Inputs are mutated by the structure-aware mutator (request_mutator.h)
// through LLVMFuzzerCustomMutator and LLVMFuzzerCustomCrossOver below.
// Two environment variables change that, for the short ctest runs of
// targets whose findings are being fixed elsewhere (tests/fuzz/
// CMakeLists.txt, FREEFORM_FUZZ_OPEN_FINDINGS):
// FREEFORM_FUZZ_MUTATOR=bytes mutates with libFuzzer's byte mutator only,
// and FREEFORM_FUZZ_ORACLES=log prints an oracle's finding, saves its
// input to $FREEFORM_FUZZ_FINDINGS (a folder, when set) and goes on
// instead of aborting.
// One server serves the whole process; calls run one at a time and each
// ends (on the server too) before the next input.
//
// One binary, rpc_fuzzer, serves every RPC: it is run through a link named
// rpc_<Service>_<Method>_fuzzer (tests/fuzz/CMakeLists.txt makes one per
// RPC), and the name says which method it calls.
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "freeform/client.h"
#include "query_oracles.h"
#include "request_mutator.h"
#include "rpc.h"
#include "server.h"

namespace freeform::server {
namespace {

using google::protobuf::Message;
using google::protobuf::MethodDescriptor;

// Each call's deadline. A call of the small limits below takes milliseconds;
// one that reaches the deadline is a finding.
constexpr auto kDeadline = std::chrono::seconds(5);
// How long a call may take to leave the server after its answer; below
// run_fuzzer.sh's -timeout of 25 s, so the harness names the failure.
constexpr auto kIdleWait = std::chrono::seconds(20);

// Limits small enough that every execution takes about a millisecond and
// stays far below libFuzzer's -rss_limit_mb, with chunking and the pool
// still exercised: a grain of 64 makes answers over 256 values heavy
// (plan.h) and a stream chunk of 256 points makes streams of several
// messages. Larger limits only make the same paths slower (a mesh of 2^16
// values took 15 ms under the sanitizers).
ServiceLimits FuzzLimits() {
  ServiceLimits limits;
  limits.max_message_bytes = 4 << 20;
  limits.max_control_points = 1024;
  limits.max_degree = 16;
  limits.max_dimension = 8;
  limits.max_derivative_order = 8;
  limits.max_parameters = 1024;
  limits.max_output_values = 1 << 13;
  limits.grain = 64;
  // Far above what one call of these limits may plan, so a refusal by the
  // budget (which names no field) would be a planning bug.
  limits.memory_budget_bytes = 256 << 20;
  limits.default_stream_chunk = 256;
  // A closest-point call examines at most 256 pieces: a piece of a
  // rational net whose weights defeat the hull bounds took about a
  // millisecond under the sanitizers, one of a degree-9 rational triangle
  // (its 10 x 10 degenerate tensor form) 5 ms, so that 1024 of them took
  // past the 5 s deadline (0.1 s in release); the bound itself is what is
  // checked.
  limits.max_closest_point_pieces = 256;
  // An intersection or section does at most 2^22 units of work, 1/64 of the
  // server's default: the comparison tracing of the fuzz build runs these
  // loops 15 to 50 times slower, and 2^28 units took past the 5 s deadline
  // (a quadtree 0.2 s in release); the bound itself is what is checked.
  limits.max_query_work = uint64_t{1} << 22;
  return limits;
}

// The full method name, e.g. "/freeform.v1.CurveService/Evaluate".
std::string& FuzzMethod() {
  static std::string* const method = new std::string();
  return *method;
}

[[noreturn]] void Fail(absl::string_view what) {
  std::fprintf(stderr, "\n%s: %s\n", FuzzMethod().c_str(),
               std::string(what).c_str());
  std::abort();
}

// MethodOfProgram returns the method a program named
// ".../rpc_<Service>_<Method>_fuzzer" fuzzes.
std::string MethodOfProgram(absl::string_view program) {
  const size_t slash = program.rfind('/');
  if (slash != absl::string_view::npos) program.remove_prefix(slash + 1);
  const absl::string_view prefix = "rpc_", suffix = "_fuzzer";
  const size_t separator = program.find('_', prefix.size());
  if (!absl::StartsWith(program, prefix) || !absl::EndsWith(program, suffix) ||
      separator == absl::string_view::npos ||
      separator + 1 >= program.size() - suffix.size()) {
    Fail(
        absl::StrCat("run rpc_fuzzer as rpc_<Service>_<Method>_fuzzer (a "
                     "link made by the build), not as ",
                     program));
  }
  const absl::string_view service =
      program.substr(prefix.size(), separator - prefix.size());
  const absl::string_view method = program.substr(
      separator + 1, program.size() - suffix.size() - separator - 1);
  return absl::StrCat("/freeform.v1.", service, "/", method);
}

void Check(bool condition, absl::string_view what) {
  if (!condition) Fail(what);
}

bool EnvironmentIs(const char* name, absl::string_view value) {
  const char* set = std::getenv(name);
  return set != nullptr && value == set;
}

// What becomes of an oracle's finding: an abort by default, or with
// FREEFORM_FUZZ_ORACLES=log a line on stderr and the input saved as
// $FREEFORM_FUZZ_FINDINGS/oracle-<hash of the input>.
class OracleFindings {
 public:
  OracleFindings()
      : log_(EnvironmentIs("FREEFORM_FUZZ_ORACLES", "log")),
        folder_(std::getenv("FREEFORM_FUZZ_FINDINGS") != nullptr
                    ? std::getenv("FREEFORM_FUZZ_FINDINGS")
                    : "") {}

  void Report(absl::string_view finding, absl::string_view input) {
    if (!log_) Fail(finding);
    // The first findings only: a run that keeps finding the same wrong
    // answer would otherwise spend its time writing.
    if (++count_ > kMaxLogged) return;
    std::fprintf(stderr, "\n%s: oracle finding %d (logged): %s\n",
                 FuzzMethod().c_str(), count_, std::string(finding).c_str());
    if (folder_.empty()) return;
    const std::string path =
        absl::StrCat(folder_, "/oracle-",
                     absl::Hex(std::hash<std::string_view>()(
                         std::string_view(input.data(), input.size()))));
    if (std::FILE* file = std::fopen(path.c_str(), "wb")) {
      std::fwrite(input.data(), 1, input.size(), file);
      std::fclose(file);
    }
  }

 private:
  static constexpr int kMaxLogged = 200;
  const bool log_;
  const std::string folder_;
  int count_ = 0;
};

std::string Describe(const grpc::Status& status) {
  return absl::StrCat("status ", status.error_code(), " \"",
                      status.error_message(), "\"");
}

std::string ToString(const grpc::ByteBuffer& buffer) {
  std::vector<grpc::Slice> slices;
  Check(buffer.Dump(&slices).ok(), "cannot read an answer's bytes");
  std::string bytes;
  for (const grpc::Slice& slice : slices) {
    bytes.append(reinterpret_cast<const char*>(slice.begin()), slice.size());
  }
  return bytes;
}

// The process's server and the generic client of the fuzzed method.
class Harness {
 public:
  Harness() {
    spdlog::set_level(spdlog::level::err);  // no access log per call
    const absl::string_view name = absl::string_view(FuzzMethod()).substr(1);
    std::string full_name(name);
    full_name[name.find('/')] = '.';
    method_ =
        google::protobuf::DescriptorPool::generated_pool()->FindMethodByName(
            full_name);
    Check(method_ != nullptr, "no such method in freeform.v1");
    google::protobuf::MessageFactory* factory =
        google::protobuf::MessageFactory::generated_factory();
    request_ = factory->GetPrototype(method_->input_type());
    response_ = factory->GetPrototype(method_->output_type());

    ServerOptions options;
    options.listen_address = "127.0.0.1:0";
    options.threads = 2;
    options.limits = FuzzLimits();
    absl::StatusOr<std::unique_ptr<FreeformServer>> server =
        FreeformServer::Start(options);
    Check(server.ok(), server.status().ToString());
    server_ = *std::move(server);
    stub_ = std::make_unique<grpc::GenericStub>(server_->InProcessChannel());
  }

  // The request type of the fuzzed method, for the mutator.
  const Message& request_prototype() const { return *request_; }

  void Run(const uint8_t* data, size_t size) {
    std::vector<std::string> messages;
    const grpc::Status status = Call(data, size, messages);
    WaitUntilServerIdle();
    std::unique_ptr<Message> request(request_->New());
    if (!request->ParseFromArray(data, static_cast<int>(size))) {
      return CheckNotARequest(status, messages);
    }
    switch (status.error_code()) {
      case grpc::StatusCode::OK:
        return CheckAnswer(
            *request, messages,
            absl::string_view(reinterpret_cast<const char*>(data), size));
      case grpc::StatusCode::INVALID_ARGUMENT:
      case grpc::StatusCode::RESOURCE_EXHAUSTED:
        return CheckFieldViolations(status);
      default:
        Fail(absl::StrCat("a valid request got ", Describe(status)));
    }
  }

 private:
  // One call from start to status, on the completion queue, one operation
  // at a time; `messages` receives every answer message.
  grpc::Status Call(const uint8_t* data, size_t size,
                    std::vector<std::string>& messages) {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + kDeadline);
    grpc::Slice slice(data, size);
    const grpc::ByteBuffer request(&slice, 1);
    std::unique_ptr<grpc::GenericClientAsyncReaderWriter> call =
        stub_->PrepareCall(&context, FuzzMethod(), &queue_);
    Check(call != nullptr, "cannot prepare the call");
    call->StartCall(this);
    Await();
    // The write fails when the server has already answered; Finish tells.
    call->WriteLast(request, grpc::WriteOptions(), this);
    Await();
    while (true) {
      grpc::ByteBuffer message;
      call->Read(&message, this);
      if (!Await()) break;
      messages.push_back(ToString(message));
    }
    grpc::Status status;
    call->Finish(&status, this);
    Check(Await(), "Finish did not complete");
    return status;
  }

  // Await waits for the one pending operation and returns its `ok`.
  bool Await() {
    void* tag = nullptr;
    bool ok = false;
    Check(queue_.Next(&tag, &ok), "the completion queue shut down");
    Check(tag == this, "unexpected completion tag");
    return ok;
  }

  // The server may still be releasing a call after its status arrived;
  // the next input starts on an idle server (and its memory budget). The
  // wait is generous (kIdleWait) because a starved machine (long fuzz
  // campaigns run beside builds) can delay the release by seconds; work
  // that goes on after the answer still ends the run.
  void WaitUntilServerIdle() {
    const auto give_up = std::chrono::steady_clock::now() + kIdleWait;
    while (server_->calls_in_flight() != 0) {
      Check(std::chrono::steady_clock::now() < give_up,
            "a call still runs on the server after its answer");
      std::this_thread::sleep_for(std::chrono::microseconds(20));
    }
  }

  void CheckNotARequest(const grpc::Status& status,
                        const std::vector<std::string>& messages) {
    Check(messages.empty(), "bytes that are not a request got an answer");
    const std::string expected = absl::StrCat(
        "request is not a valid ", method_->input_type()->full_name());
    // The message may go on after the type (": its bytes do not parse...").
    const std::string message = status.error_message();
    if (status.error_code() == grpc::StatusCode::INVALID_ARGUMENT &&
        absl::StartsWith(message, expected) &&
        (message.size() == expected.size() ||
         message[expected.size()] == ':')) {
      return;
    }
    Fail(absl::StrCat("bytes that are not a request got ", Describe(status),
                      ", not INVALID_ARGUMENT \"", expected, "\""));
  }

  void CheckFieldViolations(const grpc::Status& status) {
    const std::vector<FieldViolation> violations =
        FieldViolationsOf(FromGrpcStatus(status));
    Check(!violations.empty(),
          absl::StrCat(Describe(status), " carries no field violation"));
    for (const FieldViolation& violation : violations) {
      Check(!violation.field.empty(),
            absl::StrCat(Describe(status), " has a violation without a field"));
    }
  }

  void CheckAnswer(const Message& request,
                   const std::vector<std::string>& messages,
                   absl::string_view input) {
    if (!method_->server_streaming()) {
      Check(messages.size() == 1, absl::StrCat("an OK unary answer of ",
                                               messages.size(), " messages"));
    }
    for (const std::string& bytes : messages) {
      std::unique_ptr<Message> answer(response_->New());
      Check(answer->ParseFromString(bytes),
            absl::StrCat("an OK answer is not a ",
                         method_->output_type()->full_name()));
      Check(AllFinite(*answer),
            "an OK answer holds a value that is not finite");
      if (const std::optional<std::string> wrong = fuzz::CheckQueryAnswer(
              *method_, request, *answer, FuzzLimits())) {
        findings_.Report(*wrong, input);
      }
    }
  }

  const MethodDescriptor* method_ = nullptr;
  const Message* request_ = nullptr;
  const Message* response_ = nullptr;
  std::unique_ptr<FreeformServer> server_;
  std::unique_ptr<grpc::GenericStub> stub_;
  grpc::CompletionQueue queue_;
  OracleFindings findings_;
};

// The harness lives as long as the process (libFuzzer exits without
// unwinding the fuzzing loop).
Harness& TheHarness() {
  static Harness* const harness = new Harness();
  return *harness;
}

}  // namespace
}  // namespace freeform::server

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** argv) {
  freeform::server::FuzzMethod() =
      freeform::server::MethodOfProgram((*argv)[0]);
  freeform::server::TheHarness();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  freeform::server::TheHarness().Run(data, size);
  return 0;
}

// libFuzzer's own byte mutator, for the share of mutations that stay at
// the byte level (request_mutator.h).
extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t max_size);

extern "C" size_t LLVMFuzzerCustomMutator(uint8_t* data, size_t size,
                                          size_t max_size, unsigned int seed) {
  static const bool bytes_only =
      freeform::server::EnvironmentIs("FREEFORM_FUZZ_MUTATOR", "bytes");
  if (bytes_only) return LLVMFuzzerMutate(data, size, max_size);
  return freeform::fuzz::MutateRequest(
      freeform::server::TheHarness().request_prototype(), data, size, max_size,
      seed, &LLVMFuzzerMutate);
}

extern "C" size_t LLVMFuzzerCustomCrossOver(const uint8_t* data1, size_t size1,
                                            const uint8_t* data2, size_t size2,
                                            uint8_t* out, size_t max_out_size,
                                            unsigned int seed) {
  return freeform::fuzz::CrossOverRequests(
      freeform::server::TheHarness().request_prototype(), data1, size1, data2,
      size2, out, max_out_size, seed);
}
