// Bounds on the number of points of a curve's polyline, from the control
// points alone (the derivation is in tessellation.h).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "freeform/core/tessellation.h"

namespace freeform {
namespace {

constexpr size_t kNoBound = SIZE_MAX;
// Matches the subdivision's depth limit (tessellation.cc).
constexpr int kMaxDepth = 50;

// PieceSegments returns the segments the flatness test leaves of one
// polynomial Bezier piece of `degree` whose second differences are at most
// `second_difference` long: 2^d for the first depth d with
// degree^2 second_difference 4^-d / 8 <= tolerance / 2.
double PieceSegments(int degree, double second_difference, double tolerance) {
  if (degree < 2 || second_difference == 0.0) return 1.0;
  const double deviation =
      static_cast<double>(degree) * degree * second_difference / 8.0;
  const double halvings =
      std::ceil(0.5 * std::log2(deviation / (tolerance / 2)));
  if (!(halvings > 0.0)) return 1.0;  // also catches NaN
  return std::ldexp(1.0,
                    static_cast<int>(std::min<double>(halvings, kMaxDepth)));
}

size_t ToBound(double points) {
  if (!(points < 0x1p63)) return kNoBound;
  return static_cast<size_t>(points);
}

double Norm(const double* a, int dimension) {
  double sum = 0.0;
  for (int j = 0; j < dimension; ++j) sum += a[j] * a[j];
  return std::sqrt(sum);
}

// Differences returns the control points of a B-spline's derivative
// (The NURBS Book, eq. 3.8) from those of `points` (count of `dimension`
// values) of degree `degree` over `knots` starting at `first_knot`: Q_i =
// degree (P_{i+1} - P_i) / (u_{i+degree+1} - u_{i+1}). A basis function of
// empty support gets 0.
std::vector<double> Differences(const std::vector<double>& points,
                                int dimension, int degree,
                                absl::Span<const double> knots,
                                size_t first_knot) {
  const size_t count = points.size() / dimension;
  std::vector<double> result((count - 1) * dimension, 0.0);
  for (size_t i = 0; i + 1 < count; ++i) {
    const double width =
        knots[first_knot + i + degree + 1] - knots[first_knot + i + 1];
    if (!(width > 0.0)) continue;
    for (int j = 0; j < dimension; ++j) {
      result[i * dimension + j] =
          degree *
          (points[(i + 1) * dimension + j] - points[i * dimension + j]) / width;
    }
  }
  return result;
}

}  // namespace

size_t BezierCurvePointBound(const BezierCurveView& curve, double tolerance) {
  if (curve.rational()) return kNoBound;
  const int n = curve.degree();
  const int d = curve.control_points.dimension;
  const double* points = curve.control_points.coordinates.data();
  double second = 0.0;
  std::vector<double> difference(d);
  for (int i = 0; i + 2 <= n; ++i) {
    for (int j = 0; j < d; ++j) {
      difference[j] = (points[i * d + j] + points[(i + 2) * d + j]) -
                      2 * points[(i + 1) * d + j];
    }
    second = std::max(second, Norm(difference.data(), d));
  }
  return ToBound(PieceSegments(n, second, tolerance) + 1.0);
}

size_t BSplineCurvePointBound(const BSplineCurveView& curve, double tolerance) {
  if (curve.rational()) return kNoBound;
  const int p = curve.degree;
  const int d = curve.control_points.dimension;
  const size_t count = curve.control_points.size();
  const absl::Span<const double> knots = curve.knots;
  // Second-derivative control points: Q2_i belongs to the basis function on
  // [u_{i+2}, u_{i+p+1}), so the span [u_s, u_{s+1}) sees i = s-p .. s-2.
  std::vector<double> second;
  if (p >= 2) {
    const std::vector<double> points(curve.control_points.coordinates.begin(),
                                     curve.control_points.coordinates.end());
    second =
        Differences(Differences(points, d, p, knots, 0), d, p - 1, knots, 1);
  }
  double segments = 0.0;
  for (size_t s = p; s < count; ++s) {
    const double width = knots[s + 1] - knots[s];
    if (!(width > 0.0)) continue;
    double largest = 0.0;
    for (size_t i = s - p; p >= 2 && i + 2 <= s; ++i) {
      largest = std::max(largest, Norm(&second[i * d], d));
    }
    const double piece_second =
        p >= 2 ? width * width * largest / (p * (p - 1.0)) : 0.0;
    segments += PieceSegments(p, piece_second, tolerance);
  }
  return ToBound(segments + 1.0);
}

}  // namespace freeform
