// Admission through the in-process server: every RPC whose answer is just
// over the server's output (or message) limit is refused with
// RESOURCE_EXHAUSTED naming the field before the answer is built; a call
// over the memory budget is refused while the others complete; and streamed
// surface answers equal the unary ones bit for bit.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "freeform/core/mesh.h"
#include "freeform/core/tessellation.h"
#include "in_process_server.h"
#include "teapot.h"

namespace freeform::server {
namespace {

using ::testing::HasSubstr;

constexpr uint64_t kMiB = uint64_t{1} << 20;
// Deadline of every call, so a regression shows as DEADLINE_EXCEEDED
// (times TimeScale(): under ASan the 64-D Tessellate over its cap alone took
// over 5 s on a loaded machine).
constexpr auto kCallDeadline = std::chrono::seconds(5);
// ThreadSanitizer maps shadow memory for the memory the process touches
// (twice the application's, and more), and it counts in the resident
// memory measured here: a refusal grew the peak by 73 to 94 MiB under TSan.
// AddressSanitizer holds freed blocks in its quarantine instead of reusing
// them, so a refusal's short-lived copies all count in the peak (a 49 MiB
// Interpolate request grew it by 172 MiB, against 162 allowed).
// Under a sanitizer the allowance below grows by this factor; a call that
// wrongly built its answer would grow by the same factor, so the check
// keeps its meaning.
constexpr uint64_t kShadowMemoryFactor =
    kThreadSanitizer ? 3 : (kAddressSanitizer ? 2 : 1);
// What a refused call may add to the process's peak memory besides its
// request. Building even the smallest answer below (just over 64 MiB) took
// 128 MiB when measured with a request just under the limit.
constexpr uint64_t kRefusalMemory = 64 * kMiB * kShadowMemoryFactor;

// The limits the fixture's server runs with.
const ServiceLimits kLimits;
const uint64_t kOutputValues = kLimits.max_output_values;
const uint64_t kMessageValues =
    static_cast<uint64_t>(kLimits.max_message_bytes) / sizeof(double);
constexpr int kMaxDimension = 64;
constexpr int kMaxDegree = 64;
// The Bernstein bases stop one degree lower: the core evaluates them as a
// curve whose dimension is the number of functions.
constexpr int kMaxBasisDegree = 63;

// ------------------------------------------------------ memory, calls --

// PeakRssBytes returns this process's peak resident memory (VmHWM).
uint64_t PeakRssBytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) << 10;
  }
  return 0;
}

// ResetPeakRss lowers VmHWM to the current resident memory (Linux 4.0+), so
// the peak of each call is measured on its own, not masked by an earlier one.
void ResetPeakRss() { std::ofstream("/proc/self/clear_refs") << "5"; }

std::unique_ptr<grpc::ClientContext> DeadlineContext() {
  auto context = std::make_unique<grpc::ClientContext>();
  context->set_deadline(std::chrono::system_clock::now() +
                        Scaled(kCallDeadline));
  return context;
}

template <typename Stub, typename Request, typename Response>
using UnaryMethod = grpc::Status (Stub::*)(grpc::ClientContext*, const Request&,
                                           Response*);
template <typename Stub, typename Request, typename Response>
using StreamMethod = std::unique_ptr<grpc::ClientReader<Response>> (Stub::*)(
    grpc::ClientContext*, const Request&);

// ReadAll calls a server-streaming method and returns its messages and
// final status.
template <typename Stub, typename Request, typename Response>
absl::Status ReadAll(Stub& stub, StreamMethod<Stub, Request, Response> method,
                     const Request& request, std::vector<Response>* messages) {
  std::unique_ptr<grpc::ClientContext> context = DeadlineContext();
  std::unique_ptr<grpc::ClientReader<Response>> reader =
      (stub.*method)(context.get(), request);
  Response response;
  while (reader->Read(&response)) {
    if (messages != nullptr) messages->push_back(response);
  }
  return FromGrpcStatus(reader->Finish());
}

// ---------------------------------------------------- request builders --

// SetPoints fills `points` with `count` points of `dimension`: a bounded,
// smooth pattern (the values do not matter to admission).
void SetPoints(v1::Points* points, int dimension, uint64_t count) {
  points->set_dimension(static_cast<uint32_t>(dimension));
  auto* coordinates = points->mutable_coordinates();
  coordinates->Reserve(static_cast<int>(count * dimension));
  for (uint64_t i = 0; i < count * dimension; ++i) {
    coordinates->Add(std::sin(0.37 * static_cast<double>(i)));
  }
}

void SetNet(v1::ControlNet* net, int dimension, int count_u, int count_v) {
  net->set_dimension(static_cast<uint32_t>(dimension));
  net->set_count_u(static_cast<uint32_t>(count_u));
  net->set_count_v(static_cast<uint32_t>(count_v));
  for (int i = 0; i < count_u * count_v * dimension; ++i) {
    net->add_coordinates(std::cos(0.41 * i));
  }
}

// AddInterior adds `count` increasing values strictly inside (0, 1).
void AddInterior(google::protobuf::RepeatedField<double>* values,
                 uint64_t count) {
  values->Reserve(static_cast<int>(values->size() + count));
  for (uint64_t i = 1; i <= count; ++i) {
    values->Add(static_cast<double>(i) / static_cast<double>(count + 1));
  }
}

