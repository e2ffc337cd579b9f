// Memory bounds: every RPC of CurveService and SurfaceService, called alone
// on an in-process server with a large request, allocates at its peak no
// more than the memory its plan reserved from the server's budget, plus
// kCallMargin for gRPC's own per-call state.
//
// The bytes are counted by allocation_counter.h, which replaces this
// executable's allocator: the peak of the bytes allocated during the call,
// less those allocated before it, against what the call reserved (the
// budget's released() grows by exactly the call's reservation once the
// call is done). The client sends a request serialized before the count
// starts and drops each answer's bytes as they arrive, without parsing
// them (a generic stub): over the in-process transport those bytes are the
// server's serialized answer itself, so the client adds nothing but its
// call. Every case prints its figures (reserved, peak, peak / reserved).
// Skipped under the sanitizers, whose allocators keep freed memory.
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>
#include <grpcpp/support/byte_buffer.h>
#include <gtest/gtest.h>
#include <malloc.h>
#include <sys/mman.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <initializer_list>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "allocation_counter.h"
#include "freeform/v1/curve_service.grpc.pb.h"
#include "freeform/v1/face_service.grpc.pb.h"
#include "freeform/v1/surface_service.grpc.pb.h"
#include "server.h"

namespace freeform::server {
namespace {

using ::freeform::testing::AllocatedBytes;
using ::freeform::testing::kCountingAllocations;
using ::freeform::testing::PeakAllocatedBytes;
using ::freeform::testing::ResetPeakAllocatedBytes;

constexpr int64_t kMiB = 1 << 20;

// What a call costs beyond its reservation when its plan is right: gRPC's
// call (its arena, metadata, the reactor, the completion-queue and
// transport operations of both ends) and the frame's bookkeeping (the
// pool task, the access-log line). An empty call (EmptyCallCostsLittle)
// measures 20-30 KiB here; the margin leaves room for a stream's per-write
// operations and for the first use of a pool thread's small caches.
constexpr int64_t kCallMargin = 256 * 1024;

// An answer as the client saw it: its status and the messages' bytes.
struct Answer {
  grpc::Status status;
  size_t messages = 0;
  size_t bytes = 0;
};

void* Tag(intptr_t step) { return reinterpret_cast<void*>(step); }

// Next waits for the queue's next event and returns whether it succeeded.
bool Next(grpc::CompletionQueue& queue) {
  void* tag = nullptr;
  bool ok = false;
  return queue.Next(&tag, &ok) && ok;
}

// Call sends `request` to `method` and drops every answer message.
Answer Call(grpc::GenericStub& stub, const std::string& method,
            const grpc::ByteBuffer& request, bool streaming) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() +
                       std::chrono::seconds(120));
  grpc::CompletionQueue queue;
  Answer answer;
  if (!streaming) {
    std::unique_ptr<grpc::GenericClientAsyncResponseReader> call =
        stub.PrepareUnaryCall(&context, method, request, &queue);
    call->StartCall();
    grpc::ByteBuffer response;
    call->Finish(&response, &answer.status, Tag(1));
    Next(queue);
    answer.messages = 1;
    answer.bytes = response.Length();
  } else {
    std::unique_ptr<grpc::GenericClientAsyncReaderWriter> call =
        stub.PrepareCall(&context, method, &queue);
    call->StartCall(Tag(1));
    Next(queue);
    call->WriteLast(request, grpc::WriteOptions(), Tag(2));
    Next(queue);
    grpc::ByteBuffer message;
    while (true) {
      call->Read(&message, Tag(3));
      if (!Next(queue)) break;
      ++answer.messages;
      answer.bytes += message.Length();
      message.Clear();
    }
    call->Finish(&answer.status, Tag(4));
    Next(queue);
  }
  queue.Shutdown();
  while (Next(queue)) {
  }
  return answer;
}

// What one call reserved and allocated at its peak, and what parsing its
// request allocates at its peak (gRPC parses it before the call starts,
// so before it can reserve anything: the budget's headroom holds that).
struct Measurement {
  Answer answer;
  int64_t reserved = 0;
  int64_t peak = 0;
  int64_t parse_peak = 0;
};

// ParsePeak returns the peak of what parsing `serialized` into a message
// of `prototype`'s type allocates, the way gRPC parses a request.
int64_t ParsePeak(const google::protobuf::Message& prototype,
                  const grpc::ByteBuffer& serialized) {
  grpc::ByteBuffer bytes(serialized);  // shares the slices
  const int64_t before = AllocatedBytes();
  ResetPeakAllocatedBytes();
  {
    std::unique_ptr<google::protobuf::Message> parsed(prototype.New());
    EXPECT_TRUE(
        grpc::SerializationTraits<google::protobuf::Message>::Deserialize(
            &bytes, parsed.get())
            .ok());
  }
  return PeakAllocatedBytes() - before;
}

class MemoryBoundsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ServerOptions options;
    options.listen_address = "127.0.0.1:0";
    options.threads = 2;
    absl::StatusOr<std::unique_ptr<FreeformServer>> server =
        FreeformServer::Start(options);
    ASSERT_TRUE(server.ok()) << server.status();
    server_ = server->release();
    stub_ = new grpc::GenericStub(server_->InProcessChannel());
  }
  static void TearDownTestSuite() {
    delete stub_;
    stub_ = nullptr;
    if (server_ != nullptr) server_->Shutdown(std::chrono::seconds(5));
    delete server_;
    server_ = nullptr;
  }
  void SetUp() override {
    if (!kCountingAllocations) {
      GTEST_SKIP() << "the sanitizers keep freed memory in their own allocator";
    }
    ASSERT_NE(server_, nullptr);
  }

  // Measure makes one call and measures it.
  static Measurement Measure(const std::string& method,
                             const google::protobuf::Message& request,
                             bool streaming) {
    grpc::ByteBuffer serialized;
    bool own_buffer = false;
    EXPECT_TRUE(grpc::SerializationTraits<google::protobuf::Message>::Serialize(
                    request, &serialized, &own_buffer)
                    .ok());
    Measurement measurement;
    measurement.parse_peak = ParsePeak(request, serialized);
    const MemoryBudget& budget = server_->budget();
    const uint64_t released = budget.released();
    const int64_t before = AllocatedBytes();
    ResetPeakAllocatedBytes();
    measurement.answer = Call(*stub_, method, serialized, streaming);
    // The reservation goes with the call's record, just after the answer.
    const auto give_up =
        std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (budget.released() == released &&
           std::chrono::steady_clock::now() < give_up) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    measurement.reserved = static_cast<int64_t>(budget.released() - released);
    measurement.peak = PeakAllocatedBytes() - before;
    return measurement;
  }

  static FreeformServer* server_;
  static grpc::GenericStub* stub_;
};

