// The table of the freeform CLI's subcommands (subcommand.h) and the flags
// many of them share.
#include <algorithm>
#include <string>
#include <vector>

#include "basis.h"
#include "eval.h"
#include "health.h"
#include "interpolate.h"
#include "json_commands.h"
#include "mesh.h"
#include "queries.h"
#include "subcommand.h"
#include "subdivide.h"
#include "surface.h"
#include "tessellate.h"

namespace freeform::cli {
namespace {

using CurveStub = v1::CurveService::Stub;
using SurfaceStub = v1::SurfaceService::Stub;

// A plain JSON subcommand of one curve RPC.
template <auto kMethod>
constexpr auto kCurveCall =
    &Register<RequestOptions, AddRequestFlags, RunRequest<kMethod>>;

// A plain JSON subcommand of a curve RPC, or with --surface a surface RPC.
template <auto kCurveMethod, auto kSurfaceMethod>
constexpr auto kEitherCall =
    &Register<RequestOptions, AddCurveOrSurfaceFlags,
              RunCurveOrSurface<kCurveMethod, kSurfaceMethod>>;

const Subcommand kSubcommands[] = {
    {"eval",
     "Evaluate a curve: CurveService.Evaluate (--stream: EvaluateStream)",
     &Register<EvalOptions, AddEvalFlags, RunEval>},
    {"basis",
     "Evaluate blending functions: CurveService.EvaluateBasis (--surface: "
     "SurfaceService.EvaluateBasis)",
     &Register<BasisOptions, AddBasisFlags, RunBasis>},
    {"surface",
     "Evaluate a surface: SurfaceService.Evaluate (--stream: EvaluateStream)",
     &Register<SurfaceOptions, AddSurfaceFlags, RunSurface>},
    {"mesh", "Mesh a set of Bezier patches (teapot.json layout) as OBJ",
     &Register<MeshOptions, AddMeshFlags, RunMesh>},
    {"elevate", "Raise the degree: CurveService/SurfaceService.ElevateDegree",
     kEitherCall<&CurveStub::ElevateDegree, &SurfaceStub::ElevateDegree>},
    {"reduce", "Lower a Bezier curve's degree: CurveService.ReduceDegree",
     kCurveCall<&CurveStub::ReduceDegree>},
    {"interpolate",
     "Interpolate points: CurveService/SurfaceService.Interpolate, from JSON "
     "or from a CSV of points",
     &Register<InterpolateOptions, AddInterpolateFlags, RunInterpolate>},
    {"split", "Split a curve or patch: CurveService/SurfaceService.Split",
     kEitherCall<&CurveStub::Split, &SurfaceStub::Split>},
    {"insert-knots", "Knot insertion: CurveService/SurfaceService.InsertKnots",
     kEitherCall<&CurveStub::InsertKnots, &SurfaceStub::InsertKnots>},
    {"remove-knots",
     "Knot removal within a tolerance (one knot, or simplify): "
     "CurveService/SurfaceService.RemoveKnots",
     kEitherCall<&CurveStub::RemoveKnots, &SurfaceStub::RemoveKnots>},
    {"fit",
     "Least-squares fit: CurveService.Fit, SurfaceService.Fit (a grid) or "
     "SurfaceService.FitScattered",
     &Register<RequestOptions, AddFitFlags, RunFit>},
    {"decompose", "Bezier segments of a curve: CurveService.Decompose",
     kCurveCall<&CurveStub::Decompose>},
    {"subdivide", "Chaikin / uniform B-spline subdivision of a polygon",
     &Register<SubdivideOptions, AddSubdivideFlags, RunSubdivide>},
    {"tessellate", "Adaptive polyline of a curve or mesh of surfaces",
     &Register<TessellateOptions, AddTessellateFlags, RunTessellate>},
    {"closest",
     "Closest points of a curve or surface: CurveService/SurfaceService."
     "ClosestPoint",
     &Register<QueryOptions, AddClosestFlags, RunClosest>},
    {"intersect",
     "Intersections of two curves: CurveService.Intersect (--surface: a "
     "curve and a surface, SurfaceService.IntersectCurve)",
     kEitherCall<&CurveStub::Intersect, &SurfaceStub::IntersectCurve>},
    {"arc-length", "Arc lengths of a curve: CurveService.ArcLength",
     kCurveCall<&CurveStub::ArcLength>},
    {"at-length",
     "Parameters at arc lengths: CurveService.ParametersAtArcLength",
     kCurveCall<&CurveStub::ParametersAtArcLength>},
    {"sample-length",
     "Samples at equal arc-length spacing: CurveService.SampleByArcLength",
     &Register<QueryOptions, AddSampleLengthFlags, RunSampleByLength>},
    {"curvature",
     "Curvature and frames at parameters: CurveService/SurfaceService."
     "Curvature",
     &Register<QueryOptions, AddCurvatureFlags, RunCurvature>},
    {"frames",
     "Rotation-minimizing frames: CurveService.RotationMinimizingFrames",
     kCurveCall<&CurveStub::RotationMinimizingFrames>},
    {"bbox", "Tight bounding box: CurveService/SurfaceService.BoundingBox",
     kEitherCall<&CurveStub::BoundingBox, &SurfaceStub::BoundingBox>},
    {"section", "Plane section of a surface: SurfaceService.Section",
     &Register<QueryOptions, AddSectionFlags, RunSection>},
    {"health", "Ask the server's health service",
     &Register<HealthOptions, AddHealthFlags, RunHealth>},
};

}  // namespace

absl::Span<const Subcommand> Subcommands() { return kSubcommands; }

void AddFileFlag(CLI::App& command, std::string& file) {
  command.add_option("-f,--file", file,
                     "The request as proto3 JSON ('-' or none: stdin)");
}

void AddFormatFlag(CLI::App& command, std::string& format,
                   const std::vector<std::string>& formats) {
  const bool rows =
      std::find(formats.begin(), formats.end(), "jsonl") != formats.end();
  command
      .add_option("--format", format,
                  rows ? "Output: json, csv or jsonl (one JSON object per "
                         "row)"
                       : "Output: json or csv")
      ->check(CLI::IsMember(formats))
      ->capture_default_str();
}

}  // namespace freeform::cli
