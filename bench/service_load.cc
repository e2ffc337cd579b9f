// service_load: one generic gRPC load client for freeformd and for the
// transport baseline (bench/echo/transport_echo_server). Requests are built
// once from the proto messages and serialized; every call then goes through
// grpc::GenericStub with ByteBuffers, so both servers are driven by exactly
// the same client code and freeformd's figures can be given as ratios of the
// bare transport's (scripts/service_ratio.sh does that).
//
//   service_load --target=127.0.0.1:PORT --target_kind=echo|freeform
//                --mode=latency|throughput|stream|unary_bulk|mixed
//                [--iters=N] [--warmup=N] [--seconds=S] [--outstanding=K]
//                [--callers=64] [--cqs=2] [--decode=true] [--max_seconds=S]
//
// latency     S1: sequential unary calls (one small cubic Bezier point),
//             p50/p90/p99 in microseconds after a warm-up.
// throughput  S1: K outstanding async unary calls on one CompletionQueue for
//             --seconds (after one second of warm-up): calls/s, p50/p99.
// stream      S2: 10^6 points by a server-streaming call read to the end,
//             best and median ms over --iters, bytes received.
// unary_bulk  S2: the same 10^6 points as one unary answer.
// mixed       S3 (freeform only): --callers concurrent async callers cycling
//             through a request for every freeformd RPC for --seconds:
//             calls, p50/p99 and errors per RPC, total calls/s.
// S2 answers are decoded into one contiguous xyz array (as an application
// would) unless --decode=false. Exit status 1 if any call failed.
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <memory>
#include <numbers>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "freeform/v1/curve_service.grpc.pb.h"
#include "freeform/v1/surface_service.grpc.pb.h"
#include "transport_echo.grpc.pb.h"
#include "workloads.h"

ABSL_FLAG(std::string, target, "127.0.0.1:50051", "Loopback server address");
ABSL_FLAG(std::string, target_kind, "freeform",
          "echo (transport_echo_server) or freeform (freeformd)");
ABSL_FLAG(std::string, mode, "latency",
          "latency, throughput, stream, unary_bulk or mixed");
ABSL_FLAG(int, iters, 0,
          "Measured calls (0: 10000 for latency, 15 for stream/unary_bulk)");
ABSL_FLAG(int, warmup, -1, "Warm-up calls (-1: 1000 for latency, else 2)");
ABSL_FLAG(double, seconds, 0,
          "Measured time (0: 5 s for throughput, 60 s for mixed)");
ABSL_FLAG(int, outstanding, 16, "throughput: calls in flight");
ABSL_FLAG(std::string, workload, "s1",
          "throughput: s1 (one point per call) or s2 (--points per unary "
          "call: with many outstanding, a burst of maximal calls that "
          "exercises admission; RESOURCE_EXHAUSTED counts as refused)");
ABSL_FLAG(int, callers, 64, "mixed: concurrent callers");
ABSL_FLAG(int, cqs, 2, "mixed: completion queues, one thread each (1-4)");
ABSL_FLAG(bool, decode, true, "Parse S2 answers into one xyz array");
ABSL_FLAG(int, points, 1'000'000, "S2: points per call");
ABSL_FLAG(int, chunk_points, 65536, "S2 stream: points per message");
ABSL_FLAG(double, max_seconds, 300, "Hard bound on the run of any mode");

namespace {

namespace v1 = freeform::v1;
namespace echo = freeform::bench::echo;
using Clock = std::chrono::steady_clock;
using Coordinates = google::protobuf::RepeatedField<double>;

constexpr int kMaxReceiveBytes = 256 << 20;
constexpr int kMaxStreamMessages = 1'000'000;

// ------------------------------------------------------------- utilities --

std::chrono::system_clock::time_point DeadlineIn(double seconds) {
  return std::chrono::system_clock::now() +
         std::chrono::microseconds(static_cast<long>(seconds * 1e6));
}

Clock::time_point ClockIn(double seconds) {
  return Clock::now() +
         std::chrono::microseconds(static_cast<long>(seconds * 1e6));
}

double MicrosSince(Clock::time_point start) {
  return std::chrono::duration<double, std::micro>(Clock::now() - start)
      .count();
}

// Nearest-rank percentile (fraction in [0, 1]); 0 for no values.
double Percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const double rank = std::ceil(fraction * static_cast<double>(values.size()));
  const size_t index = rank < 1 ? 0 : static_cast<size_t>(rank) - 1;
  return values[std::min(index, values.size() - 1)];
}

grpc::ByteBuffer Serialize(const google::protobuf::MessageLite& message) {
  grpc::Slice slice(message.SerializeAsString());
  return grpc::ByteBuffer(&slice, 1);
}

std::string MethodPath(const char* service, const char* method) {
  return std::string("/") + service + "/" + method;
}

int Iters(int mode_default) {
  const int iters = absl::GetFlag(FLAGS_iters);
  return iters > 0 ? iters : mode_default;
}

int Warmup(int mode_default) {
  const int warmup = absl::GetFlag(FLAGS_warmup);
  return warmup >= 0 ? warmup : mode_default;
}

double Seconds(double mode_default) {
  const double seconds = absl::GetFlag(FLAGS_seconds);
  return std::min(seconds > 0 ? seconds : mode_default,
                  absl::GetFlag(FLAGS_max_seconds));
}