// AddClampedKnots adds the clamped uniform knots of a B-spline of `degree`
// with `count` control points on [0, 1].
void AddClampedKnots(google::protobuf::RepeatedField<double>* knots, int degree,
                     uint64_t count) {
  for (int i = 0; i <= degree; ++i) knots->Add(0.0);
  AddInterior(knots, count - degree - 1);
  for (int i = 0; i <= degree; ++i) knots->Add(1.0);
}

// The range of `count` parameters over the whole domain.
void SetRange(v1::Parameters* parameters, uint64_t count) {
  parameters->mutable_range()->set_count(static_cast<uint32_t>(count));
}

// A 64-D line at count parameters: 64 * count values, just over `values`.
v1::EvaluateCurveRequest CurveEvaluationOver(uint64_t values) {
  v1::EvaluateCurveRequest request;
  SetPoints(request.mutable_curve()->mutable_bezier()->mutable_control_points(),
            kMaxDimension, 2);
  SetRange(request.mutable_parameters(), values / kMaxDimension + 1);
  return request;
}

// The 64 Bernstein polynomials of degree 63 at count parameters.
v1::EvaluateBasisRequest CurveBasisOver(uint64_t values) {
  v1::EvaluateBasisRequest request;
  request.mutable_basis()->mutable_bernstein()->set_degree(kMaxBasisDegree);
  SetRange(request.mutable_parameters(), values / (kMaxBasisDegree + 1) + 1);
  return request;
}

// A rational 64-D Bezier curve of degree 64 cut into pieces of 65 * 65
// values each.
v1::SplitCurveRequest CurveSplitOver(uint64_t values) {
  constexpr uint64_t kPieceValues = (kMaxDegree + 1) * (kMaxDimension + 1);
  v1::SplitCurveRequest request;
  v1::BezierCurve* bezier = request.mutable_curve()->mutable_bezier();
  SetPoints(bezier->mutable_control_points(), kMaxDimension, kMaxDegree + 1);
  for (int i = 0; i <= kMaxDegree; ++i)
    bezier->add_weights(1.0 + 0.5 * (i % 2));
  const uint64_t pieces = values / kPieceValues + 1;
  AddInterior(request.mutable_parameters(), pieces - 1);
  return request;
}

// A 64-D polyline (degree-1 B-spline) refined with many knots: 64
// coordinates and one knot per resulting control point, two more knots.
v1::InsertKnotsRequest CurveKnotsOver(uint64_t values) {
  v1::InsertKnotsRequest request;
  v1::BSplineCurve* bspline = request.mutable_curve()->mutable_bspline();
  bspline->set_degree(1);
  SetPoints(bspline->mutable_control_points(), kMaxDimension, 2);
  AddClampedKnots(bspline->mutable_knots(), 1, 2);
  const uint64_t count = (values - 2) / (kMaxDimension + 1) + 1;
  AddInterior(request.mutable_knots(), count - 2);
  return request;
}

// A 64-D B-spline of degree 64 whose spans each become a Bezier segment of
// 65 * 64 values and a breakpoint.
v1::DecomposeCurveRequest CurveDecompositionOver(uint64_t values) {
  constexpr uint64_t kSegmentValues = (kMaxDegree + 1) * kMaxDimension + 1;
  const uint64_t spans = (values - 1) / kSegmentValues + 1;
  v1::DecomposeCurveRequest request;
  v1::BSplineCurve* bspline = request.mutable_curve()->mutable_bspline();
  bspline->set_degree(kMaxDegree);
  SetPoints(bspline->mutable_control_points(), kMaxDimension,
            spans + kMaxDegree);
  AddClampedKnots(bspline->mutable_knots(), kMaxDegree, spans + kMaxDegree);
  return request;
}

// A closed 64-D polygon of c points cut 10 times, every level kept: the
// levels hold c (2 + 4 + ... + 2^10) points and the last polygon c 2^10.
v1::SubdivideRequest SubdivisionOver(uint64_t values) {
  constexpr uint32_t kLevels = 10;
  constexpr uint64_t kPointsPerCorner = 3 * (1 << kLevels) - 2;
  v1::SubdivideRequest request;
  SetPoints(request.mutable_polygon(), kMaxDimension,
            values / (kPointsPerCorner * kMaxDimension) + 1);
  request.set_closed(true);
  request.set_scheme(v1::SUBDIVISION_SCHEME_CHAIKIN);
  request.set_levels(kLevels);
  request.set_keep_levels(true);
  return request;
}

// ElevatedSize is the answer of raising a degree-1 B-spline (n + 1 points,
// n spans, clamped knots) by `by`: n + 1 + n by points of 64 values and
// their knots.
struct Elevation {
  uint64_t count = 0;  // control points before
  uint64_t by = 0;
  uint64_t Points() const { return count + (count - 1) * by; }
  uint64_t Knots() const { return Points() + 1 + by + 1; }
};

