// freeform::Client: the C++ client library of the freeform service.
//
// Connects to one freeformd or to a list of replicas (client-side
// round_robin), applies a per-call deadline, retries UNAVAILABLE calls, and
// returns absl::StatusOr of plain C++ types for the common calls. Errors keep
// the server's gRPC code; an INVALID_ARGUMENT's google.rpc.BadRequest field
// violations are available through FieldViolationsOf. Every other unary
// RPC is Unary(&v1::CurveService::Stub::ArcLength, request) (any method of
// either service's stub); streams use curves() / surfaces() with
// NewContext().
//
// Thread-safe: one Client may serve many threads at once.
//
// Example:
//   auto client = freeform::Client::Create({.target = "localhost:50051"});
//   auto samples = (*client)->EvaluateBezier(
//       2, {0, 0, 1, 2, 3, 2, 4, 0}, {0.0, 0.5, 1.0}, /*derivative_order=*/1);
//   // samples->Point(0, 1) is (2, 1.5); samples->Point(1, 0) is (3, 6).
#ifndef FREEFORM_CLIENT_H_
#define FREEFORM_CLIENT_H_

#include <grpcpp/channel.h>
#include <grpcpp/client_context.h>

#include <chrono>
#include <cstddef>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "absl/functional/function_ref.h"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/v1/curve_service.grpc.pb.h"
#include "freeform/v1/face_service.grpc.pb.h"
#include "freeform/v1/surface_service.grpc.pb.h"

namespace freeform {

struct ClientOptions {
  // A gRPC target: "host:port", "dns:///name:port", "ipv4:a:p,b:p", ...
  // Ignored when `replicas` is set.
  std::string target = "localhost:50051";
  // Several "host:port" replicas balanced client-side with round_robin.
  std::vector<std::string> replicas;
  // Use round_robin over every address `target` resolves to (for a DNS
  // name with several records, such as a Kubernetes headless Service:
  // "dns:///freeformd.NAMESPACE.svc.cluster.local:50051", or with the DNS
  // server named, "dns://10.0.0.10:53/NAME:PORT"). A balanced channel
  // (this or `replicas`) health-checks every replica (grpc.health.v1
  // Watch): one that reports NOT_SERVING, as a draining freeformd does,
  // gets no new call.
  bool round_robin = false;
  // The shortest time between two DNS resolutions of `target`; 0 keeps
  // gRPC's 30 s. gRPC resolves again when a connection closes (a replica
  // drains, or sends GOAWAY at its --max_connection_age), but never sooner
  // than this after the last resolution: a new replica gets calls only
  // after both.
  std::chrono::milliseconds min_time_between_resolutions{0};
  // Deadline of each call.
  std::chrono::milliseconds timeout{30'000};
  // Largest message the client accepts.
  int max_receive_message_bytes = 64 << 20;
  // The bytes of a stream gRPC may receive ahead of the reader (the HTTP/2
  // flow-control window), so that a stream read slowly (EvaluateCurveStream
  // writing text) holds bounded memory; 0 lets gRPC grow the window with
  // the bandwidth-delay product, which on a fast link buffers up to
  // hundreds of MB of a long stream.
  int stream_window_bytes = 0;
  // Retry calls that fail with UNAVAILABLE (up to 4 attempts, backoff).
  bool retry_unavailable = true;
  // TLS: on when `use_tls`; root CA (empty = system roots) and an optional
  // client certificate and key for mutual TLS, all PEM files.
  bool use_tls = false;
  std::string root_ca_file;
  std::string cert_file;
  std::string key_file;
};

// Points (and derivatives) of a curve at a batch of parameters.
struct CurveSamples {
  int dimension = 0;
  size_t count = 0;
  // derivatives[k][r * dimension + j]: derivative k at parameter r.
  std::vector<std::vector<double>> derivatives;

  // Point returns derivative `order` at parameter index `index`.
  absl::Span<const double> Point(size_t order, size_t index) const {
    return absl::MakeConstSpan(derivatives[order])
        .subspan(index * static_cast<size_t>(dimension),
                 static_cast<size_t>(dimension));
  }
};

// Values (and derivatives) of a set of blending functions at a batch of
// parameters.
struct BasisSamples {
  size_t function_count = 0;
  size_t count = 0;
  // derivatives[k][r * function_count + i]: derivative k of function i at
  // parameter r.
  std::vector<std::vector<double>> derivatives;