grpc::Status MissingPoints() {
  return grpc::Status(grpc::StatusCode::DATA_LOSS,
                      "the answer does not hold the expected points");
}

// Shuts a completion queue down and takes its remaining events.
void Drain(grpc::CompletionQueue* cq) {
  cq->Shutdown();
  void* tag = nullptr;
  bool ok = false;
  while (cq->Next(&tag, &ok)) {
  }
}

void ReportError(const grpc::Status& status, long failures) {
  if (failures == 1) {
    std::fprintf(stderr, "call failed: code %d: %s\n", status.error_code(),
                 status.error_message().c_str());
  }
}

// --------------------------------------------------------------- decoding --

const Coordinates* PointsOf(const echo::EvalResponse& message) {
  return &message.xyz();
}
const Coordinates* PointsOf(const echo::PointsResponse& message) {
  return &message.xyz();
}
const Coordinates* PointsOf(const v1::EvaluateCurveResponse& message) {
  if (message.dimension() != 3 || message.derivatives_size() == 0) {
    return nullptr;
  }
  return &message.derivatives(0).coordinates();
}

// Decodes answers into one contiguous xyz array, keeping the parsed message
// and the array's capacity from call to call (the same for both servers).
class PointDecoder {
 public:
  virtual ~PointDecoder() = default;
  void Reset() { xyz_.clear(); }
  // Parses one message and appends its points; false if it does not parse
  // or holds no 3D points. Consumes the buffer.
  virtual bool Append(grpc::ByteBuffer* buffer) = 0;
  size_t points() const { return xyz_.size() / 3; }
  double Checksum() const {
    double sum = 0;
    for (const double value : xyz_) sum += value;
    return sum;
  }

 protected:
  std::vector<double> xyz_;
};

template <typename Message>
class ProtoPointDecoder final : public PointDecoder {
 public:
  bool Append(grpc::ByteBuffer* buffer) override {
    if (!grpc::SerializationTraits<Message>::Deserialize(buffer, &message_)
             .ok()) {
      return false;
    }
    const Coordinates* xyz = PointsOf(message_);
    if (xyz == nullptr) return false;
    xyz_.insert(xyz_.end(), xyz->begin(), xyz->end());
    return true;
  }

 private:
  Message message_;
};

// ------------------------------------------------------------- workloads --

// One call shape of S1 or S2: method, serialized request, how to decode the
// answer and how many points it must hold.
struct Workload {
  std::string method;
  grpc::ByteBuffer request;
  std::unique_ptr<PointDecoder> decoder;
  size_t points = 0;
};

constexpr double kCubic[12] = {0, 0, 0, 1, 2, 0, 3, 2, 1, 4, 0, 1};

void AddValues(std::initializer_list<double> values, Coordinates* field) {
  field->Add(values.begin(), values.end());
}

void SetPoints(const std::vector<double>& xyz, v1::Points* points) {
  points->set_dimension(3);
  points->mutable_coordinates()->Add(xyz.begin(), xyz.end());
}

v1::Curve CubicBezier() {
  v1::Curve curve;
  SetPoints({std::begin(kCubic), std::end(kCubic)},
            curve.mutable_bezier()->mutable_control_points());
  return curve;
}

// Cubic clamped B-spline with `count` control points from LCG `seed`, clamped
// uniform knots (W1 is count 100, seed 1).
v1::Curve BSplineCurve(int count, uint64_t seed) {
  v1::Curve curve;
  v1::BSplineCurve* bspline = curve.mutable_bspline();
  bspline->set_degree(3);
  SetPoints(freeform::bench::RandomPoints(seed, static_cast<size_t>(count), 3),
            bspline->mutable_control_points());
  const std::vector<double> knots =
      freeform::bench::ClampedUniformKnots(count, 3);
  bspline->mutable_knots()->Add(knots.begin(), knots.end());
  return curve;
}

void SetRange(uint32_t count, v1::Parameters* parameters) {
  v1::UniformRange* range = parameters->mutable_range();
  range->set_start(0.0);
  range->set_end(1.0);
  range->set_count(count);
}

Workload EchoS1() {
  echo::EvalRequest request;
  request.mutable_control_points()->Add(std::begin(kCubic), std::end(kCubic));
  request.add_params(0.37);
  request.set_degree(3);
  return {MethodPath(echo::TransportEcho::service_full_name(), "Eval"),
          Serialize(request),
          std::make_unique<ProtoPointDecoder<echo::EvalResponse>>(), 1};
}

Workload FreeformS1() {
  v1::EvaluateCurveRequest request;
  *request.mutable_curve() = CubicBezier();
  request.mutable_parameters()->mutable_list()->add_values(0.37);
  return {MethodPath(v1::CurveService::service_full_name(), "Evaluate"),
          Serialize(request),
          std::make_unique<ProtoPointDecoder<v1::EvaluateCurveResponse>>(), 1};
}

// chunk_points 0: the unary form.
Workload EchoS2(uint32_t points, uint32_t chunk_points) {
  echo::BulkRequest request;
  request.set_num_points(points);
  request.set_chunk_points(chunk_points);
  const char* method = chunk_points ? "BulkPointsStream" : "BulkPoints";
  return {MethodPath(echo::TransportEcho::service_full_name(), method),
          Serialize(request),
          std::make_unique<ProtoPointDecoder<echo::PointsResponse>>(), points};
}

