// `freeform eval` (eval.h): an answer as the response message's JSON, or
// as rows (CSV, JSON lines, or with --stream a JSON document) written chunk
// by chunk with a progress bar.
#include "eval.h"

#include <cstdio>
#include <memory>
#include <vector>

#include "absl/strings/str_cat.h"
#include "input.h"
#include "output.h"
#include "row_stream.h"
#include "rows.h"
#include "subcommand.h"

namespace freeform::cli {
namespace {

using Span = absl::Span<const double>;

// The number of parameters a request asks for.
uint64_t ParameterCount(const v1::EvaluateCurveRequest& request) {
  return request.parameters().has_list()
             ? static_cast<uint64_t>(request.parameters().list().values_size())
             : request.parameters().range().count();
}

// Writes one answer chunk as rows: "point" (x0, x1, ...), then "d1" (d1x0,
// ...), "d2", ...
absl::Status WriteCurveChunk(const v1::EvaluateCurveResponse& chunk,
                             RowWriter& writer) {
  if (!writer.begun()) {
    std::vector<ColumnGroup> groups;
    for (int k = 0; k < chunk.derivatives_size(); ++k) {
      groups.push_back({.json_name = k == 0 ? "point" : absl::StrCat("d", k),
                        .csv_prefix = k == 0 ? "x" : absl::StrCat("d", k, "x"),
                        .width = chunk.dimension()});
    }
    writer.Begin(std::move(groups),
                 {{"dimension", chunk.dimension()},
                  {"derivativeOrder", chunk.derivatives_size() - 1}});
  }
  std::vector<Span> columns;
  for (const v1::Points& points : chunk.derivatives()) {
    columns.emplace_back(points.coordinates().data(),
                         points.coordinates_size());
  }
  return writer.Rows(chunk.first_index(), chunk.count(), columns);
}

int RunCurveStream(const CommonFlags& flags, Client& client,
                   const v1::EvaluateCurveRequest& request, RowFormat format) {
  return StreamRows(flags, client, &Client::EvaluateCurveStream, request,
                    ParameterCount(request), format, &WriteCurveChunk);
}

}  // namespace

void AddEvalFlags(CLI::App& command, EvalOptions& options) {
  AddFileFlag(command, options.file);
  AddStreamFlags(command, options.stream, options.format,
                 "any number of points");
}

int RunEval(const CommonFlags& flags, const EvalOptions& options) {
  absl::StatusOr<v1::EvaluateCurveRequest> request =
      ParseJson<v1::EvaluateCurveRequest>(options.file);
  if (!request.ok()) return InputError(request.status());
  absl::StatusOr<RowFormat> format = ParseRowFormat(options.format);
  if (!format.ok()) return InputError(format.status());
  std::unique_ptr<Client> client = Connect(flags);
  if (client == nullptr) return kExitUsage;
  if (options.stream) return RunCurveStream(flags, *client, *request, *format);
  absl::StatusOr<v1::EvaluateCurveResponse> response =
      client->Unary(&v1::CurveService::Stub::Evaluate, *request);
  if (!response.ok()) return ReportError(response.status());
  if (*format == RowFormat::kJson) return PrintJson(flags, *response);
  RowWriter writer(*format, stdout);
  if (absl::Status status = WriteCurveChunk(*response, writer); !status.ok()) {
    return ReportError(status);
  }
  return FinishRows(writer);
}

}  // namespace freeform::cli
