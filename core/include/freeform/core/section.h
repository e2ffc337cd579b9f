// Sections of surfaces by a plane (contours for slicing and CAM): the
// curves where a surface meets the hyperplane n . x = n . p, as polylines
// whose vertices lie on the section, and the parts of the surface lying in
// the plane, as regions.
//
// The surface is cut into (rational) Bezier pieces (DecomposeSurface in
// surface.h), divided by a power of two (exact) to coordinates of about 1.
// On a piece the signed distance times the weight, g = n . (w P) -
// (n . p) w (n of length 1, computed after dividing by its largest
// component), is a scalar polynomial Bezier patch whose coefficients are
// those of the net, and the section is its zero set (docs/references.md,
// 'Plane sections of Bezier patches'). A coefficient within 64 rounding
// errors of the magnitude of its terms is zero:
//   - a piece whose coefficients are all zero lies in the plane: it is a
//     region (its boundary is not traced);
//   - an edge of a piece whose coefficients are all zero lies in the plane
//     and is traced as an arc, once (an edge two pieces share, or one of a
//     region, is not traced again);
// and the parameter square of every other piece is split as a quadtree:
//   - a cell whose coefficients all have one sign (0 counting positive;
//     those on an edge of the piece lying in the plane left out) holds no
//     other section point (convex hull property);
//   - a cell whose coefficients rise (or fall) strictly along u holds the
//     section as a graph u = h(v) (likewise with u and v exchanged): every
//     line of constant v meets it at most once. Its boundary points are
//     found on the four edges (on the edges of constant u by isolating the
//     roots of the edge's Bezier coefficients by sign variations, all by
//     false position on the piece's function), taken in order of v and
//     paired into arcs; each arc gets vertices at the roots of g on lines of
//     constant v, inserted at midpoints until the middle vertex lies within
//     `tolerance` of the chord (a midpoint test, not a bound);
//   - other cells are halved, down to kMaxSectionDepth levels (tangential
//     touching points and crossings of the section with itself are not
//     resolved further: they may be missing or break a polyline there).
// Every vertex is checked to lie within `tolerance` of the plane. Arcs are
// joined into polylines where their end points coincide (within 1e-9 of the
// control points' extent), across cells, pieces and seams, and a polyline
// that returns to its start is closed.
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
  // finite, and at least kResolution (2^-48) times the largest magnitude of
  // a control point coordinate, what double precision resolves on the
  // surface (tessellation_checks.h).
  double tolerance = 1e-6;
  // The most polyline vertices plus region corners returned
  // (RESOURCE_EXHAUSTED naming "max_points" beyond). Each vertex costs at
  // most 200 evaluations of g and one of the surface.
  size_t max_points = size_t{1} << 20;
  // The most work the quadtree does (cells, root isolation and the roots on
  // cell boundaries), in units of about one multiply-add, each step charged
  // by the size of the net it touches (RESOURCE_EXHAUSTED naming
  // "max_work" beyond).
  uint64_t max_work = uint64_t{1} << 28;
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
// Regions: region k, a Bezier piece lying in the plane, is the surface over
// the parameter polygon of corners region_offsets[k] ..
// region_offsets[k + 1] - 1, corner r at (region_corners[2 r],
// region_corners[2 r + 1]) (a span rectangle of a B-spline, the domain of a
// Bezier surface or the triangle of a triangular patch).
struct Sections {
  int dimension = 0;
  std::vector<size_t> offsets = {0};
  std::vector<double> points;
  std::vector<double> parameters;
  std::vector<uint8_t> closed;
  std::vector<size_t> region_offsets = {0};
  std::vector<double> region_corners;
  // With fit_tolerance > 0: curves[k] is the B-spline of polyline k (a
  // closed polyline gives a curve whose ends meet); else empty.
  std::vector<BSplineCurveData> curves;
};

// IntersectSurfacePlane returns the section of a valid surface by the
// hyperplane through `plane_point` with normal `plane_normal` (both of the
// surface's dimension; a plane farther from the surface than doubles reach
// meets nothing). Fails with INVALID_ARGUMENT naming "plane_point" or
// "plane_normal" (size, not finite, a zero normal: "plane_normal"),
// "tolerance" (also below the resolution), "fit_tolerance", "surface" (a
// vertex that double precision cannot place within the tolerance of the
// plane: where extreme weights make the surface jump between neighbouring
// parameters; or one whose parameters, rounded to doubles, put the surface
// beyond the tolerance of it: knot spans a few ulps of their position),
// RESOURCE_EXHAUSTED naming "max_points" or "max_work", and
// with the token's CANCELLED / DEADLINE_EXCEEDED.
absl::StatusOr<Sections> IntersectSurfacePlane(
    const Surface& surface, absl::Span<const double> plane_point,
    absl::Span<const double> plane_normal, const SectionOptions& options = {},
    const CancellationToken* cancel = nullptr);

}  // namespace freeform

#endif  // FREEFORM_CORE_SECTION_H_
