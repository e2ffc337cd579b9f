// `freeform interpolate`: a curve or surface through points
// (CurveService/SurfaceService.Interpolate) from a JSON request, or a
// curve through the points of a CSV file with the method set by flags.
#ifndef FREEFORM_CLIENT_CLI_INTERPOLATE_H_
#define FREEFORM_CLIENT_CLI_INTERPOLATE_H_

#include <string>

#include "CLI/CLI.hpp"
#include "absl/status/statusor.h"
#include "common.h"
#include "freeform/v1/curve_service.pb.h"

namespace freeform::cli {

struct InterpolateOptions {
  std::string file;
  bool surface = false;
  // Points from CSV instead of a request, with the method's flags.
  std::string csv;
  int degree = 3;
  std::string parameterization = "chord_length";
  bool closed = false;
  // Cubic spline of function data: the first column is the abscissa.
  std::string spline;
  int least_squares_points = 0;
};

void AddInterpolateFlags(CLI::App& command, InterpolateOptions& options);
int RunInterpolate(const CommonFlags& flags, const InterpolateOptions& options);

// CsvRequest builds the request of --csv and the method's flags.
absl::StatusOr<v1::InterpolateCurveRequest> CsvRequest(
    const InterpolateOptions& options);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_INTERPOLATE_H_
