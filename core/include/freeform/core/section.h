// Sections of surfaces by a plane (contours for slicing and CAM): the
// curves where a surface meets the hyperplane n . x = n . p, as polylines
// whose vertices lie on the section.
//
// The surface is cut into (rational) Bezier pieces (DecomposeSurface in
// surface.h). On a piece the signed distance times the weight,
// g = n . (w P) - (n . p) w, is a scalar polynomial Bezier patch whose
// coefficients are those of the net, and the section is its zero set
// (docs/references.md, 'Plane sections of Bezier patches'). The parameter
// square is split as a quadtree:
//   - a cell whose coefficients all have one strict sign holds no section
//     point (convex hull property);
//   - a cell whose coefficients rise (or fall) strictly along u holds the
//     section as a graph u = h(v) (likewise with u and v exchanged): every
//     line of constant v meets it at most once. Its boundary points are
//     found on the four edges (on the edges of constant u by isolating the
//     roots of the edge's Bezier coefficients by sign variations, all by
//     bisection on the piece's function), taken in order of v and paired
//     into arcs; each arc gets vertices at the roots of g on lines of
//     constant v, inserted at midpoints until the middle vertex lies within
//     `tolerance` of the chord (a midpoint test, not a bound);
//   - other cells are halved, down to kMaxSectionDepth levels (tangential
//     touching points and crossings of the section with itself are not
//     resolved further: they may be missing or break a polyline there).
// Cells whose coefficients are all within rounding of 0 lie in the plane
// and give no polyline. Arcs are joined into polylines where their end
// points coincide (within 1e-9 of the control points' extent), across
// cells, pieces and seams, and a polyline that returns to its start is
// closed.
//
// Thread-safe; allocates per call.
#ifndef FREEFORM_CORE_SECTION_H_
#define FREEFORM_CORE_SECTION_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/geometry_data.h"
#include "freeform/core/surface.h"

namespace freeform {

// The most quadtree levels a piece's parameter square is halved through.
inline constexpr int kMaxSectionDepth = 40;

struct SectionOptions {
  // Chordal tolerance of the polylines (see the file comment). Positive,
  // finite.
  double tolerance = 1e-6;
  // The most polyline vertices returned (RESOURCE_EXHAUSTED naming
  // "max_points" beyond).
  size_t max_points = size_t{1} << 20;
  // The most quadtree cells examined (RESOURCE_EXHAUSTED naming "max_cells"
  // beyond): bounds the work.
  size_t max_cells = size_t{1} << 20;
  // When positive, every polyline is also fitted by a cubic B-spline (a
  // lower degree for fewer than 4 vertices) that passes within this
  // distance of each of its vertices at their chord-length parameters:
  // least squares through the vertices (ApproximateCurve, the ends
  // interpolated), the control points doubled until the largest residual
  // is within it, up to interpolation through every vertex. Finite, >= 0.
  double fit_tolerance = 0.0;
};

// Polylines: polyline k has the vertices offsets[k] .. offsets[k + 1] - 1;
// vertex r is points[r * dimension ...] at the surface parameters
// parameters[2 r], parameters[2 r + 1] (as EvaluateSurface takes them).
// A closed polyline repeats its first vertex at its end.
struct Sections {
  int dimension = 0;
  std::vector<size_t> offsets = {0};
  std::vector<double> points;
  std::vector<double> parameters;
  std::vector<uint8_t> closed;
  // With fit_tolerance > 0: curves[k] is the B-spline of polyline k (a
  // closed polyline gives a curve whose ends meet); else empty.
  std::vector<BSplineCurveData> curves;
};

// IntersectSurfacePlane returns the section of a valid surface by the
// hyperplane through `plane_point` with normal `plane_normal` (both of the
// surface's dimension). Fails with INVALID_ARGUMENT naming "plane_point" or
// "plane_normal" (size, not finite, a zero normal: "plane_normal"),
// "tolerance", "fit_tolerance", RESOURCE_EXHAUSTED naming "max_points" or
// "max_cells", and with the token's CANCELLED / DEADLINE_EXCEEDED.
absl::StatusOr<Sections> IntersectSurfacePlane(
    const Surface& surface, absl::Span<const double> plane_point,
    absl::Span<const double> plane_normal, const SectionOptions& options = {},
    const CancellationToken* cancel = nullptr);

}  // namespace freeform

#endif  // FREEFORM_CORE_SECTION_H_
