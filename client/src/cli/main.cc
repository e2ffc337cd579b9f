// freeform: command-line client of freeformd.
//
//   freeform eval   [--address HOST:PORT] [--file REQUEST.json] [--stream]
//                   [--format json|csv]
//   freeform basis  [--address HOST:PORT] [--file REQUEST.json] [--surface]
//                   [--format json|csv]
//   freeform surface [--address HOST:PORT] [--file REQUEST.json] [--stream]
//                   [--format json|csv] [--obj MESH.obj]
//   freeform mesh   [--address HOST:PORT] --bezier-patches PATCHES.json
//                   [--grid N] [--obj MESH.obj]
//   freeform elevate [--address HOST:PORT] [--file REQUEST.json] [--surface]
//   freeform reduce [--address HOST:PORT] [--file REQUEST.json]
//   freeform interpolate [--address HOST:PORT] [--file REQUEST.json]
//                   [--surface] | [--csv POINTS.csv [--degree P]
//                   [--parameterization KIND] [--closed]
//                   [--spline END] [--least-squares N]]
//   freeform split|insert-knots [--surface] [--file REQUEST.json]
//   freeform remove-knots [--surface] [--file REQUEST.json]
//   freeform fit [--surface [--scattered]] [--file REQUEST.json]
//   freeform decompose [--file REQUEST.json]
//   freeform subdivide [--file REQUEST.json] [--svg PICTURE.svg]
//   freeform tessellate [--surface [--max-normal-angle RADIANS]]
//                   [--file REQUEST.json]
//                   [--svg PICTURE.svg [--combs [--comb-scale S]] |
//                    --obj MESH.obj | --stl MESH.stl]
//   freeform closest [--surface] [--file REQUEST.json]
//                   [--points X,Y[,Z];...] [--csv POINTS.csv]
//                   [--format json|csv]
//   freeform intersect|bbox [--surface] [--file REQUEST.json]
//   freeform arc-length|at-length|frames [--file REQUEST.json]
//   freeform sample-length [--file REQUEST.json] [--count N]
//                   [--format json|csv]
//   freeform curvature [--surface] [--file REQUEST.json] [--format json|csv]
//   freeform section [--file REQUEST.json] [--svg PICTURE.svg]
//   freeform health [--address HOST:PORT] [--service NAME]
//
// Requests are the canonical proto3 JSON of the request message (from a file
// or stdin); answers are printed as proto3 JSON or CSV. The query
// subcommands (closest ... section) live in cli_queries.cc. Exit status: 0 on
// success, 1 when the server answers with an error (printed on stderr with
// its field violations), 2 for unusable input.
#include <iostream>
#include <map>
#include <optional>
#include <string>

#include "CLI/CLI.hpp"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "cli_common.h"
#include "cli_queries.h"
#include "curvature_comb.h"
#include "freeform/client.h"
#include "nlohmann/json.hpp"
#include "obj_mesh.h"
#include "stl_mesh.h"
#include "svg_drawing.h"

