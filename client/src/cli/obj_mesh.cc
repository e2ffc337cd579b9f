#include "obj_mesh.h"

namespace freeform::cli {

void ObjMesh::AddGrid(const std::string& name, size_t count_u, size_t count_v,
                      absl::Span<const double> points,
                      absl::Span<const double> normals) {
  const size_t first = vertex_count();
  groups_.push_back({.name = name, .first_triangle = triangles_.size()});
  vertices_.insert(vertices_.end(), points.begin(), points.end());
  normals_.insert(normals_.end(), normals.begin(), normals.end());
  for (size_t i = 0; i + 1 < count_u; ++i) {
    for (size_t j = 0; j + 1 < count_v; ++j) {
      const size_t p00 = first + i * count_v + j;
      const size_t p01 = p00 + 1;
      const size_t p10 = p00 + count_v;
      const size_t p11 = p10 + 1;
      triangles_.push_back({p00, p10, p11});
      triangles_.push_back({p00, p11, p01});
    }
  }
}

void ObjMesh::AddTriangles(
    const std::string& name,
    const google::protobuf::RepeatedField<double>& vertices,
    const google::protobuf::RepeatedField<double>& normals,
    const google::protobuf::RepeatedField<uint32_t>& triangles) {
  const size_t first = vertex_count();
  groups_.push_back({.name = name, .first_triangle = triangles_.size()});
  vertices_.insert(vertices_.end(), vertices.begin(), vertices.end());
  normals_.insert(normals_.end(), normals.begin(), normals.end());
  for (int t = 0; t + 2 < triangles.size(); t += 3) {
    triangles_.push_back({first + triangles[t], first + triangles[t + 1],
                          first + triangles[t + 2]});
  }
}

void ObjMesh::Write(std::ostream& out) const {
  out.precision(17);
  out << "# freeform: " << vertex_count() << " vertices, " << triangle_count()
      << " triangles\n";
  for (size_t v = 0; v < vertex_count(); ++v) {
    out << "v " << vertices_[3 * v] << " " << vertices_[3 * v + 1] << " "
        << vertices_[3 * v + 2] << "\n";
  }
  const bool with_normals = normals_.size() == vertices_.size();
  if (with_normals) {
    for (size_t v = 0; v < vertex_count(); ++v) {
      out << "vn " << normals_[3 * v] << " " << normals_[3 * v + 1] << " "
          << normals_[3 * v + 2] << "\n";
    }
  }
  size_t group = 0;
  for (size_t t = 0; t < triangles_.size(); ++t) {
    while (group < groups_.size() && groups_[group].first_triangle == t) {
      out << "g " << groups_[group++].name << "\n";
    }
    out << "f";
    for (size_t index : triangles_[t]) {
      out << " " << index + 1;
      if (with_normals) out << "//" << index + 1;
    }
    out << "\n";
  }
}

}  // namespace freeform::cli
