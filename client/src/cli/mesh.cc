// `freeform mesh` (mesh.h).
#include "mesh.h"

#include <memory>

#include "absl/strings/str_cat.h"
#include "input.h"
#include "nlohmann/json.hpp"
#include "obj_mesh.h"
#include "output.h"
#include "subcommand.h"

namespace freeform::cli {
namespace {

// One patch's surface message; nlohmann's exceptions (a value that is not
// a number) are the caller's to catch.
v1::Surface PatchSurface(const nlohmann::json& patch, int degree_u,
                         int degree_v) {
  v1::Surface surface;
  v1::ControlNet* net = surface.mutable_bezier()->mutable_control_net();
  net->set_dimension(3);
  net->set_count_u(static_cast<uint32_t>(degree_u + 1));
  net->set_count_v(static_cast<uint32_t>(degree_v + 1));
  for (const nlohmann::json& point : patch.at("control_points")) {
    for (const nlohmann::json& value : point) {
      net->add_coordinates(value.get<double>());
    }
  }
  return surface;
}

// The grid request of one patch.
v1::EvaluateSurfaceRequest GridRequest(const v1::Surface& surface, int grid) {
  v1::EvaluateSurfaceRequest request;
  *request.mutable_surface() = surface;
  v1::SurfaceGrid* points = request.mutable_parameters()->mutable_grid();
  points->mutable_u()->mutable_range()->set_count(static_cast<uint32_t>(grid));
  points->mutable_v()->mutable_range()->set_count(static_cast<uint32_t>(grid));
  request.set_normals(true);
  return request;
}

}  // namespace

absl::StatusOr<std::vector<v1::Surface>> ReadBezierPatches(
    const std::string& file) {
  absl::StatusOr<std::string> text = ReadInput(file, "the patches");
  if (!text.ok()) return text.status();
  try {
    const nlohmann::json json = nlohmann::json::parse(*text);
    if (!json.contains("patches")) {
      return absl::InvalidArgumentError(
          absl::StrCat(file, ": not a JSON object with \"patches\""));
    }
    const int degree_u = json.value("degree_u", 3);
    const int degree_v = json.value("degree_v", 3);
    std::vector<v1::Surface> surfaces;
    for (const nlohmann::json& patch : json["patches"]) {
      surfaces.push_back(PatchSurface(patch, degree_u, degree_v));
    }
    return surfaces;
  } catch (const nlohmann::json::parse_error& error) {
    return absl::InvalidArgumentError(absl::StrCat(
        file, ":", LineAndColumn(*text, error.byte > 0 ? error.byte - 1 : 0),
        ": malformed JSON"));
  } catch (const nlohmann::json::exception& error) {
    return absl::InvalidArgumentError(absl::StrCat(file, ": ", error.what()));
  }
}

void AddMeshFlags(CLI::App& command, MeshOptions& options) {
  command
      .add_option("--bezier-patches", options.patches_file,
                  "JSON with degree_u, degree_v and patches[].control_points")
      ->required();
  command.add_option("--grid", options.grid, "Points per side of each patch")
      ->check(CLI::Range(2, 4096))
      ->capture_default_str();
  command.add_option("--obj", options.obj, "Output file ('-' for stdout)")
      ->capture_default_str();
}

int RunMesh(const CommonFlags& flags, const MeshOptions& options) {
  absl::StatusOr<std::vector<v1::Surface>> surfaces =
      ReadBezierPatches(options.patches_file);
  if (!surfaces.ok()) return InputError(surfaces.status());
  std::unique_ptr<Client> client = Connect(flags);
  if (client == nullptr) return kExitUsage;
  ObjMesh mesh;
  const auto grid = static_cast<size_t>(options.grid);
  for (size_t p = 0; p < surfaces->size(); ++p) {
    absl::StatusOr<SurfaceEvaluation> evaluation =
        client->EvaluateSurface(GridRequest((*surfaces)[p], options.grid));
    if (!evaluation.ok()) return ReportError(evaluation.status());
    mesh.AddGrid(absl::StrCat("patch", p), grid, grid,
                 evaluation->partials[0].values, evaluation->normals);
  }
  return WriteObj(mesh, options.obj);
}

}  // namespace freeform::cli