v1::ElevateCurveDegreeRequest CurveElevationOver(uint64_t values) {
  Elevation elevation{.count = 2, .by = kMaxDegree - 1};
  while (elevation.Points() * kMaxDimension + elevation.Knots() <= values) {
    ++elevation.count;
  }
  v1::ElevateCurveDegreeRequest request;
  v1::BSplineCurve* bspline = request.mutable_curve()->mutable_bspline();
  bspline->set_degree(1);
  SetPoints(bspline->mutable_control_points(), kMaxDimension, elevation.count);
  AddClampedKnots(bspline->mutable_knots(), 1, elevation.count);
  request.set_by(static_cast<uint32_t>(elevation.by));
  return request;
}

// Global cubic interpolation of n 7-D points: 7 n control point values,
// n + 4 knots and n parameters. Seven dimensions give the smallest request
// with an answer over the message limit within the 10^6 point limit.
v1::InterpolateCurveRequest CurveInterpolationOver(uint64_t values) {
  constexpr int kDimension = 7;
  v1::InterpolateCurveRequest request;
  SetPoints(request.mutable_points(), kDimension,
            (values - 4) / (kDimension + 2) + 1);
  request.mutable_bspline()->set_degree(3);
  return request;
}

// Interpolation of 2 x n 8-D points by a surface of degrees (1, 3): 16 n
// control point values, 4 + (n + 4) knots and 2 + n parameters. A thin net
// of 8-D points gives the smallest request with an answer over the message
// limit within the 10^6 point limit.
v1::InterpolateSurfaceRequest SurfaceInterpolationOver(uint64_t values) {
  constexpr int kDimension = 8;
  const uint64_t columns = (values - 10) / (2 * kDimension + 2) + 1;
  v1::InterpolateSurfaceRequest request;
  SetNet(request.mutable_points(), kDimension, 2, static_cast<int>(columns));
  request.set_degree_u(1);
  request.set_degree_v(3);
  return request;
}

// A 64-D bilinear patch on a grid of count x 1 points.
v1::EvaluateSurfaceRequest SurfaceEvaluationOver(uint64_t values) {
  v1::EvaluateSurfaceRequest request;
  SetNet(request.mutable_surface()->mutable_bezier()->mutable_control_net(),
         kMaxDimension, 2, 2);
  v1::SurfaceGrid* grid = request.mutable_parameters()->mutable_grid();
  SetRange(grid->mutable_u(), values / kMaxDimension + 1);
  SetRange(grid->mutable_v(), 1);
  return request;
}

// The 64 x 64 products of Bernstein polynomials of degree 63 on a grid of
// count x 1 points.
v1::EvaluateSurfaceBasisRequest SurfaceBasisOver(uint64_t values) {
  constexpr uint64_t kFunctions = (kMaxBasisDegree + 1) * (kMaxBasisDegree + 1);
  v1::EvaluateSurfaceBasisRequest request;
  request.mutable_tensor()->mutable_u()->mutable_bernstein()->set_degree(
      kMaxBasisDegree);
  request.mutable_tensor()->mutable_v()->mutable_bernstein()->set_degree(
      kMaxBasisDegree);
  v1::SurfaceGrid* grid = request.mutable_parameters()->mutable_grid();
  SetRange(grid->mutable_u(), values / kFunctions + 1);
  SetRange(grid->mutable_v(), 1);
  return request;
}

// A bilinear 64-D B-spline surface of 2 x 88 points refined in u: each new
// row holds 88 points of 64 values and one knot (88 columns keep the
// request smallest).
v1::InsertSurfaceKnotsRequest SurfaceKnotsOver(uint64_t values) {
  constexpr int kColumns = 88;
  constexpr uint64_t kRowValues = kColumns * kMaxDimension + 1;
  const uint64_t rows = (values - kColumns - 4) / kRowValues + 1;
  v1::InsertSurfaceKnotsRequest request;
  v1::BSplineSurface* bspline = request.mutable_surface()->mutable_bspline();
  bspline->set_degree_u(1);
  bspline->set_degree_v(1);
  SetNet(bspline->mutable_control_net(), kMaxDimension, 2, kColumns);
  AddClampedKnots(bspline->mutable_knots_u(), 1, 2);
  AddClampedKnots(bspline->mutable_knots_v(), 1, kColumns);
  request.set_direction(v1::SURFACE_DIRECTION_U);
  AddInterior(request.mutable_knots(), rows - 2);
  return request;
}

// The smallest elevation of a bilinear 64-D B-spline surface (at most 40 x
// 40 points) whose answer is over `values`.
v1::ElevateSurfaceDegreeRequest SurfaceElevationOver(uint64_t values) {
  Elevation best_u, best_v;
  uint64_t best = UINT64_MAX;
  for (uint64_t count_u = 2; count_u <= 40; ++count_u) {
    for (uint64_t count_v = 2; count_v <= 40; ++count_v) {
      for (uint64_t by_u = 1; by_u < kMaxDegree; ++by_u) {
        for (uint64_t by_v = 1; by_v < kMaxDegree; ++by_v) {
          const Elevation u{.count = count_u, .by = by_u};
          const Elevation v{.count = count_v, .by = by_v};
          const uint64_t size =
              u.Points() * v.Points() * kMaxDimension + u.Knots() + v.Knots();
          if (size > values && size < best) {
            best = size;
            best_u = u;
            best_v = v;
          }
        }
      }
    }
  }
  v1::ElevateSurfaceDegreeRequest request;
  v1::BSplineSurface* bspline = request.mutable_surface()->mutable_bspline();
  bspline->set_degree_u(1);
  bspline->set_degree_v(1);
  SetNet(bspline->mutable_control_net(), kMaxDimension,
         static_cast<int>(best_u.count), static_cast<int>(best_v.count));
  AddClampedKnots(bspline->mutable_knots_u(), 1, best_u.count);
  AddClampedKnots(bspline->mutable_knots_v(), 1, best_v.count);
  request.set_by_u(static_cast<uint32_t>(best_u.by));
  request.set_by_v(static_cast<uint32_t>(best_v.by));
  return request;
}