Workload FreeformS2(uint32_t points, uint32_t chunk_points) {
  v1::EvaluateCurveRequest request;
  *request.mutable_curve() = BSplineCurve(100, 1);
  SetRange(points, request.mutable_parameters());
  request.set_chunk_size(chunk_points);
  const char* method = chunk_points ? "EvaluateStream" : "Evaluate";
  return {MethodPath(v1::CurveService::service_full_name(), method),
          Serialize(request),
          std::make_unique<ProtoPointDecoder<v1::EvaluateCurveResponse>>(),
          points};
}

Workload SelectWorkload(bool echo_kind, const std::string& mode) {
  const bool bulk_throughput =
      mode == "throughput" && absl::GetFlag(FLAGS_workload) == "s2";
  if (mode == "latency" || (mode == "throughput" && !bulk_throughput)) {
    return echo_kind ? EchoS1() : FreeformS1();
  }
  const auto points = static_cast<uint32_t>(
      std::clamp(absl::GetFlag(FLAGS_points), 1, 1 << 24));
  const auto chunk = static_cast<uint32_t>(
      mode == "stream"
          ? std::clamp(absl::GetFlag(FLAGS_chunk_points), 1, 1 << 24)
          : 0);
  return echo_kind ? EchoS2(points, chunk) : FreeformS2(points, chunk);
}

// -------------------------------------------- one call at a time (S1, S2) --

// A generic stub and a completion queue for calls made one after the other.
class SequentialCaller {
 public:
  explicit SequentialCaller(const std::shared_ptr<grpc::Channel>& channel)
      : stub_(channel) {}
  ~SequentialCaller() { Drain(&cq_); }

  grpc::Status Unary(const Workload& workload, grpc::ByteBuffer* response) {
    grpc::ClientContext context;
    context.set_deadline(DeadlineIn(60));
    grpc::Status status;
    auto call = stub_.PrepareUnaryCall(&context, workload.method,
                                       workload.request, &cq_);
    call->StartCall();
    call->Finish(response, &status, this);
    Wait();
    return status;
  }

  // Reads the whole answer, handing each message to on_message (which may
  // consume it); bytes receives the total size of the messages.
  template <typename OnMessage>
  grpc::Status Stream(const Workload& workload, size_t* bytes,
                      OnMessage on_message) {
    grpc::ClientContext context;
    context.set_deadline(DeadlineIn(60));
    auto call = stub_.PrepareCall(&context, workload.method, &cq_);
    call->StartCall(this);
    if (Wait()) {
      call->WriteLast(workload.request, grpc::WriteOptions(), this);
      Wait();
    }
    ReadAll(call.get(), bytes, on_message);
    grpc::Status status;
    call->Finish(&status, this);
    Wait();
    return status;
  }

 private:
  template <typename OnMessage>
  void ReadAll(grpc::GenericClientAsyncReaderWriter* call, size_t* bytes,
               OnMessage& on_message) {
    *bytes = 0;
    for (int i = 0; i < kMaxStreamMessages; ++i) {
      grpc::ByteBuffer message;
      call->Read(&message, this);
      if (!Wait()) return;
      *bytes += message.Length();
      on_message(&message);
    }
  }

  bool Wait() {
    void* tag = nullptr;
    bool ok = false;
    return cq_.Next(&tag, &ok) && ok;
  }

  grpc::GenericStub stub_;
  grpc::CompletionQueue cq_;
};

// Decodes one unary answer; false unless it holds the expected points.
bool DecodeUnary(Workload& workload, grpc::ByteBuffer* response) {
  workload.decoder->Reset();
  return workload.decoder->Append(response) &&
         workload.decoder->points() == workload.points;
}

int RunLatency(const std::shared_ptr<grpc::Channel>& channel,
               Workload& workload) {
  SequentialCaller caller(channel);
  const int iters = Iters(10000);
  const int warmup = Warmup(1000);
  const Clock::time_point hard_end = ClockIn(absl::GetFlag(FLAGS_max_seconds));
  std::vector<double> micros;
  long failures = 0;
  for (int i = 0; i < warmup + iters && Clock::now() < hard_end; ++i) {
    const Clock::time_point start = Clock::now();
    grpc::ByteBuffer response;
    grpc::Status status = caller.Unary(workload, &response);
    if (status.ok() && !DecodeUnary(workload, &response)) {
      status = MissingPoints();
    }
    const double elapsed = MicrosSince(start);
    if (!status.ok()) {
      ReportError(status, ++failures);
    } else if (i >= warmup) {
      micros.push_back(elapsed);
    }
  }
  std::printf(
      "latency calls=%zu p50_us=%.1f p90_us=%.1f p99_us=%.1f failures=%ld\n",
      micros.size(), Percentile(micros, 0.5), Percentile(micros, 0.9),
      Percentile(micros, 0.99), failures);
  return failures || micros.empty() ? 1 : 0;
}

