// `freeform tessellate` (tessellate.h).
#include "tessellate.h"

#include "absl/strings/str_cat.h"
#include "curvature_comb.h"
#include "obj_mesh.h"
#include "run_call.h"
#include "stl_mesh.h"
#include "subcommand.h"
#include "svg_drawing.h"

namespace freeform::cli {
namespace {

// The control points of a Bezier or B-spline request curve (to draw them).
absl::Span<const double> ControlPolygon(const v1::Curve& curve,
                                        int& dimension) {
  const v1::Points& points = curve.has_bspline()
                                 ? curve.bspline().control_points()
                                 : curve.bezier().control_points();
  dimension = static_cast<int>(points.dimension());
  return absl::MakeConstSpan(points.coordinates().data(),
                             points.coordinates_size());
}

// --combs draws plane curves only.
absl::Status CheckCombs(const v1::TessellateCurveRequest& request,
                        const TessellateOptions& options) {
  if (!options.combs) return absl::OkStatus();
  if (options.svg.empty()) {
    return absl::InvalidArgumentError("--combs needs --svg");
  }
  const int dimension = CurveDimension(request.curve());
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
SvgDrawing DrawTessellation(const v1::TessellateCurveRequest& request,
                            const v1::TessellateCurveResponse& polyline) {
  SvgDrawing drawing;
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

int RunCurve(const CommonFlags& flags, const TessellateOptions& options) {
  return RunCall(
      flags, options.file, &v1::CurveService::Stub::Tessellate,
      [&](v1::TessellateCurveRequest& request) {
        return CheckCombs(request, options);
      },
      [&](Client& client, const v1::TessellateCurveRequest& request,
          const v1::TessellateCurveResponse& polyline) {
        if (options.svg.empty()) return PrintJson(flags, polyline);
        SvgDrawing drawing = DrawTessellation(request, polyline);
        if (options.combs) {
          const absl::Status comb = AddCurvatureComb(
              client, request.curve(), polyline,
              options.comb_scale > 0 ? std::optional(options.comb_scale)
                                     : std::nullopt,
              drawing);
          if (!comb.ok()) return ReportError(comb);
        }
        return WriteSvg(drawing, options.svg);
      });
}

// The mesh as binary STL, OBJ or JSON.
int WriteMesh(const CommonFlags& flags, const TessellateOptions& options,
              const v1::TessellateSurfaceResponse& mesh) {
  if (!options.stl.empty()) {
    return WriteOutput(
        options.stl,
        [&](std::ostream& out) {
          WriteBinaryStl(mesh.vertices().coordinates(), mesh.triangles(), out);
        },
        absl::StrCat(": ", mesh.triangles_size() / 3, " triangles"));
  }
  if (options.obj.empty()) return PrintJson(flags, mesh);
  ObjMesh out;
  out.AddTriangles("mesh", mesh.vertices().coordinates(),
                   mesh.normals().coordinates(), mesh.triangles());
  return WriteObj(out, options.obj);
}

// Surfaces, with the normal-angle limit of --max-normal-angle when given
// (the server checks it).
int RunSurfaces(const CommonFlags& flags, const TessellateOptions& options) {
  return RunCall(
      flags, options.file, &v1::SurfaceService::Stub::Tessellate,
      [&](v1::TessellateSurfaceRequest& request) {
        if (!options.obj.empty()) request.set_normals(true);
        if (options.max_normal_angle.has_value()) {
          request.set_max_normal_angle(*options.max_normal_angle);
        }
        return absl::OkStatus();
      },
      [&](Client&, const v1::TessellateSurfaceRequest&,
          const v1::TessellateSurfaceResponse& mesh) {
        return WriteMesh(flags, options, mesh);
      });
}

}  // namespace

void AddTessellateFlags(CLI::App& command, TessellateOptions& options) {
  AddFileFlag(command, options.file);
  command.add_flag("--surface", options.surface,
                   "The request is a TessellateSurfaceRequest");
  command.add_option("--svg", options.svg,
                     "Curves: draw the polyline and control polygon");
  command
      .add_option("--obj", options.obj,
                  "Surfaces: write the mesh as OBJ ('-': stdout)")
      ->excludes(command.add_option(
          "--stl", options.stl,
          "Surfaces: write the mesh as binary STL ('-': stdout)"));
  command.add_flag("--combs", options.combs,
                   "With --svg: draw the curvature comb (2D curves)");
  command
      .add_option("--comb-scale", options.comb_scale,
                  "Tooth length per unit of curvature (default: the "
                  "longest tooth is 15% of the drawing)")
      ->check(CLI::PositiveNumber);
  command.add_option(
      "--max-normal-angle", options.max_normal_angle,
      "Surfaces: the largest angle in radians between the unit normals at the "
      "two ends of a mesh edge (sets max_normal_angle)");
}

int RunTessellate(const CommonFlags& flags, const TessellateOptions& options) {
  if (options.max_normal_angle.has_value() && !options.surface) {
    return InputError(absl::InvalidArgumentError(
        "freeform tessellate: --max-normal-angle needs --surface"));
  }
  return options.surface ? RunSurfaces(flags, options)
                         : RunCurve(flags, options);
}

}  // namespace freeform::cli
