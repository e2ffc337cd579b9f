// `freeform subdivide`: Chaikin / uniform B-spline subdivision of a polygon
// (CurveService.Subdivide), printed as JSON or drawn as SVG with every
// level.
#ifndef FREEFORM_CLIENT_CLI_SUBDIVIDE_H_
#define FREEFORM_CLIENT_CLI_SUBDIVIDE_H_

#include <string>

#include "CLI/CLI.hpp"
#include "common.h"

namespace freeform::cli {

struct SubdivideOptions {
  std::string file;
  std::string svg;
};

void AddSubdivideFlags(CLI::App& command, SubdivideOptions& options);
int RunSubdivide(const CommonFlags& flags, const SubdivideOptions& options);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_SUBDIVIDE_H_
