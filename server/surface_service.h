// SurfaceServiceImpl: freeform.v1.SurfaceService on top of the core.
//
// Evaluation converts the request to core views (no copies), checks the
// server's limits, runs the core on the shared thread pool under the RPC's
// cancellation token and writes partials and normals straight into the
// response. RPCs of later issues answer UNIMPLEMENTED, naming the issue.
// Thread-safe: one instance serves all calls.
#ifndef FREEFORM_SERVER_SURFACE_SERVICE_H_
#define FREEFORM_SERVER_SURFACE_SERVICE_H_

#include "freeform/core/thread_pool.h"
#include "freeform/v1/surface_service.grpc.pb.h"
#include "service_limits.h"

namespace freeform::server {

class SurfaceServiceImpl final : public v1::SurfaceService::Service {
 public:
  SurfaceServiceImpl(ThreadPool* pool, const ServiceLimits& limits);

  grpc::Status Evaluate(grpc::ServerContext* context,
                        const v1::EvaluateSurfaceRequest* request,
                        v1::EvaluateSurfaceResponse* response) override;
  grpc::Status EvaluateStream(
      grpc::ServerContext* context, const v1::EvaluateSurfaceRequest* request,
      grpc::ServerWriter<v1::EvaluateSurfaceResponse>* writer) override;
  grpc::Status EvaluateBasis(
      grpc::ServerContext* context,
      const v1::EvaluateSurfaceBasisRequest* request,
      v1::EvaluateSurfaceBasisResponse* response) override;
  grpc::Status Split(grpc::ServerContext* context,
                     const v1::SplitSurfaceRequest* request,
                     v1::SplitSurfaceResponse* response) override;
  grpc::Status InsertKnots(grpc::ServerContext* context,
                           const v1::InsertSurfaceKnotsRequest* request,
                           v1::InsertSurfaceKnotsResponse* response) override;
  grpc::Status Tessellate(grpc::ServerContext* context,
                          const v1::TessellateSurfaceRequest* request,
                          v1::TessellateSurfaceResponse* response) override;
  grpc::Status TessellateStream(
      grpc::ServerContext* context, const v1::TessellateSurfaceRequest* request,
      grpc::ServerWriter<v1::TessellateSurfaceResponse>* writer) override;
  grpc::Status ElevateDegree(
      grpc::ServerContext* context,
      const v1::ElevateSurfaceDegreeRequest* request,
      v1::ElevateSurfaceDegreeResponse* response) override;
  grpc::Status Interpolate(grpc::ServerContext* context,
                           const v1::InterpolateSurfaceRequest* request,
                           v1::InterpolateSurfaceResponse* response) override;

 private:
  ThreadPool* const pool_;
  const ServiceLimits limits_;
  HeavyWorkAdmission admission_;
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_SURFACE_SERVICE_H_
