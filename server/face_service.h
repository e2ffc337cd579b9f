// FaceServiceImpl: freeform.v1.FaceService on top of the core's trimmed
// faces (core/trimmed_surface.h, core/face_mesh.h): Classify, Evaluate,
// Area and Tessellate. Each call prepares its face (prepare_face.h) and
// samples, plans the answer and the face's working memory, and validates
// the face on the pool under the call's token before answering.
// Thread-safe: one instance serves all calls.
#ifndef FREEFORM_SERVER_FACE_SERVICE_H_
#define FREEFORM_SERVER_FACE_SERVICE_H_

#include "freeform/v1/face_service.grpc.pb.h"
#include "rpc.h"

namespace freeform::server {

class FaceServiceImpl final : public v1::FaceService::CallbackService {
 public:
  // `frame` must outlive the service.
  explicit FaceServiceImpl(RpcFrame* frame) : frame_(frame) {}

  grpc::ServerUnaryReactor* Classify(
      grpc::CallbackServerContext* context,
      const v1::ClassifyFacePointsRequest* request,
      v1::ClassifyFacePointsResponse* response) override;
  grpc::ServerUnaryReactor* Evaluate(
      grpc::CallbackServerContext* context,
      const v1::EvaluateFaceRequest* request,
      v1::EvaluateFaceResponse* response) override;
  grpc::ServerUnaryReactor* Area(grpc::CallbackServerContext* context,
                                 const v1::FaceAreaRequest* request,
                                 v1::FaceAreaResponse* response) override;
  grpc::ServerUnaryReactor* Tessellate(
      grpc::CallbackServerContext* context,
      const v1::TessellateFaceRequest* request,
      v1::TessellateFaceResponse* response) override;

 private:
  RpcFrame* frame_;
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_FACE_SERVICE_H_
