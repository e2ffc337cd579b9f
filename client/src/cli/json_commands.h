// The freeform CLI's plain JSON subcommands: one request read as proto3
// JSON, one unary RPC, the answer printed as JSON. With --surface a
// subcommand sends the SurfaceService form of its request (elevate, split,
// insert-knots, remove-knots, fit, intersect, bbox); fit --surface
// --scattered sends SurfaceService.FitScattered.
#ifndef FREEFORM_CLIENT_CLI_JSON_COMMANDS_H_
#define FREEFORM_CLIENT_CLI_JSON_COMMANDS_H_

#include <string>

#include "CLI/CLI.hpp"
#include "common.h"
#include "run_call.h"

namespace freeform::cli {

struct RequestOptions {
  std::string file;
  bool surface = false;
  bool scattered = false;  // fit only
};

// -f/--file only.
void AddRequestFlags(CLI::App& command, RequestOptions& options);
// -f/--file and --surface.
void AddCurveOrSurfaceFlags(CLI::App& command, RequestOptions& options);
// fit: -f/--file, --surface and --scattered.
void AddFitFlags(CLI::App& command, RequestOptions& options);

// Sends `kMethod` (a CurveService or SurfaceService stub method).
template <auto kMethod>
int RunRequest(const CommonFlags& flags, const RequestOptions& options) {
  return RunJsonCall(flags, options.file, kMethod);
}

// Sends `kCurveMethod`, or `kSurfaceMethod` with --surface.
template <auto kCurveMethod, auto kSurfaceMethod>
int RunCurveOrSurface(const CommonFlags& flags, const RequestOptions& options) {
  return options.surface ? RunJsonCall(flags, options.file, kSurfaceMethod)
                         : RunJsonCall(flags, options.file, kCurveMethod);
}

// fit: CurveService.Fit, SurfaceService.Fit or SurfaceService.FitScattered.
int RunFit(const CommonFlags& flags, const RequestOptions& options);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_JSON_COMMANDS_H_
