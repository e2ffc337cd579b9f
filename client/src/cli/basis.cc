// `freeform basis` (basis.h): the response message's JSON, or one row per
// parameter: every function's value (f0, f1, ...), then each derivative's
// (d1f0, ...).
#include "basis.h"

#include <cstdio>
#include <vector>

#include "absl/strings/str_cat.h"
#include "rows.h"
#include "run_call.h"
#include "subcommand.h"

namespace freeform::cli {
namespace {

using Span = absl::Span<const double>;

// Writes `values` (one span per derivative order, each count *
// function_count values) as rows.
int WriteRows(RowFormat format, size_t function_count, size_t count,
              const std::vector<Span>& values) {
  RowWriter writer(format, stdout);
  std::vector<ColumnGroup> groups;
  for (size_t k = 0; k < values.size(); ++k) {
    groups.push_back({.json_name = k == 0 ? "values" : absl::StrCat("d", k),
                      .csv_prefix = k == 0 ? "f" : absl::StrCat("d", k, "f"),
                      .width = function_count});
  }
  writer.Begin(std::move(groups),
               {{"functionCount", static_cast<int64_t>(function_count)}});
  if (absl::Status status = writer.Rows(0, count, values); !status.ok()) {
    return ReportError(status);
  }
  return FinishRows(writer);
}

int PrintCurveBasis(const CommonFlags& flags, RowFormat format,
                    const v1::EvaluateBasisResponse& response) {
  if (format == RowFormat::kJson) return PrintJson(flags, response);
  std::vector<Span> values;
  for (const v1::BasisValues& derivative : response.derivatives()) {
    values.emplace_back(derivative.values().data(), derivative.values_size());
  }
  return WriteRows(format, response.function_count(), response.count(), values);
}

int PrintSurfaceBasis(const CommonFlags& flags, RowFormat format,
                      const v1::EvaluateSurfaceBasisResponse& response) {
  if (format == RowFormat::kJson) return PrintJson(flags, response);
  return WriteRows(format, response.function_count(), response.count(),
                   {Span(response.values().data(), response.values_size())});
}

// Runs `method` and prints its answer with `print`.
template <typename Stub, typename Request, typename Response>
int RunAndPrint(const CommonFlags& flags, const BasisOptions& options,
                RpcMethod<Stub, Request, Response> method,
                int (*print)(const CommonFlags&, RowFormat, const Response&)) {
  absl::StatusOr<RowFormat> format = ParseRowFormat(options.format);
  if (!format.ok()) return InputError(format.status());
  return RunCall(flags, options.file, method, &KeepRequest<Request>,
                 [&](Client&, const Request&, const Response& response) {
                   return print(flags, *format, response);
                 });
}

}  // namespace

void AddBasisFlags(CLI::App& command, BasisOptions& options) {
  AddFileFlag(command, options.file);
  command.add_flag("--surface", options.surface,
                   "The request is an EvaluateSurfaceBasisRequest "
                   "(SurfaceService.EvaluateBasis)");
  AddFormatFlag(command, options.format, {"json", "csv", "jsonl"});
}

int RunBasis(const CommonFlags& flags, const BasisOptions& options) {
  if (options.surface) {
    return RunAndPrint(flags, options, &v1::SurfaceService::Stub::EvaluateBasis,
                       &PrintSurfaceBasis);
  }
  return RunAndPrint(flags, options, &v1::CurveService::Stub::EvaluateBasis,
                     &PrintCurveBasis);
}

}  // namespace freeform::cli