FreeformServer* MemoryBoundsTest::server_ = nullptr;
grpc::GenericStub* MemoryBoundsTest::stub_ = nullptr;

// Escape keeps the compiler from dropping an allocation nothing reads.
void Escape(void* pointer) { asm volatile("" : : "g"(pointer) : "memory"); }

// The counter itself, against allocations of known sizes. Other threads
// (gRPC's, once a server has run in this process) allocate a little
// meanwhile, and a block's usable size is rounded up: the blocks' figures
// are checked within kNoise; the mappings' page counts exactly (to half a
// page), as this suite runs before any server starts.
TEST(AllocationCounterTest, CountsKnownAllocations) {
  if (!kCountingAllocations) GTEST_SKIP() << "a sanitizer's allocator";
  constexpr int64_t kBlock = 10 * kMiB;
  constexpr double kNoise = 64 * 1024;
  const int64_t before = AllocatedBytes();
  auto held = [before] {
    return static_cast<double>(AllocatedBytes() - before);
  };
  auto peak = [before] {
    return static_cast<double>(PeakAllocatedBytes() - before);
  };
  ResetPeakAllocatedBytes();
  void* block = std::malloc(kBlock);
  ASSERT_NE(block, nullptr);
  Escape(block);
  EXPECT_NEAR(held(), kBlock, kNoise);
  block = std::realloc(block, 2 * kBlock);
  ASSERT_NE(block, nullptr);
  Escape(block);
  EXPECT_NEAR(held(), 2 * kBlock, kNoise);
  std::free(block);
  EXPECT_NEAR(held(), 0, kNoise);
  // realloc grows in place (a mapping is remapped) or copies (both blocks
  // exist for a moment).
  EXPECT_GE(peak(), 2 * kBlock);
  EXPECT_LE(peak(), 3 * kBlock + kNoise);

  ResetPeakAllocatedBytes();
  {
    auto values = std::make_unique<std::vector<double>>(kBlock / 8);
    Escape(values->data());
    void* zeroed = std::calloc(kBlock / 8, 8);
    void* aligned = nullptr;
    ASSERT_EQ(posix_memalign(&aligned, 4096, kBlock), 0);
    void* aligned_too = aligned_alloc(64, kBlock);
    void* memaligned = memalign(256, kBlock);
    for (void* pointer : {zeroed, aligned, aligned_too, memaligned}) {
      ASSERT_NE(pointer, nullptr);
      Escape(pointer);
    }
    EXPECT_NEAR(held(), 5 * kBlock, kNoise);
    for (void* pointer : {zeroed, aligned, aligned_too, memaligned}) {
      std::free(pointer);
    }
  }
  EXPECT_NEAR(held(), 0, kNoise);
  EXPECT_NEAR(peak(), 5 * kBlock, kNoise);

  // An anonymous mapping trimmed at both ends as zeroed_array.cc trims
  // one, split in the middle, then unmapped whole: its pages count whether
  // touched or not.
  const int64_t page = sysconf(_SC_PAGESIZE);
  const double kHalfPage = static_cast<double>(page) / 2;
  const int64_t mapping_start = AllocatedBytes();
  auto mapped_bytes = [mapping_start] {
    return static_cast<double>(AllocatedBytes() - mapping_start);
  };
  char* mapped =
      static_cast<char*>(mmap(nullptr, kBlock, PROT_READ | PROT_WRITE,
                              MAP_PRIVATE | MAP_ANONYMOUS, -1, 0));
  ASSERT_NE(mapped, MAP_FAILED);
  EXPECT_NEAR(mapped_bytes(), kBlock, kHalfPage);
  ASSERT_EQ(munmap(mapped, page), 0);
  ASSERT_EQ(munmap(mapped + kBlock - page, page), 0);
  EXPECT_NEAR(mapped_bytes(), static_cast<double>(kBlock - 2 * page),
              kHalfPage);
  ASSERT_EQ(munmap(mapped + kBlock / 2, page), 0);
  EXPECT_NEAR(mapped_bytes(), static_cast<double>(kBlock - 3 * page),
              kHalfPage);
  ASSERT_EQ(munmap(mapped, kBlock), 0);  // the rest, holes included
  EXPECT_NEAR(mapped_bytes(), 0, kHalfPage);
  EXPECT_EQ(::freeform::testing::LostMappings(), 0);
}

// The smallest call: what gRPC and the frame cost beside a plan (the
// margin's measure).
TEST_F(MemoryBoundsTest, EmptyCallCostsLittle) {
  v1::EvaluateCurveRequest request;
  v1::BezierCurve& line = *request.mutable_curve()->mutable_bezier();
  line.mutable_control_points()->set_dimension(1);
  line.mutable_control_points()->mutable_coordinates()->Add(0.0);
  line.mutable_control_points()->mutable_coordinates()->Add(1.0);
  request.mutable_parameters()->mutable_list()->add_values(0.5);
  // Warm up (the channel, the pool threads), then measure.
  constexpr char kMethod[] = "/freeform.v1.CurveService/Evaluate";
  Measure(kMethod, request, false);
  const Measurement measured = Measure(kMethod, request, false);
  ASSERT_TRUE(measured.answer.status.ok())
      << measured.answer.status.error_message();
  std::fprintf(stderr,
               "memory: empty call reserved %lld bytes, allocated %lld at "
               "its peak\n",
               static_cast<long long>(measured.reserved),
               static_cast<long long>(measured.peak));
  EXPECT_LE(measured.peak, measured.reserved + kCallMargin / 4);
}

