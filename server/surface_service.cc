#include "surface_service.h"

#include "rpc.h"

namespace freeform::server {

SurfaceServiceImpl::SurfaceServiceImpl(ThreadPool* pool,
                                       const ServiceLimits& limits)
    : pool_(pool), limits_(limits) {}

grpc::Status SurfaceServiceImpl::Evaluate(
    grpc::ServerContext* context, const v1::EvaluateSurfaceRequest* request,
    v1::EvaluateSurfaceResponse*) {
  return RunUnimplemented("SurfaceService.Evaluate", context, *request,
                          "issue #4");
}

grpc::Status SurfaceServiceImpl::EvaluateStream(
    grpc::ServerContext* context, const v1::EvaluateSurfaceRequest* request,
    grpc::ServerWriter<v1::EvaluateSurfaceResponse>*) {
  return RunUnimplemented("SurfaceService.EvaluateStream", context, *request,
                          "issue #4");
}

grpc::Status SurfaceServiceImpl::EvaluateBasis(
    grpc::ServerContext* context,
    const v1::EvaluateSurfaceBasisRequest* request,
    v1::EvaluateSurfaceBasisResponse*) {
  return RunUnimplemented("SurfaceService.EvaluateBasis", context, *request,
                          "issue #4");
}

grpc::Status SurfaceServiceImpl::Split(grpc::ServerContext* context,
                                       const v1::SplitSurfaceRequest* request,
                                       v1::SplitSurfaceResponse*) {
  return RunUnimplemented("SurfaceService.Split", context, *request,
                          "issue #5");
}

grpc::Status SurfaceServiceImpl::InsertKnots(
    grpc::ServerContext* context, const v1::InsertSurfaceKnotsRequest* request,
    v1::InsertSurfaceKnotsResponse*) {
  return RunUnimplemented("SurfaceService.InsertKnots", context, *request,
                          "issue #5");
}

grpc::Status SurfaceServiceImpl::Tessellate(
    grpc::ServerContext* context, const v1::TessellateSurfaceRequest* request,
    v1::TessellateSurfaceResponse*) {
  return RunUnimplemented("SurfaceService.Tessellate", context, *request,
                          "issue #5");
}

grpc::Status SurfaceServiceImpl::TessellateStream(
    grpc::ServerContext* context, const v1::TessellateSurfaceRequest* request,
    grpc::ServerWriter<v1::TessellateSurfaceResponse>*) {
  return RunUnimplemented("SurfaceService.TessellateStream", context, *request,
                          "issue #5");
}

grpc::Status SurfaceServiceImpl::ElevateDegree(
    grpc::ServerContext* context,
    const v1::ElevateSurfaceDegreeRequest* request,
    v1::ElevateSurfaceDegreeResponse*) {
  return RunUnimplemented("SurfaceService.ElevateDegree", context, *request,
                          "issue #6");
}

grpc::Status SurfaceServiceImpl::Interpolate(
    grpc::ServerContext* context, const v1::InterpolateSurfaceRequest* request,
    v1::InterpolateSurfaceResponse*) {
  return RunUnimplemented("SurfaceService.Interpolate", context, *request,
                          "issue #7");
}

}  // namespace freeform::server