// Times one S2 call end to end, decoding included (millis, bytes).
grpc::Status TimeBulkCall(SequentialCaller& caller, Workload& workload,
                          bool streamed, double* millis, size_t* bytes) {
  const bool decode = absl::GetFlag(FLAGS_decode);
  workload.decoder->Reset();
  bool parsed = true;
  const Clock::time_point start = Clock::now();
  grpc::Status status;
  if (streamed) {
    status = caller.Stream(workload, bytes, [&](grpc::ByteBuffer* message) {
      if (decode) parsed = workload.decoder->Append(message) && parsed;
    });
  } else {
    grpc::ByteBuffer response;
    status = caller.Unary(workload, &response);
    *bytes = response.Length();
    if (decode && status.ok()) parsed = workload.decoder->Append(&response);
  }
  *millis = MicrosSince(start) / 1000;
  const bool complete =
      !decode || (parsed && workload.decoder->points() == workload.points);
  if (status.ok() && !complete) return MissingPoints();
  return status;
}

int RunBulk(const std::shared_ptr<grpc::Channel>& channel, Workload& workload,
            const std::string& mode) {
  SequentialCaller caller(channel);
  const int iters = Iters(15);
  const int warmup = Warmup(2);
  const Clock::time_point hard_end = ClockIn(absl::GetFlag(FLAGS_max_seconds));
  std::vector<double> millis;
  long failures = 0;
  size_t bytes = 0;
  for (int i = 0; i < warmup + iters && Clock::now() < hard_end; ++i) {
    double elapsed = 0;
    const grpc::Status status =
        TimeBulkCall(caller, workload, mode == "stream", &elapsed, &bytes);
    if (!status.ok()) {
      ReportError(status, ++failures);
      if (failures >= 3) break;
    } else if (i >= warmup) {
      millis.push_back(elapsed);
    }
  }
  std::printf(
      "%s calls=%zu best_ms=%.2f p50_ms=%.2f bytes=%zu points=%zu "
      "checksum=%.6f failures=%ld\n",
      mode.c_str(), millis.size(), Percentile(millis, 0),
      Percentile(millis, 0.5), bytes, workload.decoder->points(),
      workload.decoder->Checksum(), failures);
  return failures || millis.empty() ? 1 : 0;
}

// ------------------------------------------ K outstanding calls (S1 load) --

struct AsyncSlot {
  std::unique_ptr<grpc::ClientContext> context;
  std::unique_ptr<grpc::GenericClientAsyncResponseReader> call;
  grpc::ByteBuffer response;
  grpc::Status status;
  Clock::time_point start;
};

void Launch(grpc::GenericStub& stub, grpc::CompletionQueue& cq,
            const Workload& workload, AsyncSlot* slot) {
  slot->call.reset();  // lives in the old context's call: drop it first
  slot->context = std::make_unique<grpc::ClientContext>();
  slot->context->set_deadline(DeadlineIn(10));
  slot->response.Clear();
  slot->start = Clock::now();
  slot->call = stub.PrepareUnaryCall(slot->context.get(), workload.method,
                                     workload.request, &cq);
  slot->call->StartCall();
  slot->call->Finish(&slot->response, &slot->status, slot);
}

int RunThroughput(const std::shared_ptr<grpc::Channel>& channel,
                  Workload& workload) {
  grpc::GenericStub stub(channel);
  grpc::CompletionQueue cq;
  const int outstanding = std::clamp(absl::GetFlag(FLAGS_outstanding), 1, 1024);
  const double seconds = Seconds(5.0);
  const Clock::time_point window_start = ClockIn(1.0);
  const Clock::time_point window_end = ClockIn(1.0 + seconds);
  std::vector<AsyncSlot> slots(static_cast<size_t>(outstanding));
  for (AsyncSlot& slot : slots) Launch(stub, cq, workload, &slot);
  long live = outstanding, done = 0, failures = 0, refused = 0;
  std::vector<double> micros;
  // Bounded: no call starts after window_end and each has a 10 s deadline.
  while (live > 0) {
    void* tag = nullptr;
    bool ok = false;
    if (!cq.Next(&tag, &ok)) break;
    --live;
    auto* slot = static_cast<AsyncSlot*>(tag);
    const Clock::time_point now = Clock::now();
    if (slot->status.ok() && !DecodeUnary(workload, &slot->response)) {
      slot->status = MissingPoints();
    }
    const bool good = slot->status.ok();
    if (slot->status.error_code() == grpc::StatusCode::RESOURCE_EXHAUSTED) {
      ++refused;
    } else if (!good) {
      ReportError(slot->status, ++failures);
    }
    if (good && now >= window_start && now < window_end) {
      ++done;
      micros.push_back(MicrosSince(slot->start));
    }
    if (now < window_end) {
      Launch(stub, cq, workload, slot);
      ++live;
    }
  }
  Drain(&cq);
  std::printf(
      "throughput outstanding=%d seconds=%.1f calls_per_s=%.0f p50_us=%.1f "
      "p99_us=%.1f refused=%ld failures=%ld\n",
      outstanding, seconds, static_cast<double>(done) / seconds,
      Percentile(micros, 0.5), Percentile(micros, 0.99), refused, failures);
  return failures || done == 0 ? 1 : 0;
}

// ------------------------------------------------ mixed load (S3) requests --

// One freeformd RPC of the mixed load.
struct RpcSpec {
  std::string name;
  std::string method;
  bool streaming = false;
  grpc::ByteBuffer request;
};

