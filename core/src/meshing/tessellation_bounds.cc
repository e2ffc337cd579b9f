// Bounds on the number of points of a curve's polyline, from the control
// points alone (the derivation is in tessellation.h).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "absl/types/span.h"
#include "base/scaled.h"
#include "base/tessellation_checks.h"
#include "freeform/core/subdivision.h"
#include "freeform/core/tessellation.h"
#include "geometry/variant_dispatch.h"

namespace freeform {
namespace {

constexpr size_t kNoBound = SIZE_MAX;

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
  return std::ldexp(1.0, static_cast<int>(std::min<double>(
                             halvings, internal::kMaxSubdivisionDepth)));
}

size_t ToBound(double points) {
  if (!(points < 0x1p63)) return kNoBound;
  return static_cast<size_t>(points);
}

// Norm returns |a|, scaled so that squares of tiny values (homogeneous
// points of subnormal weights) do not underflow to 0 nor huge ones
// overflow.
double Norm(const double* a, int dimension) {
  return internal::ScaledNorm(a, dimension);
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

// MaxSecondDifference returns the longest second difference
// |V_i - 2 V_{i+1} + V_{i+2}| of `values`, points of `dimension` values.
double MaxSecondDifference(absl::Span<const double> values, int dimension) {
  const size_t count = values.size() / dimension;
  double largest = 0.0;
  std::vector<double> difference(dimension);
  for (size_t i = 0; i + 2 < count; ++i) {
    for (int j = 0; j < dimension; ++j) {
      difference[j] =
          (values[i * dimension + j] + values[(i + 2) * dimension + j]) -
          2 * values[(i + 1) * dimension + j];
    }
    largest = std::max(largest, Norm(difference.data(), dimension));
  }
  return largest;
}

// The control points of a rational curve, taken about the centre c of
// their bounding box: the spatial homogeneous parts w_i (P_i - c) and the
// distances |P_i - c| (tessellation.h: the projected deviation bound).
struct CenteredHomogeneous {
  std::vector<double> spatial;
  std::vector<double> radii;
};

CenteredHomogeneous AboutTheirCentre(const PointsView& points,
                                     absl::Span<const double> weights) {
  const int d = points.dimension;
  const size_t count = points.size();
  std::vector<double> centre(d);
  for (int j = 0; j < d; ++j) {
    double low = points.coordinates[j], high = low;
    for (size_t i = 1; i < count; ++i) {
      low = std::min(low, points.coordinates[i * d + j]);
      high = std::max(high, points.coordinates[i * d + j]);
    }
    centre[j] = 0.5 * low + 0.5 * high;
  }
  CenteredHomogeneous result{.spatial = std::vector<double>(count * d),
                             .radii = std::vector<double>(count)};
  std::vector<double> offset(d);
  for (size_t i = 0; i < count; ++i) {
    for (int j = 0; j < d; ++j) {
      offset[j] = points.coordinates[i * d + j] - centre[j];
      result.spatial[i * d + j] = weights[i] * offset[j];
    }
    result.radii[i] = Norm(offset.data(), d);
  }
  return result;
}

// RationalSecondDifference turns bounds on a homogeneous piece's second
// differences (spatial part, weight part) into the bound on its projected
// deviation: (spatial + radius * weight) / smallest_weight.
double RationalSecondDifference(double spatial, double weight, double radius,
                                double smallest_weight) {
  return (spatial + radius * weight) / smallest_weight;
}

double Smallest(absl::Span<const double> values) {
  return *std::min_element(values.begin(), values.end());
}

double Largest(absl::Span<const double> values) {
  return *std::max_element(values.begin(), values.end());
}

// KnotsOfUnitSpan returns `knots` divided by the power of two at or above
// their span, which is exact. The bound below does not change under a change
// of parameter's scale (each span's width^2 cancels the second derivative's
// 1 / width^2), but computed on knots 3e168 apart the derivative's control
// points (1 / width^2 ~ 1e-338) are subnormal and the bound falls short. The
// span is taken as twice its half, which stays finite for knots of opposite
// extreme signs.
std::vector<double> KnotsOfUnitSpan(absl::Span<const double> knots) {
  const int exponent =
      internal::ExponentAbove(0.5 * knots.back() - 0.5 * knots.front()) + 1;
  std::vector<double> scaled(knots.size());
  for (size_t i = 0; i < knots.size(); ++i) {
    scaled[i] = std::ldexp(knots[i], -exponent);
  }
  return scaled;
}

}  // namespace

size_t BezierCurvePointBound(const BezierCurveView& curve, double tolerance) {
  const int n = curve.degree();
  const int d = curve.control_points.dimension;
  const absl::Span<const double> points = curve.control_points.coordinates;
  if (!curve.rational()) {
    return ToBound(PieceSegments(n, MaxSecondDifference(points, d), tolerance) +
                   1.0);
  }
  // A weight of 0 leaves the first pieces without a hull: no bound.
  if (!(Smallest(curve.weights) > 0.0)) return kNoBound;
  const CenteredHomogeneous homogeneous =
      AboutTheirCentre(curve.control_points, curve.weights);
  const double second = RationalSecondDifference(
      MaxSecondDifference(homogeneous.spatial, d),
      MaxSecondDifference(curve.weights, 1), Largest(homogeneous.radii),
      Smallest(curve.weights));
  return ToBound(PieceSegments(n, second, tolerance) + 1.0);
}

size_t BSplineCurvePointBound(const BSplineCurveView& curve, double tolerance) {
  const int p = curve.degree;
  const int d = curve.control_points.dimension;
  const size_t count = curve.control_points.size();
  const std::vector<double> scaled_knots = KnotsOfUnitSpan(curve.knots);
  const absl::Span<const double> knots = scaled_knots;
  const absl::Span<const double> weights = curve.weights;
  const bool rational = curve.rational();
  if (rational && !(Smallest(weights) > 0.0)) return kNoBound;
  CenteredHomogeneous homogeneous;
  if (rational) {
    homogeneous = AboutTheirCentre(curve.control_points, weights);
  } else {
    homogeneous.spatial.assign(curve.control_points.coordinates.begin(),
                               curve.control_points.coordinates.end());
  }
  // Second-derivative control points: Q2_i belongs to the basis function on
  // [u_{i+2}, u_{i+p+1}), so the span [u_s, u_{s+1}) sees i = s-p .. s-2.
  std::vector<double> second, second_weights;
  if (p >= 2) {
    second = Differences(Differences(homogeneous.spatial, d, p, knots, 0), d,
                         p - 1, knots, 1);
    if (rational) {
      const std::vector<double> w(weights.begin(), weights.end());
      second_weights =
          Differences(Differences(w, 1, p, knots, 0), 1, p - 1, knots, 1);
    }
  }
  double segments = 0.0;
  for (size_t s = p; s < count; ++s) {
    const double width = knots[s + 1] - knots[s];
    if (!(width > 0.0)) continue;
    double largest = 0.0, largest_weight = 0.0;
    for (size_t i = s - p; p >= 2 && i + 2 <= s; ++i) {
      largest = std::max(largest, Norm(&second[i * d], d));
      if (rational) {
        largest_weight = std::max(largest_weight, std::abs(second_weights[i]));
      }
    }
    if (rational) {
      // The span's Bezier points lie in the hull of its p + 1 active ones.
      const size_t first = s - p, active = static_cast<size_t>(p) + 1;
      largest = RationalSecondDifference(
          largest, largest_weight,
          Largest(
              absl::MakeConstSpan(homogeneous.radii).subspan(first, active)),
          Smallest(weights.subspan(first, active)));
    }
    const double piece_second =
        p >= 2 ? width * width * largest / (p * (p - 1.0)) : 0.0;
    segments += PieceSegments(p, piece_second, tolerance);
  }
  return ToBound(segments + 1.0);
}

size_t CurvePointBound(const Curve& curve, double tolerance) {
  return std::visit(
      internal::Overloaded{
          [&](const BezierCurve& bezier) {
            return BezierCurvePointBound(bezier.view(), tolerance);
          },
          [&](const BSplineCurve& bspline) {
            return BSplineCurvePointBound(bspline.view(), tolerance);
          },
          [&](const auto&) {
            absl::StatusOr<BezierDecomposition> pieces = DecomposeCurve(curve);
            if (!pieces.ok()) return kNoBound;
            // Each piece's polyline starts where the previous one ends.
            size_t points = 1;
            for (const BezierCurveData& piece : pieces->segments) {
              const size_t bound =
                  BezierCurvePointBound(piece.view(), tolerance);
              if (bound == kNoBound || bound > kNoBound - points) {
                return kNoBound;
              }
              points += bound - 1;
            }
            return points;
          }},
      curve);
}

}  // namespace freeform
