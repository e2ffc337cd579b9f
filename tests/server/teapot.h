// TeapotRequest: the Utah teapot of examples/teapot.json (32 bicubic Bezier
// patches) as a TessellateSurfaceRequest, for the service tests that mesh
// it.
#ifndef FREEFORM_TESTS_SERVER_TEAPOT_H_
#define FREEFORM_TESTS_SERVER_TEAPOT_H_

#include <fstream>
#include <sstream>
#include <string>

#include "freeform/v1/surface_service.pb.h"

namespace freeform::server {

// Minimal reader of the patches' numbers: 16 points of 3 per patch after
// each "control_points".
inline v1::TessellateSurfaceRequest TeapotRequest() {
  std::ifstream file(FREEFORM_SOURCE_DIR "/examples/teapot.json");
  std::stringstream text;
  text << file.rdbuf();
  const std::string json = text.str();
  v1::TessellateSurfaceRequest request;
  size_t at = 0;
  while ((at = json.find("\"control_points\"", at)) != std::string::npos) {
    v1::ControlNet* net =
        request.add_surfaces()->mutable_bezier()->mutable_control_net();
    net->set_dimension(3);
    net->set_count_u(4);
    net->set_count_v(4);
    size_t cursor = json.find('[', at);
    for (int value = 0; value < 48; ++value) {
      cursor = json.find_first_of("-0123456789", cursor);
      size_t used = 0;
      net->add_coordinates(std::stod(json.substr(cursor, 32), &used));
      cursor += used;
    }
    at = cursor;
  }
  return request;
}

}  // namespace freeform::server

#endif  // FREEFORM_TESTS_SERVER_TEAPOT_H_
