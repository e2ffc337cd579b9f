#include "stl_mesh.h"

#include <array>
#include <cmath>
#include <cstring>
#include <string>

namespace freeform::cli {
namespace {

// STL is little-endian; so are the machines this builds for.
template <typename T>
void Put(std::ostream& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.write(bytes, sizeof(T));
}

}  // namespace

void WriteBinaryStl(const google::protobuf::RepeatedField<double>& vertices,
                    const google::protobuf::RepeatedField<uint32_t>& triangles,
                    std::ostream& out) {
  std::string header = "binary STL written by freeform";
  header.resize(80, ' ');
  out.write(header.data(), 80);
  const int count = triangles.size() / 3;
  Put<uint32_t>(out, static_cast<uint32_t>(count));
  for (int t = 0; t < count; ++t) {
    std::array<const double*, 3> corner;
    for (int k = 0; k < 3; ++k) {
      corner[k] =
          vertices.data() + 3 * static_cast<size_t>(triangles[3 * t + k]);
    }
    double e1[3], e2[3];
    for (int x = 0; x < 3; ++x) {
      e1[x] = corner[1][x] - corner[0][x];
      e2[x] = corner[2][x] - corner[0][x];
    }
    double normal[3] = {e1[1] * e2[2] - e1[2] * e2[1],
                        e1[2] * e2[0] - e1[0] * e2[2],
                        e1[0] * e2[1] - e1[1] * e2[0]};
    const double length = std::hypot(normal[0], normal[1], normal[2]);
    for (double& n : normal) n = length > 0 ? n / length : 0.0;
    for (const double n : normal) Put<float>(out, static_cast<float>(n));
    for (const double* p : corner) {
      for (int x = 0; x < 3; ++x) Put<float>(out, static_cast<float>(p[x]));
    }
    Put<uint16_t>(out, 0);
  }
}

}  // namespace freeform::cli
