// The freeform CLI's plain JSON subcommands (json_commands.h).
#include "json_commands.h"

#include "subcommand.h"

namespace freeform::cli {

void AddRequestFlags(CLI::App& command, RequestOptions& options) {
  AddFileFlag(command, options.file);
}

void AddCurveOrSurfaceFlags(CLI::App& command, RequestOptions& options) {
  AddFileFlag(command, options.file);
  command.add_flag("--surface", options.surface,
                   "Send the SurfaceService form of the request");
}

void AddFitFlags(CLI::App& command, RequestOptions& options) {
  AddCurveOrSurfaceFlags(command, options);
  command.add_flag(
      "--scattered", options.scattered,
      "With --surface: the request is a FitScatteredSurfaceRequest");
}

int RunFit(const CommonFlags& flags, const RequestOptions& options) {
  if (options.scattered && !options.surface) {
    return InputError(absl::InvalidArgumentError(
        "freeform fit: --scattered needs --surface"));
  }
  if (options.scattered) {
    return RunJsonCall(flags, options.file,
                       &v1::SurfaceService::Stub::FitScattered);
  }
  return RunCurveOrSurface<&v1::CurveService::Stub::Fit,
                           &v1::SurfaceService::Stub::Fit>(flags, options);
}

}  // namespace freeform::cli