// A smooth bumpy sheet over [0,1]^2: count_u x count_v points.
v1::ControlNet BumpyNet(uint32_t count_u, uint32_t count_v) {
  v1::ControlNet net;
  net.set_dimension(3);
  net.set_count_u(count_u);
  net.set_count_v(count_v);
  for (uint32_t i = 0; i < count_u; ++i) {
    for (uint32_t j = 0; j < count_v; ++j) {
      const double u = static_cast<double>(i) / (count_u - 1);
      const double v = static_cast<double>(j) / (count_v - 1);
      net.add_coordinates(u);
      net.add_coordinates(v);
      net.add_coordinates(0.3 * std::sin(3 * u) * std::cos(2 * v));
    }
  }
  return net;
}

v1::Surface BezierPatch() {
  v1::Surface surface;
  *surface.mutable_bezier()->mutable_control_net() = BumpyNet(4, 4);
  return surface;
}

// Bicubic clamped B-spline surface with count x count control points.
v1::Surface BSplinePatch(int count) {
  v1::Surface surface;
  v1::BSplineSurface* bspline = surface.mutable_bspline();
  bspline->set_degree_u(3);
  bspline->set_degree_v(3);
  const auto n = static_cast<uint32_t>(count);
  *bspline->mutable_control_net() = BumpyNet(n, n);
  const std::vector<double> knots =
      freeform::bench::ClampedUniformKnots(count, 3);
  bspline->mutable_knots_u()->Add(knots.begin(), knots.end());
  bspline->mutable_knots_v()->Add(knots.begin(), knots.end());
  return surface;
}

void SetGrid(uint32_t count, v1::SurfaceParameters* parameters) {
  SetRange(count, parameters->mutable_grid()->mutable_u());
  SetRange(count, parameters->mutable_grid()->mutable_v());
}

// Points on a rising spiral, the data of the interpolation requests.
std::vector<double> Helix(int count) {
  std::vector<double> xyz;
  for (int i = 0; i < count; ++i) {
    const double a = 0.2 * i;
    xyz.insert(xyz.end(), {std::cos(a), std::sin(a), 0.05 * i});
  }
  return xyz;
}

// A closed 3D polygon of `count` points.
std::vector<double> Polygon(int count) {
  std::vector<double> xyz;
  for (int i = 0; i < count; ++i) {
    const double a = 2 * std::numbers::pi * i / count;
    xyz.insert(xyz.end(), {std::cos(a), std::sin(a), 0.2 * (i % 2)});
  }
  return xyz;
}

RpcSpec CurveRpc(const char* name, const google::protobuf::MessageLite& request,
                 bool streaming = false) {
  return {std::string("Curve.") + name,
          MethodPath(v1::CurveService::service_full_name(), name), streaming,
          Serialize(request)};
}

RpcSpec SurfaceRpc(const char* name,
                   const google::protobuf::MessageLite& request,
                   bool streaming = false) {
  return {std::string("Surface.") + name,
          MethodPath(v1::SurfaceService::service_full_name(), name), streaming,
          Serialize(request)};
}

v1::EvaluateCurveRequest CurveEvaluate(bool streamed) {
  v1::EvaluateCurveRequest request;
  if (streamed) {
    *request.mutable_curve() = BSplineCurve(20, 5);
    SetRange(4096, request.mutable_parameters());
    request.set_chunk_size(1024);
  } else {
    *request.mutable_curve() = CubicBezier();
    SetRange(64, request.mutable_parameters());
    request.set_derivative_order(1);
  }
  return request;
}

v1::EvaluateBasisRequest CurveBasis() {
  v1::EvaluateBasisRequest request;
  v1::BSplineBasis* basis = request.mutable_basis()->mutable_bspline();
  basis->set_degree(3);
  const std::vector<double> knots = freeform::bench::ClampedUniformKnots(10, 3);
  basis->mutable_knots()->Add(knots.begin(), knots.end());
  SetRange(64, request.mutable_parameters());
  request.set_derivative_order(1);
  return request;
}

v1::SplitCurveRequest CurveSplit() {
  v1::SplitCurveRequest request;
  *request.mutable_curve() = CubicBezier();
  AddValues({0.25, 0.5, 0.75}, request.mutable_parameters());
  return request;
}

v1::InsertKnotsRequest CurveInsertKnots() {
  v1::InsertKnotsRequest request;
  *request.mutable_curve() = BSplineCurve(20, 5);
  AddValues({0.3, 0.5, 0.5, 0.7}, request.mutable_knots());
  return request;
}

v1::DecomposeCurveRequest CurveDecompose() {
  v1::DecomposeCurveRequest request;
  *request.mutable_curve() = BSplineCurve(20, 5);
  return request;
}

v1::SubdivideRequest CurveSubdivide() {
  v1::SubdivideRequest request;
  SetPoints(Polygon(16), request.mutable_polygon());
  request.set_closed(true);
  request.set_scheme(v1::SUBDIVISION_SCHEME_CHAIKIN);
  request.set_levels(3);
  return request;
}

v1::TessellateCurveRequest CurveTessellate() {
  v1::TessellateCurveRequest request;
  *request.mutable_curve() = BSplineCurve(20, 5);
  request.set_tolerance(1e-3);
  return request;
}

v1::ElevateCurveDegreeRequest CurveElevate() {
  v1::ElevateCurveDegreeRequest request;
  *request.mutable_curve() = BSplineCurve(20, 5);
  request.set_by(1);
  return request;
}