namespace {

using freeform::cli::CommonFlags;
using freeform::cli::Connect;
using freeform::cli::InputError;
using freeform::cli::ParseJson;
using freeform::cli::PrintJson;
using freeform::cli::ReadCsvRows;
using freeform::cli::ReadInput;
using freeform::cli::ReportError;
using freeform::cli::RunCall;
using freeform::cli::RunJsonCall;
using freeform::cli::ToJson;
using freeform::cli::WriteSvg;
using CurveStub = freeform::v1::CurveService::Stub;
using SurfaceStub = freeform::v1::SurfaceService::Stub;

// One CSV row per parameter: index, then each derivative's coordinates.
void PrintCsv(const freeform::CurveSamples& samples) {
  std::cout << "index";
  for (size_t k = 0; k < samples.derivatives.size(); ++k) {
    for (int j = 0; j < samples.dimension; ++j) {
      std::cout << "," << (k == 0 ? "x" : absl::StrCat("d", k, "x")) << j;
    }
  }
  std::cout << "\n";
  std::cout.precision(17);
  for (size_t r = 0; r < samples.count; ++r) {
    std::cout << r;
    for (size_t k = 0; k < samples.derivatives.size(); ++k) {
      for (double value : samples.Point(k, r)) std::cout << "," << value;
    }
    std::cout << "\n";
  }
}

// Rebuilds one response message from joined samples, for JSON output.
freeform::v1::EvaluateCurveResponse ToResponse(
    const freeform::CurveSamples& samples) {
  freeform::v1::EvaluateCurveResponse response;
  response.set_dimension(static_cast<uint32_t>(samples.dimension));
  response.set_count(static_cast<uint32_t>(samples.count));
  for (const std::vector<double>& values : samples.derivatives) {
    freeform::v1::Points* points = response.add_derivatives();
    points->set_dimension(static_cast<uint32_t>(samples.dimension));
    points->mutable_coordinates()->Add(values.begin(), values.end());
  }
  return response;
}

int RunEval(const CommonFlags& flags, const std::string& file, bool stream,
            const std::string& format) {
  absl::StatusOr<freeform::v1::EvaluateCurveRequest> request =
      ParseJson<freeform::v1::EvaluateCurveRequest>(file);
  if (!request.ok()) return InputError(request.status());
  std::unique_ptr<freeform::Client> client = Connect(flags);
  if (client == nullptr) return 2;
  absl::StatusOr<freeform::CurveSamples> samples =
      stream ? client->EvaluateCurveStreamed(*request)
             : client->EvaluateCurve(*request);
  if (!samples.ok()) return ReportError(samples.status());
  if (format == "csv") {
    PrintCsv(*samples);
  } else {
    std::cout << ToJson(ToResponse(*samples));
  }
  return 0;
}

// One CSV row per parameter: index, then each derivative's function values.
void PrintBasisCsv(const freeform::BasisSamples& samples) {
  std::cout << "index";
  for (size_t k = 0; k < samples.derivatives.size(); ++k) {
    for (size_t i = 0; i < samples.function_count; ++i) {
      std::cout << "," << (k == 0 ? "" : absl::StrCat("d", k)) << "f" << i;
    }
  }
  std::cout << "\n";
  std::cout.precision(17);
  for (size_t r = 0; r < samples.count; ++r) {
    std::cout << r;
    for (size_t k = 0; k < samples.derivatives.size(); ++k) {
      for (size_t i = 0; i < samples.function_count; ++i) {
        std::cout << "," << samples.Value(k, r, i);
      }
    }
    std::cout << "\n";
  }
}

// Prints basis samples as CSV or as the response message's JSON.
template <typename Response>
int PrintBasis(const freeform::BasisSamples& samples, const std::string& format,
               Response& response) {
  if (format == "csv") {
    PrintBasisCsv(samples);
  } else {
    std::cout << ToJson(response);
  }
  return 0;
}

int RunBasis(const CommonFlags& flags, const std::string& file,
             const std::string& format, bool surface) {
  std::unique_ptr<freeform::Client> client;
  if (surface) {
    absl::StatusOr<freeform::v1::EvaluateSurfaceBasisRequest> request =
        ParseJson<freeform::v1::EvaluateSurfaceBasisRequest>(file);
    if (!request.ok()) return InputError(request.status());
    if ((client = Connect(flags)) == nullptr) return 2;
    absl::StatusOr<freeform::BasisSamples> samples =
        client->EvaluateSurfaceBasis(*request);
    if (!samples.ok()) return ReportError(samples.status());
    freeform::v1::EvaluateSurfaceBasisResponse response;
    response.set_function_count(static_cast<uint32_t>(samples->function_count));
    response.set_count(static_cast<uint32_t>(samples->count));
    response.mutable_values()->Add(samples->derivatives[0].begin(),
                                   samples->derivatives[0].end());
    return PrintBasis(*samples, format, response);
  }
  absl::StatusOr<freeform::v1::EvaluateBasisRequest> request =
      ParseJson<freeform::v1::EvaluateBasisRequest>(file);
  if (!request.ok()) return InputError(request.status());
  if ((client = Connect(flags)) == nullptr) return 2;
  absl::StatusOr<freeform::BasisSamples> samples =
      client->EvaluateBasis(*request);
  if (!samples.ok()) return ReportError(samples.status());
  freeform::v1::EvaluateBasisResponse response;
  response.set_function_count(static_cast<uint32_t>(samples->function_count));
  response.set_count(static_cast<uint32_t>(samples->count));
  for (const std::vector<double>& values : samples->derivatives) {
    response.add_derivatives()->mutable_values()->Add(values.begin(),
                                                      values.end());
  }
  return PrintBasis(*samples, format, response);
}

// Number of values a grid axis resolves to.
size_t AxisCount(const freeform::v1::Parameters& axis) {
  return axis.has_list() ? static_cast<size_t>(axis.list().values_size())
                         : axis.range().count();
}

freeform::v1::EvaluateSurfaceResponse ToSurfaceResponse(
    const freeform::SurfaceEvaluation& evaluation) {
  freeform::v1::EvaluateSurfaceResponse response;
  response.set_dimension(static_cast<uint32_t>(evaluation.dimension));
  response.set_count(static_cast<uint32_t>(evaluation.count));
  for (const auto& partial : evaluation.partials) {
    freeform::v1::PartialDerivative* out = response.add_partials();
    out->set_order_u(static_cast<uint32_t>(partial.order_u));
    out->set_order_v(static_cast<uint32_t>(partial.order_v));
    out->mutable_values()->set_dimension(
        static_cast<uint32_t>(evaluation.dimension));
    out->mutable_values()->mutable_coordinates()->Add(partial.values.begin(),
                                                      partial.values.end());
  }
  if (!evaluation.normals.empty()) {
    response.mutable_normals()->set_dimension(3);
    response.mutable_normals()->mutable_coordinates()->Add(
        evaluation.normals.begin(), evaluation.normals.end());
  }
  return response;
}

// One CSV row per point: index, every partial's coordinates, the normal.
void PrintSurfaceCsv(const freeform::SurfaceEvaluation& evaluation) {
  std::cout << "index";
  for (const auto& partial : evaluation.partials) {
    for (int j = 0; j < evaluation.dimension; ++j) {
      std::cout << ",s" << partial.order_u << partial.order_v << "_" << j;
    }
  }
  if (!evaluation.normals.empty()) std::cout << ",nx,ny,nz";
  std::cout << "\n";
  std::cout.precision(17);
  const size_t dim = static_cast<size_t>(evaluation.dimension);
  for (size_t r = 0; r < evaluation.count; ++r) {
    std::cout << r;
    for (const auto& partial : evaluation.partials) {
      for (size_t j = 0; j < dim; ++j) {
        std::cout << "," << partial.values[r * dim + j];
      }
    }
    for (size_t j = 0; !evaluation.normals.empty() && j < 3; ++j) {
      std::cout << "," << evaluation.normals[3 * r + j];
    }
    std::cout << "\n";
  }
}

int WriteObj(const freeform::cli::ObjMesh& mesh, const std::string& path) {
  return freeform::cli::WriteOutput(
      path, [&](std::ostream& out) { mesh.Write(out); },
      absl::StrCat(": ", mesh.vertex_count(), " vertices, ",
                   mesh.triangle_count(), " triangles"));
}

int RunSurface(const CommonFlags& flags, const std::string& file, bool stream,
               const std::string& format, const std::string& obj) {
  absl::StatusOr<freeform::v1::EvaluateSurfaceRequest> request =
      ParseJson<freeform::v1::EvaluateSurfaceRequest>(file);
  if (!request.ok()) return InputError(request.status());
  if (!obj.empty()) {
    if (!request->parameters().has_grid()) {
      std::cerr << "error: --obj needs grid parameters\n";
      return 2;
    }
    request->set_normals(true);
  }
  std::unique_ptr<freeform::Client> client = Connect(flags);
  if (client == nullptr) return 2;
  absl::StatusOr<freeform::SurfaceEvaluation> evaluation =
      stream ? client->EvaluateSurfaceStreamed(*request)
             : client->EvaluateSurface(*request);
  if (!evaluation.ok()) return ReportError(evaluation.status());
  if (!obj.empty()) {
    freeform::cli::ObjMesh mesh;
    mesh.AddGrid("surface", AxisCount(request->parameters().grid().u()),
                 AxisCount(request->parameters().grid().v()),
                 evaluation->partials[0].values, evaluation->normals);
    return WriteObj(mesh, obj);
  }
  if (format == "csv") {
    PrintSurfaceCsv(*evaluation);
  } else {
    std::cout << ToJson(ToSurfaceResponse(*evaluation));
  }
  return 0;
}

// Reads a set of Bezier patches in the layout of examples/teapot.json:
// {"degree_u": m, "degree_v": n, "patches": [{"control_points":
// [[x, y, z], ...]}, ...]} with (m+1)(n+1) row-major points per patch.
absl::StatusOr<std::vector<freeform::v1::Surface>> ReadBezierPatches(
    const std::string& file) {
  absl::StatusOr<std::string> text = ReadInput(file);
  if (!text.ok()) return text.status();
  const nlohmann::json json = nlohmann::json::parse(*text, nullptr, false);
  if (json.is_discarded() || !json.contains("patches")) {
    return absl::InvalidArgumentError(
        absl::StrCat(file, ": not a JSON object with \"patches\""));
  }
  const int degree_u = json.value("degree_u", 3);
  const int degree_v = json.value("degree_v", 3);
  std::vector<freeform::v1::Surface> surfaces;
  for (const nlohmann::json& patch : json["patches"]) {
    freeform::v1::Surface surface;
    freeform::v1::ControlNet* net =
        surface.mutable_bezier()->mutable_control_net();
    net->set_dimension(3);
    net->set_count_u(static_cast<uint32_t>(degree_u + 1));
    net->set_count_v(static_cast<uint32_t>(degree_v + 1));
    for (const nlohmann::json& point : patch.at("control_points")) {
      for (const nlohmann::json& value : point) {
        net->add_coordinates(value.get<double>());
      }
    }
    surfaces.push_back(std::move(surface));
  }
  return surfaces;
}

int RunMesh(const CommonFlags& flags, const std::string& patches_file, int grid,
            const std::string& obj) {
  absl::StatusOr<std::vector<freeform::v1::Surface>> surfaces =
      ReadBezierPatches(patches_file);
  if (!surfaces.ok()) return InputError(surfaces.status());
  std::unique_ptr<freeform::Client> client = Connect(flags);
  if (client == nullptr) return 2;
  freeform::cli::ObjMesh mesh;
  for (size_t p = 0; p < surfaces->size(); ++p) {
    freeform::v1::EvaluateSurfaceRequest request;
    *request.mutable_surface() = (*surfaces)[p];
    request.mutable_parameters()
        ->mutable_grid()
        ->mutable_u()
        ->mutable_range()
        ->set_count(static_cast<uint32_t>(grid));
    request.mutable_parameters()
        ->mutable_grid()
        ->mutable_v()
        ->mutable_range()
        ->set_count(static_cast<uint32_t>(grid));
    request.set_normals(true);
    absl::StatusOr<freeform::SurfaceEvaluation> evaluation =
        client->EvaluateSurface(request);
    if (!evaluation.ok()) return ReportError(evaluation.status());
    mesh.AddGrid(absl::StrCat("patch", p), static_cast<size_t>(grid),
                 static_cast<size_t>(grid), evaluation->partials[0].values,
                 evaluation->normals);
  }
  return WriteObj(mesh, obj);
}

struct CsvInterpolation {
  std::string csv;
  int degree = 3;
  std::string parameterization = "chord_length";
  bool closed = false;
  // Cubic spline of function data: the first column is the abscissa.
  std::string spline;
  int least_squares_points = 0;
};

// Builds an InterpolateCurveRequest from CSV points and flags.
absl::StatusOr<freeform::v1::InterpolateCurveRequest> CsvRequest(
    const CsvInterpolation& options) {
  absl::StatusOr<std::vector<std::vector<double>>> rows =
      ReadCsvRows(options.csv);
  if (!rows.ok()) return rows.status();
  freeform::v1::InterpolateCurveRequest request;
  const bool spline = !options.spline.empty();
  const size_t first = spline ? 1 : 0;
  if (rows->front().size() <= first) {
    return absl::InvalidArgumentError("the CSV rows need more columns");
  }
  freeform::v1::Points* points = request.mutable_points();
  points->set_dimension(static_cast<uint32_t>(rows->front().size() - first));
  for (const std::vector<double>& row : *rows) {
    points->mutable_coordinates()->Add(row.begin() + first, row.end());
  }
  const std::map<std::string, freeform::v1::Parameterization> kinds = {
      {"uniform", freeform::v1::PARAMETERIZATION_UNIFORM},
      {"chord_length", freeform::v1::PARAMETERIZATION_CHORD_LENGTH},
      {"centripetal", freeform::v1::PARAMETERIZATION_CENTRIPETAL},
      {"universal", freeform::v1::PARAMETERIZATION_UNIVERSAL}};
  if (spline) {
    const std::map<std::string, freeform::v1::SplineEndCondition> ends = {
        {"natural", freeform::v1::SPLINE_END_CONDITION_NATURAL},
        {"not_a_knot", freeform::v1::SPLINE_END_CONDITION_NOT_A_KNOT},
        {"periodic", freeform::v1::SPLINE_END_CONDITION_PERIODIC}};
    auto* method = request.mutable_cubic_spline();
    method->set_end_condition(ends.at(options.spline));
    for (const std::vector<double>& row : *rows) {
      method->add_parameters(row[0]);
    }
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
  return request;
}

// AddRequestCommand adds the subcommand `name` that sends one request read
// as proto3 JSON (`request`, the message's name) from --file or stdin, with
// --surface for the SurfaceService form (`surface_request`).
CLI::App* AddRequestCommand(CLI::App& app, const std::string& name,
                            const std::string& description, CommonFlags& flags,
                            std::string& file, const std::string& request,
                            bool& surface, const std::string& surface_request) {
  CLI::App* command = app.add_subcommand(name, description);
  AddCommonFlags(*command, flags);
  command->add_option("-f,--file", file,
                      request + " as proto3 JSON (default: stdin)");
  command->add_flag("--surface", surface,
                    "The request is a " + surface_request);
  return command;
}

int RunFit(const CommonFlags& flags, const std::string& file, bool surface,
           bool scattered) {
  if (scattered && !surface) {
    std::cerr << "freeform fit: --scattered needs --surface\n";
    return 2;
  }
  if (scattered) return RunJsonCall(flags, file, &SurfaceStub::FitScattered);
  return surface ? RunJsonCall(flags, file, &SurfaceStub::Fit)
                 : RunJsonCall(flags, file, &CurveStub::Fit);
}

int RunInterpolate(const CommonFlags& flags, const std::string& file,
                   bool surface, const CsvInterpolation& csv) {
  if (surface) {
    return RunJsonCall(flags, file, &SurfaceStub::Interpolate);
  }
  if (csv.csv.empty()) {
    return RunJsonCall(flags, file, &CurveStub::Interpolate);
  }
  absl::StatusOr<freeform::v1::InterpolateCurveRequest> request =
      CsvRequest(csv);
  if (!request.ok()) return InputError(request.status());
  std::unique_ptr<freeform::Client> client = Connect(flags);
  if (client == nullptr) return 2;
  absl::StatusOr<freeform::v1::InterpolateCurveResponse> response =
      client->InterpolateCurve(*request);
  if (!response.ok()) return ReportError(response.status());
  return PrintJson(*response);
}

// The control points of a Bezier or B-spline request curve (to draw them).
absl::Span<const double> ControlPolygon(const freeform::v1::Curve& curve,
                                        int& dimension) {
  const freeform::v1::Points& points = curve.has_bspline()
                                           ? curve.bspline().control_points()
                                           : curve.bezier().control_points();
  dimension = static_cast<int>(points.dimension());
  return absl::MakeConstSpan(points.coordinates().data(),
                             points.coordinates_size());
}

// The polygon and every level of a subdivision.
freeform::cli::SvgDrawing DrawSubdivision(
    const freeform::v1::SubdivideRequest& request,
    const freeform::v1::SubdivideResponse& result) {
  freeform::cli::SvgDrawing drawing;
  const int dimension = static_cast<int>(request.polygon().dimension());
  drawing.AddPolyline(request.polygon().coordinates(), dimension,
                      {.color = "#999999",
                       .width = 1,
                       .dashed = true,
                       .dots = true,
                       .closed = request.closed()});
  const char* colors[] = {"#d95f02", "#7570b3", "#e7298a", "#66a61e",
                          "#1f5fbf"};
  for (int level = 0; level < result.levels_size(); ++level) {
    const bool last = level + 1 == result.levels_size();
    drawing.AddPolyline(result.levels(level).coordinates(), dimension,
                        {.color = last ? "#1f5fbf" : colors[level % 4],
                         .width = last ? 2.0 : 1.0,
                         .dashed = false,
                         .dots = false,
                         .closed = request.closed()});
  }
  return drawing;
}

// The tessellation's output: JSON, or a picture or mesh.
struct TessellateOutput {
  std::string svg;
  std::string obj;
  std::string stl;
  bool combs = false;
  double comb_scale = 0;  // 0: the default
};

// RunTessellateSurfaces sends a TessellateSurfaceRequest, with the
// normal-angle limit of --max-normal-angle when given (the server checks
// it).
int RunTessellateSurfaces(const CommonFlags& flags, const std::string& file,
                          const TessellateOutput& output,
                          std::optional<double> max_normal_angle) {
  const std::string& obj = output.obj;
  return RunCall(
      flags, file, &SurfaceStub::Tessellate,
      [&](freeform::v1::TessellateSurfaceRequest& request) {
        if (!obj.empty()) request.set_normals(true);
        if (max_normal_angle.has_value()) {
          request.set_max_normal_angle(*max_normal_angle);
        }
        return absl::OkStatus();
      },
      [&](freeform::Client&, const freeform::v1::TessellateSurfaceRequest&,
          const freeform::v1::TessellateSurfaceResponse& mesh) {
        if (!output.stl.empty()) {
          return freeform::cli::WriteOutput(
              output.stl,
              [&](std::ostream& out) {
                freeform::cli::WriteBinaryStl(mesh.vertices().coordinates(),
                                              mesh.triangles(), out);
              },
              absl::StrCat(": ", mesh.triangles_size() / 3, " triangles"));
        }
        if (obj.empty()) return PrintJson(mesh);
        freeform::cli::ObjMesh out;
        out.AddTriangles("mesh", mesh.vertices().coordinates(),
                         mesh.normals().coordinates(), mesh.triangles());
        return WriteObj(out, obj);
      });
}

// --combs draws plane curves only.
absl::Status CheckCombs(const freeform::v1::TessellateCurveRequest& request,
                        const TessellateOutput& output) {
  if (!output.combs) return absl::OkStatus();
  if (output.svg.empty()) {
    return absl::InvalidArgumentError("--combs needs --svg");
  }
  const int dimension = freeform::cli::CurveDimension(request.curve());
  // Without a curve (0) the server's answer names what is missing.
  if (dimension != 2 && dimension != 0) {
    return absl::InvalidArgumentError(
        absl::StrCat("--combs draws curvature combs of 2D curves only; this "
                     "curve has dimension ",
                     dimension));
  }
  return absl::OkStatus();
}

// The control polygon and the polyline of a tessellated curve.
freeform::cli::SvgDrawing DrawTessellation(
    const freeform::v1::TessellateCurveRequest& request,
    const freeform::v1::TessellateCurveResponse& polyline) {
  freeform::cli::SvgDrawing drawing;
  int dimension = 0;
  const absl::Span<const double> control =
      ControlPolygon(request.curve(), dimension);
  drawing.AddPolyline(control, dimension,
                      {.color = "#999999",
                       .width = 1,
                       .dashed = true,
                       .dots = true,
                       .closed = false,
                       .label = "control"});
  drawing.AddPolyline(polyline.points().coordinates(),
                      static_cast<int>(polyline.points().dimension()),
                      {.color = "#1f5fbf",
                       .width = 2,
                       .dashed = false,
                       .dots = false,
                       .closed = false,
                       .label = "curve"});
  return drawing;
}

int RunTessellateCurve(const CommonFlags& flags, const std::string& file,
                       const TessellateOutput& output) {
  return RunCall(
      flags, file, &CurveStub::Tessellate,
      [&](freeform::v1::TessellateCurveRequest& request) {
        return CheckCombs(request, output);
      },
      [&](freeform::Client& client,
          const freeform::v1::TessellateCurveRequest& request,
          const freeform::v1::TessellateCurveResponse& polyline) {
        if (output.svg.empty()) return PrintJson(polyline);
        freeform::cli::SvgDrawing drawing = DrawTessellation(request, polyline);
        if (output.combs) {
          const absl::Status comb = freeform::cli::AddCurvatureComb(
              client, request.curve(), polyline,
              output.comb_scale > 0 ? std::optional(output.comb_scale)
                                    : std::nullopt,
              drawing);
          if (!comb.ok()) return ReportError(comb);
        }
        return WriteSvg(drawing, output.svg);
      });
}

int RunSubdivide(const CommonFlags& flags, const std::string& file,
                 const std::string& svg) {
  return RunCall(
      flags, file, &CurveStub::Subdivide,
      [&](freeform::v1::SubdivideRequest& request) {
        if (!svg.empty()) request.set_keep_levels(true);
        return absl::OkStatus();
      },
      [&](freeform::Client&, const freeform::v1::SubdivideRequest& request,
          const freeform::v1::SubdivideResponse& result) {
        return svg.empty() ? PrintJson(result)
                           : WriteSvg(DrawSubdivision(request, result), svg);
      });
}

int RunHealth(const CommonFlags& flags, const std::string& service) {
  std::unique_ptr<freeform::Client> client = Connect(flags);
  if (client == nullptr) return 2;
  absl::Status status = client->CheckHealth(service);
  if (!status.ok()) return ReportError(status);
  std::cout << "SERVING\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"freeform: command-line client of the freeform gRPC service"};
  app.require_subcommand(1);
  CommonFlags flags;

  CLI::App* eval =
      app.add_subcommand("eval", "Evaluate a curve: CurveService.Evaluate");
  std::string file;
  bool stream = false;
  std::string format = "json";
  AddCommonFlags(*eval, flags);
  eval->add_option("-f,--file", file,
                   "EvaluateCurveRequest as proto3 JSON (default: stdin)");
  eval->add_flag("--stream", stream, "Use EvaluateStream (large batches)");
  eval->add_option("--format", format, "Output: json or csv")
      ->check(CLI::IsMember({"json", "csv"}))
      ->capture_default_str();

  CLI::App* basis = app.add_subcommand(
      "basis", "Evaluate blending functions: CurveService.EvaluateBasis");
  AddCommonFlags(*basis, flags);
  basis->add_option("-f,--file", file,
                    "EvaluateBasisRequest as proto3 JSON (default: stdin)");
  bool surface_basis = false;
  basis->add_flag("--surface", surface_basis,
                  "The request is an EvaluateSurfaceBasisRequest "
                  "(SurfaceService.EvaluateBasis)");
  basis->add_option("--format", format, "Output: json or csv")
      ->check(CLI::IsMember({"json", "csv"}))
      ->capture_default_str();

  CLI::App* surface = app.add_subcommand(
      "surface", "Evaluate a surface: SurfaceService.Evaluate");
  std::string obj;
  AddCommonFlags(*surface, flags);
  surface->add_option("-f,--file", file,
                      "EvaluateSurfaceRequest as proto3 JSON (default: stdin)");
  surface->add_flag("--stream", stream, "Use EvaluateStream (large grids)");
  surface->add_option("--format", format, "Output: json or csv")
      ->check(CLI::IsMember({"json", "csv"}))
      ->capture_default_str();
  surface->add_option("--obj", obj,
                      "Write the grid as an OBJ triangle mesh to this file "
                      "('-' for stdout)");

  CLI::App* mesh_command = app.add_subcommand(
      "mesh", "Mesh a set of Bezier patches (teapot.json layout) as OBJ");
  std::string patches_file;
  int grid = 16;
  std::string mesh_obj = "-";
  AddCommonFlags(*mesh_command, flags);
  mesh_command
      ->add_option("--bezier-patches", patches_file,
                   "JSON with degree_u, degree_v and patches[].control_points")
      ->required();
  mesh_command->add_option("--grid", grid, "Points per side of each patch")
      ->check(CLI::Range(2, 4096))
      ->capture_default_str();
  mesh_command->add_option("--obj", mesh_obj, "Output file ('-' for stdout)")
      ->capture_default_str();

  bool surface_request = false;
  CLI::App* elevate = AddRequestCommand(
      app, "elevate",
      "Raise the degree: CurveService/SurfaceService.ElevateDegree", flags,
      file, "Elevate*DegreeRequest", surface_request,
      "ElevateSurfaceDegreeRequest");

  CLI::App* reduce = app.add_subcommand(
      "reduce", "Lower a Bezier curve's degree: CurveService.ReduceDegree");
  AddCommonFlags(*reduce, flags);
  reduce->add_option(
      "-f,--file", file,
      "ReduceCurveDegreeRequest as proto3 JSON (default: stdin)");

  CLI::App* interpolate =
      app.add_subcommand("interpolate",
                         "Interpolate points: CurveService/SurfaceService."
                         "Interpolate, from JSON or from a CSV of points");
  CsvInterpolation csv;
  AddCommonFlags(*interpolate, flags);
  interpolate->add_option(
      "-f,--file", file, "Interpolate*Request as proto3 JSON (default: stdin)");
  interpolate->add_flag("--surface", surface_request,
                        "The request is an InterpolateSurfaceRequest");
  interpolate->add_option("--csv", csv.csv,
                          "Points from CSV, one per line (x,y[,z...])");
  interpolate->add_option("--degree", csv.degree, "Degree (with --csv)")
      ->capture_default_str();
  interpolate
      ->add_option("--parameterization", csv.parameterization,
                   "uniform, chord_length, centripetal or universal")
      ->check(CLI::IsMember(
          {"uniform", "chord_length", "centripetal", "universal"}))
      ->capture_default_str();
  interpolate->add_flag("--closed", csv.closed, "Interpolate a closed curve");
  interpolate
      ->add_option("--spline", csv.spline,
                   "Cubic spline of function data (first CSV column is x): "
                   "natural, not_a_knot or periodic")
      ->check(CLI::IsMember({"natural", "not_a_knot", "periodic"}));
  interpolate->add_option(
      "--least-squares", csv.least_squares_points,
      "Least-squares fit with this many control points instead");

  CLI::App* split = AddRequestCommand(
      app, "split", "Split a curve or patch: CurveService/SurfaceService.Split",
      flags, file, "Split*Request", surface_request, "SplitSurfaceRequest");
  CLI::App* insert = AddRequestCommand(
      app, "insert-knots",
      "Knot insertion: CurveService/SurfaceService.InsertKnots", flags, file,
      "Insert*KnotsRequest", surface_request, "InsertSurfaceKnotsRequest");
  CLI::App* remove = AddRequestCommand(
      app, "remove-knots",
      "Knot removal within a tolerance (one knot, or simplify): "
      "CurveService/SurfaceService.RemoveKnots",
      flags, file, "Remove*KnotsRequest", surface_request,
      "RemoveSurfaceKnotsRequest");
  CLI::App* fit = AddRequestCommand(
      app, "fit",
      "Least-squares fit: CurveService.Fit, SurfaceService.Fit (a grid) or "
      "SurfaceService.FitScattered",
      flags, file, "Fit*Request", surface_request,
      "FitSurfaceRequest (a grid of points)");
  bool scattered = false;
  fit->add_flag("--scattered", scattered,
                "With --surface: the request is a FitScatteredSurfaceRequest");

  CLI::App* decompose = app.add_subcommand(
      "decompose", "Bezier segments of a curve: CurveService.Decompose");
  AddCommonFlags(*decompose, flags);
  decompose->add_option("-f,--file", file,
                        "DecomposeCurveRequest as proto3 JSON");

  CLI::App* subdivide = app.add_subcommand(
      "subdivide", "Chaikin / uniform B-spline subdivision of a polygon");
  std::string svg;
  AddCommonFlags(*subdivide, flags);
  subdivide->add_option("-f,--file", file, "SubdivideRequest as proto3 JSON");
  subdivide->add_option(
      "--svg", svg, "Draw the polygon and every level as SVG ('-': stdout)");

  CLI::App* tessellate = app.add_subcommand(
      "tessellate", "Adaptive polyline of a curve or mesh of surfaces");
  AddCommonFlags(*tessellate, flags);
  tessellate->add_option("-f,--file", file,
                         "Tessellate*Request as proto3 JSON");
  tessellate->add_flag("--surface", surface_request,
                       "The request is a TessellateSurfaceRequest");
  TessellateOutput tessellation;
  tessellate->add_option("--svg", tessellation.svg,
                         "Curves: draw the polyline and control polygon");
  tessellate
      ->add_option("--obj", tessellation.obj,
                   "Surfaces: write the mesh as OBJ ('-': stdout)")
      ->excludes(tessellate->add_option(
          "--stl", tessellation.stl,
          "Surfaces: write the mesh as binary STL ('-': stdout)"));
  tessellate->add_flag("--combs", tessellation.combs,
                       "With --svg: draw the curvature comb (2D curves)");
  tessellate
      ->add_option("--comb-scale", tessellation.comb_scale,
                   "Tooth length per unit of curvature (default: the "
                   "longest tooth is 15% of the drawing)")
      ->check(CLI::PositiveNumber);
  double max_normal_angle = 0;
  CLI::Option* normal_angle = tessellate->add_option(
      "--max-normal-angle", max_normal_angle,
      "Surfaces: the largest angle in radians between the unit normals at the "
      "two ends of a mesh edge (sets max_normal_angle)");

  freeform::cli::QueryCommands queries(app, flags);

  CLI::App* health =
      app.add_subcommand("health", "Ask the server's health service");
  std::string service;
  AddCommonFlags(*health, flags);
  health->add_option("--service", service,
                     "Service name (empty: the whole server)");

  CLI11_PARSE(app, argc, argv);
  if (eval->parsed()) return RunEval(flags, file, stream, format);
  if (basis->parsed()) return RunBasis(flags, file, format, surface_basis);
  if (surface->parsed()) return RunSurface(flags, file, stream, format, obj);
  if (elevate->parsed()) {
    return surface_request
               ? RunJsonCall(flags, file, &SurfaceStub::ElevateDegree)
               : RunJsonCall(flags, file, &CurveStub::ElevateDegree);
  }
  if (reduce->parsed()) {
    return RunJsonCall(flags, file, &CurveStub::ReduceDegree);
  }
  if (split->parsed()) {
    return surface_request ? RunJsonCall(flags, file, &SurfaceStub::Split)
                           : RunJsonCall(flags, file, &CurveStub::Split);
  }
  if (insert->parsed()) {
    return surface_request ? RunJsonCall(flags, file, &SurfaceStub::InsertKnots)
                           : RunJsonCall(flags, file, &CurveStub::InsertKnots);
  }
  if (remove->parsed()) {
    return surface_request ? RunJsonCall(flags, file, &SurfaceStub::RemoveKnots)
                           : RunJsonCall(flags, file, &CurveStub::RemoveKnots);
  }
  if (fit->parsed()) return RunFit(flags, file, surface_request, scattered);
  if (decompose->parsed()) {
    return RunJsonCall(flags, file, &CurveStub::Decompose);
  }
  if (subdivide->parsed()) return RunSubdivide(flags, file, svg);
  if (tessellate->parsed()) {
    const bool angle = normal_angle->count() > 0;
    if (angle && !surface_request) {
      std::cerr << "freeform tessellate: --max-normal-angle needs --surface\n";
      return 2;
    }
    return surface_request
               ? RunTessellateSurfaces(
                     flags, file, tessellation,
                     angle ? std::optional(max_normal_angle) : std::nullopt)
               : RunTessellateCurve(flags, file, tessellation);
  }
  if (std::optional<int> status = queries.Run()) return *status;
  if (interpolate->parsed()) {
    return RunInterpolate(flags, file, surface_request, csv);
  }
  if (mesh_command->parsed()) {
    return RunMesh(flags, patches_file, grid, mesh_obj);
  }
  return RunHealth(flags, service);
}