  double Value(size_t order, size_t index, size_t function) const {
    return derivatives[order][index * function_count + function];
  }
};

// Points, partial derivatives and normals of a surface at a batch of
// (u, v) points or on a grid (u-major: point (i, j) is i * count(v) + j).
struct SurfaceEvaluation {
  struct Partial {
    int order_u = 0;
    int order_v = 0;
    // count * dimension values.
    std::vector<double> values;
  };
  int dimension = 0;
  size_t count = 0;
  // In the server's order: (0,0), (1,0), (0,1), (2,0), (1,1), (0,2), ...
  std::vector<Partial> partials;
  // count * 3 values when normals were asked for.
  std::vector<double> normals;

  // Point returns partial (order_u, order_v) at point `index`, or an empty
  // span when that partial was not computed.
  absl::Span<const double> Point(int order_u, int order_v, size_t index) const;
};

// One google.rpc.BadRequest field violation.
struct FieldViolation {
  std::string field;
  std::string description;
};

// FromGrpcStatus converts a gRPC status; the binary error details travel as
// the payload FieldViolationsOf reads.
absl::Status FromGrpcStatus(const grpc::Status& status);

// FieldViolationsOf returns the field violations an error carries (empty
// when it carries none).
std::vector<FieldViolation> FieldViolationsOf(const absl::Status& status);

class Client {
 public:
  // Create builds a channel from `options` (no connection is made yet).
  static absl::StatusOr<std::unique_ptr<Client>> Create(
      const ClientOptions& options);
  // Wraps an existing channel, for tests and custom setups.
  Client(std::shared_ptr<grpc::Channel> channel, const ClientOptions& options);

  // EvaluateBezier evaluates the Bezier curve with `control_points`
  // (dimension coordinates each) at `parameters`, with derivatives up to
  // `derivative_order`.
  absl::StatusOr<CurveSamples> EvaluateBezier(
      int dimension, absl::Span<const double> control_points,
      absl::Span<const double> parameters, int derivative_order = 0);

  // EvaluateCurve runs CurveService.Evaluate.
  absl::StatusOr<CurveSamples> EvaluateCurve(
      const v1::EvaluateCurveRequest& request);

  // EvaluateCurveStreamed runs CurveService.EvaluateStream and joins the
  // chunks, for answers larger than one message.
  absl::StatusOr<CurveSamples> EvaluateCurveStreamed(
      const v1::EvaluateCurveRequest& request);

  // EvaluateCurveStream runs CurveService.EvaluateStream and hands each
  // chunk to `on_chunk` as it arrives, so an answer of any size is read in
  // constant memory. The chunks are checked to follow one another
  // (first_index); an error from `on_chunk` cancels the call and is
  // returned.
  absl::Status EvaluateCurveStream(
      const v1::EvaluateCurveRequest& request,
      absl::FunctionRef<absl::Status(const v1::EvaluateCurveResponse&)>
          on_chunk);

  // EvaluateSurface runs SurfaceService.Evaluate.
  absl::StatusOr<SurfaceEvaluation> EvaluateSurface(
      const v1::EvaluateSurfaceRequest& request);

  // EvaluateSurfaceStreamed runs SurfaceService.EvaluateStream and joins the
  // chunks.
  absl::StatusOr<SurfaceEvaluation> EvaluateSurfaceStreamed(
      const v1::EvaluateSurfaceRequest& request);

  // EvaluateSurfaceStream runs SurfaceService.EvaluateStream chunk by
  // chunk, as EvaluateCurveStream does.
  absl::Status EvaluateSurfaceStream(
      const v1::EvaluateSurfaceRequest& request,
      absl::FunctionRef<absl::Status(const v1::EvaluateSurfaceResponse&)>
          on_chunk);

  // EvaluateSurfaceBasis runs SurfaceService.EvaluateBasis (values only:
  // derivatives[0] of the result).
  absl::StatusOr<BasisSamples> EvaluateSurfaceBasis(
      const v1::EvaluateSurfaceBasisRequest& request);

