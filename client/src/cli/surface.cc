// `freeform surface` (surface.h): rows of partials and normals, the
// response message's JSON, or an OBJ mesh of a grid.
#include "surface.h"

#include <cstdio>
#include <memory>
#include <vector>

#include "absl/strings/str_cat.h"
#include "input.h"
#include "obj_mesh.h"
#include "output.h"
#include "row_stream.h"
#include "rows.h"
#include "subcommand.h"

namespace freeform::cli {
namespace {

using Span = absl::Span<const double>;

// Number of values a grid axis resolves to.
uint64_t AxisCount(const v1::Parameters& axis) {
  return axis.has_list() ? static_cast<uint64_t>(axis.list().values_size())
                         : axis.range().count();
}

// The number of points a request asks for.
uint64_t PointCount(const v1::EvaluateSurfaceRequest& request) {
  const v1::SurfaceParameters& parameters = request.parameters();
  if (parameters.has_grid()) {
    return AxisCount(parameters.grid().u()) * AxisCount(parameters.grid().v());
  }
  return static_cast<uint64_t>(parameters.points().uv_size() / 2);
}

// A partial's JSON name: "point" for (0, 0), else "d" and one u or v per
// differentiation ("du", "dv", "duv", ...).
std::string PartialName(const v1::PartialDerivative& partial) {
  if (partial.order_u() == 0 && partial.order_v() == 0) return "point";
  return absl::StrCat("d", std::string(partial.order_u(), 'u'),
                      std::string(partial.order_v(), 'v'));
}

// Writes one answer chunk as rows: every partial (CSV columns
// s{order_u}{order_v}_j), then the normal (nx, ny, nz) when asked for.
absl::Status WriteSurfaceChunk(const v1::EvaluateSurfaceResponse& chunk,
                               RowWriter& writer) {
  const bool normals = chunk.has_normals();
  if (!writer.begun()) {
    std::vector<ColumnGroup> groups;
    for (const v1::PartialDerivative& partial : chunk.partials()) {
      groups.push_back({.json_name = PartialName(partial),
                        .csv_prefix = absl::StrCat("s", partial.order_u(),
                                                   partial.order_v(), "_"),
                        .width = chunk.dimension()});
    }
    if (normals) {
      groups.push_back({.json_name = "normal",
                        .csv_prefix = "n",
                        .width = 3,
                        .csv_names = {"nx", "ny", "nz"}});
    }
    writer.Begin(std::move(groups), {{"dimension", chunk.dimension()}});
  }
  std::vector<Span> columns;
  for (const v1::PartialDerivative& partial : chunk.partials()) {
    const auto& values = partial.values().coordinates();
    columns.emplace_back(values.data(), values.size());
  }
  if (normals) {
    const auto& values = chunk.normals().coordinates();
    columns.emplace_back(values.data(), values.size());
  }
  return writer.Rows(chunk.first_index(), chunk.count(), columns);
}

int RunSurfaceStream(const CommonFlags& flags, Client& client,
                     const v1::EvaluateSurfaceRequest& request,
                     RowFormat format) {
  return StreamRows(flags, client, &Client::EvaluateSurfaceStream, request,
                    PointCount(request), format, &WriteSurfaceChunk);
}

// --obj: the grid as a triangle mesh with normals.
int RunObj(Client& client, const v1::EvaluateSurfaceRequest& request,
           bool stream, const std::string& path) {
  absl::StatusOr<SurfaceEvaluation> evaluation =
      stream ? client.EvaluateSurfaceStreamed(request)
             : client.EvaluateSurface(request);
  if (!evaluation.ok()) return ReportError(evaluation.status());
  ObjMesh mesh;
  mesh.AddGrid("surface", AxisCount(request.parameters().grid().u()),
               AxisCount(request.parameters().grid().v()),
               evaluation->partials[0].values, evaluation->normals);
  return WriteObj(mesh, path);
}

}  // namespace

void AddSurfaceFlags(CLI::App& command, SurfaceOptions& options) {
  AddFileFlag(command, options.file);
  AddStreamFlags(command, options.stream, options.format, "large grids");
  command.add_option("--obj", options.obj,
                     "Write the grid as an OBJ triangle mesh to this file "
                     "('-' for stdout)");
}

int RunSurface(const CommonFlags& flags, const SurfaceOptions& options) {
  absl::StatusOr<v1::EvaluateSurfaceRequest> request =
      ParseJson<v1::EvaluateSurfaceRequest>(options.file);
  if (!request.ok()) return InputError(request.status());
  absl::StatusOr<RowFormat> format = ParseRowFormat(options.format);
  if (!format.ok()) return InputError(format.status());
  if (!options.obj.empty()) {
    if (!request->parameters().has_grid()) {
      return InputError(
          absl::InvalidArgumentError("--obj needs grid parameters"));
    }
    request->set_normals(true);
  }
  std::unique_ptr<Client> client = Connect(flags);
  if (client == nullptr) return kExitUsage;
  if (!options.obj.empty()) {
    return RunObj(*client, *request, options.stream, options.obj);
  }
  if (options.stream)
    return RunSurfaceStream(flags, *client, *request, *format);
  absl::StatusOr<v1::EvaluateSurfaceResponse> response =
      client->Unary(&v1::SurfaceService::Stub::Evaluate, *request);
  if (!response.ok()) return ReportError(response.status());
  if (*format == RowFormat::kJson) return PrintJson(flags, *response);
  RowWriter writer(*format, stdout);
  if (absl::Status status = WriteSurfaceChunk(*response, writer);
      !status.ok()) {
    return ReportError(status);
  }
  return FinishRows(writer);
}

}  // namespace freeform::cli