// Geometry of the large requests.

// UniformKnots returns the clamped uniform knots on [0, 1] of `count`
// control points of `degree`.
std::vector<double> UniformKnots(int count, int degree) {
  std::vector<double> knots(static_cast<size_t>(degree + 1), 0.0);
  const int spans = count - degree;
  for (int k = 1; k < spans; ++k)
    knots.push_back(static_cast<double>(k) / spans);
  knots.insert(knots.end(), static_cast<size_t>(degree + 1), 1.0);
  return knots;
}

// Helix returns a clamped B-spline of `count` control points on a helix.
v1::Curve Helix(int count, int degree = 3) {
  v1::Curve curve;
  v1::BSplineCurve& bspline = *curve.mutable_bspline();
  bspline.set_degree(static_cast<uint32_t>(degree));
  bspline.mutable_control_points()->set_dimension(3);
  auto& points = *bspline.mutable_control_points()->mutable_coordinates();
  points.Reserve(3 * count);
  for (int i = 0; i < count; ++i) {
    points.Add(std::cos(0.05 * i));
    points.Add(std::sin(0.05 * i));
    points.Add(0.001 * i);
  }
  const std::vector<double> knots = UniformKnots(count, degree);
  bspline.mutable_knots()->Add(knots.begin(), knots.end());
  return curve;
}

// Wave returns a clamped bicubic B-spline surface of count_u x count_v
// control points over [0, 1]^2 with a wavy height.
v1::Surface Wave(int count_u, int count_v, int degree = 3) {
  v1::Surface surface;
  v1::BSplineSurface& bspline = *surface.mutable_bspline();
  bspline.set_degree_u(static_cast<uint32_t>(degree));
  bspline.set_degree_v(static_cast<uint32_t>(degree));
  v1::ControlNet& net = *bspline.mutable_control_net();
  net.set_dimension(3);
  net.set_count_u(static_cast<uint32_t>(count_u));
  net.set_count_v(static_cast<uint32_t>(count_v));
  net.mutable_coordinates()->Reserve(3 * count_u * count_v);
  for (int i = 0; i < count_u; ++i) {
    for (int j = 0; j < count_v; ++j) {
      net.add_coordinates(static_cast<double>(i) / (count_u - 1));
      net.add_coordinates(static_cast<double>(j) / (count_v - 1));
      net.add_coordinates(0.05 * std::sin(20.0 * i / count_u) *
                          std::cos(15.0 * j / count_v));
    }
  }
  const std::vector<double> knots_u = UniformKnots(count_u, degree);
  const std::vector<double> knots_v = UniformKnots(count_v, degree);
  bspline.mutable_knots_u()->Add(knots_u.begin(), knots_u.end());
  bspline.mutable_knots_v()->Add(knots_v.begin(), knots_v.end());
  return surface;
}

// Flat returns a bicubic B-spline surface of count x count control points
// on the plane z = 0 over [0, 1]^2.
v1::Surface Flat(int count) {
  v1::Surface surface = Wave(count, count);
  auto& coordinates =
      *surface.mutable_bspline()->mutable_control_net()->mutable_coordinates();
  for (int k = 2; k < coordinates.size(); k += 3) coordinates[k] = 0.0;
  return surface;
}

// Interior returns `count` increasing values strictly inside (0, 1).
std::vector<double> Interior(int count) {
  std::vector<double> values(static_cast<size_t>(count));
  for (int k = 0; k < count; ++k) {
    values[k] = (k + 0.5) / count;
  }
  return values;
}

void SetRange(v1::Parameters& parameters, uint32_t count) {
  parameters.mutable_range()->set_count(count);
}

void SetGrid(v1::SurfaceParameters& parameters, uint32_t count_u,
             uint32_t count_v) {
  SetRange(*parameters.mutable_grid()->mutable_u(), count_u);
  SetRange(*parameters.mutable_grid()->mutable_v(), count_v);
}

// Points returns `count` points in 3D near the helix and the wave.
void SetScattered(v1::Points& points, int count) {
  points.set_dimension(3);
  points.mutable_coordinates()->Reserve(3 * count);
  for (int k = 0; k < count; ++k) {
    const double s = (k + 0.5) / count;
    points.add_coordinates(std::fmod(s * 997.0, 1.0));
    points.add_coordinates(std::fmod(s * 991.0, 1.0));
    points.add_coordinates(0.1 * std::sin(40.0 * s));
  }
}

// SetSmooth writes `count` points along a smooth spatial curve.
void SetSmooth(v1::Points& points, int count) {
  points.set_dimension(3);
  points.mutable_coordinates()->Reserve(3 * count);
  for (int k = 0; k < count; ++k) {
    const double s = static_cast<double>(k) / (count - 1);
    points.add_coordinates(std::cos(6.0 * s));
    points.add_coordinates(std::sin(6.0 * s));
    points.add_coordinates(s);
  }
}

// Segment returns the 3D segment between two points (six coordinates).
v1::Curve Segment(std::initializer_list<double> ends) {
  v1::Curve curve;
  v1::Points& points = *curve.mutable_bezier()->mutable_control_points();
  points.set_dimension(3);
  points.mutable_coordinates()->Add(ends.begin(), ends.end());
  return curve;
}

// SetPlane sets a section's plane through `point` with `normal`.
void SetPlane(std::initializer_list<double> point,
              std::initializer_list<double> normal,
              v1::SectionSurfaceRequest& request) {
  request.mutable_plane_point()->Add(point.begin(), point.end());
  request.mutable_plane_normal()->Add(normal.begin(), normal.end());
}

// A large call of one RPC.
struct RpcCase {
  std::string method;  // "CurveService.Evaluate"
  // What the case stresses besides a large answer ("" for that alone).
  std::string variant;
  bool streaming = false;
  // False for work that may run into a limit of the server: a refusal
  // after work must stay within the reservation too.
  bool answers_ok = true;
  std::function<std::unique_ptr<google::protobuf::Message>()> request;
};

