// `freeform surface`: points, partial derivatives and normals of a surface
// (SurfaceService.Evaluate, or EvaluateStream with --stream, written as the
// chunks arrive), or a grid's OBJ mesh.
#ifndef FREEFORM_CLIENT_CLI_SURFACE_H_
#define FREEFORM_CLIENT_CLI_SURFACE_H_

#include <string>

#include "CLI/CLI.hpp"
#include "common.h"

namespace freeform::cli {

struct SurfaceOptions {
  std::string file;
  bool stream = false;
  std::string format = "json";
  std::string obj;
};

void AddSurfaceFlags(CLI::App& command, SurfaceOptions& options);
int RunSurface(const CommonFlags& flags, const SurfaceOptions& options);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_SURFACE_H_