  // EvaluateBasis runs CurveService.EvaluateBasis.
  absl::StatusOr<BasisSamples> EvaluateBasis(
      const v1::EvaluateBasisRequest& request);

  // Unary calls `method` of `stub` with this client's deadline and returns
  // the response, or the server's error (see FieldViolationsOf). For RPCs
  // without a convenience method, e.g.
  //   client.Unary(client.curves(), &v1::CurveService::Stub::ElevateDegree,
  //                request);
  template <typename Stub, typename Request, typename Response>
  absl::StatusOr<Response> Unary(
      Stub& stub,
      grpc::Status (Stub::*method)(grpc::ClientContext*, const Request&,
                                   Response*),
      const Request& request) {
    std::unique_ptr<grpc::ClientContext> context = NewContext();
    Response response;
    if (grpc::Status status = (stub.*method)(context.get(), request, &response);
        !status.ok()) {
      return FromGrpcStatus(status);
    }
    return response;
  }

  // Unary on this client's stub of the method's service, e.g.
  //   client.Unary(&v1::CurveService::Stub::ArcLength, request);
  template <typename Stub, typename Request, typename Response>
  absl::StatusOr<Response> Unary(
      grpc::Status (Stub::*method)(grpc::ClientContext*, const Request&,
                                   Response*),
      const Request& request) {
    return Unary(StubOf<Stub>(), method, request);
  }

  // The degree and interpolation RPCs.
  absl::StatusOr<v1::ElevateCurveDegreeResponse> ElevateCurveDegree(
      const v1::ElevateCurveDegreeRequest& request) {
    return Unary(*curves_, &v1::CurveService::Stub::ElevateDegree, request);
  }
  absl::StatusOr<v1::ReduceCurveDegreeResponse> ReduceCurveDegree(
      const v1::ReduceCurveDegreeRequest& request) {
    return Unary(*curves_, &v1::CurveService::Stub::ReduceDegree, request);
  }
  absl::StatusOr<v1::InterpolateCurveResponse> InterpolateCurve(
      const v1::InterpolateCurveRequest& request) {
    return Unary(*curves_, &v1::CurveService::Stub::Interpolate, request);
  }
  absl::StatusOr<v1::ElevateSurfaceDegreeResponse> ElevateSurfaceDegree(
      const v1::ElevateSurfaceDegreeRequest& request) {
    return Unary(*surfaces_, &v1::SurfaceService::Stub::ElevateDegree, request);
  }
  absl::StatusOr<v1::InterpolateSurfaceResponse> InterpolateSurface(
      const v1::InterpolateSurfaceRequest& request) {
    return Unary(*surfaces_, &v1::SurfaceService::Stub::Interpolate, request);
  }

  // Knot removal and fitting.
  absl::StatusOr<v1::RemoveCurveKnotsResponse> RemoveCurveKnots(
      const v1::RemoveCurveKnotsRequest& request) {
    return Unary(*curves_, &v1::CurveService::Stub::RemoveKnots, request);
  }
  absl::StatusOr<v1::FitCurveResponse> FitCurve(
      const v1::FitCurveRequest& request) {
    return Unary(*curves_, &v1::CurveService::Stub::Fit, request);
  }
  absl::StatusOr<v1::RemoveSurfaceKnotsResponse> RemoveSurfaceKnots(
      const v1::RemoveSurfaceKnotsRequest& request) {
    return Unary(*surfaces_, &v1::SurfaceService::Stub::RemoveKnots, request);
  }
  absl::StatusOr<v1::FitSurfaceResponse> FitSurface(
      const v1::FitSurfaceRequest& request) {
    return Unary(*surfaces_, &v1::SurfaceService::Stub::Fit, request);
  }
  absl::StatusOr<v1::FitScatteredSurfaceResponse> FitScatteredSurface(
      const v1::FitScatteredSurfaceRequest& request) {
    return Unary(*surfaces_, &v1::SurfaceService::Stub::FitScattered, request);
  }

