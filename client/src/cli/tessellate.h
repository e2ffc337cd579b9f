// `freeform tessellate`: an adaptive polyline of a curve
// (CurveService.Tessellate; JSON, or SVG with an optional curvature comb)
// or a mesh of surfaces with --surface (SurfaceService.Tessellate; JSON,
// OBJ or binary STL).
#ifndef FREEFORM_CLIENT_CLI_TESSELLATE_H_
#define FREEFORM_CLIENT_CLI_TESSELLATE_H_

#include <optional>
#include <string>

#include "CLI/CLI.hpp"
#include "common.h"

namespace freeform::cli {

struct TessellateOptions {
  std::string file;
  bool surface = false;
  std::string svg;
  std::string obj;
  std::string stl;
  bool combs = false;
  double comb_scale = 0;  // 0: the default
  // Surfaces: the largest angle between the normals at an edge's ends.
  std::optional<double> max_normal_angle;
};

void AddTessellateFlags(CLI::App& command, TessellateOptions& options);
int RunTessellate(const CommonFlags& flags, const TessellateOptions& options);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_TESSELLATE_H_
