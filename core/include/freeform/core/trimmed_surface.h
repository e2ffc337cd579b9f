// Trimmed faces: a surface cut by closed loops of 2D curves in its (u, v)
// domain, validated once, then classified and measured.
//
// A TrimmedSurface is a tensor-product Surface (Bezier, B-spline or NURBS),
// an optional outer loop running counter-clockwise in (u, v) (absent: the
// whole parameter rectangle), holes running clockwise, and an orientation
// flag (reversed: the face normal is -S_u x S_v). Each loop is a closed
// chain of 2D curves of any kind the core has (curve.h). Like the curves, a
// face holds views of the caller's arrays: they must outlive it.
//
// TrimmedSurface::Create checks every rule of a face once, with the field
// path of the offending part relative to the face ("outer.curves[2]",
// "holes[1].curves[0]", "holes[3]"), and precomputes what classification
// needs: each loop's Bezier pieces, a polyline within a certified Hausdorff
// distance of the loop, and a uniform grid of the polylines' segments.
//
// Example:
//   TrimmedSurfaceParts parts{.surface = plane, .outer = std::nullopt,
//                             .holes = {TrimLoop{{circle_clockwise}}}};
//   absl::StatusOr<TrimmedSurface> face =
//       TrimmedSurface::Create(std::move(parts), 1e-9);
//   absl::StatusOr<std::vector<PointLocation>> where =
//       ClassifyPoints(*face, uv, 1e-12);
//   absl::StatusOr<FaceAreaResult> area = FaceArea(*face, 1e-10);
//
// Thread-safe: a face is immutable after Create; every function here is
// const on it and may run concurrently.
#ifndef FREEFORM_CORE_TRIMMED_SURFACE_H_
#define FREEFORM_CORE_TRIMMED_SURFACE_H_

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/bounding_box.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/curve.h"
#include "freeform/core/surface.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/thread_pool.h"

namespace freeform {

namespace internal {
struct FaceBoundary;
}  // namespace internal

// A closed chain of 2D curves: curve j ends where curve j + 1 starts, and
// the last ends where the first starts (within the face's tolerance).
struct TrimLoop {
  std::vector<Curve> curves;
};

// The raw parts of a face, before validation.
struct TrimmedSurfaceParts {
  Surface surface;
  // Counter-clockwise in (u, v); absent: the whole parameter rectangle.
  std::optional<TrimLoop> outer;
  // Clockwise, each inside the outer loop, none inside another.
  std::vector<TrimLoop> holes;
  // When set, the face normal is -S_u x S_v.
  bool reversed = false;
};

// The most Bezier pieces all the loops of a face may have together, and
// the most segments of their certified polylines (RESOURCE_EXHAUSTED
// naming "outer" or "holes" beyond).
inline constexpr uint64_t kMaxFaceTrimPieces = uint64_t{1} << 22;
inline constexpr uint64_t kMaxFaceBoundarySegments = uint64_t{1} << 24;

// A validated face.
class TrimmedSurface {
 public:
  // Create validates `parts` with `tolerance`, the closure and geometry
  // tolerance in (u, v) (positive, finite; at least 2^-46 of the trims'
  // largest coordinate), and precomputes the loops' polylines and grid.
  // Fails with INVALID_ARGUMENT naming:
  //   "tolerance" (not positive and finite, or too small to resolve);
  //   "surface" (a triangular patch: not supported as a face yet);
  //   "outer.curves" / "holes[i].curves" (a loop without curves);
  //   "<loop>.curves[j]" for a curve that is not 2D, that does not start
  //     within tolerance of the end of curve j - 1 (the last for j = 0; the
  //     gap is in the message), that leaves the surface's parameter
  //     rectangle by more than the tolerance (certified by the control
  //     points of its Bezier pieces, subdivided where they poke out), or
  //     that crosses or touches (within tolerance) another curve of its own
  //     loop or of another loop (the other is named in the message;
  //     neighbours in a loop may meet only at their shared end);
  //   "outer" (signed area not positive: not counter-clockwise), "holes[i]"
  //     (signed area not negative, outside the outer loop or the domain, or
  //     inside another hole).
  // Curves of zero length (control points within the tolerance of each
  // other) are allowed and skipped; trims may touch or run along the
  // parameter rectangle's edges (without an outer loop, a hole may touch
  // it). Fails with RESOURCE_EXHAUSTED when the loops exceed
  // kMaxFaceTrimPieces or kMaxFaceBoundarySegments, and with the token's
  // CANCELLED / DEADLINE_EXCEEDED.
  static absl::StatusOr<TrimmedSurface> Create(
      TrimmedSurfaceParts parts, double tolerance,
      const CancellationToken* cancel = nullptr);