v1::ReduceCurveDegreeRequest CurveReduce() {
  v1::ReduceCurveDegreeRequest request;
  SetPoints(
      freeform::bench::RandomPoints(6, 6, 3),
      request.mutable_curve()->mutable_bezier()->mutable_control_points());
  request.set_by(1);
  return request;
}

v1::InterpolateCurveRequest CurveInterpolate() {
  v1::InterpolateCurveRequest request;
  SetPoints(Helix(100), request.mutable_points());
  request.mutable_bspline()->set_degree(3);
  return request;
}

std::vector<RpcSpec> CurveSpecs() {
  std::vector<RpcSpec> specs;
  specs.push_back(CurveRpc("Evaluate", CurveEvaluate(false)));
  specs.push_back(CurveRpc("EvaluateStream", CurveEvaluate(true), true));
  specs.push_back(CurveRpc("EvaluateBasis", CurveBasis()));
  specs.push_back(CurveRpc("Split", CurveSplit()));
  specs.push_back(CurveRpc("InsertKnots", CurveInsertKnots()));
  specs.push_back(CurveRpc("Decompose", CurveDecompose()));
  specs.push_back(CurveRpc("Subdivide", CurveSubdivide()));
  specs.push_back(CurveRpc("Tessellate", CurveTessellate()));
  specs.push_back(CurveRpc("ElevateDegree", CurveElevate()));
  specs.push_back(CurveRpc("ReduceDegree", CurveReduce()));
  specs.push_back(CurveRpc("Interpolate", CurveInterpolate()));
  return specs;
}

v1::EvaluateSurfaceRequest SurfaceEvaluate(bool streamed) {
  v1::EvaluateSurfaceRequest request;
  if (streamed) {
    *request.mutable_surface() = BSplinePatch(8);
    SetGrid(64, request.mutable_parameters());
    request.set_chunk_size(1024);
  } else {
    *request.mutable_surface() = BezierPatch();
    SetGrid(16, request.mutable_parameters());
    request.set_derivative_order(1);
    request.set_normals(true);
  }
  return request;
}

v1::EvaluateSurfaceBasisRequest SurfaceBasis() {
  v1::EvaluateSurfaceBasisRequest request;
  v1::TensorBasis* tensor = request.mutable_tensor();
  tensor->mutable_u()->mutable_bernstein()->set_degree(3);
  v1::BSplineBasis* v = tensor->mutable_v()->mutable_bspline();
  v->set_degree(2);
  const std::vector<double> knots = freeform::bench::ClampedUniformKnots(6, 2);
  v->mutable_knots()->Add(knots.begin(), knots.end());
  SetGrid(8, request.mutable_parameters());
  return request;
}

v1::SplitSurfaceRequest SurfaceSplit() {
  v1::SplitSurfaceRequest request;
  *request.mutable_surface() = BezierPatch();
  request.set_direction(v1::SURFACE_DIRECTION_U);
  request.set_parameter(0.4);
  return request;
}

v1::InsertSurfaceKnotsRequest SurfaceInsertKnots() {
  v1::InsertSurfaceKnotsRequest request;
  *request.mutable_surface() = BSplinePatch(8);
  request.set_direction(v1::SURFACE_DIRECTION_V);
  AddValues({0.3, 0.7}, request.mutable_knots());
  return request;
}

v1::TessellateSurfaceRequest SurfaceTessellate(bool streamed) {
  v1::TessellateSurfaceRequest request;
  *request.add_surfaces() = BezierPatch();
  request.set_tolerance(1e-3);
  request.set_normals(!streamed);
  if (streamed) request.set_chunk_size(128);
  return request;
}

v1::ElevateSurfaceDegreeRequest SurfaceElevate() {
  v1::ElevateSurfaceDegreeRequest request;
  *request.mutable_surface() = BezierPatch();
  request.set_by_u(1);
  request.set_by_v(1);
  return request;
}

v1::InterpolateSurfaceRequest SurfaceInterpolate() {
  v1::InterpolateSurfaceRequest request;
  *request.mutable_points() = BumpyNet(10, 10);
  request.set_degree_u(3);
  request.set_degree_v(3);
  return request;
}

std::vector<RpcSpec> SurfaceSpecs() {
  std::vector<RpcSpec> specs;
  specs.push_back(SurfaceRpc("Evaluate", SurfaceEvaluate(false)));
  specs.push_back(SurfaceRpc("EvaluateStream", SurfaceEvaluate(true), true));
  specs.push_back(SurfaceRpc("EvaluateBasis", SurfaceBasis()));
  specs.push_back(SurfaceRpc("Split", SurfaceSplit()));
  specs.push_back(SurfaceRpc("InsertKnots", SurfaceInsertKnots()));
  specs.push_back(SurfaceRpc("Tessellate", SurfaceTessellate(false)));
  specs.push_back(
      SurfaceRpc("TessellateStream", SurfaceTessellate(true), true));
  specs.push_back(SurfaceRpc("ElevateDegree", SurfaceElevate()));
  specs.push_back(SurfaceRpc("Interpolate", SurfaceInterpolate()));
  return specs;
}

// ----------------------------------------------- mixed load (S3) callers --

struct RpcStats {
  long calls = 0;
  long errors = 0;
  std::string first_error;
  std::vector<double> micros;

