// Closest points (point inversion and projection) on curves and surfaces:
// for each query point, the parameters, points and distance of the global
// minimum of the distance to the geometry, certified by branch and bound.
//
// The geometry is cut into (rational) Bezier pieces (DecomposeCurve in
// curve.h, DecomposeSurface in surface.h), kept in homogeneous form. For
// one query q every piece carries a lower bound of its distance to q from
// the hull of its control points: the larger of the distance to their
// bounding box and min_i e . (q - P_i), e the unit vector from the control
// point nearest q to q (second order in the piece's size; a rational piece
// needs positive weights for the hull property, and one with a weight 0
// gets the bound 0 and is halved first).
// A polynomial curve part is bounded instead by the smallest Bernstein
// coefficient of |C(s) - q|^2 / 2, a polynomial of twice the degree.
// The piece nearest q by the bounding box of its control points is examined
// first; every other piece whose box or enclosing ball is farther than the
// best distance it sets is never looked at. The rest are taken in the order
// of their bounds (docs/references.md, 'Closest points by branch and
// bound'):
//   - the best distance found so far, `best`, starts from the pieces' end
//     points (curves) and corners (surfaces), which lie on the geometry;
//   - a piece whose bound exceeds best + tolerance cannot hold a minimum
//     that matters and is dropped, with every piece after it;
//   - otherwise projected Newton, clamped to the piece's parameter box, runs
//     from the better of its best corner and its control point nearest to q
//     (the active-set step handles minima on the box's edges and corners);
//   - on a polynomial curve part whose squared distance is strictly convex
//     (the second differences of its coefficients are positive) the
//     quadratic lower bound about Newton's point certifies the part at once:
//     it holds a single minimum, and its bound is within rounding of it;
//   - a piece whose bound is within `tolerance` of the best value found on
//     it, and which is such a convex part or whose control points span at
//     most L = 16 max(separation, tolerance, sqrt(tolerance * best)), is
//     resolved; any other is halved by de Casteljau (a surface in the
//     direction of its longer control polygon) and its halves go back.
//     The size limit keeps two minima within tolerance of the best in
//     different pieces unless they are closer than L (near the focal set
//     of the geometry, where the distance is nearly flat, such minima may
//     be reported as one); the pieces it adds are few, since the distance
//     rises by more than the tolerance within about L of a minimum.
// Finally every candidate within tolerance of the best is polished by
// Newton on its whole Bezier piece, and the minima within `tolerance` of
// the smallest distance are returned, closest first, those closer to each
// other than `separation` counted once: on a curve only when their
// parameters also agree to 1e-9 of the domain (a point reached at two
// parameters, such as a self-intersection or the seam of a closed curve,
// gives both), on a surface always (a collapsed edge such as a pole gives
// one minimum).
//
// Certified: no point of the geometry is closer to q than the returned
// lower bound, which is within `tolerance` of the returned distance for a
// complete answer (up to the rounding of the hull bounds and evaluators,
// about 1e-15 of the coordinates' scale). Each returned point is the
// geometry evaluated at its returned parameters, and the distance is the
// distance from q to the nearest of them, recomputed from those points (not
// the search's own approximation of the piece).
//
// Extreme scale and weights: the search runs on the geometry's copy
// rescaled by powers of two (coordinates and weights at most 1: exact), q
// scaled with it, and distances are norms with scaled squares, so
// geometry and queries of any size from 1e-300 to 1e300 give the same
// answers. A query farther than 2^500 (about 3e150) times the geometry's
// largest coordinate from the origin is at the same distance from every
// point of the geometry to rounding: it gets the geometry's point farthest
// along its direction, its exact distance, and complete = false. Where a
// rational piece's weights vary so steeply that the geometry moves more
// than the tolerance between adjacent double parameters (weights of 1e15
// and more next to 1), the point at the nearest double parameter may lie
// farther than the certified lower bound plus the tolerance: no parameter
// answers the query, and the call fails (INVALID_ARGUMENT "weights", or
// "tolerance" for polynomial geometry, saying by how much it misses). A
// further minimum that no double parameter reaches while the nearest one
// is answered (the second leg of such a corner) is left out, and the
// answer says complete = false: every returned minimum is within the
// tolerance of the returned distance at its returned parameters.
//
// When the minimum is attained along a whole curve or region (the centre
// of a circle or of a sphere patch, a point on the axis of a surface of
// revolution) the answer is a bounded set: up to max_minima minima at least
// `separation` apart, all at the minimum distance, with complete = false.
// A constant piece (all its control points equal, of any degree, degree 0
// included) is such a stretch: on a curve max_minima of its parameters,
// evenly spread, on a surface its one point, with complete = false. The
// same flag marks a query that used up max_pieces before every piece was
// resolved (then lower_bound may be below distance - tolerance).
//
// Triangular patches are searched through their degenerate tensor form and
// answer barycentric (u, v) (or Cartesian points of their domain triangle).
//
// Thread-safe; the pieces' bounds are prepared once per batch, queries run
// in chunks on the context's pool and allocate per chunk.
#ifndef FREEFORM_CORE_CLOSEST_POINT_H_
#define FREEFORM_CORE_CLOSEST_POINT_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "freeform/core/curve.h"
#include "freeform/core/points.h"
#include "freeform/core/surface.h"
#include "freeform/core/thread_pool.h"