// gtest prints a case by its method.
void PrintTo(const RpcCase& rpc, std::ostream* out) {
  *out << rpc.method << (rpc.variant.empty() ? "" : " ") << rpc.variant;
}

template <typename Request>
std::unique_ptr<google::protobuf::Message> Make(
    const std::function<void(Request&)>& fill) {
  auto request = std::make_unique<Request>();
  fill(*request);
  return request;
}

// Case returns the case of `method`, whose request `fill` writes.
template <typename Request>
RpcCase Case(std::string method, std::function<void(Request&)> fill,
             bool streaming = false) {
  return {.method = std::move(method),
          .variant = "",
          .streaming = streaming,
          .request = [fill = std::move(fill)] { return Make<Request>(fill); }};
}

// LargeGeometry returns the case of `method` whose request `fill` writes
// around large geometry (many Bezier pieces) with a small answer.
template <typename Request>
RpcCase LargeGeometry(std::string method, std::function<void(Request&)> fill) {
  RpcCase rpc = Case<Request>(std::move(method), std::move(fill));
  rpc.variant = "LargeGeometry";
  return rpc;
}

// Deep returns the case of `method` whose request `fill` writes so that the
// work refines as far as the limits let it.
template <typename Request>
RpcCase Deep(std::string method, std::function<void(Request&)> fill) {
  RpcCase rpc = Case<Request>(std::move(method), std::move(fill));
  rpc.variant = "DeepSearch";
  rpc.answers_ok = false;
  return rpc;
}

