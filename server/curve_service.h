// CurveServiceImpl: freeform.v1.CurveService on top of the core.
//
// Evaluation, refinement and construction (curve_service.cc,
// curve_operations.cc, curve_refinement.cc), knot removal and fitting
// (curve_approximation.cc) and the queries
// (curve_queries.cc, curve_measures.cc). Each handler converts the request to
// core views (no copies), checks the server's limits, runs the core on the
// shared thread pool under the RPC's cancellation token and writes results
// straight into the response. Thread-safe: one instance serves all calls.
#ifndef FREEFORM_SERVER_CURVE_SERVICE_H_
#define FREEFORM_SERVER_CURVE_SERVICE_H_

#include "freeform/v1/curve_service.grpc.pb.h"
#include "rpc.h"

namespace freeform::server {

class CurveServiceImpl final : public v1::CurveService::CallbackService {
 public:
  // `frame` must outlive the service.
  explicit CurveServiceImpl(RpcFrame* frame) : frame_(frame) {}

  grpc::ServerUnaryReactor* Evaluate(
      grpc::CallbackServerContext* context,
      const v1::EvaluateCurveRequest* request,
      v1::EvaluateCurveResponse* response) override;
  grpc::ServerWriteReactor<v1::EvaluateCurveResponse>* EvaluateStream(
      grpc::CallbackServerContext* context,
      const v1::EvaluateCurveRequest* request) override;
  grpc::ServerUnaryReactor* EvaluateBasis(
      grpc::CallbackServerContext* context,
      const v1::EvaluateBasisRequest* request,
      v1::EvaluateBasisResponse* response) override;
  grpc::ServerUnaryReactor* Split(grpc::CallbackServerContext* context,
                                  const v1::SplitCurveRequest* request,
                                  v1::SplitCurveResponse* response) override;
  grpc::ServerUnaryReactor* InsertKnots(
      grpc::CallbackServerContext* context,
      const v1::InsertKnotsRequest* request,
      v1::InsertKnotsResponse* response) override;
  grpc::ServerUnaryReactor* Decompose(
      grpc::CallbackServerContext* context,
      const v1::DecomposeCurveRequest* request,
      v1::DecomposeCurveResponse* response) override;
  grpc::ServerUnaryReactor* Subdivide(grpc::CallbackServerContext* context,
                                      const v1::SubdivideRequest* request,
                                      v1::SubdivideResponse* response) override;
  grpc::ServerUnaryReactor* Tessellate(
      grpc::CallbackServerContext* context,
      const v1::TessellateCurveRequest* request,
      v1::TessellateCurveResponse* response) override;
  grpc::ServerUnaryReactor* ElevateDegree(
      grpc::CallbackServerContext* context,
      const v1::ElevateCurveDegreeRequest* request,
      v1::ElevateCurveDegreeResponse* response) override;
  grpc::ServerUnaryReactor* ReduceDegree(
      grpc::CallbackServerContext* context,
      const v1::ReduceCurveDegreeRequest* request,
      v1::ReduceCurveDegreeResponse* response) override;
  grpc::ServerUnaryReactor* Interpolate(
      grpc::CallbackServerContext* context,
      const v1::InterpolateCurveRequest* request,
      v1::InterpolateCurveResponse* response) override;
  grpc::ServerUnaryReactor* RemoveKnots(
      grpc::CallbackServerContext* context,
      const v1::RemoveCurveKnotsRequest* request,
      v1::RemoveCurveKnotsResponse* response) override;
  grpc::ServerUnaryReactor* Fit(grpc::CallbackServerContext* context,
                                const v1::FitCurveRequest* request,
                                v1::FitCurveResponse* response) override;

  grpc::ServerUnaryReactor* ClosestPoint(
      grpc::CallbackServerContext* context,
      const v1::CurveClosestPointRequest* request,
      v1::ClosestPointResponse* response) override;
  grpc::ServerUnaryReactor* Intersect(
      grpc::CallbackServerContext* context,
      const v1::IntersectCurvesRequest* request,
      v1::IntersectCurvesResponse* response) override;
  grpc::ServerUnaryReactor* ArcLength(grpc::CallbackServerContext* context,
                                      const v1::ArcLengthRequest* request,
                                      v1::ArcLengthResponse* response) override;
  grpc::ServerUnaryReactor* ParametersAtArcLength(
      grpc::CallbackServerContext* context,
      const v1::ParametersAtArcLengthRequest* request,
      v1::ParametersAtArcLengthResponse* response) override;
  grpc::ServerUnaryReactor* SampleByArcLength(
      grpc::CallbackServerContext* context,
      const v1::SampleByArcLengthRequest* request,
      v1::SampleByArcLengthResponse* response) override;
  grpc::ServerUnaryReactor* Curvature(
      grpc::CallbackServerContext* context,
      const v1::CurveCurvatureRequest* request,
      v1::CurveCurvatureResponse* response) override;
  grpc::ServerUnaryReactor* RotationMinimizingFrames(
      grpc::CallbackServerContext* context,
      const v1::RotationMinimizingFramesRequest* request,
      v1::RotationMinimizingFramesResponse* response) override;
  grpc::ServerUnaryReactor* BoundingBox(
      grpc::CallbackServerContext* context,
      const v1::CurveBoundingBoxRequest* request,
      v1::BoundingBoxResponse* response) override;

 private:
  RpcFrame* const frame_;
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_CURVE_SERVICE_H_
