// `freeform interpolate` (interpolate.h).
#include "interpolate.h"

#include <algorithm>
#include <map>
#include <vector>

#include "input.h"
#include "run_call.h"
#include "subcommand.h"

namespace freeform::cli {
namespace {

// Accepts "chord-length" for "chord_length": values are spelled like the
// flags, and the earlier snake_case spelling still works.
std::string Snake(std::string value) {
  std::replace(value.begin(), value.end(), '-', '_');
  return value;
}

void SetMethod(const InterpolateOptions& options,
               const std::vector<std::vector<double>>& rows,
               v1::InterpolateCurveRequest& request) {
  const std::map<std::string, v1::Parameterization> kinds = {
      {"uniform", v1::PARAMETERIZATION_UNIFORM},
      {"chord_length", v1::PARAMETERIZATION_CHORD_LENGTH},
      {"centripetal", v1::PARAMETERIZATION_CENTRIPETAL},
      {"universal", v1::PARAMETERIZATION_UNIVERSAL}};
  if (!options.spline.empty()) {
    const std::map<std::string, v1::SplineEndCondition> ends = {
        {"natural", v1::SPLINE_END_CONDITION_NATURAL},
        {"not_a_knot", v1::SPLINE_END_CONDITION_NOT_A_KNOT},
        {"periodic", v1::SPLINE_END_CONDITION_PERIODIC}};
    auto* method = request.mutable_cubic_spline();
    method->set_end_condition(ends.at(options.spline));
    for (const std::vector<double>& row : rows) method->add_parameters(row[0]);
  } else if (options.least_squares_points > 0) {
    auto* method = request.mutable_least_squares();
    method->set_degree(static_cast<uint32_t>(options.degree));
    method->set_control_point_count(
        static_cast<uint32_t>(options.least_squares_points));
    method->set_parameterization(kinds.at(options.parameterization));
  } else {
    auto* method = request.mutable_bspline();
    method->set_degree(static_cast<uint32_t>(options.degree));
    method->set_parameterization(kinds.at(options.parameterization));
    method->set_closed(options.closed);
  }
}

}  // namespace

absl::StatusOr<v1::InterpolateCurveRequest> CsvRequest(
    const InterpolateOptions& options) {
  absl::StatusOr<std::vector<std::vector<double>>> rows =
      ReadCsvRows(options.csv);
  if (!rows.ok()) return rows.status();
  const size_t first = options.spline.empty() ? 0 : 1;
  if (rows->front().size() <= first) {
    return absl::InvalidArgumentError("the CSV rows need more columns");
  }
  v1::InterpolateCurveRequest request;
  v1::Points* points = request.mutable_points();
  points->set_dimension(static_cast<uint32_t>(rows->front().size() - first));
  for (const std::vector<double>& row : *rows) {
    points->mutable_coordinates()->Add(row.begin() + first, row.end());
  }
  SetMethod(options, *rows, request);
  return request;
}

void AddInterpolateFlags(CLI::App& command, InterpolateOptions& options) {
  AddFileFlag(command, options.file);
  command.add_flag("--surface", options.surface,
                   "The request is an InterpolateSurfaceRequest");
  command.add_option("--csv", options.csv,
                     "Points from CSV, one per line (x,y[,z...])");
  command.add_option("--degree", options.degree, "Degree (with --csv)")
      ->capture_default_str();
  command
      .add_option("--parameterization", options.parameterization,
                  "uniform, chord-length, centripetal or universal")
      ->transform(Snake)
      ->check(CLI::IsMember(
          {"uniform", "chord_length", "centripetal", "universal"}))
      ->capture_default_str();
  command.add_flag("--closed", options.closed, "Interpolate a closed curve");
  command
      .add_option("--spline", options.spline,
                  "Cubic spline of function data (first CSV column is x): "
                  "natural, not-a-knot or periodic")
      ->transform(Snake)
      ->check(CLI::IsMember({"natural", "not_a_knot", "periodic"}));
  command.add_option("--least-squares", options.least_squares_points,
                     "Least-squares fit with this many control points instead");
}

int RunInterpolate(const CommonFlags& flags,
                   const InterpolateOptions& options) {
  if (options.surface) {
    return RunJsonCall(flags, options.file,
                       &v1::SurfaceService::Stub::Interpolate);
  }
  if (options.csv.empty()) {
    return RunJsonCall(flags, options.file,
                       &v1::CurveService::Stub::Interpolate);
  }
  absl::StatusOr<v1::InterpolateCurveRequest> request = CsvRequest(options);
  if (!request.ok()) return InputError(request.status());
  std::unique_ptr<Client> client = Connect(flags);
  if (client == nullptr) return kExitUsage;
  absl::StatusOr<v1::InterpolateCurveResponse> response =
      client->InterpolateCurve(*request);
  if (!response.ok()) return ReportError(response.status());
  return PrintJson(flags, *response);
}

}  // namespace freeform::cli