  void Record(const grpc::Status& status, double elapsed_us) {
    ++calls;
    if (status.ok()) {
      micros.push_back(elapsed_us);
    } else if (++errors == 1) {
      first_error =
          std::to_string(status.error_code()) + " " + status.error_message();
    }
  }
  void Merge(const RpcStats& other) {
    calls += other.calls;
    errors += other.errors;
    if (first_error.empty()) first_error = other.first_error;
    micros.insert(micros.end(), other.micros.begin(), other.micros.end());
  }
};

// One caller of the mixed load: makes one call at a time, cycling through
// the specs, as a small state machine driven by its completion queue (the
// caller itself is the tag: it has at most one operation pending).
class MixedCaller {
 public:
  MixedCaller(grpc::GenericStub* stub, grpc::CompletionQueue* cq,
              const std::vector<RpcSpec>* specs, size_t first)
      : stub_(stub), cq_(cq), specs_(specs), next_(first % specs->size()) {}

  void Start() {
    spec_ = &(*specs_)[next_];
    next_ = (next_ + 1) % specs_->size();
    unary_.reset();  // these live in the old context's call: drop them first
    stream_.reset();
    context_ = std::make_unique<grpc::ClientContext>();
    context_->set_deadline(DeadlineIn(30));
    response_.Clear();
    status_ = grpc::Status();
    messages_ = 0;
    start_ = Clock::now();
    spec_->streaming ? StartStream() : StartUnary();
  }

  // Handles this caller's completion; true once the call has finished, its
  // result recorded in stats (indexed like the specs).
  bool Proceed(bool ok, std::vector<RpcStats>* stats) {
    if (step_ == Step::kFinishing) {
      Record(stats);
      return true;
    }
    if (step_ == Step::kStarting && ok) {
      step_ = Step::kWriting;
      stream_->WriteLast(spec_->request, grpc::WriteOptions(), this);
    } else if ((step_ == Step::kWriting || step_ == Step::kReading) && ok) {
      ReadNext();
    } else {
      step_ = Step::kFinishing;
      stream_->Finish(&status_, this);
    }
    return false;
  }

  void Cancel() {
    if (context_) context_->TryCancel();
  }

 private:
  enum class Step { kStarting, kWriting, kReading, kFinishing };

  void StartUnary() {
    step_ = Step::kFinishing;
    unary_ = stub_->PrepareUnaryCall(context_.get(), spec_->method,
                                     spec_->request, cq_);
    unary_->StartCall();
    unary_->Finish(&response_, &status_, this);
  }

  void StartStream() {
    step_ = Step::kStarting;
    stream_ = stub_->PrepareCall(context_.get(), spec_->method, cq_);
    stream_->StartCall(this);
  }

  void ReadNext() {
    if (step_ == Step::kReading) ++messages_;
    if (messages_ >= kMaxStreamMessages) context_->TryCancel();
    step_ = Step::kReading;
    response_.Clear();
    stream_->Read(&response_, this);
  }

  void Record(std::vector<RpcStats>* stats) {
    const bool empty =
        spec_->streaming ? messages_ == 0 : response_.Length() == 0;
    if (status_.ok() && empty) {
      status_ = grpc::Status(grpc::StatusCode::DATA_LOSS, "empty answer");
    }
    const auto index = static_cast<size_t>(spec_ - specs_->data());
    (*stats)[index].Record(status_, MicrosSince(start_));
  }

  grpc::GenericStub* const stub_;
  grpc::CompletionQueue* const cq_;
  const std::vector<RpcSpec>* const specs_;
  size_t next_;
  const RpcSpec* spec_ = nullptr;
  Step step_ = Step::kFinishing;
  std::unique_ptr<grpc::ClientContext> context_;
  std::unique_ptr<grpc::GenericClientAsyncResponseReader> unary_;
  std::unique_ptr<grpc::GenericClientAsyncReaderWriter> stream_;
  grpc::ByteBuffer response_;
  grpc::Status status_;
  long messages_ = 0;
  Clock::time_point start_;
};

// Drives `callers` on one completion queue until `end` (no call starts
// later), then until the last call finishes; cancels stragglers 30 s later
// and gives up waiting for them 10 s after that.
void DriveCallers(grpc::CompletionQueue* cq,
                  std::vector<std::unique_ptr<MixedCaller>>* callers,
                  Clock::time_point end, std::vector<RpcStats>* stats) {
  for (auto& caller : *callers) caller->Start();
  size_t busy = callers->size();
  const Clock::time_point cancel_at = end + std::chrono::seconds(30);
  bool cancelled = false;
  while (busy > 0) {
    void* tag = nullptr;
    bool ok = false;
    const auto event = cq->AsyncNext(&tag, &ok, DeadlineIn(0.5));
    if (event == grpc::CompletionQueue::SHUTDOWN) break;
    const Clock::time_point now = Clock::now();
    if (now > cancel_at && !cancelled) {
      for (auto& caller : *callers) caller->Cancel();
      cancelled = true;
    }
    if (now > cancel_at + std::chrono::seconds(10)) break;
    if (event == grpc::CompletionQueue::TIMEOUT) continue;
    auto* caller = static_cast<MixedCaller*>(tag);
    if (!caller->Proceed(ok, stats)) continue;
    if (now < end) {
      caller->Start();
    } else {
      --busy;
    }
  }
}

