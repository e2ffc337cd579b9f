// The two exact predicates of planar triangulation (Shewchuk 1997,
// docs/references.md): a floating-point evaluation with Shewchuk's a-priori
// error bound decides whenever it can, and an exact evaluation with
// expansions (expansion.h) decides the rest. The sign of the result is
// always exact when every coordinate is 0 or has a magnitude in
// [kMinTriangulationMagnitude, kMaxTriangulationMagnitude]
// (constrained_delaunay.h): then all coordinates are multiples of 2^-232,
// every term of degree 4 is 0 or normal, and none overflows; the caller
// checks the range (InTriangulationRange). The magnitude of the result is
// only approximate. Pure functions, safe from any thread. Internal to the
// core.
#ifndef FREEFORM_CORE_SRC_TRIANGULATION_PREDICATES_H_
#define FREEFORM_CORE_SRC_TRIANGULATION_PREDICATES_H_

#include "freeform/core/constrained_delaunay.h"

namespace freeform::internal {

// InTriangulationRange returns whether `value` is 0 or a finite double of a
// magnitude in [kMinTriangulationMagnitude, kMaxTriangulationMagnitude].
bool InTriangulationRange(double value);

// Orient2d returns a positive value when a, b, c turn counter-clockwise,
// negative when clockwise, zero when collinear (twice the signed area of
// the triangle, approximately).
double Orient2d(Point2 a, Point2 b, Point2 c);

// InCircle returns a positive value when d lies inside the circle through
// a, b, c (which turn counter-clockwise), negative outside, zero on it.
double InCircle(Point2 a, Point2 b, Point2 c, Point2 d);

// The exact evaluations behind the two predicates, for the tests.
double Orient2dExact(Point2 a, Point2 b, Point2 c);
double InCircleExact(Point2 a, Point2 b, Point2 c, Point2 d);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_TRIANGULATION_PREDICATES_H_