// LargestToleranceOver returns about the largest tolerance at which
// `count`, which decreases with the tolerance, is over `cap`: steps of 4
// down from 1, then `bisections` in log scale.
template <typename Count>
double LargestToleranceOver(size_t cap, int bisections, Count count) {
  double under = 1.0, over = 0.25;
  EXPECT_LE(count(under), cap);
  while (count(over) <= cap && over > 1e-300) {
    under = over;
    over /= 4;
  }
  for (int i = 0; i < bisections; ++i) {
    const double middle = std::sqrt(over * under);
    (count(middle) > cap ? over : under) = middle;
  }
  return over;
}

// A parabola of `dimension`, (0, 0), (1/2, 1), (1, 0) in its first two
// coordinates, polylined with a tolerance that needs more than `cap` points
// (the other coordinates are zero, so the points are those of the 2-D
// parabola). Its polylines have 2^k + 1 points, so the first tolerance in
// steps of 4 over `cap` is the largest.
v1::TessellateCurveRequest CurvePolylineOver(size_t cap, int dimension) {
  const std::vector<double> parabola = {0, 0, 0.5, 1, 1, 0};
  const BezierCurveView view{
      .control_points = {.dimension = 2, .coordinates = parabola},
      .weights = {}};
  const double tolerance = LargestToleranceOver(cap, 0, [&](double candidate) {
    absl::StatusOr<Polyline> polyline =
        TessellateBezierCurve(view, candidate, cap + 1);
    return polyline.ok() ? polyline->parameters.size() : cap + 1;
  });
  v1::TessellateCurveRequest request;
  v1::Points* points =
      request.mutable_curve()->mutable_bezier()->mutable_control_points();
  points->set_dimension(static_cast<uint32_t>(dimension));
  for (int i = 0; i < 3; ++i) {
    Append(points->mutable_coordinates(),
           {parabola[2 * i], parabola[2 * i + 1]});
    for (int j = 2; j < dimension; ++j) points->add_coordinates(0.0);
  }
  request.set_tolerance(tolerance);
  return request;
}

// A bicubic bump meshed with the largest tolerance whose planned mesh has
// more than `cap` vertices.
v1::TessellateSurfaceRequest MeshOver(size_t cap) {
  std::vector<double> net;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      net.insert(net.end(),
                 {i / 3.0, j / 3.0, (i % 3 != 0 && j % 3 != 0) ? 1.0 : 0.0});
    }
  }
  const absl::StatusOr<BezierSurface> surface =
      BezierSurface::Create({.control_net = {.dimension = 3,
                                             .count_u = 4,
                                             .count_v = 4,
                                             .coordinates = net},
                             .weights = {}});
  EXPECT_TRUE(surface.ok());
  const Surface surfaces[] = {*surface};
  const double tolerance = LargestToleranceOver(cap, 60, [&](double candidate) {
    absl::StatusOr<std::shared_ptr<const MeshPlan>> plan = PlanMesh(
        surfaces, {.tolerance = candidate, .max_vertices = UINT32_MAX});
    return plan.ok() ? PlannedMeshSize(**plan).vertices : SIZE_MAX;
  });
  v1::TessellateSurfaceRequest request;
  v1::ControlNet* patch =
      request.add_surfaces()->mutable_bezier()->mutable_control_net();
  patch->set_dimension(3);
  patch->set_count_u(4);
  patch->set_count_v(4);
  patch->mutable_coordinates()->Add(net.begin(), net.end());
  request.set_tolerance(tolerance);
  request.set_normals(true);
  return request;
}

// ---------------------------------------------------------------- cases --

// One RPC with a request whose answer is just over a limit.
struct OverLimitCase {
  std::string rpc;
  // Accepted paths of the field violation (or paths under them).
  std::vector<std::string> fields;
  uint64_t request_bytes = 0;
  std::function<absl::Status()> call;
};

// Case holds `request` and calls `call` with it.
template <typename Request, typename Call>
OverLimitCase Case(std::string rpc, std::vector<std::string> fields,
                   Request request, Call call) {
  auto shared = std::make_shared<const Request>(std::move(request));
  return {.rpc = std::move(rpc),
          .fields = std::move(fields),
          .request_bytes = shared->ByteSizeLong(),
          .call = [shared, call] { return call(*shared); }};
}

template <typename Stub, typename Request, typename Response>
OverLimitCase Unary(std::string rpc, std::vector<std::string> fields,
                    Stub& stub, UnaryMethod<Stub, Request, Response> method,
                    Request request) {
  return Case(
      std::move(rpc), std::move(fields), std::move(request),
      [&stub, method](const Request& sent) {
        std::unique_ptr<grpc::ClientContext> context = DeadlineContext();
        Response response;
        return FromGrpcStatus((stub.*method)(context.get(), sent, &response));
      });
}

