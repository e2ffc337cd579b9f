// The freeform CLI's query subcommands (cli_queries.h): requests read as
// proto3 JSON and sent with RunCall; the flags that add to a request, the
// CSV printers and the section's SVG picture.
#include "cli_queries.h"

#include <iostream>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"
#include "absl/types/span.h"
#include "google/protobuf/repeated_field.h"

namespace freeform::cli {
namespace {

using google::protobuf::RepeatedField;

// One CSV line, built field by field.
class CsvRow {
 public:
  CsvRow& Add(absl::string_view text) {
    fields_.emplace_back(text);
    return *this;
  }
  CsvRow& Add(double value) { return Add(FormatNumber(value)); }
  CsvRow& AddAll(absl::Span<const double> values) {
    for (double value : values) Add(value);
    return *this;
  }
  // Column names prefix0, prefix1, ... prefix{count - 1}.
  CsvRow& AddNames(absl::string_view prefix, size_t count) {
    for (size_t j = 0; j < count; ++j) Add(absl::StrCat(prefix, j));
    return *this;
  }
  void Print() const { std::cout << absl::StrJoin(fields_, ",") << "\n"; }

 private:
  std::vector<std::string> fields_;
};

// Values [index * width, (index + 1) * width) of `values`, or fewer when
// `values` ends before.
absl::Span<const double> Slice(const RepeatedField<double>& values,
                               size_t index, size_t width) {
  const absl::Span<const double> all(values.data(), values.size());
  if (index * width >= all.size()) return {};
  return all.subspan(index * width, width);
}

// An enum value's name without its common prefix (REGULAR, STRAIGHT, ...).
std::string ShortName(const std::string& name, absl::string_view prefix) {
  return std::string(absl::StripPrefix(name, prefix));
}

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

// closest --format csv: one row per minimum.
int PrintClosestCsv(const v1::ClosestPointResponse& response) {
  const size_t parameters = response.parameter_count();
  const size_t dimension = response.points().dimension();
  CsvRow header;
  header.Add("query").Add("distance");
  if (parameters == 1) {
    header.Add("t");
  } else {
    header.Add("u").Add("v");
  }
  header.AddNames("x", dimension).Print();
  size_t minimum = 0;
  for (int query = 0; query < response.minima_counts_size(); ++query) {
    for (uint32_t k = 0; k < response.minima_counts(query); ++k, ++minimum) {
      CsvRow()
          .Add(absl::StrCat(query))
          .Add(response.distances(query))
          .AddAll(Slice(response.parameters(), minimum, parameters))
          .AddAll(Slice(response.points().coordinates(), minimum, dimension))
          .Print();
    }
  }
  return 0;
}

// sample-length --format csv: parameter and point per row.
int PrintSamplesCsv(const v1::SampleByArcLengthResponse& response) {
  const size_t dimension = response.points().dimension();
  CsvRow().Add("t").AddNames("x", dimension).Print();
  for (int k = 0; k < response.parameters_size(); ++k) {
    CsvRow()
        .Add(response.parameters(k))
        .AddAll(Slice(response.points().coordinates(), k, dimension))
        .Print();
  }
  return 0;
}

// curvature --format csv for a curve: one row per parameter.
int PrintCurveCurvatureCsv(const v1::CurveCurvatureResponse& response) {
  const size_t dimension = response.dimension();
  const bool spatial = !response.torsions().empty();
  CsvRow header;
  header.Add("index").Add("curvature");
  if (spatial) header.Add("torsion");
  header.Add("status").AddNames("t", dimension).AddNames("n", dimension);
  if (spatial) header.AddNames("b", 3);
  header.Print();
  for (int k = 0; k < response.curvatures_size(); ++k) {
    CsvRow row;
    row.Add(absl::StrCat(k)).Add(response.curvatures(k));
    if (spatial) row.Add(response.torsions(k));
    row.Add(ShortName(v1::CurvePointStatus_Name(response.statuses(k)),
                      "CURVE_POINT_STATUS_"))
        .AddAll(Slice(response.tangents().coordinates(), k, dimension))
        .AddAll(Slice(response.normals().coordinates(), k, dimension));
    if (spatial) row.AddAll(Slice(response.binormals().coordinates(), k, 3));
    row.Print();
  }
  return 0;
}

// curvature --surface --format csv: one row per point.
int PrintSurfaceCurvatureCsv(const v1::SurfaceCurvatureResponse& response) {
  CsvRow()
      .Add("index")
      .Add("gaussian")
      .Add("mean")
      .Add("k1")
      .Add("k2")
      .Add("status")
      .AddNames("n", 3)
      .AddNames("d1_", 3)
      .AddNames("d2_", 3)
      .Print();
  for (int k = 0; k < response.gaussian_size(); ++k) {
    CsvRow()
        .Add(absl::StrCat(k))
        .Add(response.gaussian(k))
        .Add(response.mean(k))
        .AddAll(Slice(response.principal_curvatures(), k, 2))
        .Add(ShortName(v1::SurfacePointStatus_Name(response.statuses(k)),
                       "SURFACE_POINT_STATUS_"))
        .AddAll(Slice(response.normals().coordinates(), k, 3))
        .AddAll(Slice(response.principal_directions(), k, 6))
        .Print();
  }
  return 0;
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
                                                  : PrintJson(response);
                 });
}

