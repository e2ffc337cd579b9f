// `freeform subdivide` (subdivide.h).
#include "subdivide.h"

#include "run_call.h"
#include "subcommand.h"
#include "svg_drawing.h"

namespace freeform::cli {
namespace {

// The polygon and every level of a subdivision.
SvgDrawing DrawSubdivision(const v1::SubdivideRequest& request,
                           const v1::SubdivideResponse& result) {
  SvgDrawing drawing;
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

}  // namespace

void AddSubdivideFlags(CLI::App& command, SubdivideOptions& options) {
  AddFileFlag(command, options.file);
  command.add_option("--svg", options.svg,
                     "Draw the polygon and every level as SVG ('-': stdout)");
}

int RunSubdivide(const CommonFlags& flags, const SubdivideOptions& options) {
  return RunCall(
      flags, options.file, &v1::CurveService::Stub::Subdivide,
      [&](v1::SubdivideRequest& request) {
        if (!options.svg.empty()) request.set_keep_levels(true);
        return absl::OkStatus();
      },
      [&](Client&, const v1::SubdivideRequest& request,
          const v1::SubdivideResponse& result) {
        return options.svg.empty()
                   ? PrintJson(flags, result)
                   : WriteSvg(DrawSubdivision(request, result), options.svg);
      });
}

}  // namespace freeform::cli
