// CurveServiceImpl: freeform.v1.CurveService on top of the core.
//
// Each handler converts the request to core views (no copies), checks the
// server's limits, runs the core on the shared thread pool under the RPC's
// cancellation token and writes results straight into the response.
// Thread-safe: one instance serves all calls.
#ifndef FREEFORM_SERVER_CURVE_SERVICE_H_
#define FREEFORM_SERVER_CURVE_SERVICE_H_

#include "freeform/core/thread_pool.h"
#include "freeform/v1/curve_service.grpc.pb.h"
#include "service_limits.h"

namespace freeform::server {

class CurveServiceImpl final : public v1::CurveService::Service {
 public:
  // `pool` must outlive the service.
  CurveServiceImpl(ThreadPool* pool, const ServiceLimits& limits);

  grpc::Status Evaluate(grpc::ServerContext* context,
                        const v1::EvaluateCurveRequest* request,
                        v1::EvaluateCurveResponse* response) override;
  grpc::Status EvaluateStream(
      grpc::ServerContext* context, const v1::EvaluateCurveRequest* request,
      grpc::ServerWriter<v1::EvaluateCurveResponse>* writer) override;
  grpc::Status EvaluateBasis(grpc::ServerContext* context,
                             const v1::EvaluateBasisRequest* request,
                             v1::EvaluateBasisResponse* response) override;
  grpc::Status Split(grpc::ServerContext* context,
                     const v1::SplitCurveRequest* request,
                     v1::SplitCurveResponse* response) override;
  grpc::Status InsertKnots(grpc::ServerContext* context,
                           const v1::InsertKnotsRequest* request,
                           v1::InsertKnotsResponse* response) override;
  grpc::Status Decompose(grpc::ServerContext* context,
                         const v1::DecomposeCurveRequest* request,
                         v1::DecomposeCurveResponse* response) override;
  grpc::Status Subdivide(grpc::ServerContext* context,
                         const v1::SubdivideRequest* request,
                         v1::SubdivideResponse* response) override;
  grpc::Status Tessellate(grpc::ServerContext* context,
                          const v1::TessellateCurveRequest* request,
                          v1::TessellateCurveResponse* response) override;
  grpc::Status ElevateDegree(grpc::ServerContext* context,
                             const v1::ElevateCurveDegreeRequest* request,
                             v1::ElevateCurveDegreeResponse* response) override;
  grpc::Status ReduceDegree(grpc::ServerContext* context,
                            const v1::ReduceCurveDegreeRequest* request,
                            v1::ReduceCurveDegreeResponse* response) override;
  grpc::Status Interpolate(grpc::ServerContext* context,
                           const v1::InterpolateCurveRequest* request,
                           v1::InterpolateCurveResponse* response) override;

 private:
  ThreadPool* const pool_;
  const ServiceLimits limits_;
  HeavyWorkAdmission admission_;
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_CURVE_SERVICE_H_
