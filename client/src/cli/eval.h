// `freeform eval`: points and derivatives of a curve
// (CurveService.Evaluate, or EvaluateStream with --stream, written as the
// chunks arrive).
#ifndef FREEFORM_CLIENT_CLI_EVAL_H_
#define FREEFORM_CLIENT_CLI_EVAL_H_

#include <string>

#include "CLI/CLI.hpp"
#include "common.h"

namespace freeform::cli {

struct EvalOptions {
  std::string file;
  bool stream = false;
  std::string format = "json";
};

void AddEvalFlags(CLI::App& command, EvalOptions& options);
int RunEval(const CommonFlags& flags, const EvalOptions& options);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_EVAL_H_
