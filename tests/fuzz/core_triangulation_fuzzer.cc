// libFuzzer target of the constrained Delaunay triangulation
// (TriangulateConstrained, ConstrainedTriangulation::InsertPoint): points
// on a small grid (duplicates, collinear and cocircular points) or fuzzed
// values (core_fuzz_input.h, sometimes wild), segments between any indices
// (some out of range, crossing or overlapping), either region. A refusal
// must be INVALID_ARGUMENT naming its field; an accepted input must give
// counter-clockwise triangles, each directed edge once, every unconstrained
// edge locally Delaunay, every segment a chain of constrained edges, and on
// the grid (where long double areas are exact) the hull covered exactly.
// Then a few points are inserted one at a time and the checks repeated.
#include <array>
#include <cstdint>
#include <vector>

#include "core_fuzz_input.h"
#include "freeform/core/constrained_delaunay.h"
#include "triangulation_checks.h"

namespace freeform::fuzz {
namespace {

using Region = ConstrainedTriangulationOptions::Region;

Point2 FuzzedPoint(CoreFuzzInput& input, bool on_grid) {
  if (on_grid) return {input.Int(0, 15) / 8.0, input.Int(0, 15) / 8.0};
  return {input.Value(), input.Value()};
}

void CheckMesh(const PlanarTriangulation& mesh,
               absl::Span<const std::array<int32_t, 2>> segments, bool on_grid,
               bool whole_hull) {
  const std::string triangles = testing::CheckTriangles(mesh);
  Check(triangles.empty(), triangles);
  const std::string present = testing::CheckSegmentsPresent(mesh, segments);
  Check(present.empty(), present);
  if (on_grid && whole_hull) {
    const std::string cover = testing::CheckHullCover(mesh);
    Check(cover.empty(), cover);
  }
}

void Run(const uint8_t* data, size_t size) {
  CoreFuzzInput input(data, size);
  const bool on_grid = input.Bool();
  const Region region =
      input.Bool() ? Region::kConvexHull : Region::kInsideSegments;
  std::vector<Point2> points(static_cast<size_t>(input.Int(0, 120)));
  for (Point2& p : points) p = FuzzedPoint(input, on_grid);
  const auto count = static_cast<int>(points.size());
  std::vector<std::array<int32_t, 2>> segments(
      static_cast<size_t>(input.Int(0, 60)));
  for (auto& s : segments) s = {input.Int(-1, count), input.Int(-1, count)};

  absl::StatusOr<ConstrainedTriangulation> built =
      ConstrainedTriangulation::Build(points, segments, nullptr);
  if (!built.ok()) return CheckRefusal(built.status(), "a triangulation");
  CheckMesh(built->Result(region), segments, on_grid,
            region == Region::kConvexHull);
  for (int i = input.Int(0, 20); i > 0; --i) {
    const absl::StatusOr<int32_t> vertex =
        built->InsertPoint(FuzzedPoint(input, on_grid));
    if (!vertex.ok()) {
      CheckRefusal(vertex.status(), "an inserted point");
      continue;
    }
    Check(*vertex >= 0 && static_cast<size_t>(*vertex) < built->point_count(),
          "InsertPoint returned a vertex out of range");
  }
  CheckMesh(built->Result(Region::kConvexHull), segments, on_grid, true);
}

}  // namespace
}  // namespace freeform::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  freeform::fuzz::Run(data, size);
  return 0;
}