// The cases whose geometry has many Bezier pieces: the queries cut it.
std::vector<RpcCase> LargeGeometryCases() {
  constexpr int kCurvePoints = 300'000;
  constexpr int kNetSide = 400;
  return {
      LargeGeometry<v1::CurveClosestPointRequest>(
          "CurveService.ClosestPoint",
          [](v1::CurveClosestPointRequest& request) {
            *request.mutable_curve() = Helix(kCurvePoints);
            SetScattered(*request.mutable_queries(), 4);
          }),
      LargeGeometry<v1::IntersectCurvesRequest>(
          "CurveService.Intersect",
          [](v1::IntersectCurvesRequest& request) {
            *request.mutable_first() = Helix(kCurvePoints);
            *request.mutable_second() =
                Segment({1.0, 0.0, -1.0, 1.0, 0.0, 400.0});
          }),
      LargeGeometry<v1::ArcLengthRequest>("CurveService.ArcLength",
                                          [](v1::ArcLengthRequest& request) {
                                            *request.mutable_curve() =
                                                Helix(kCurvePoints);
                                          }),
      Deep<v1::ArcLengthRequest>(
          "CurveService.ArcLength",
          [](v1::ArcLengthRequest& request) {
            // Every control point three times: the speed vanishes once in
            // every span, where the quadrature halves the most.
            *request.mutable_curve() = Helix(kCurvePoints / 10);
            auto& points = *request.mutable_curve()
                                ->mutable_bspline()
                                ->mutable_control_points()
                                ->mutable_coordinates();
            for (int k = 0; k < points.size(); ++k) {
              points[k] =
                  request.curve().bspline().control_points().coordinates(
                      k / 9 * 3 + k % 3);
            }
          }),
      Deep<v1::IntersectCurveSurfaceRequest>(
          "SurfaceService.IntersectCurve",
          [](v1::IntersectCurveSurfaceRequest& request) {
            // A straight segment lying in a flat surface: every part of
            // it is within the tolerance of the surface, so the search
            // halves to its cap of pairs, a hit at every leaf.
            *request.mutable_surface() = Flat(4);
            *request.mutable_curve() = Helix(4);
            auto& points = *request.mutable_curve()
                                ->mutable_bspline()
                                ->mutable_control_points()
                                ->mutable_coordinates();
            const int count = points.size() / 3;
            for (int k = 0; k < count; ++k) {
              points[3 * k] = 0.1 + 0.8 * k / (count - 1);
              points[3 * k + 1] = 0.2 + 0.5 * k / (count - 1);
              points[3 * k + 2] = 0.0;
            }
            request.mutable_options()->set_tolerance(1e-6);
          }),
      Deep<v1::IntersectCurvesRequest>(
          "CurveService.Intersect",
          [](v1::IntersectCurvesRequest& request) {
            // A straight B-spline against a straight line on it: an
            // overlap everywhere, which its many pieces cannot report as one.
            *request.mutable_first() = Helix(100'000);
            auto& points = *request.mutable_first()
                                ->mutable_bspline()
                                ->mutable_control_points()
                                ->mutable_coordinates();
            for (int k = 0; k < points.size(); ++k) {
              points[k] = k % 3 == 0 ? k / 3 * 1e-3 : 0.0;
            }
            *request.mutable_second() =
                Segment({-1.0, 0.0, 0.0, 1e4, 0.0, 0.0});
            request.mutable_options()->set_tolerance(1e-12);
          }),
      Deep<v1::SectionSurfaceRequest>(
          "SurfaceService.Section",
          [](v1::SectionSurfaceRequest& request) {
            // The plane of a flat surface: every cell meets it.
            *request.mutable_surface() = Flat(40);
            SetPlane({0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, request);
            request.set_tolerance(1e-9);
          }),
      Deep<v1::SurfaceClosestPointRequest>(
          "SurfaceService.ClosestPoint",
          [](v1::SurfaceClosestPointRequest& request) {
            // Points above a flat surface at equal distance from a whole
            // region of it.
            *request.mutable_surface() = Flat(200);
            request.mutable_queries()->set_dimension(3);
            for (int k = 0; k < 64; ++k) {
              for (double x : {0.5, 0.5, 1.0}) {
                request.mutable_queries()->add_coordinates(x);
              }
            }
            request.mutable_options()->set_max_minima(64);
          }),
      LargeGeometry<v1::ParametersAtArcLengthRequest>(
          "CurveService.ParametersAtArcLength",
          [](v1::ParametersAtArcLengthRequest& request) {
            *request.mutable_curve() = Helix(kCurvePoints);
            for (double length : {1.0, 10.0, 100.0}) {
              request.add_lengths(length);
            }
          }),
      LargeGeometry<v1::SampleByArcLengthRequest>(
          "CurveService.SampleByArcLength",
          [](v1::SampleByArcLengthRequest& request) {
            *request.mutable_curve() = Helix(kCurvePoints);
            request.set_count(1000);
          }),
      LargeGeometry<v1::CurveCurvatureRequest>(
          "CurveService.Curvature",
          [](v1::CurveCurvatureRequest& request) {
            *request.mutable_curve() = Helix(kCurvePoints);
            SetRange(*request.mutable_parameters(), 1000);
          }),
      LargeGeometry<v1::EvaluateCurveRequest>(
          "CurveService.Evaluate",
          [](v1::EvaluateCurveRequest& request) {
            *request.mutable_curve() = Helix(kCurvePoints);
            SetRange(*request.mutable_parameters(), 1000);
          }),
      LargeGeometry<v1::SurfaceClosestPointRequest>(
          "SurfaceService.ClosestPoint",
          [](v1::SurfaceClosestPointRequest& request) {
            *request.mutable_surface() = Wave(kNetSide, kNetSide);
            SetScattered(*request.mutable_queries(), 4);
          }),
      LargeGeometry<v1::IntersectCurveSurfaceRequest>(
          "SurfaceService.IntersectCurve",
          [](v1::IntersectCurveSurfaceRequest& request) {
            *request.mutable_surface() = Wave(kNetSide, kNetSide);
            *request.mutable_curve() =
                Segment({0.3, 0.4, -1.0, 0.35, 0.45, 1.0});
          }),
      LargeGeometry<v1::SectionSurfaceRequest>(
          "SurfaceService.Section",
          [](v1::SectionSurfaceRequest& request) {
            *request.mutable_surface() = Wave(kNetSide, kNetSide);
            SetPlane({0.5, 0.0, 0.0}, {1.0, 0.0, 0.0}, request);
          }),
      LargeGeometry<v1::SurfaceCurvatureRequest>(
          "SurfaceService.Curvature",
          [](v1::SurfaceCurvatureRequest& request) {
            *request.mutable_surface() = Wave(kNetSide, kNetSide);
            SetGrid(*request.mutable_parameters(), 30, 30);
          }),
      LargeGeometry<v1::TessellateSurfaceRequest>(
          "SurfaceService.Tessellate",
          [](v1::TessellateSurfaceRequest& request) {
            *request.add_surfaces() = Wave(kNetSide * 3 / 4, kNetSide * 3 / 4);
            request.set_tolerance(1.0);
          }),
  };
}

std::vector<RpcCase> CurveCases() {
  return {
      Case<v1::EvaluateCurveRequest>("CurveService.Evaluate",
                                     [](v1::EvaluateCurveRequest& request) {
                                       *request.mutable_curve() = Helix(1000);
                                       SetRange(*request.mutable_parameters(),
                                                1'300'000);
                                       request.set_derivative_order(1);
                                     }),
      Case<v1::EvaluateCurveRequest>(
          "CurveService.EvaluateStream",
          [](v1::EvaluateCurveRequest& request) {
            *request.mutable_curve() = Helix(1000);
            SetRange(*request.mutable_parameters(), 3'000'000);
          },
          /*streaming=*/true),
      Case<v1::EvaluateBasisRequest>(
          "CurveService.EvaluateBasis",
          [](v1::EvaluateBasisRequest& request) {
            v1::BSplineBasis& basis =
                *request.mutable_basis()->mutable_bspline();
            basis.set_degree(3);
            const std::vector<double> knots = UniformKnots(20, 3);
            basis.mutable_knots()->Add(knots.begin(), knots.end());
            SetRange(*request.mutable_parameters(), 150'000);
            request.set_derivative_order(1);
          }),
      Case<v1::SplitCurveRequest>(
          "CurveService.Split",
          [](v1::SplitCurveRequest& request) {
            v1::Points& points = *request.mutable_curve()
                                      ->mutable_bezier()
                                      ->mutable_control_points();
            points.set_dimension(3);
            for (int i = 0; i < 16; ++i) {
              points.add_coordinates(i);
              points.add_coordinates(i % 3);
              points.add_coordinates(i % 5);
            }
            const std::vector<double> cuts = Interior(150'000);
            request.mutable_parameters()->Add(cuts.begin(), cuts.end());
          }),
      Case<v1::InsertKnotsRequest>(
          "CurveService.InsertKnots",
          [](v1::InsertKnotsRequest& request) {
            *request.mutable_curve() = Helix(500'000);
            const std::vector<double> knots = Interior(500'000);
            request.mutable_knots()->Add(knots.begin(), knots.end());
          }),
      Case<v1::DecomposeCurveRequest>("CurveService.Decompose",
                                      [](v1::DecomposeCurveRequest& request) {
                                        *request.mutable_curve() =
                                            Helix(400'000);
                                      }),
      Case<v1::SubdivideRequest>(
          "CurveService.Subdivide",
          [](v1::SubdivideRequest& request) {
            SetScattered(*request.mutable_polygon(), 10'000);
            request.set_scheme(v1::SUBDIVISION_SCHEME_CHAIKIN);
            request.set_levels(6);
            request.set_keep_levels(true);
          }),
      Case<v1::TessellateCurveRequest>("CurveService.Tessellate",
                                       [](v1::TessellateCurveRequest& request) {
                                         *request.mutable_curve() =
                                             Helix(10'000);
                                         request.set_tolerance(3e-7);
                                       }),
      Case<v1::ElevateCurveDegreeRequest>(
          "CurveService.ElevateDegree",
          [](v1::ElevateCurveDegreeRequest& request) {
            *request.mutable_curve() = Helix(300'000);
            request.set_by(2);
          }),
      Case<v1::ReduceCurveDegreeRequest>(
          "CurveService.ReduceDegree",
          [](v1::ReduceCurveDegreeRequest& request) {
            v1::Points& points = *request.mutable_curve()
                                      ->mutable_bezier()
                                      ->mutable_control_points();
            points.set_dimension(3);
            for (int i = 0; i <= 64; ++i) {
              points.add_coordinates(std::cos(0.05 * i));
              points.add_coordinates(std::sin(0.05 * i));
              points.add_coordinates(0.01 * i);
            }
            request.set_by(32);
          }),
      Case<v1::InterpolateCurveRequest>(
          "CurveService.Interpolate",
          [](v1::InterpolateCurveRequest& request) {
            SetScattered(*request.mutable_points(), 500'000);
            request.mutable_bspline()->set_degree(3);
          }),
      Case<v1::RemoveCurveKnotsRequest>(
          "CurveService.RemoveKnots",
          [](v1::RemoveCurveKnotsRequest& request) {
            *request.mutable_curve() = Helix(1'000'000);
            request.set_knot(request.curve().bspline().knots(500'000));
            request.set_tolerance(1e-3);
          }),
      Case<v1::FitCurveRequest>("CurveService.Fit",
                                [](v1::FitCurveRequest& request) {
                                  SetSmooth(*request.mutable_points(), 300'000);
                                  request.set_degree(3);
                                  request.set_tolerance(1e-4);
                                }),
      Case<v1::CurveClosestPointRequest>(
          "CurveService.ClosestPoint",
          [](v1::CurveClosestPointRequest& request) {
            *request.mutable_curve() = Helix(1000);
            SetScattered(*request.mutable_queries(), 50'000);
          }),
      Case<v1::IntersectCurvesRequest>("CurveService.Intersect",
                                       [](v1::IntersectCurvesRequest& request) {
                                         *request.mutable_first() =
                                             Helix(20'000);
                                         *request.mutable_second() = Segment(
                                             {-2.0, 0.0, 0.0, 2.0, 0.0, 20.0});
                                       }),
      Case<v1::ArcLengthRequest>(
          "CurveService.ArcLength",
          [](v1::ArcLengthRequest& request) {
            *request.mutable_curve() = Helix(1000);
            constexpr int kIntervals = 200'000;
            request.mutable_intervals()->Reserve(kIntervals);
            for (int k = 0; k < kIntervals; ++k) {
              v1::ParameterInterval& interval = *request.add_intervals();
              interval.set_start(static_cast<double>(k) / kIntervals);
              interval.set_end(static_cast<double>(k + 1) / kIntervals);
            }
          }),
      Case<v1::ParametersAtArcLengthRequest>(
          "CurveService.ParametersAtArcLength",
          [](v1::ParametersAtArcLengthRequest& request) {
            *request.mutable_curve() = Helix(1000);
            request.mutable_lengths()->Reserve(1'000'000);
            for (int k = 0; k < 1'000'000; ++k) {
              request.add_lengths(k * 4e-5);
            }
          }),
      Case<v1::SampleByArcLengthRequest>(
          "CurveService.SampleByArcLength",
          [](v1::SampleByArcLengthRequest& request) {
            *request.mutable_curve() = Helix(1000);
            request.set_count(1'000'000);
          }),
      Case<v1::CurveCurvatureRequest>("CurveService.Curvature",
                                      [](v1::CurveCurvatureRequest& request) {
                                        *request.mutable_curve() = Helix(1000);
                                        SetRange(*request.mutable_parameters(),
                                                 500'000);
                                      }),
      Case<v1::RotationMinimizingFramesRequest>(
          "CurveService.RotationMinimizingFrames",
          [](v1::RotationMinimizingFramesRequest& request) {
            *request.mutable_curve() = Helix(1000);
            SetRange(*request.mutable_parameters(), 700'000);
          }),
      Case<v1::CurveBoundingBoxRequest>(
          "CurveService.BoundingBox",
          [](v1::CurveBoundingBoxRequest& request) {
            *request.mutable_curve() = Helix(500'000);
          }),
  };
}

std::vector<RpcCase> SurfaceCases() {
  return {
      Case<v1::EvaluateSurfaceRequest>(
          "SurfaceService.Evaluate",
          [](v1::EvaluateSurfaceRequest& request) {
            *request.mutable_surface() = Wave(50, 50);
            SetGrid(*request.mutable_parameters(), 800, 800);
            request.set_derivative_order(1);
            request.set_normals(true);
          }),
      Case<v1::EvaluateSurfaceRequest>(
          "SurfaceService.EvaluateStream",
          [](v1::EvaluateSurfaceRequest& request) {
            *request.mutable_surface() = Wave(50, 50);
            SetGrid(*request.mutable_parameters(), 1500, 1500);
            request.set_normals(true);
          },
          /*streaming=*/true),
      Case<v1::EvaluateSurfaceBasisRequest>(
          "SurfaceService.EvaluateBasis",
          [](v1::EvaluateSurfaceBasisRequest& request) {
            for (v1::Basis* basis : {request.mutable_tensor()->mutable_u(),
                                     request.mutable_tensor()->mutable_v()}) {
              basis->mutable_bspline()->set_degree(3);
              const std::vector<double> knots = UniformKnots(10, 3);
              basis->mutable_bspline()->mutable_knots()->Add(knots.begin(),
                                                             knots.end());
            }
            SetGrid(*request.mutable_parameters(), 250, 250);
          }),
      Case<v1::SplitSurfaceRequest>(
          "SurfaceService.Split",
          [](v1::SplitSurfaceRequest& request) {
            v1::ControlNet& net = *request.mutable_surface()
                                       ->mutable_bezier()
                                       ->mutable_control_net();
            net.set_dimension(3);
            net.set_count_u(65);
            net.set_count_v(65);
            for (int i = 0; i < 65 * 65; ++i) {
              net.add_coordinates(i / 65);
              net.add_coordinates(i % 65);
              net.add_coordinates(std::sin(i));
            }
            request.set_direction(v1::SURFACE_DIRECTION_U);
            request.set_parameter(0.3);
          }),
      Case<v1::InsertSurfaceKnotsRequest>(
          "SurfaceService.InsertKnots",
          [](v1::InsertSurfaceKnotsRequest& request) {
            *request.mutable_surface() = Wave(700, 700);
            request.set_direction(v1::SURFACE_DIRECTION_U);
            const std::vector<double> knots = Interior(700);
            request.mutable_knots()->Add(knots.begin(), knots.end());
          }),
      Case<v1::TessellateSurfaceRequest>(
          "SurfaceService.Tessellate",
          [](v1::TessellateSurfaceRequest& request) {
            *request.add_surfaces() = Wave(40, 40);
            request.set_tolerance(1e-3);
            request.set_max_edge_length(0.0035);
            request.set_normals(true);
          }),
      Case<v1::TessellateSurfaceRequest>(
          "SurfaceService.TessellateStream",
          [](v1::TessellateSurfaceRequest& request) {
            *request.add_surfaces() = Wave(40, 40);
            request.set_tolerance(1e-3);
            request.set_max_edge_length(0.002);
            request.set_normals(true);
          },
          /*streaming=*/true),
      Case<v1::ElevateSurfaceDegreeRequest>(
          "SurfaceService.ElevateDegree",
          [](v1::ElevateSurfaceDegreeRequest& request) {
            *request.mutable_surface() = Wave(400, 400);
            request.set_by_u(1);
            request.set_by_v(1);
          }),
      Case<v1::InterpolateSurfaceRequest>(
          "SurfaceService.Interpolate",
          [](v1::InterpolateSurfaceRequest& request) {
            *request.mutable_points() = Wave(600, 600).bspline().control_net();
            request.set_degree_u(3);
            request.set_degree_v(3);
          }),
      Case<v1::RemoveSurfaceKnotsRequest>(
          "SurfaceService.RemoveKnots",
          [](v1::RemoveSurfaceKnotsRequest& request) {
            *request.mutable_surface() = Wave(700, 700);
            request.set_direction(v1::SURFACE_DIRECTION_U);
            request.set_knot(request.surface().bspline().knots_u(350));
            request.set_tolerance(1e-3);
          }),
      Case<v1::FitSurfaceRequest>("SurfaceService.Fit",
                                  [](v1::FitSurfaceRequest& request) {
                                    *request.mutable_points() =
                                        Wave(600, 600).bspline().control_net();
                                    request.set_degree_u(3);
                                    request.set_degree_v(3);
                                    request.set_tolerance(1e-3);
                                  }),
      Case<v1::FitScatteredSurfaceRequest>(
          "SurfaceService.FitScattered",
          [](v1::FitScatteredSurfaceRequest& request) {
            SetScattered(*request.mutable_points(), 300'000);
            request.set_degree_u(3);
            request.set_degree_v(3);
            request.set_control_count_u(40);
            request.set_control_count_v(40);
          }),
      Case<v1::SurfaceClosestPointRequest>(
          "SurfaceService.ClosestPoint",
          [](v1::SurfaceClosestPointRequest& request) {
            *request.mutable_surface() = Wave(50, 50);
            SetScattered(*request.mutable_queries(), 2'000);
          }),
      Case<v1::IntersectCurveSurfaceRequest>(
          "SurfaceService.IntersectCurve",
          [](v1::IntersectCurveSurfaceRequest& request) {
            *request.mutable_surface() = Wave(50, 50);
            v1::BSplineCurve& curve =
                *request.mutable_curve()->mutable_bspline();
            curve.set_degree(3);
            curve.mutable_control_points()->set_dimension(3);
            constexpr int kCount = 2'000;
            for (int i = 0; i < kCount; ++i) {
              const double s = static_cast<double>(i) / (kCount - 1);
              curve.mutable_control_points()->add_coordinates(
                  std::fmod(s * 37.0, 1.0) * 0.9 + 0.05);
              curve.mutable_control_points()->add_coordinates(s * 0.9 + 0.05);
              curve.mutable_control_points()->add_coordinates(i % 2 ? 1.0
                                                                    : -1.0);
            }
            const std::vector<double> knots = UniformKnots(kCount, 3);
            curve.mutable_knots()->Add(knots.begin(), knots.end());
          }),
      Case<v1::SectionSurfaceRequest>(
          "SurfaceService.Section",
          [](v1::SectionSurfaceRequest& request) {
            *request.mutable_surface() = Wave(200, 200);
            SetPlane({0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, request);
            request.set_max_points(1'000'000);
            request.set_tolerance(1e-5);
          }),
      Case<v1::SurfaceCurvatureRequest>(
          "SurfaceService.Curvature",
          [](v1::SurfaceCurvatureRequest& request) {
            *request.mutable_surface() = Wave(50, 50);
            SetGrid(*request.mutable_parameters(), 600, 600);
          }),
      Case<v1::SurfaceBoundingBoxRequest>(
          "SurfaceService.BoundingBox",
          [](v1::SurfaceBoundingBoxRequest& request) {
            *request.mutable_surface() = Wave(500, 500);
          }),
  };
}

// A face of the unit plane with `holes` circular holes (NURBS circles,
// clockwise) on a square lattice, and an outer loop of `segments` straight
// segments (a degree-1 B-spline along the square [0.01, 0.99]^2).
v1::TrimmedSurface LatticeFace(int holes, int segments) {
  v1::TrimmedSurface face;
  v1::ControlNet& net =
      *face.mutable_surface()->mutable_bezier()->mutable_control_net();
  net.set_dimension(3);
  net.set_count_u(2);
  net.set_count_v(2);
  for (double x : {0., 0., 0., 0., 1., 0., 1., 0., 0., 1., 1., 0.}) {
    net.add_coordinates(x);
  }
  v1::BSplineCurve& outer =
      *face.mutable_outer()->add_curves()->mutable_bspline();
  outer.set_degree(1);
  outer.mutable_control_points()->set_dimension(2);
  const int side = segments / 4;
  const double corners[5][2] = {
      {0.01, 0.01}, {0.99, 0.01}, {0.99, 0.99}, {0.01, 0.99}, {0.01, 0.01}};
  for (int c = 0; c < 4; ++c) {
    for (int k = 0; k < side; ++k) {
      const double t = static_cast<double>(k) / side;
      for (int j = 0; j < 2; ++j) {
        outer.mutable_control_points()->add_coordinates(
            corners[c][j] + t * (corners[c + 1][j] - corners[c][j]));
      }
    }
  }
  outer.mutable_control_points()->add_coordinates(0.01);
  outer.mutable_control_points()->add_coordinates(0.01);
  const std::vector<double> knots = UniformKnots(4 * side + 1, 1);
  outer.mutable_knots()->Add(knots.begin(), knots.end());
  const int per_row = static_cast<int>(std::ceil(std::sqrt(holes)));
  const double pitch = 0.9 / per_row, radius = 0.3 * pitch;
  const double s = std::sqrt(0.5);
  const double unit[9][3] = {{1, 0, 1},   {1, -1, s}, {0, -1, 1},
                             {-1, -1, s}, {-1, 0, 1}, {-1, 1, s},
                             {0, 1, 1},   {1, 1, s},  {1, 0, 1}};
  for (int h = 0; h < holes; ++h) {
    const double cu = 0.05 + pitch * (h % per_row + 0.5);
    const double cv = 0.05 + pitch * (h / per_row + 0.5);
    v1::BSplineCurve& circle =
        *face.add_holes()->add_curves()->mutable_bspline();
    circle.set_degree(2);
    circle.mutable_control_points()->set_dimension(2);
    for (const auto& p : unit) {
      circle.mutable_control_points()->add_coordinates(cu + radius * p[0]);
      circle.mutable_control_points()->add_coordinates(cv + radius * p[1]);
      circle.add_weights(p[2]);
    }
    for (double k : {0., 0., 0., .25, .25, .5, .5, .75, .75, 1., 1., 1.}) {
      circle.add_knots(k);
    }
  }
  return face;
}

// FaceService: many holes and a long outer loop (the face's pieces,
// polylines and grid), with a large answer where there is one.
std::vector<RpcCase> FaceCases() {
  return {
      Case<v1::ClassifyFacePointsRequest>(
          "FaceService.Classify",
          [](v1::ClassifyFacePointsRequest& request) {
            *request.mutable_face() = LatticeFace(2500, 100'000);
            SetGrid(*request.mutable_parameters(), 1000, 1000);
          }),
      Case<v1::EvaluateFaceRequest>(
          "FaceService.Evaluate",
          [](v1::EvaluateFaceRequest& request) {
            *request.mutable_face() = LatticeFace(400, 4000);
            SetGrid(*request.mutable_parameters(), 600, 600);
            request.set_derivative_order(1);
            request.set_normals(true);
          }),
      Case<v1::TessellateFaceRequest>("FaceService.Tessellate",
                                      [](v1::TessellateFaceRequest& request) {
                                        *request.mutable_face() =
                                            LatticeFace(400, 4000);
                                        request.set_tolerance(1e-5);
                                        request.set_max_vertices(400'000);
                                      }),
      Case<v1::FaceAreaRequest>("FaceService.Area",
                                [](v1::FaceAreaRequest& request) {
                                  *request.mutable_face() =
                                      LatticeFace(100, 1000);
                                  request.set_tolerance(1e-9);
                                }),
  };
}

std::vector<RpcCase> AllCases() {
  std::vector<RpcCase> cases = CurveCases();
  for (std::vector<RpcCase> more :
       {SurfaceCases(), LargeGeometryCases(), FaceCases()}) {
    for (RpcCase& rpc : more) cases.push_back(std::move(rpc));
  }
  return cases;
}

template <typename Bytes>
double Megabytes(Bytes bytes) {
  return static_cast<double>(bytes) / 1e6;
}

class RpcMemoryTest : public MemoryBoundsTest,
                      public ::testing::WithParamInterface<RpcCase> {};

TEST_P(RpcMemoryTest, PeakStaysWithinTheReservation) {
  const RpcCase& rpc = GetParam();
  std::string path = "/freeform.v1." + rpc.method;
  path[path.rfind('.')] = '/';
  std::unique_ptr<google::protobuf::Message> request = rpc.request();
  const auto start = std::chrono::steady_clock::now();
  const Measurement measured = Measure(path, *request, rpc.streaming);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
  if (rpc.answers_ok) {
    ASSERT_TRUE(measured.answer.status.ok())
        << rpc.method << ": " << measured.answer.status.error_message();
  } else {
    EXPECT_NE(measured.answer.status.error_code(), grpc::StatusCode::INTERNAL)
        << measured.answer.status.error_message();
  }
  std::fprintf(
      stderr,
      "memory: %-52s request %7.1f MB, answer %7.1f MB in %6zu messages, "
      "reserved %7.1f MB, peak %7.1f MB, peak/reserved %.2f (parsing "
      "%.1f MB), %.2f s%s%s\n",
      (rpc.method + (rpc.variant.empty() ? "" : " " + rpc.variant)).c_str(),
      Megabytes(request->ByteSizeLong()), Megabytes(measured.answer.bytes),
      measured.answer.messages, Megabytes(measured.reserved),
      Megabytes(measured.peak),
      static_cast<double>(measured.peak) /
          static_cast<double>(measured.reserved),
      Megabytes(measured.parse_peak), seconds,
      measured.answer.status.ok() ? "" : ", answered ",
      measured.answer.status.ok()
          ? ""
          : measured.answer.status.error_message().substr(0, 60).c_str());
  // Either parsing the request (before the call) or the call itself is
  // the peak; the call must stay within what it reserved.
  EXPECT_LE(measured.peak,
            std::max(measured.parse_peak, measured.reserved) + kCallMargin)
      << rpc.method << " allocated " << measured.peak
      << " bytes at its peak and reserved " << measured.reserved;
}

std::string CaseName(const ::testing::TestParamInfo<RpcCase>& info) {
  std::string name = info.param.method;
  name[name.find('.')] = '_';
  return info.param.variant.empty() ? name : name + "_" + info.param.variant;
}

INSTANTIATE_TEST_SUITE_P(EveryRpc, RpcMemoryTest,
                         ::testing::ValuesIn(AllCases()), CaseName);

}  // namespace
}  // namespace freeform::server