  // Subdivision, refinement and tessellation.
  absl::StatusOr<v1::SplitCurveResponse> SplitCurve(
      const v1::SplitCurveRequest& request) {
    return Unary(*curves_, &v1::CurveService::Stub::Split, request);
  }
  absl::StatusOr<v1::InsertKnotsResponse> InsertCurveKnots(
      const v1::InsertKnotsRequest& request) {
    return Unary(*curves_, &v1::CurveService::Stub::InsertKnots, request);
  }
  absl::StatusOr<v1::DecomposeCurveResponse> DecomposeCurve(
      const v1::DecomposeCurveRequest& request) {
    return Unary(*curves_, &v1::CurveService::Stub::Decompose, request);
  }
  absl::StatusOr<v1::SubdivideResponse> SubdividePolygon(
      const v1::SubdivideRequest& request) {
    return Unary(*curves_, &v1::CurveService::Stub::Subdivide, request);
  }
  absl::StatusOr<v1::TessellateCurveResponse> TessellateCurve(
      const v1::TessellateCurveRequest& request) {
    return Unary(*curves_, &v1::CurveService::Stub::Tessellate, request);
  }
  absl::StatusOr<v1::SplitSurfaceResponse> SplitSurface(
      const v1::SplitSurfaceRequest& request) {
    return Unary(*surfaces_, &v1::SurfaceService::Stub::Split, request);
  }
  absl::StatusOr<v1::InsertSurfaceKnotsResponse> InsertSurfaceKnots(
      const v1::InsertSurfaceKnotsRequest& request) {
    return Unary(*surfaces_, &v1::SurfaceService::Stub::InsertKnots, request);
  }
  absl::StatusOr<v1::TessellateSurfaceResponse> TessellateSurfaces(
      const v1::TessellateSurfaceRequest& request) {
    return Unary(*surfaces_, &v1::SurfaceService::Stub::Tessellate, request);
  }

  // The trimmed faces' RPCs.
  absl::StatusOr<v1::ClassifyFacePointsResponse> ClassifyFacePoints(
      const v1::ClassifyFacePointsRequest& request) {
    return Unary(*faces_, &v1::FaceService::Stub::Classify, request);
  }
  absl::StatusOr<v1::EvaluateFaceResponse> EvaluateFace(
      const v1::EvaluateFaceRequest& request) {
    return Unary(*faces_, &v1::FaceService::Stub::Evaluate, request);
  }
  absl::StatusOr<v1::FaceAreaResponse> FaceArea(
      const v1::FaceAreaRequest& request) {
    return Unary(*faces_, &v1::FaceService::Stub::Area, request);
  }
  absl::StatusOr<v1::TessellateFaceResponse> TessellateFace(
      const v1::TessellateFaceRequest& request) {
    return Unary(*faces_, &v1::FaceService::Stub::Tessellate, request);
  }

  // CheckHealth asks grpc.health.v1.Health; OK means SERVING, UNAVAILABLE
  // means NOT_SERVING; other codes are transport errors.
  absl::Status CheckHealth(const std::string& service = "");

  // NewContext returns a context with this client's deadline.
  std::unique_ptr<grpc::ClientContext> NewContext() const;

  v1::CurveService::Stub& curves() { return *curves_; }
  v1::SurfaceService::Stub& surfaces() { return *surfaces_; }
  v1::FaceService::Stub& faces() { return *faces_; }
  const std::shared_ptr<grpc::Channel>& channel() const { return channel_; }

 private:
  // The stub of `Stub`'s service.
  template <typename Stub>
  Stub& StubOf() {
    if constexpr (std::is_same_v<Stub, v1::CurveService::Stub>) {
      return *curves_;
    } else if constexpr (std::is_same_v<Stub, v1::FaceService::Stub>) {
      return *faces_;
    } else {
      static_assert(std::is_same_v<Stub, v1::SurfaceService::Stub>,
                    "a stub of CurveService, SurfaceService or FaceService");
      return *surfaces_;
    }
  }

  ClientOptions options_;
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::CurveService::Stub> curves_;
  std::unique_ptr<v1::SurfaceService::Stub> surfaces_;
  std::unique_ptr<v1::FaceService::Stub> faces_;
};

}  // namespace freeform

#endif  // FREEFORM_CLIENT_H_