template <typename Stub, typename Request, typename Response>
OverLimitCase Stream(std::string rpc, std::vector<std::string> fields,
                     Stub& stub, StreamMethod<Stub, Request, Response> method,
                     Request request) {
  return Case(std::move(rpc), std::move(fields), std::move(request),
              [&stub, method](const Request& sent) {
                return ReadAll<Stub, Request, Response>(stub, method, sent,
                                                        nullptr);
              });
}

class AdmissionTest : public InProcessServerTest {
 protected:
  v1::CurveService::Stub& curves() { return client_->curves(); }
  v1::SurfaceService::Stub& surfaces() { return client_->surfaces(); }

  // The unary RPCs whose answer grows with the request, each with a request
  // whose answer is just over `values` numbers. Not here, because no
  // request has an answer just over either limit:
  // - CurveService.ReduceDegree: its answer is smaller than its request.
  // - SurfaceService.Split: at most 2 x 65 x 65 points of 65 values (the
  //   degree limit), far below both limits.
  std::vector<OverLimitCase> UnaryCasesOver(uint64_t values) {
    using CS = v1::CurveService::Stub;
    using SS = v1::SurfaceService::Stub;
    std::vector<OverLimitCase> cases = {
        Unary("CurveService.Evaluate", {"parameters"}, curves(), &CS::Evaluate,
              CurveEvaluationOver(values)),
        Unary("CurveService.EvaluateBasis", {"parameters"}, curves(),
              &CS::EvaluateBasis, CurveBasisOver(values)),
        Unary("CurveService.Split", {"parameters"}, curves(), &CS::Split,
              CurveSplitOver(values)),
        Unary("CurveService.InsertKnots", {"knots"}, curves(), &CS::InsertKnots,
              CurveKnotsOver(values)),
        Unary("CurveService.Decompose", {"curve"}, curves(), &CS::Decompose,
              CurveDecompositionOver(values)),
        Unary("CurveService.Subdivide", {"levels", "keep_levels"}, curves(),
              &CS::Subdivide, SubdivisionOver(values)),
        Unary("CurveService.ElevateDegree", {"by"}, curves(),
              &CS::ElevateDegree, CurveElevationOver(values)),
        Unary("SurfaceService.Evaluate", {"parameters"}, surfaces(),
              &SS::Evaluate, SurfaceEvaluationOver(values)),
        Unary("SurfaceService.EvaluateBasis", {"parameters"}, surfaces(),
              &SS::EvaluateBasis, SurfaceBasisOver(values)),
        Unary("SurfaceService.InsertKnots", {"knots"}, surfaces(),
              &SS::InsertKnots, SurfaceKnotsOver(values)),
        Unary("SurfaceService.ElevateDegree", {"by_u", "by_v"}, surfaces(),
              &SS::ElevateDegree, SurfaceElevationOver(values)),
    };
    // Interpolation answers about as many values as it is sent: only the
    // message limit can be passed by a request that fits one message.
    if (values <= kMessageValues) {
      cases.push_back(Unary("CurveService.Interpolate", {"points"}, curves(),
                            &CS::Interpolate, CurveInterpolationOver(values)));
      cases.push_back(Unary("SurfaceService.Interpolate", {"points"},
                            surfaces(), &SS::Interpolate,
                            SurfaceInterpolationOver(values)));
    }
    return cases;
  }

  // The streams over the output limit, and the tessellations whose answer
  // is just over the number of points the server allows: a curve's point
  // costs its coordinates and its parameter; a unary mesh may hold what
  // fits one message at 92 bytes a vertex (position, normal, (u, v), patch
  // index and about two triangles), a streamed one max_output_values / 16
  // vertices (surface_refinement.cc).
  std::vector<OverLimitCase> StreamAndTessellationCases() {
    using CS = v1::CurveService::Stub;
    using SS = v1::SurfaceService::Stub;
    const auto polyline_cap = [](int dimension) -> size_t {
      return std::min<uint64_t>({kLimits.max_parameters,
                                 kMessageValues / (dimension + 1),
                                 kOutputValues / (dimension + 1)});
    };
    const size_t streamed_mesh_cap =
        std::min<uint64_t>(kLimits.max_parameters, kOutputValues / 16);
    const size_t mesh_cap = std::min<uint64_t>(
        streamed_mesh_cap,
        static_cast<uint64_t>(kLimits.max_message_bytes) / 92);
    return {
        Stream("CurveService.EvaluateStream", {"parameters"}, curves(),
               &CS::EvaluateStream, CurveEvaluationOver(kOutputValues)),
        Stream("SurfaceService.EvaluateStream", {"parameters"}, surfaces(),
               &SS::EvaluateStream, SurfaceEvaluationOver(kOutputValues)),
        // The polyline's a-priori bound is over the cap before any work,
        // yet the server subdivides up to the cap before it refuses: 0.2 s
        // in 64-D, 0.7 s and 56 MB in 2-D (measured, not asserted).
        Unary("CurveService.Tessellate", {"tolerance", "max_points"}, curves(),
              &CS::Tessellate, CurvePolylineOver(polyline_cap(64), 64)),
        Unary("CurveService.Tessellate (2-D)", {"tolerance", "max_points"},
              curves(), &CS::Tessellate, CurvePolylineOver(polyline_cap(2), 2)),
        Unary("SurfaceService.Tessellate", {"tolerance", "max_vertices"},
              surfaces(), &SS::Tessellate, MeshOver(mesh_cap)),
        Stream("SurfaceService.TessellateStream", {"tolerance", "max_vertices"},
               surfaces(), &SS::TessellateStream, MeshOver(streamed_mesh_cap)),
    };
  }