// An Amend that sends the request as read.
template <typename Request>
absl::Status KeepRequest(Request&) {
  return absl::OkStatus();
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

// Runs the curve's RPC, or the surface's with --surface.
template <typename CurveMethod, typename SurfaceMethod>
int RunEither(const CommonFlags& flags, const QueryOptions& options,
              CurveMethod curve, SurfaceMethod surface) {
  return options.surface ? RunJsonCall(flags, options.file, surface)
                         : RunJsonCall(flags, options.file, curve);
}

}  // namespace

QueryCommands::QueryCommands(CLI::App& app, CommonFlags& flags)
    : flags_(flags) {
  CLI::App* closest =
      Add(app, "closest",
          "Closest points of a curve or surface: CurveService/SurfaceService."
          "ClosestPoint",
          "CurveClosestPointRequest",
          [this] { return RunClosest(flags_, options_); });
  AddSurfaceFlag(closest, "SurfaceClosestPointRequest");
  closest->add_option("--points", options_.points,
                      "Query points x,y[,z];x,y... added to the request's");
  closest->add_option("--csv", options_.csv,
                      "CSV file of query points (x,y[,z] per line) added to "
                      "the request's");
  AddFormatFlag(closest);

  CLI::App* intersect = Add(
      app, "intersect",
      "Intersections of two curves: CurveService.Intersect (--surface: a "
      "curve and a surface, SurfaceService.IntersectCurve)",
      "IntersectCurvesRequest", [this] {
        return RunEither(flags_, options_, &v1::CurveService::Stub::Intersect,
                         &v1::SurfaceService::Stub::IntersectCurve);
      });
  AddSurfaceFlag(intersect, "IntersectCurveSurfaceRequest");

  Add(app, "arc-length", "Arc lengths of a curve: CurveService.ArcLength",
      "ArcLengthRequest", [this] {
        return RunJsonCall(flags_, options_.file,
                           &v1::CurveService::Stub::ArcLength);
      });
  Add(app, "at-length",
      "Parameters at arc lengths: CurveService.ParametersAtArcLength",
      "ParametersAtArcLengthRequest", [this] {
        return RunJsonCall(flags_, options_.file,
                           &v1::CurveService::Stub::ParametersAtArcLength);
      });

  CLI::App* sample =
      Add(app, "sample-length",
          "Samples at equal arc-length spacing: CurveService.SampleByArcLength",
          "SampleByArcLengthRequest",
          [this] { return RunSampleByLength(flags_, options_); });
  sample->add_option("--count", options_.count,
                     "Number of samples (overrides the request's count)");
  AddFormatFlag(sample);

  CLI::App* curvature =
      Add(app, "curvature",
          "Curvature and frames at parameters: CurveService/SurfaceService."
          "Curvature",
          "CurveCurvatureRequest",
          [this] { return RunCurvature(flags_, options_); });
  AddSurfaceFlag(curvature, "SurfaceCurvatureRequest");
  AddFormatFlag(curvature);

  Add(app, "frames",
      "Rotation-minimizing frames: CurveService.RotationMinimizingFrames",
      "RotationMinimizingFramesRequest", [this] {
        return RunJsonCall(flags_, options_.file,
                           &v1::CurveService::Stub::RotationMinimizingFrames);
      });

  CLI::App* bbox = Add(
      app, "bbox",
      "Tight bounding box: CurveService/SurfaceService.BoundingBox",
      "CurveBoundingBoxRequest", [this] {
        return RunEither(flags_, options_, &v1::CurveService::Stub::BoundingBox,
                         &v1::SurfaceService::Stub::BoundingBox);
      });
  AddSurfaceFlag(bbox, "SurfaceBoundingBoxRequest");

  CLI::App* section = Add(
      app, "section", "Plane section of a surface: SurfaceService.Section",
      "SectionSurfaceRequest", [this] { return RunSection(flags_, options_); });
  section->add_option("--svg", options_.svg,
                      "Draw the polylines projected on (x, y) as SVG ('-': "
                      "stdout) instead of printing JSON");
}

CLI::App* QueryCommands::Add(CLI::App& app, const std::string& name,
                             const std::string& description,
                             const std::string& request,
                             std::function<int()> run) {
  CLI::App* command = app.add_subcommand(name, description);
  AddCommonFlags(*command, flags_);
  command->add_option("-f,--file", options_.file,
                      request + " as proto3 JSON (default: stdin)");
  commands_.emplace_back(command, std::move(run));
  return command;
}

void QueryCommands::AddSurfaceFlag(CLI::App* command,
                                   const std::string& request) {
  command->add_flag("--surface", options_.surface,
                    "The request is a " + request);
}

void QueryCommands::AddFormatFlag(CLI::App* command) {
  command->add_option("--format", options_.format, "Output: json or csv")
      ->check(CLI::IsMember({"json", "csv"}))
      ->capture_default_str();
}

std::optional<int> QueryCommands::Run() const {
  for (const auto& [command, run] : commands_) {
    if (command->parsed()) return run();
  }
  return std::nullopt;
}

}  // namespace freeform::cli
