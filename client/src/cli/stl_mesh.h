// WriteBinaryStl: a triangle mesh as binary STL (an 80-byte header, the
// triangle count, and per triangle its unit normal, three vertices as
// 32-bit floats and a zero attribute word), the format 3D printing and CAD
// viewers read.
#ifndef FREEFORM_CLIENT_CLI_STL_MESH_H_
#define FREEFORM_CLIENT_CLI_STL_MESH_H_

#include <google/protobuf/repeated_field.h>

#include <cstdint>
#include <ostream>

namespace freeform::cli {

// WriteBinaryStl writes the triangles (three 0-based indices each) of the
// 3D `vertices`; facet normals follow the right-hand rule of the vertex
// order (0 for a degenerate triangle).
void WriteBinaryStl(const google::protobuf::RepeatedField<double>& vertices,
                    const google::protobuf::RepeatedField<uint32_t>& triangles,
                    std::ostream& out);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_STL_MESH_H_