  // SettledBudgetInUse returns the budget in use once the server has
  // finished the calls the client has seen end: a call releases its
  // reservation when it is done on the server's side, which may come just
  // after the client has its status.
  uint64_t SettledBudgetInUse() const {
    for (int i = 0; i < 200 && server_->budget().in_use() != 0; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return server_->budget().in_use();
  }

  // ExpectRefusedCheaply makes the call and checks RESOURCE_EXHAUSTED with
  // one field violation on an accepted path, a peak memory that grew by
  // less than kRefusalMemory besides two copies of the request (the
  // client's serialized one and the server's parsed one), and no memory
  // left reserved.
  void ExpectRefusedCheaply(const OverLimitCase& over) {
    SCOPED_TRACE(over.rpc);
    ResetPeakRss();
    const uint64_t before = PeakRssBytes();
    const absl::Status status = over.call();
    // The kernel syncs its counters lazily: a peak may read a little low.
    const uint64_t grown = std::max(PeakRssBytes(), before) - before;
    EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted) << status;
    const std::vector<FieldViolation> violations = FieldViolationsOf(status);
    EXPECT_EQ(violations.size(), 1u) << status;
    if (!violations.empty()) {
      const std::string& field = violations[0].field;
      EXPECT_TRUE(std::any_of(over.fields.begin(), over.fields.end(),
                              [&](const std::string& accepted) {
                                return field == accepted ||
                                       field.rfind(accepted + ".", 0) == 0 ||
                                       field.rfind(accepted + "[", 0) == 0;
                              }))
          << "field " << field << " of " << status;
    }
    EXPECT_LT(grown,
              kRefusalMemory + 2 * over.request_bytes * kShadowMemoryFactor)
        << "peak memory grew by " << grown / kMiB << " MiB for a request of "
        << over.request_bytes / kMiB << " MiB";
    EXPECT_EQ(SettledBudgetInUse(), 0u);
  }
};

// Unary answers trip the 64 MiB message limit before the output limit of
// 64 * 10^6 values; either is fine.
TEST_F(AdmissionTest, EveryUnaryRpcJustOverTheOutputLimitIsRefusedCheaply) {
  for (const OverLimitCase& over : UnaryCasesOver(kOutputValues)) {
    ExpectRefusedCheaply(over);
  }
}

TEST_F(AdmissionTest, EveryUnaryRpcJustOverTheMessageLimitIsRefusedCheaply) {
  for (const OverLimitCase& over : UnaryCasesOver(kMessageValues)) {
    ExpectRefusedCheaply(over);
  }
}

TEST_F(AdmissionTest, StreamsAndTessellationsJustOverTheLimitAreRefused) {
  for (const OverLimitCase& over : StreamAndTessellationCases()) {
    ExpectRefusedCheaply(over);
  }
}

// A grid is refused by its size, not after its axes are made: a 2 KB
// request for 10^7 u values of a 64-D patch (over the output limit), or for
// a 10^7 x 10^7 grid (over --max_parameters), must not cost the hundreds of
// MiB its axes would take.
TEST_F(AdmissionTest, GridsOverTheLimitsAreRefusedCheaply) {
  using SS = v1::SurfaceService::Stub;
  v1::EvaluateSurfaceRequest request = SurfaceEvaluationOver(kOutputValues);
  v1::SurfaceGrid* grid = request.mutable_parameters()->mutable_grid();
  SetRange(grid->mutable_u(), kLimits.max_parameters);
  ExpectRefusedCheaply(Unary("SurfaceService.Evaluate", {"parameters"},
                             surfaces(), &SS::Evaluate, request));
  SetRange(grid->mutable_v(), kLimits.max_parameters);
  ExpectRefusedCheaply(Stream("SurfaceService.EvaluateStream", {"parameters"},
                              surfaces(), &SS::EvaluateStream, request));
}

// --------------------------------------------------------------- budget --

// A cubic Bezier curve of `dimension` at `count` parameters.
v1::EvaluateCurveRequest CubicAt(int dimension, uint64_t count) {
  v1::EvaluateCurveRequest request;
  SetPoints(request.mutable_curve()->mutable_bezier()->mutable_control_points(),
            dimension, 4);
  SetRange(request.mutable_parameters(), count);
  return request;
}

