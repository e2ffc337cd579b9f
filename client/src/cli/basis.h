// `freeform basis`: values and derivatives of blending functions
// (CurveService.EvaluateBasis; SurfaceService.EvaluateBasis with --surface).
#ifndef FREEFORM_CLIENT_CLI_BASIS_H_
#define FREEFORM_CLIENT_CLI_BASIS_H_

#include <string>

#include "CLI/CLI.hpp"
#include "common.h"

namespace freeform::cli {

struct BasisOptions {
  std::string file;
  bool surface = false;
  std::string format = "json";
};

void AddBasisFlags(CLI::App& command, BasisOptions& options);
int RunBasis(const CommonFlags& flags, const BasisOptions& options);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_BASIS_H_
