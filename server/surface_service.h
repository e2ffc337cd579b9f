// SurfaceServiceImpl: freeform.v1.SurfaceService on top of the core.
//
// Evaluation converts the request to core views (no copies), checks the
// server's limits, runs the core on the shared thread pool under the RPC's
// cancellation token and writes partials and normals straight into the
// response; knot removal and fitting are in surface_approximation.cc, the
// queries in surface_queries.cc.
// Thread-safe: one instance serves all calls.
#ifndef FREEFORM_SERVER_SURFACE_SERVICE_H_
#define FREEFORM_SERVER_SURFACE_SERVICE_H_

#include "freeform/v1/surface_service.grpc.pb.h"
#include "rpc.h"

namespace freeform::server {

class SurfaceServiceImpl final : public v1::SurfaceService::CallbackService {
 public:
  // `frame` must outlive the service.
  explicit SurfaceServiceImpl(RpcFrame* frame) : frame_(frame) {}

  grpc::ServerUnaryReactor* Evaluate(
      grpc::CallbackServerContext* context,
      const v1::EvaluateSurfaceRequest* request,
      v1::EvaluateSurfaceResponse* response) override;
  grpc::ServerWriteReactor<v1::EvaluateSurfaceResponse>* EvaluateStream(
      grpc::CallbackServerContext* context,
      const v1::EvaluateSurfaceRequest* request) override;
  grpc::ServerUnaryReactor* EvaluateBasis(
      grpc::CallbackServerContext* context,
      const v1::EvaluateSurfaceBasisRequest* request,
      v1::EvaluateSurfaceBasisResponse* response) override;
  grpc::ServerUnaryReactor* Split(grpc::CallbackServerContext* context,
                                  const v1::SplitSurfaceRequest* request,
                                  v1::SplitSurfaceResponse* response) override;
  grpc::ServerUnaryReactor* InsertKnots(
      grpc::CallbackServerContext* context,
      const v1::InsertSurfaceKnotsRequest* request,
      v1::InsertSurfaceKnotsResponse* response) override;
  grpc::ServerUnaryReactor* Tessellate(
      grpc::CallbackServerContext* context,
      const v1::TessellateSurfaceRequest* request,
      v1::TessellateSurfaceResponse* response) override;
  grpc::ServerWriteReactor<v1::TessellateSurfaceResponse>* TessellateStream(
      grpc::CallbackServerContext* context,
      const v1::TessellateSurfaceRequest* request) override;
  grpc::ServerUnaryReactor* ElevateDegree(
      grpc::CallbackServerContext* context,
      const v1::ElevateSurfaceDegreeRequest* request,
      v1::ElevateSurfaceDegreeResponse* response) override;
  grpc::ServerUnaryReactor* Interpolate(
      grpc::CallbackServerContext* context,
      const v1::InterpolateSurfaceRequest* request,
      v1::InterpolateSurfaceResponse* response) override;
  grpc::ServerUnaryReactor* RemoveKnots(
      grpc::CallbackServerContext* context,
      const v1::RemoveSurfaceKnotsRequest* request,
      v1::RemoveSurfaceKnotsResponse* response) override;
  grpc::ServerUnaryReactor* Fit(grpc::CallbackServerContext* context,
                                const v1::FitSurfaceRequest* request,
                                v1::FitSurfaceResponse* response) override;
  grpc::ServerUnaryReactor* FitScattered(
      grpc::CallbackServerContext* context,
      const v1::FitScatteredSurfaceRequest* request,
      v1::FitScatteredSurfaceResponse* response) override;

  grpc::ServerUnaryReactor* ClosestPoint(
      grpc::CallbackServerContext* context,
      const v1::SurfaceClosestPointRequest* request,
      v1::ClosestPointResponse* response) override;
  grpc::ServerUnaryReactor* IntersectCurve(
      grpc::CallbackServerContext* context,
      const v1::IntersectCurveSurfaceRequest* request,
      v1::IntersectCurveSurfaceResponse* response) override;
  grpc::ServerUnaryReactor* Section(
      grpc::CallbackServerContext* context,
      const v1::SectionSurfaceRequest* request,
      v1::SectionSurfaceResponse* response) override;
  grpc::ServerUnaryReactor* Curvature(
      grpc::CallbackServerContext* context,
      const v1::SurfaceCurvatureRequest* request,
      v1::SurfaceCurvatureResponse* response) override;
  grpc::ServerUnaryReactor* BoundingBox(
      grpc::CallbackServerContext* context,
      const v1::SurfaceBoundingBoxRequest* request,
      v1::BoundingBoxResponse* response) override;

 private:
  RpcFrame* const frame_;
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_SURFACE_SERVICE_H_
