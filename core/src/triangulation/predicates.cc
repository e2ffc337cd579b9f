#include "triangulation/predicates.h"

#include <cmath>

#include "triangulation/expansion.h"

namespace freeform::internal {
namespace {

// Half an ulp of 1: the unit roundoff of double arithmetic.
constexpr double kEpsilon = 0x1p-53;
// Shewchuk's bounds on the error of the floating-point evaluation, relative
// to the permanent (the same sum with every term's magnitude).
constexpr double kOrientErrorBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;
constexpr double kInCircleErrorBound = (10.0 + 96.0 * kEpsilon) * kEpsilon;

// The exact sign as a double.
double SignOf(const Expansion& value) {
  return static_cast<double>(value.Sign());
}

// The 2 x 2 determinant a_x b_y - a_y b_x of exact coordinate differences.
Expansion Determinant(const Expansion& ax, const Expansion& ay,
                      const Expansion& bx, const Expansion& by) {
  return ax * by - ay * bx;
}

}  // namespace

bool InTriangulationRange(double value) {
  const double magnitude = std::abs(value);
  return value == 0.0 || (magnitude >= kMinTriangulationMagnitude &&
                          magnitude <= kMaxTriangulationMagnitude);
}

double Orient2dExact(Point2 a, Point2 b, Point2 c) {
  return SignOf(Determinant(
      Expansion::Difference(a.x, c.x), Expansion::Difference(a.y, c.y),
      Expansion::Difference(b.x, c.x), Expansion::Difference(b.y, c.y)));
}

double Orient2d(Point2 a, Point2 b, Point2 c) {
  const double left = (a.x - c.x) * (b.y - c.y);
  const double right = (a.y - c.y) * (b.x - c.x);
  const double determinant = left - right;
  // Terms of opposite signs (or a zero term): no cancellation, the sign of
  // the rounded difference is right.
  if ((left > 0.0 && right <= 0.0) || (left < 0.0 && right >= 0.0) ||
      left == 0.0) {
    return determinant;
  }
  const double bound = kOrientErrorBound * std::abs(left + right);
  if (std::abs(determinant) >= bound) return determinant;
  return Orient2dExact(a, b, c);
}

double InCircleExact(Point2 a, Point2 b, Point2 c, Point2 d) {
  const Expansion adx = Expansion::Difference(a.x, d.x);
  const Expansion ady = Expansion::Difference(a.y, d.y);
  const Expansion bdx = Expansion::Difference(b.x, d.x);
  const Expansion bdy = Expansion::Difference(b.y, d.y);
  const Expansion cdx = Expansion::Difference(c.x, d.x);
  const Expansion cdy = Expansion::Difference(c.y, d.y);
  const Expansion a_lift = adx * adx + ady * ady;
  const Expansion b_lift = bdx * bdx + bdy * bdy;
  const Expansion c_lift = cdx * cdx + cdy * cdy;
  return SignOf(a_lift * Determinant(bdx, bdy, cdx, cdy) +
                b_lift * Determinant(cdx, cdy, adx, ady) +
                c_lift * Determinant(adx, ady, bdx, bdy));
}

double InCircle(Point2 a, Point2 b, Point2 c, Point2 d) {
  const double adx = a.x - d.x, ady = a.y - d.y;
  const double bdx = b.x - d.x, bdy = b.y - d.y;
  const double cdx = c.x - d.x, cdy = c.y - d.y;
  const double bdx_cdy = bdx * cdy, cdx_bdy = cdx * bdy;
  const double cdx_ady = cdx * ady, adx_cdy = adx * cdy;
  const double adx_bdy = adx * bdy, bdx_ady = bdx * ady;
  const double a_lift = adx * adx + ady * ady;
  const double b_lift = bdx * bdx + bdy * bdy;
  const double c_lift = cdx * cdx + cdy * cdy;
  const double determinant = a_lift * (bdx_cdy - cdx_bdy) +
                             b_lift * (cdx_ady - adx_cdy) +
                             c_lift * (adx_bdy - bdx_ady);
  const double permanent = (std::abs(bdx_cdy) + std::abs(cdx_bdy)) * a_lift +
                           (std::abs(cdx_ady) + std::abs(adx_cdy)) * b_lift +
                           (std::abs(adx_bdy) + std::abs(bdx_ady)) * c_lift;
  const double bound = kInCircleErrorBound * permanent;
  if (std::abs(determinant) > bound) return determinant;
  return InCircleExact(a, b, c, d);
}

}  // namespace freeform::internal