  const Surface& surface() const { return parts_.surface; }
  const std::optional<TrimLoop>& outer() const { return parts_.outer; }
  const std::vector<TrimLoop>& holes() const { return parts_.holes; }
  bool reversed() const { return parts_.reversed; }
  double tolerance() const { return tolerance_; }
  // The precomputed pieces, polylines and grid (internal to the core).
  const internal::FaceBoundary& boundary() const { return *boundary_; }

 private:
  TrimmedSurface(TrimmedSurfaceParts parts, double tolerance,
                 std::shared_ptr<const internal::FaceBoundary> boundary)
      : parts_(std::move(parts)),
        tolerance_(tolerance),
        boundary_(std::move(boundary)) {}

  TrimmedSurfaceParts parts_;
  double tolerance_;
  std::shared_ptr<const internal::FaceBoundary> boundary_;
};

// The work of creating a face, known before it is made.
struct TrimmedSurfaceWork {
  // An upper bound of the memory TrimmedSurface::Create uses and the face
  // then holds: the loops' Bezier pieces, the monotone parts of the
  // crossing check, the polylines by the tessellation's a-priori bound and
  // their grid.
  uint64_t bytes = 0;
  // The loops' Bezier pieces (FaceAreaWorkBytes needs them).
  uint64_t pieces = 0;
};

// TrimmedSurfaceWorkBytes returns the work of TrimmedSurface::Create(parts,
// tolerance), cutting the loops into their Bezier pieces as Create does.
// Fails as Create does on the pieces (a curve not 2D, too many pieces or
// segments) and with the token's status; the other rules are Create's to
// check.
absl::StatusOr<TrimmedSurfaceWork> TrimmedSurfaceWorkBytes(
    const TrimmedSurfaceParts& parts, double tolerance,
    const CancellationToken* cancel = nullptr);

// Where a (u, v) point lies with respect to a face.
enum class PointLocation : uint8_t { kOutside, kInside, kOnBoundary };

// ClassifyPoints returns the location of every (u, v) pair of `uv`
// (u_0, v_0, u_1, v_1, ...): on the boundary when the point is within
// `tolerance` of a trim curve (or of the parameter rectangle's edge when
// the face has no outer loop), else inside or outside by the winding number
// of the loops. Points farther than `tolerance` outside the parameter
// rectangle are outside.
//
// Certified: each loop's polyline lies within a Hausdorff distance e of the
// loop (TessellateBezierCurve's flatness bound per piece). A point farther
// than e + tolerance from every segment gets the polyline's winding number,
// which is the loop's (the arc and the chord of every segment lie in the
// hull of the segment's control points, within e of the chord), and is not
// on the boundary. Near a segment the segment's arc is re-tessellated with
// e / 8, recursively, until each sub-chord either is farther than its bound
// plus `tolerance` (its winding counts), or is within `tolerance` minus its
// bound (a curve point is within `tolerance`: on the boundary); the
// recursion stops at a bound of max(tolerance / 256, 2^-44 of the piece's
// coordinates), where the chord's distance decides. So a point farther than
// tolerance (1 + 1/256) from the trims is never on the boundary, one within
// tolerance (1 - 1/256) always is.
//
// Fast for many points: the segments are found through a uniform grid of
// the parameter rectangle (rows for the winding ray, cells for the
// distance). The points run in chunks of at most 1024 on the context's
// pool. Fails with INVALID_ARGUMENT naming "uv" (odd count), "uv[i]" (not
// finite) or "tolerance" (negative or not finite), and with the context
// token's CANCELLED / DEADLINE_EXCEEDED (checked before each chunk).
absl::StatusOr<std::vector<PointLocation>> ClassifyPoints(
    const TrimmedSurface& face, absl::Span<const double> uv, double tolerance,
    const ExecutionContext& context = {});

// ClassifySamples is ClassifyPoints for surface samples (pairs or a grid,
// u-major), writing one location per sample into `locations`, the samples
// split over the context's pool. Fails with INVALID_ARGUMENT naming
// "locations" (not one per sample), "uv[i]" / "u[i]" / "v[i]" (not
// finite) or "tolerance", and with the token's status.
absl::Status ClassifySamples(const TrimmedSurface& face,
                             const SurfaceSamples& samples, double tolerance,
                             absl::Span<PointLocation> locations,
                             const ExecutionContext& context = {});

// OrientFaceNormals turns unit normals of the face's surface (x, y, z
// triples) into the face's normals: reversed when the face is.
void OrientFaceNormals(const TrimmedSurface& face, absl::Span<double> normals);

// The area of a face and a bound of its error.
struct FaceAreaResult {
  double area = 0.0;
  double error_bound = 0.0;
};

// FaceArea returns the surface area over the trimmed domain D,
// the integral of |S_u x S_v| du dv (the Gram determinant's root for other
// dimensions), reduced exactly to the boundary by Green's theorem: with
// F(u, v) = integral of |S_u x S_v|(s, v) ds from u_start to u, the area is
// the sum over the loops (the parameter rectangle when there is no outer
// loop) of the integral of F(c(t)) v'(t) dt along each trim piece. The
// outer integrals are adaptive Gauss-Kronrod (7-15), the intervals of all
// pieces (cut where a segment crosses a knot line) refined together, the
// interval of largest error first; the inner F adaptive Gauss-Kronrod over
// each knot span of the surface in u, the 15 nodes of an outer interval in
// one surface evaluation. error_bound adds the outer |K15 - G7| estimates
// and every inner estimate weighted by |v'| and the outer rule's weights.
// The work stops when error_bound is at most `tolerance` (absolute,
// positive, finite) or after kMaxFaceAreaIntervals halvings (error_bound
// then says how far it got). Fails with INVALID_ARGUMENT "tolerance",
// RESOURCE_EXHAUSTED naming "max_work" when more than `max_points` surface
// points would be evaluated (a tolerance the work cannot reach), and with
// the token's CANCELLED / DEADLINE_EXCEEDED (polled in the inner integrals
// too).
inline constexpr size_t kMaxFaceAreaIntervals = size_t{1} << 16;

// FaceAreaWorkBytes bounds the working memory of FaceArea on a face of
// `surface` whose loops have `pieces` Bezier pieces
// (TrimmedSurfaceWork::pieces).
uint64_t FaceAreaWorkBytes(const Surface& surface, uint64_t pieces);

absl::StatusOr<FaceAreaResult> FaceArea(
    const TrimmedSurface& face, double tolerance,
    const CancellationToken* cancel = nullptr,
    uint64_t max_points = UINT64_MAX);

// Samples of one trim curve, in its parameter order.
struct TrimSamples {
  std::vector<double> uv;          // (u, v) pairs on the curve
  std::vector<double> parameters;  // the curve's own parameter of each
};

// SampleTrimCurve samples curve `curve` of the outer loop (hole = -1) or of
// holes[hole] so that the face's 3D curve S(c(t)) between consecutive
// samples lies within `tolerance` (3D, absolute) of the chord between their
// points: the first sample at the curve's start, the last at its end,
// every point evaluated on the trim curve.
//
// Certified: each Bezier part c of the trim on [0, 1] is accepted when
// max |(S o c)''| / 8, the bound of linear interpolation's error, is at
// most `tolerance`, the second derivative bounded from control points
// alone (the hodographs of the part's homogeneous coordinates, and the
// first and second differences of the homogeneous nets of the surface's
// Bezier pieces that the part's control box meets, through the quotient
// rule for rational geometry; the derivation is in
// core/src/faces/trim_sampling.cc); any other part is halved. The bound
// is conservative (it uses the largest derivatives over the box), so
// there are more samples than a measured deviation would need.
//
// Fails with INVALID_ARGUMENT naming "tolerance" (not positive and finite,
// or not met after 40 halvings, where the surface's parametrization
// degenerates), "hole" (not -1 or a hole's index; -1 without an outer
// loop) or "curve" (not a curve of the loop), RESOURCE_EXHAUSTED naming
// "max_samples" when more samples would be needed, and with the token's
// CANCELLED / DEADLINE_EXCEEDED.
absl::StatusOr<TrimSamples> SampleTrimCurve(
    const TrimmedSurface& face, int hole, int curve, double tolerance,
    size_t max_samples = size_t{1} << 20,
    const CancellationToken* cancel = nullptr);

// FaceBoundingBox returns the tight axis-aligned box of the face's points
// S(u, v), (u, v) in the trimmed domain: for each side, branch and bound
// over the surface's Bezier parts (bounding_box.h's hull bounds), parts
// whose (u, v) rectangle lies outside the face dropped (its centre
// outside and not on the boundary as ClassifyPoints decides it with a
// tolerance of 0.51 times the rectangle's diagonal), the
// values at the trims' polyline vertices and at the corners of parts on the
// face as lower bounds, until the largest upper bound is within `tolerance`
// of the best lower bound (or after kMaxBoxHalvings halvings). Every side
// is widened by 2^-44 of the surface's largest control coordinate for
// rounding: the box holds every point of the face, and a side is within
// `tolerance` plus that margin of a point of the face when the search
// ends within its budget. Fails with INVALID_ARGUMENT "tolerance" (not
// positive and finite) and with the token's CANCELLED / DEADLINE_EXCEEDED.
absl::StatusOr<BoundingBox> FaceBoundingBox(
    const TrimmedSurface& face, double tolerance,
    const CancellationToken* cancel = nullptr);

}  // namespace freeform

#endif  // FREEFORM_CORE_TRIMMED_SURFACE_H_
