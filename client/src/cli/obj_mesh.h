// Triangle meshes of surface grids, written as Wavefront OBJ (for the CLI's
// --obj output): a grid of nu x nv evaluated points becomes (nu-1)(nv-1)
// quads, each split into two triangles ordered counter-clockwise seen
// against the normal S_u x S_v. Not thread-safe (one mesh, one writer).
#ifndef FREEFORM_CLIENT_CLI_OBJ_MESH_H_
#define FREEFORM_CLIENT_CLI_OBJ_MESH_H_

#include <array>
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "absl/types/span.h"
#include "google/protobuf/repeated_field.h"

namespace freeform::cli {

class ObjMesh {
 public:
  // AddGrid appends a u-major grid of `count_u` x `count_v` 3D points (and
  // unit normals, when `normals` is not empty) as one OBJ group.
  void AddGrid(const std::string& name, size_t count_u, size_t count_v,
               absl::Span<const double> points,
               absl::Span<const double> normals);

  // AddTriangles appends an indexed triangle mesh (3D vertices, optional
  // per-vertex normals, 0-based vertex indices) as one OBJ group.
  void AddTriangles(const std::string& name,
                    const google::protobuf::RepeatedField<double>& vertices,
                    const google::protobuf::RepeatedField<double>& normals,
                    const google::protobuf::RepeatedField<uint32_t>& triangles);

  // Write prints the mesh as OBJ text.
  void Write(std::ostream& out) const;

  size_t vertex_count() const { return vertices_.size() / 3; }
  size_t triangle_count() const { return triangles_.size(); }

 private:
  struct Group {
    std::string name;
    size_t first_triangle = 0;
  };
  std::vector<double> vertices_;
  std::vector<double> normals_;
  std::vector<std::array<size_t, 3>> triangles_;  // 0-based vertex indices
  std::vector<Group> groups_;
};

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_OBJ_MESH_H_
