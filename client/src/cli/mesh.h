// `freeform mesh`: a set of Bezier patches in the layout of
// examples/teapot.json, each evaluated on a grid (SurfaceService.Evaluate)
// and written as one OBJ mesh.
#ifndef FREEFORM_CLIENT_CLI_MESH_H_
#define FREEFORM_CLIENT_CLI_MESH_H_

#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "absl/status/statusor.h"
#include "common.h"
#include "freeform/v1/geometry.pb.h"

namespace freeform::cli {

struct MeshOptions {
  std::string patches_file;
  int grid = 16;
  std::string obj = "-";
};

void AddMeshFlags(CLI::App& command, MeshOptions& options);
int RunMesh(const CommonFlags& flags, const MeshOptions& options);

// ReadBezierPatches reads {"degree_u": m, "degree_v": n, "patches":
// [{"control_points": [[x, y, z], ...]}, ...]} with (m+1)(n+1) row-major
// points per patch; malformed input is an error naming the file.
absl::StatusOr<std::vector<v1::Surface>> ReadBezierPatches(
    const std::string& file);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_MESH_H_
