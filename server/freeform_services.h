// The freeform.v1 services freeformd serves, by full name: the one list
// that the server's registration check, the metrics' method names and the
// HTTP gateway's routing read. Adding a service adds it here.
#ifndef FREEFORM_SERVER_FREEFORM_SERVICES_H_
#define FREEFORM_SERVER_FREEFORM_SERVICES_H_

#include <array>

#include "freeform/v1/curve_service.grpc.pb.h"
#include "freeform/v1/face_service.grpc.pb.h"
#include "freeform/v1/surface_service.grpc.pb.h"

namespace freeform::server {

inline std::array<const char*, 3> FreeformServiceNames() {
  return {v1::CurveService::service_full_name(),
          v1::SurfaceService::service_full_name(),
          v1::FaceService::service_full_name()};
}

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_FREEFORM_SERVICES_H_
