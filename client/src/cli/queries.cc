// The freeform CLI's query subcommands (queries.h): requests read as
// proto3 JSON and sent with RunCall, the flags that add to a request, and
// the section's SVG picture.
#include "queries.h"

#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "input.h"
#include "query_csv.h"
#include "run_call.h"
#include "subcommand.h"
#include "svg_drawing.h"

namespace freeform::cli {
namespace {

// Parses "x,y[,z];x,y..." into points.
absl::StatusOr<std::vector<std::vector<double>>> ParsePointList(
    const std::string& text) {
  std::vector<std::vector<double>> points;
  for (absl::string_view point :
       absl::StrSplit(text, ';', absl::SkipWhitespace())) {
    std::optional<std::vector<double>> coordinates = ParseCsvLine(point);
    if (!coordinates.has_value()) {
      return absl::InvalidArgumentError(
          absl::StrCat("--points: \"", point, "\" is not x,y[,z...]"));
    }
    points.push_back(*std::move(coordinates));
  }
  return points;
}

// Appends points to `queries`, which takes their dimension when it has
// none.
absl::Status AppendPoints(const std::vector<std::vector<double>>& points,
                          absl::string_view source, v1::Points& queries) {
  for (size_t k = 0; k < points.size(); ++k) {
    if (queries.dimension() == 0 && queries.coordinates().empty()) {
      queries.set_dimension(static_cast<uint32_t>(points[k].size()));
    }
    if (points[k].size() != queries.dimension()) {
      return absl::InvalidArgumentError(absl::StrCat(
          source, ": point ", k + 1, " has ", points[k].size(),
          " coordinates where the queries have ", queries.dimension()));
    }
    queries.mutable_coordinates()->Add(points[k].begin(), points[k].end());
  }
  return absl::OkStatus();
}

// Adds the points of --points and --csv to the request's queries.
absl::Status AddQueryPoints(const QueryOptions& options, v1::Points& queries) {
  if (!options.points.empty()) {
    absl::StatusOr<std::vector<std::vector<double>>> points =
        ParsePointList(options.points);
    if (!points.ok()) return points.status();
    if (absl::Status status = AppendPoints(*points, "--points", queries);
        !status.ok()) {
      return status;
    }
  }
  if (options.csv.empty()) return absl::OkStatus();
  absl::StatusOr<std::vector<std::vector<double>>> rows =
      ReadCsvRows(options.csv);
  if (!rows.ok()) return rows.status();
  return AppendPoints(*rows, options.csv, queries);
}

// section --svg: the polylines projected on (x, y).
int DrawSection(const v1::SectionSurfaceResponse& response,
                const std::string& path) {
  const char* colors[] = {"#1f5fbf", "#d95f02", "#1b9e77", "#7570b3",
                          "#e7298a"};
  SvgDrawing drawing;
  for (int k = 0; k < response.polylines_size(); ++k) {
    const v1::Points& points = response.polylines(k).points();
    drawing.AddPolyline(points.coordinates(),
                        static_cast<int>(points.dimension()),
                        {.color = colors[k % std::size(colors)],
                         .width = 2,
                         .label = "section"});
  }
  return WriteSvg(drawing, path);
}

// Runs `method` and prints the answer as JSON, or with `csv` for --format
// csv.
template <typename Stub, typename Request, typename Response>
int RunWithCsv(const CommonFlags& flags, const QueryOptions& options,
               RpcMethod<Stub, Request, Response> method, Amend<Request> amend,
               int (*csv)(const Response&)) {
  return RunCall(flags, options.file, method, amend,
                 [&](Client&, const Request&, const Response& response) {
                   return options.format == "csv" ? csv(response)
                                                  : PrintJson(flags, response);
                 });
}

template <typename Stub, typename Request>
int RunClosestOn(const CommonFlags& flags, const QueryOptions& options,
                 RpcMethod<Stub, Request, v1::ClosestPointResponse> method) {
  return RunWithCsv(
      flags, options, method,
      [&](Request& request) {
        return AddQueryPoints(options, *request.mutable_queries());
      },
      &PrintClosestCsv);
}

}  // namespace

int RunClosest(const CommonFlags& flags, const QueryOptions& options) {
  const auto from_stdin = [](const std::string& file) {
    return file.empty() || file == "-";
  };
  if (!options.csv.empty() && from_stdin(options.csv) &&
      from_stdin(options.file)) {
    return InputError(absl::InvalidArgumentError(
        "--csv - reads the points from stdin: give the request with --file"));
  }
  if (options.surface) {
    return RunClosestOn(flags, options,
                        &v1::SurfaceService::Stub::ClosestPoint);
  }
  return RunClosestOn(flags, options, &v1::CurveService::Stub::ClosestPoint);
}

int RunSampleByLength(const CommonFlags& flags, const QueryOptions& options) {
  return RunWithCsv(
      flags, options, &v1::CurveService::Stub::SampleByArcLength,
      [&](v1::SampleByArcLengthRequest& request) {
        if (options.count > 0) request.set_count(options.count);
        return absl::OkStatus();
      },
      &PrintSamplesCsv);
}

int RunCurvature(const CommonFlags& flags, const QueryOptions& options) {
  if (options.surface) {
    return RunWithCsv(flags, options, &v1::SurfaceService::Stub::Curvature,
                      &KeepRequest<v1::SurfaceCurvatureRequest>,
                      &PrintSurfaceCurvatureCsv);
  }
  return RunWithCsv(flags, options, &v1::CurveService::Stub::Curvature,
                    &KeepRequest<v1::CurveCurvatureRequest>,
                    &PrintCurveCurvatureCsv);
}

int RunSection(const CommonFlags& flags, const QueryOptions& options) {
  if (options.svg.empty()) {
    return RunJsonCall(flags, options.file, &v1::SurfaceService::Stub::Section);
  }
  return RunCall(flags, options.file, &v1::SurfaceService::Stub::Section,
                 &KeepRequest<v1::SectionSurfaceRequest>,
                 [&](Client&, const v1::SectionSurfaceRequest&,
                     const v1::SectionSurfaceResponse& response) {
                   return DrawSection(response, options.svg);
                 });
}

void AddClosestFlags(CLI::App& command, QueryOptions& options) {
  AddFileFlag(command, options.file);
  command.add_flag("--surface", options.surface,
                   "The request is a SurfaceClosestPointRequest");
  command.add_option("--points", options.points,
                     "Query points x,y[,z];x,y... added to the request's");
  command.add_option("--csv", options.csv,
                     "CSV file of query points (x,y[,z] per line) added to "
                     "the request's");
  AddFormatFlag(command, options.format, {"json", "csv"});
}

void AddSampleLengthFlags(CLI::App& command, QueryOptions& options) {
  AddFileFlag(command, options.file);
  command.add_option("--count", options.count,
                     "Number of samples (overrides the request's count)");
  AddFormatFlag(command, options.format, {"json", "csv"});
}

void AddCurvatureFlags(CLI::App& command, QueryOptions& options) {
  AddFileFlag(command, options.file);
  command.add_flag("--surface", options.surface,
                   "The request is a SurfaceCurvatureRequest");
  AddFormatFlag(command, options.format, {"json", "csv"});
}

void AddSectionFlags(CLI::App& command, QueryOptions& options) {
  AddFileFlag(command, options.file);
  command.add_option("--svg", options.svg,
                     "Draw the polylines projected on (x, y) as SVG ('-': "
                     "stdout) instead of printing JSON");
}

}  // namespace freeform::cli