// A stream holds its reservation (three chunks in flight) while its client
// does not read; meanwhile a call that does not fit the rest of the budget
// is refused and a small one is served. Once the stream is read to its end,
// the refused call fits.
TEST_F(AdmissionTest, CallOverTheBudgetIsRefusedWhileOthersComplete) {
  ServiceLimits limits;
  limits.memory_budget_bytes = 48 * kMiB;
  StartServer(limits);
  // Over TCP, so that HTTP/2 flow control stops the stream's writes.
  ClientOptions options;
  options.target = absl::StrCat("127.0.0.1:", server_->port());
  options.timeout = Scaled(std::chrono::seconds(20));
  absl::StatusOr<std::unique_ptr<Client>> remote = Client::Create(options);
  ASSERT_TRUE(remote.ok()) << remote.status();

  // 2 * 10^6 points of 10-D in chunks of 65536: 160 MB in all, 3 chunks of
  // 5.2 MB in flight reserve 30 MiB.
  constexpr uint64_t kStreamPoints = 2'000'000;
  v1::EvaluateCurveRequest streamed = CubicAt(10, kStreamPoints);
  streamed.set_chunk_size(65536);
  std::unique_ptr<grpc::ClientContext> context = (*remote)->NewContext();
  std::unique_ptr<grpc::ClientReader<v1::EvaluateCurveResponse>> reader =
      (*remote)->curves().EvaluateStream(context.get(), streamed);
  v1::EvaluateCurveResponse chunk;
  ASSERT_TRUE(reader->Read(&chunk));
  uint64_t points = chunk.count();
  EXPECT_GE(server_->budget().in_use(), 30 * kMiB);

  // 2 * 10^6 values: 32 MB planned, which fits the budget but not what the
  // stream leaves of it.
  const v1::EvaluateCurveRequest large = CubicAt(2, 1'000'000);
  absl::StatusOr<CurveSamples> refused = client_->EvaluateCurve(large);
  EXPECT_EQ(refused.status().code(), absl::StatusCode::kResourceExhausted)
      << refused.status();
  EXPECT_THAT(std::string(refused.status().message()),
              HasSubstr("--memory_budget"));
  absl::StatusOr<CurveSamples> small = client_->EvaluateCurve(CubicAt(2, 3));
  ASSERT_TRUE(small.ok()) << small.status();
  EXPECT_EQ(small->count, 3u);

  while (reader->Read(&chunk)) {
    EXPECT_EQ(chunk.first_index(), points);
    points += chunk.count();
  }
  const grpc::Status finished = reader->Finish();
  EXPECT_TRUE(finished.ok()) << finished.error_message();
  EXPECT_EQ(points, kStreamPoints);

  EXPECT_EQ(SettledBudgetInUse(), 0u);
  absl::StatusOr<CurveSamples> retried = client_->EvaluateCurve(large);
  ASSERT_TRUE(retried.ok()) << retried.status();
  EXPECT_EQ(retried->count, 1'000'000u);
}

// ---------------------------------------------------- stream and unary --

// ExpectSameBits checks that two arrays hold the same doubles bit for bit.
void ExpectSameBits(const google::protobuf::RepeatedField<double>& unary,
                    const std::vector<double>& streamed,
                    const std::string& what) {
  ASSERT_EQ(static_cast<size_t>(unary.size()), streamed.size()) << what;
  for (size_t i = 0; i < streamed.size(); ++i) {
    if (std::bit_cast<uint64_t>(unary[static_cast<int>(i)]) !=
        std::bit_cast<uint64_t>(streamed[i])) {
      ADD_FAILURE() << what << "[" << i << "]: unary "
                    << unary[static_cast<int>(i)] << ", streamed "
                    << streamed[i];
      return;
    }
  }
}

template <typename T>
void Extend(std::vector<T>& joined,
            const google::protobuf::RepeatedField<T>& part) {
  joined.insert(joined.end(), part.begin(), part.end());
}

// A random bicubic NURBS surface in 3D with interior knots in both
// directions.
v1::Surface RandomNurbsSurface() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  v1::Surface surface;
  v1::BSplineSurface* bspline = surface.mutable_bspline();
  bspline->set_degree_u(3);
  bspline->set_degree_v(3);
  v1::ControlNet* net = bspline->mutable_control_net();
  net->set_dimension(3);
  net->set_count_u(7);
  net->set_count_v(6);
  for (int i = 0; i < 7 * 6; ++i) {
    Append(
        net->mutable_coordinates(),
        {i / 6 + 0.2 * uniform(rng), i % 6 + 0.2 * uniform(rng), uniform(rng)});
    bspline->add_weights(1.25 + 0.75 * uniform(rng));
  }
  Append(bspline->mutable_knots_u(), {0, 0, 0, 0, 0.2, 0.5, 0.7, 1, 1, 1, 1});
  Append(bspline->mutable_knots_v(), {0, 0, 0, 0, 0.4, 0.6, 1, 1, 1, 1});
  return surface;
}