namespace freeform {

// The most minima one query may return.
inline constexpr int kMaxMinimaPerQuery = 1024;

struct ClosestPointOptions {
  // Distances are certified to within `tolerance`, and every minimum whose
  // distance is within it of the smallest is returned. Positive, finite.
  double tolerance = 1e-9;
  // Minima whose points are closer than this count as one (on a curve
  // when their parameters agree too). >= 0, finite.
  double separation = 1e-7;
  // The most minima returned per query, in [1, kMaxMinimaPerQuery].
  int max_minima = 8;
  // The most pieces one query examines (>= 1): bounds the work.
  size_t max_pieces = 4096;
};

// The answer for a batch of queries. Query r owns max_minima slots:
// minimum k of query r has its parameters at
// parameters[(r * max_minima + k) * parameter_count ...] and its point at
// points[(r * max_minima + k) * dimension ...]; slots past counts[r] are 0.
struct ClosestPoints {
  int dimension = 0;
  // 1 for curves, 2 for surfaces ((u, v) as EvaluateSurface takes them).
  int parameter_count = 1;
  int max_minima = 0;
  std::vector<double> distances;     // per query: the minimum distance
  std::vector<double> lower_bounds;  // per query: certified lower bound
  // Per query: minima returned, >= 1 (0, with an infinite distance, only
  // when every distance overflows the double range).
  std::vector<int> counts;
  std::vector<uint8_t> complete;  // per query: 1 when all were returned
  std::vector<double> parameters;
  std::vector<double> points;
};

// ClosestPointsValues returns the number of doubles a ClosestPoints of
// `queries` queries holds (distances, lower bounds, parameters and points),
// so a caller can bound the answer before any work.
size_t ClosestPointsValues(size_t queries, int dimension, int parameter_count,
                           int max_minima);

// CurveClosestPoints answers every query point of `queries` on a valid
// curve. Fails with INVALID_ARGUMENT naming "queries.dimension" (not the
// curve's dimension), "queries.coordinates..." (ValidatePoints; at least
// one query; a query whose distance exceeds the largest double),
// "tolerance", "separation", "max_minima" or "max_pieces", "weights" or
// "tolerance" for a minimum no double parameter reaches (see above), and
// with the context's CANCELLED / DEADLINE_EXCEEDED.
absl::StatusOr<ClosestPoints> CurveClosestPoints(
    const Curve& curve, const PointsView& queries,
    const ClosestPointOptions& options = {},
    const ExecutionContext& context = {});

// SurfaceClosestPoints is CurveClosestPoints for a valid surface of any
// kind.
absl::StatusOr<ClosestPoints> SurfaceClosestPoints(
    const Surface& surface, const PointsView& queries,
    const ClosestPointOptions& options = {},
    const ExecutionContext& context = {});

}  // namespace freeform

#endif  // FREEFORM_CORE_CLOSEST_POINT_H_
