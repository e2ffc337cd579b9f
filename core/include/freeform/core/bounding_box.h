// Tight axis-aligned bounding boxes of curves and surfaces: the box of the
// geometry itself, not of its control points.
//
// The geometry is cut into (rational) Bezier pieces (DecomposeCurve,
// DecomposeSurface; a triangular patch stays one triangle) and each side of the
// box is found by branch and bound with the convex hull property
// (docs/references.md, 'Tight bounding boxes by subdivision'): for the largest
// value of coordinate j, every piece's largest control coordinate is an upper
// bound of the piece (a rational piece needs positive weights; one with a zero
// weight has no bound and is split first), and its end points (curves) or
// corners (patches) lie on the geometry, so they are lower bounds. The piece of
// largest upper bound is halved by de Casteljau until its upper bound is within
// `tolerance` of the best value found on the geometry: a tensor patch
// alternately in u and v (as SplitBezierSurface; a curve is a patch of one
// column), a triangular patch at the midpoint of the edge opposite its newest
// vertex (as BisectTriangularPatch). The pieces stay in homogeneous form in
// one flat array for the whole search, so a halving allocates nothing. Halving
// a piece divides the gap between its hull and the geometry by about four (two
// halvings for a triangle), so a smooth extreme needs about log4(size /
// tolerance) halvings.
//
// Accuracy contract: the box contains every point of the geometry (as far
// as double arithmetic can tell: each side is widened by the margin 2^-44
// of the control points' largest coordinate on its axis, about 6e-14 of it,
// which covers the rounding of the subdivision and of the evaluators; each
// axis is computed on the geometry's copy scaled by its own power of two, so
// that a huge coordinate on one axis costs no digits of another in the
// homogeneous points w P), and
// no side is
// farther than `tolerance` plus twice that margin from a point of the
// geometry. A tolerance below the margin is met as the margin: hull bounds
// cannot come closer than rounding, and chasing them would split without
// end. A piece is not halved more than kMaxBoxDepth times, which a
// tolerance of at least the margin never reaches on pieces of a sensible
// size.
//
// Work bound: the search for one side halves at most kMaxBoxHalvings
// pieces, and stops once the halvings have cost kMaxBoxHalvingWork (a
// halving is counted as the piece's control values times the points of its
// longest side): 16,384 halvings of a bicubic 3-D piece, a few hundred of a
// degree-20 piece in 64-D, one of a degree-64 one. A request's search thus
// costs at most 2 x dimension sides of that, whatever its degree. An isolated
// extreme needs about log4(size / tolerance) halvings, but an extreme attained
// along a curve (a ridge of the surface that the halvings cross) needs about
// sqrt(size / tolerance) pieces along it: 4 million for a tolerance at the
// margin. Past the budget the side is the best upper bound reached, still a
// bound of the geometry; on such a ridge it is within about 4 size /
// kMaxBoxHalvings^2 of it (1.5e-8 of the size; tests/core/bounding_box_test.cc,
// RidgeExtremeEndsWithinTheHalvingBudget). Pieces without a bound (a zero
// weight inside) are halved beyond that budget, up to four times it, since a
// halving or two usually bounds them; a side still unbounded then, or one
// with a corner at infinity, is infinite, and so are the sides not yet
// searched: the box is unbounded.
//
// Thread-safe; allocates per call.
#ifndef FREEFORM_CORE_BOUNDING_BOX_H_
#define FREEFORM_CORE_BOUNDING_BOX_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/curve.h"
#include "freeform/core/surface.h"

namespace freeform {

// The most halvings of one piece (in u and v together for a patch).
inline constexpr int kMaxBoxDepth = 120;

// The most halvings in the search for one side of a box (see the file
// comment).
inline constexpr int kMaxBoxHalvings = 1 << 14;

// The most work of the halvings in the search for one side: kMaxBoxHalvings
// halvings of a bicubic piece in 3-D (48 values, 4 points along the split).
inline constexpr size_t kMaxBoxHalvingWork = size_t{kMaxBoxHalvings} * 48 * 4;

// CurveBoundingBoxBytes and SurfaceBoundingBoxBytes return an upper bound,
// known before any work, of the memory CurveBoundingBox and
// SurfaceBoundingBox allocate at their peak for a valid geometry: its
// Bezier pieces while they are cut (at most three times their values) and
// then lifted, the pieces' records, and the halves and heap of the search
// (at most 2 kMaxBoxHalvings halves, fewer when halving a piece costs more
// work).
uint64_t CurveBoundingBoxBytes(const Curve& curve);
uint64_t SurfaceBoundingBoxBytes(const Surface& surface);

// An axis-aligned box: lower[j] <= x_j <= upper[j] for every point x.
struct BoundingBox {
  std::vector<double> lower;
  std::vector<double> upper;
};

// BoundingBoxValues returns the number of values of the box of geometry of
// `dimension`: lower and upper per coordinate.
constexpr size_t BoundingBoxValues(int dimension) {
  return 2 * static_cast<size_t>(dimension);
}

// CurveBoundingBox returns the box of `curve` over its domain (see the file
// comment). Fails with INVALID_ARGUMENT "tolerance" (not positive and
// finite) and with the token's CANCELLED / DEADLINE_EXCEEDED.
absl::StatusOr<BoundingBox> CurveBoundingBox(
    const Curve& curve, double tolerance,
    const CancellationToken* cancel = nullptr);

// SurfaceBoundingBox returns the box of `surface` over its domain (its
// triangle for a triangular patch). Fails like CurveBoundingBox.
absl::StatusOr<BoundingBox> SurfaceBoundingBox(
    const Surface& surface, double tolerance,
    const CancellationToken* cancel = nullptr);

}  // namespace freeform

#endif  // FREEFORM_CORE_BOUNDING_BOX_H_