// Unary Evaluate against EvaluateStream of the same request: the chunks
// cover the points in order and join into the unary answer bit for bit.
void ExpectStreamEqualsUnary(v1::SurfaceService::Stub& stub,
                             const v1::EvaluateSurfaceRequest& request,
                             uint64_t points) {
  std::unique_ptr<grpc::ClientContext> context = DeadlineContext();
  v1::EvaluateSurfaceResponse unary;
  const grpc::Status status = stub.Evaluate(context.get(), request, &unary);
  ASSERT_TRUE(status.ok()) << status.error_message();
  ASSERT_EQ(unary.count(), points);
  std::vector<v1::EvaluateSurfaceResponse> chunks;
  const absl::Status streamed = ReadAll(
      stub, &v1::SurfaceService::Stub::EvaluateStream, request, &chunks);
  ASSERT_TRUE(streamed.ok()) << streamed;
  EXPECT_GT(chunks.size(), 2u);
  std::vector<std::vector<double>> partials(unary.partials_size());
  std::vector<double> normals;
  uint64_t covered = 0;
  for (const v1::EvaluateSurfaceResponse& chunk : chunks) {
    EXPECT_EQ(chunk.first_index(), covered);
    covered += chunk.count();
    ASSERT_EQ(chunk.partials_size(), unary.partials_size());
    for (int k = 0; k < chunk.partials_size(); ++k) {
      EXPECT_EQ(chunk.partials(k).order_u(), unary.partials(k).order_u());
      EXPECT_EQ(chunk.partials(k).order_v(), unary.partials(k).order_v());
      Extend(partials[k], chunk.partials(k).values().coordinates());
    }
    Extend(normals, chunk.normals().coordinates());
  }
  EXPECT_EQ(covered, points);
  for (int k = 0; k < unary.partials_size(); ++k) {
    ExpectSameBits(unary.partials(k).values().coordinates(), partials[k],
                   absl::StrCat("partial ", k));
  }
  ExpectSameBits(unary.normals().coordinates(), normals, "normals");
}

// Partials to order 2 and normals of a NURBS surface, on a grid whose rows
// (37 points) the requested chunk sizes do not divide, and at (u, v) pairs
// laid out like that grid, where chunks end inside a row.
TEST_F(AdmissionTest, SurfaceStreamEqualsUnaryBitForBit) {
  v1::EvaluateSurfaceRequest grid;
  *grid.mutable_surface() = RandomNurbsSurface();
  grid.set_derivative_order(2);
  grid.set_normals(true);
  SetRange(grid.mutable_parameters()->mutable_grid()->mutable_u(), 101);
  SetRange(grid.mutable_parameters()->mutable_grid()->mutable_v(), 37);
  for (uint32_t chunk : {100u, 20u, 1000u}) {
    SCOPED_TRACE(absl::StrCat("grid, chunk_size ", chunk));
    grid.set_chunk_size(chunk);
    ExpectStreamEqualsUnary(surfaces(), grid, 101 * 37);
  }

  v1::EvaluateSurfaceRequest pairs = grid;
  auto* uv = pairs.mutable_parameters()->mutable_points()->mutable_uv();
  for (int i = 0; i < 101; ++i) {
    for (int j = 0; j < 37; ++j) Append(uv, {i / 100.0, j / 36.0});
  }
  for (uint32_t chunk : {100u, 20u, 1000u}) {
    SCOPED_TRACE(absl::StrCat("pairs, chunk_size ", chunk));
    pairs.set_chunk_size(chunk);
    ExpectStreamEqualsUnary(surfaces(), pairs, 101 * 37);
  }
}

// The teapot meshed by Tessellate and by TessellateStream: the streamed
// vertices, normals, (u, v), patch indices and triangles, joined, are the
// unary mesh exactly.
TEST_F(AdmissionTest, TeapotStreamEqualsUnaryBitForBit) {
  v1::TessellateSurfaceRequest request = TeapotRequest();
  ASSERT_EQ(request.surfaces_size(), 32);
  request.set_tolerance(1e-3);
  request.set_normals(true);
  request.set_chunk_size(1000);
  std::unique_ptr<grpc::ClientContext> context = DeadlineContext();
  v1::TessellateSurfaceResponse unary;
  const grpc::Status status =
      surfaces().Tessellate(context.get(), request, &unary);
  ASSERT_TRUE(status.ok()) << status.error_message();
  std::vector<v1::TessellateSurfaceResponse> chunks;
  const absl::Status streamed =
      ReadAll(surfaces(), &v1::SurfaceService::Stub::TessellateStream, request,
              &chunks);
  ASSERT_TRUE(streamed.ok()) << streamed;
  EXPECT_GT(chunks.size(), 2u);
  std::vector<double> vertices, normals, uv;
  std::vector<uint32_t> triangles, surface_index;
  for (const v1::TessellateSurfaceResponse& chunk : chunks) {
    // Indices refer only to vertices sent before or with this chunk.
    const uint32_t sent = static_cast<uint32_t>(
        (vertices.size() + chunk.vertices().coordinates_size()) / 3);
    for (uint32_t index : chunk.triangles()) ASSERT_LT(index, sent);
    Extend(vertices, chunk.vertices().coordinates());
    Extend(normals, chunk.normals().coordinates());
    Extend(uv, chunk.uv());
    Extend(surface_index, chunk.surface_index());
    Extend(triangles, chunk.triangles());
  }
  EXPECT_GT(unary.vertices().coordinates_size(), 3000);
  ExpectSameBits(unary.vertices().coordinates(), vertices, "vertices");
  ExpectSameBits(unary.normals().coordinates(), normals, "normals");
  ExpectSameBits(unary.uv(), uv, "uv");
  EXPECT_EQ(std::vector<uint32_t>(unary.surface_index().begin(),
                                  unary.surface_index().end()),
            surface_index);
  EXPECT_EQ(
      std::vector<uint32_t>(unary.triangles().begin(), unary.triangles().end()),
      triangles);
}

}  // namespace
}  // namespace freeform::server