void PrintMixed(const std::vector<RpcSpec>& specs,
                const std::vector<RpcStats>& stats, double seconds) {
  std::printf("%-24s %9s %10s %10s %7s  %s\n", "rpc", "calls", "p50_us",
              "p99_us", "errors", "first error");
  long total = 0, errors = 0;
  for (size_t i = 0; i < specs.size(); ++i) {
    const RpcStats& s = stats[i];
    std::printf("%-24s %9ld %10.0f %10.0f %7ld  %s\n", specs[i].name.c_str(),
                s.calls, Percentile(s.micros, 0.5), Percentile(s.micros, 0.99),
                s.errors, s.first_error.c_str());
    total += s.calls;
    errors += s.errors;
  }
  std::printf(
      "mixed callers=%d seconds=%.1f calls=%ld calls_per_s=%.0f "
      "errors=%ld\n",
      absl::GetFlag(FLAGS_callers), seconds, total,
      static_cast<double>(total) / seconds, errors);
}

std::vector<RpcSpec> AllRpcs() {
  std::vector<RpcSpec> specs = CurveSpecs();
  for (RpcSpec& spec : SurfaceSpecs()) specs.push_back(std::move(spec));
  return specs;
}

// The mixed load's state: callers spread over one completion queue per
// thread, and per-thread results.
struct MixedLoad {
  std::vector<grpc::CompletionQueue> cqs;
  std::vector<std::vector<std::unique_ptr<MixedCaller>>> callers;
  std::vector<std::vector<RpcStats>> stats;

  MixedLoad(grpc::GenericStub* stub, const std::vector<RpcSpec>* specs,
            int threads, int callers_total)
      : cqs(static_cast<size_t>(threads)),
        callers(cqs.size()),
        stats(cqs.size(), std::vector<RpcStats>(specs->size())) {
    for (int c = 0; c < callers_total; ++c) {
      const auto group = static_cast<size_t>(c % threads);
      callers[group].push_back(std::make_unique<MixedCaller>(
          stub, &cqs[group], specs, static_cast<size_t>(c)));
    }
  }
  ~MixedLoad() {
    for (grpc::CompletionQueue& cq : cqs) Drain(&cq);  // before the callers
  }

  void Run(Clock::time_point end) {
    std::vector<std::thread> workers;
    for (size_t t = 0; t < cqs.size(); ++t) {
      workers.emplace_back(DriveCallers, &cqs[t], &callers[t], end, &stats[t]);
    }
    for (std::thread& worker : workers) worker.join();
  }

  std::vector<RpcStats> Merged() const {
    std::vector<RpcStats> merged(stats[0].size());
    for (const std::vector<RpcStats>& group : stats) {
      for (size_t i = 0; i < group.size(); ++i) merged[i].Merge(group[i]);
    }
    return merged;
  }
};

int RunMixed(const std::shared_ptr<grpc::Channel>& channel) {
  const std::vector<RpcSpec> specs = AllRpcs();
  grpc::GenericStub stub(channel);
  MixedLoad load(&stub, &specs, std::clamp(absl::GetFlag(FLAGS_cqs), 1, 4),
                 std::clamp(absl::GetFlag(FLAGS_callers), 1, 4096));
  const Clock::time_point start = Clock::now();
  load.Run(ClockIn(Seconds(60.0)));
  const double elapsed = MicrosSince(start) / 1e6;
  const std::vector<RpcStats> stats = load.Merged();
  PrintMixed(specs, stats, elapsed);
  const bool failed = std::any_of(stats.begin(), stats.end(),
                                  [](const RpcStats& s) { return s.errors; });
  return failed ? 1 : 0;
}

// ------------------------------------------------------------------ main --

std::shared_ptr<grpc::Channel> Connect(const std::string& target) {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(kMaxReceiveBytes);
  auto channel = grpc::CreateCustomChannel(
      target, grpc::InsecureChannelCredentials(), args);
  if (!channel->WaitForConnected(DeadlineIn(10))) return nullptr;
  return channel;
}

int Run(const std::shared_ptr<grpc::Channel>& channel, const std::string& kind,
        const std::string& mode) {
  if (mode == "mixed") {
    if (kind != "freeform") {
      std::fprintf(stderr, "--mode=mixed needs --target_kind=freeform\n");
      return 2;
    }
    return RunMixed(channel);
  }
  Workload workload = SelectWorkload(kind == "echo", mode);
  if (mode == "latency") return RunLatency(channel, workload);
  if (mode == "throughput") return RunThroughput(channel, workload);
  if (mode == "stream" || mode == "unary_bulk") {
    return RunBulk(channel, workload, mode);
  }
  std::fprintf(stderr, "unknown --mode=%s\n", mode.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  absl::ParseCommandLine(argc, argv);
  const std::string target = absl::GetFlag(FLAGS_target);
  const std::string kind = absl::GetFlag(FLAGS_target_kind);
  if (target.rfind("127.0.0.1:", 0) != 0) {
    std::fprintf(stderr, "--target must be 127.0.0.1:PORT\n");
    return 2;
  }
  if (kind != "echo" && kind != "freeform") {
    std::fprintf(stderr, "--target_kind must be echo or freeform\n");
    return 2;
  }
  const std::shared_ptr<grpc::Channel> channel = Connect(target);
  if (!channel) {
    std::fprintf(stderr, "cannot connect to %s\n", target.c_str());
    return 1;
  }
  return Run(channel, kind, absl::GetFlag(FLAGS_mode));
}
