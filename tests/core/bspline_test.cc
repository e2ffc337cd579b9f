#include "freeform/core/bspline.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "freeform/core/bezier.h"
#include "freeform/core/curve.h"
#include "freeform/core/status.h"
#include "freeform/core/surface.h"
#include "test_util.h"

namespace freeform {
namespace {

using ::freeform::testing_util::RandomValues;

using ::freeform::testing_util::RandomKnots;
using ::testing::DoubleNear;
using ::testing::HasSubstr;
using ::testing::Pointwise;

using Buffers = std::vector<std::vector<double>>;
// Reference values in long double, [order][index].
using Table = std::vector<std::vector<long double>>;

constexpr double kSqrt2 = std::numbers::sqrt2;

// `orders` output buffers of count * width doubles and the spans over them.
struct Output {
  Output(int orders, size_t count, size_t width)
      : buffers(static_cast<size_t>(orders),
                std::vector<double>(count * width)),
        spans(buffers.begin(), buffers.end()) {}
  Buffers buffers;
  std::vector<absl::Span<double>> spans;
};

BSplineCurveView Curve(int degree, const std::vector<double>& coordinates,
                       int dimension, const std::vector<double>& knots,
                       const std::vector<double>& weights = {}) {
  return BSplineCurveView{
      .degree = degree,
      .control_points = {.dimension = dimension, .coordinates = coordinates},
      .knots = knots,
      .weights = weights};
}

Buffers Evaluate(const BSplineCurveView& curve,
                 const std::vector<double>& params, int orders,
                 const ExecutionContext& context = {}) {
  Output out(orders, params.size(),
             static_cast<size_t>(curve.control_points.dimension));
  const absl::Status status =
      EvaluateBSplineCurve(curve, params, out.spans, context);
  EXPECT_TRUE(status.ok()) << status;
  return out.buffers;
}

Buffers EvaluateBasis(int degree, const std::vector<double>& knots,
                      const std::vector<double>& weights,
                      const std::vector<double>& params, int orders) {
  Output out(orders, params.size(), knots.size() - degree - 1);
  const absl::Status status =
      EvaluateBSplineBasis(degree, knots, weights, params, out.spans);
  EXPECT_TRUE(status.ok()) << status;
  return out.buffers;
}

std::vector<double> Uniform(int intervals, double start = 0.0,
                            double end = 1.0) {
  std::vector<double> params;
  for (int r = 0; r <= intervals; ++r) {
    params.push_back(start + (end - start) * r / intervals);
  }
  params.back() = end;
  return params;
}

std::vector<double> RandomWeights(std::mt19937_64& rng, size_t count) {
  std::uniform_real_distribution<double> uniform(0.25, 4.0);
  std::vector<double> weights(count);
  for (double& weight : weights) weight = uniform(rng);
  return weights;
}

// The ends of the domain, every knot inside it and random values.
std::vector<double> TestParameters(std::mt19937_64& rng, int p, int n,
                                   const std::vector<double>& knots) {
  const double start = knots[static_cast<size_t>(p)];
  const double end = knots[static_cast<size_t>(n + 1)];
  std::vector<double> params = {end, start};
  for (double knot : knots) {
    if (start < knot && knot < end) params.push_back(knot);
  }
  std::uniform_real_distribution<double> uniform(start, end);
  for (int r = 0; r < 20; ++r) params.push_back(uniform(rng));
  return params;
}

long double Ratio(long double numerator, long double denominator) {
  return denominator == 0 ? 0.0L : numerator / denominator;
}

// N^(k)_{i,p}(u) for k = 0..max_order and every i, straight from the
// Cox-de Boor definition (docs/references.md, 'Cox-de Boor recurrence'; 0/0
// read as 0) in long double, derivatives by
// N'_{i,q} = q N_{i,q-1} / (u_{i+q} - u_i) -
// q N_{i+1,q-1} / (u_{i+q+1} - u_{i+1}) applied k times. Degree 0 functions
// are the indicators of [u_i, u_{i+1}), except at the end u_{n+1} of the
// domain, where the last non-empty interval is closed on the right instead
// (the left-hand limit).
Table ReferenceBasis(int p, const std::vector<double>& knots, double u,
                     int max_order) {
  const int m = static_cast<int>(knots.size());
  const double end = knots[static_cast<size_t>(m - p - 1)];
  const long double x = u;
  const auto knot = [&](int i) -> long double {
    return knots[static_cast<size_t>(i)];
  };
  Table level(static_cast<size_t>(max_order) + 1,
              std::vector<long double>(static_cast<size_t>(m - 1), 0.0L));
  for (int i = 0; i + 1 < m; ++i) {
    const bool inside = u < end ? knot(i) <= x && x < knot(i + 1)
                                : knot(i) < x && x <= knot(i + 1);
    level[0][static_cast<size_t>(i)] = inside ? 1.0L : 0.0L;
  }
  for (int q = 1; q <= p; ++q) {
    Table next(level.size(),
               std::vector<long double>(static_cast<size_t>(m - 1 - q)));
    for (int i = 0; i < m - 1 - q; ++i) {
      const size_t s = static_cast<size_t>(i);
      const long double a = knot(i + q) - knot(i);
      const long double b = knot(i + q + 1) - knot(i + 1);
      next[0][s] = Ratio(x - knot(i), a) * level[0][s] +
                   Ratio(knot(i + q + 1) - x, b) * level[0][s + 1];
      for (size_t k = 1; k < level.size(); ++k) {
        next[k][s] =
            q * (Ratio(level[k - 1][s], a) - Ratio(level[k - 1][s + 1], b));
      }
    }
    level = std::move(next);
  }
  return level;
}

// sum_i c_i N^(k)_i P_i (c_i = w_i, or 1 without weights) for every order:
// [k][j] of a curve of `dimension`.
Table Combine(const Table& basis, const std::vector<double>& points,
              int dimension, const std::vector<double>& weights) {
  Table result(basis.size(),
               std::vector<long double>(static_cast<size_t>(dimension)));
  for (size_t k = 0; k < basis.size(); ++k) {
    for (size_t i = 0; i < basis[k].size(); ++i) {
      const long double c = weights.empty() ? 1.0L : weights[i];
      for (size_t j = 0; j < result[k].size(); ++j) {
        result[k][j] += c * basis[k][i] * points[i * result[k].size() + j];
      }
    }
  }
  return result;
}

// The derivatives of C = A / W from those of A and W, by Leibniz's rule on
// A = W C: C^(k) = (A^(k) - sum_{i=1..k} binom(k, i) W^(i) C^(k-i)) / W.
Table Quotient(const Table& numerator, const std::vector<long double>& weight) {
  Table result = numerator;
  for (size_t k = 0; k < result.size(); ++k) {
    long double binomial = 1;
    for (size_t i = 1; i <= k; ++i) {
      binomial = binomial * static_cast<long double>(k - i + 1) /
                 static_cast<long double>(i);
      for (size_t j = 0; j < result[k].size(); ++j) {
        result[k][j] -= binomial * weight[i] * result[k - i][j];
      }
    }
    for (long double& value : result[k]) value /= weight[0];
  }
  return result;
}

// The reference derivatives of a (rational) B-spline curve at u.
Table ReferenceCurve(const BSplineCurveView& curve,
                     const std::vector<double>& points,
                     const std::vector<double>& knots,
                     const std::vector<double>& weights, double u,
                     int max_order) {
  const Table basis = ReferenceBasis(curve.degree, knots, u, max_order);
  const int dimension = curve.control_points.dimension;
  const Table numerator = Combine(basis, points, dimension, weights);
  if (weights.empty()) return numerator;
  std::vector<long double> weight;
  for (const auto& order : Combine(basis, weights, 1, {})) {
    weight.push_back(order[0]);
  }
  return Quotient(numerator, weight);
}

long double MaxAbs(const std::vector<long double>& values) {
  long double largest = 0;
  for (long double value : values) largest = std::max(largest, std::abs(value));
  return largest;
}

// Expects every point of result[0] (2D) on the unit circle and, when there
// is a result[1], the tangent orthogonal to the radius: C . C' = 0.
void ExpectOnUnitCircle(const Buffers& result, double tangent_tolerance) {
  for (size_t r = 0; 2 * r < result[0].size(); ++r) {
    const double* c = &result[0][2 * r];
    EXPECT_NEAR(std::hypot(c[0], c[1]), 1.0, 1e-14) << r;
    if (result.size() < 2) continue;
    const double* d = &result[1][2 * r];
    EXPECT_NEAR(c[0] * d[0] + c[1] * d[1], 0.0, tangent_tolerance) << r;
  }
}

// On the knots 0,0,0,1,1,1 the B-splines of degree 2 are (1-u)^2, 2u(1-u),
// u^2, and on its sub-vectors 0,0,1,1 and 0,1 those of degree 1 and 0 are
// 1-u, u and 1 (docs/references.md,
// 'Worked example: the B-splines on the knots 0, 0, 0, 1, 1, 1').
TEST(BSplineTest, ExerciseOneBasisOnBezierKnots) {
  const std::vector<double> params = Uniform(16);
  const auto quadratic = EvaluateBasis(2, {0, 0, 0, 1, 1, 1}, {}, params, 3);
  const auto linear = EvaluateBasis(1, {0, 0, 1, 1}, {}, params, 2);
  const auto constant = EvaluateBasis(0, {0, 1}, {}, params, 2);
  for (size_t r = 0; r < params.size(); ++r) {
    const double u = params[r];
    const double* n2 = &quadratic[0][3 * r];
    EXPECT_NEAR(n2[0], (1 - u) * (1 - u), 1e-15);
    EXPECT_NEAR(n2[1], 2 * u * (1 - u), 1e-15);
    EXPECT_NEAR(n2[2], u * u, 1e-15);
    const double* d2 = &quadratic[1][3 * r];
    EXPECT_NEAR(d2[0], -2 * (1 - u), 1e-14);
    EXPECT_NEAR(d2[1], 2 - 4 * u, 1e-14);
    EXPECT_NEAR(d2[2], 2 * u, 1e-14);
    EXPECT_NEAR(quadratic[2][3 * r + 1], -4, 1e-14);
    EXPECT_NEAR(linear[0][2 * r], 1 - u, 1e-15);
    EXPECT_NEAR(linear[0][2 * r + 1], u, 1e-15);
    EXPECT_EQ(linear[1][2 * r], -1);
    EXPECT_EQ(linear[1][2 * r + 1], 1);
    EXPECT_EQ(constant[0][r], 1);
    EXPECT_EQ(constant[1][r], 0);
  }
}

// The rational quadratic (1,0), (1,1), (0,1) with weights 1, 1, 2 (shape
// factor w1^2 / (w0 w2) = 1/2, as for 1, sqrt(2)/2, 1) is a quarter of the
// unit circle.
TEST(BSplineTest, RationalQuarterCircle) {
  const std::vector<double> points = {1, 0, 1, 1, 0, 1};
  const std::vector<double> knots = {0, 0, 0, 1, 1, 1};
  const std::vector<double> weights = {1, 1, 2};
  const std::vector<double> params = Uniform(10'000);
  const auto result = Evaluate(Curve(2, points, 2, knots, weights), params, 2);
  ExpectOnUnitCircle(result, 1e-14);
  EXPECT_GE(*std::min_element(result[0].begin(), result[0].end()), 0.0);
}

// The circle as a NURBS with 9 points (docs/references.md,
// 'Worked example: the 9-point NURBS circle'). It stays on the unit circle,
// and C' is continuous at the double knots with
// C'(1/4) = 8 w1 (P2 - P1) = 4 sqrt(2) (-1, 0) from both sides.
TEST(BSplineTest, NinePointCircle) {
  const double h = kSqrt2 / 2;
  const std::vector<double> points = {1, 0,  1,  1, 0,  1, -1, 1, -1,
                                      0, -1, -1, 0, -1, 1, -1, 1, 0};
  const std::vector<double> knots = {0,   0,    0,    0.25, 0.25, 0.5,
                                     0.5, 0.75, 0.75, 1,    1,    1};
  const std::vector<double> weights = {1, h, 1, h, 1, h, 1, h, 1};
  const BSplineCurveView circle = Curve(2, points, 2, knots, weights);
  const std::vector<double> params = Uniform(10'000);
  ExpectOnUnitCircle(Evaluate(circle, params, 2), 1e-13);
  const double speed = 4 * kSqrt2;
  const auto knotted =
      Evaluate(circle, {0.25, 0.25 - 1e-9, 0.5, 0.75, 0.0, 1.0}, 2);
  const std::vector<double> expected = {-speed, 0, -speed, 0,     0, -speed,
                                        speed,  0, 0,      speed, 0, speed};
  EXPECT_THAT(knotted[1], Pointwise(DoubleNear(1e-6), expected));
  EXPECT_NEAR(knotted[1][0], -speed, 1e-13);
  EXPECT_NEAR(knotted[1][1], 0.0, 1e-13);
  EXPECT_NEAR(knotted[0][0], 0.0, 1e-15);  // C(1/4) = P2 = (0, 1)
  EXPECT_NEAR(knotted[0][1], 1.0, 1e-15);
}

// A zero interior weight is a point at infinity: the half circle (1,0,1),
// (0,1,0), (-1,0,1). Inserting the knot 1/2 gives the control points
// (1,0), (1,1), (-1,1), (-1,0) with weights 1, 1/2, 1/2, 1 (Q_0^w = P_0^w
// keeps the weight 1), the same curve with the same parametrization
// (docs/references.md,
// 'Worked example: the half circle with a point at infinity').
TEST(BSplineTest, ZeroInteriorWeightHalfCircleAndKnotInsertion) {
  const std::vector<double> points = {1, 0, 0, 1, -1, 0};
  const std::vector<double> knots = {0, 0, 0, 1, 1, 1};
  const std::vector<double> weights = {1, 0, 1};
  const std::vector<double> params = Uniform(10'000);
  const auto half = Evaluate(Curve(2, points, 2, knots, weights), params, 3);
  ExpectOnUnitCircle(half, 1e-13);
  for (size_t r = 0; r < params.size(); ++r) EXPECT_GE(half[0][2 * r + 1], 0.0);
  const std::vector<double> inserted_points = {1, 0, 1, 1, -1, 1, -1, 0};
  const std::vector<double> inserted_knots = {0, 0, 0, 0.5, 1, 1, 1};
  const std::vector<double> inserted_weights = {1, 0.5, 0.5, 1};
  const auto inserted =
      Evaluate(Curve(2, inserted_points, 2, inserted_knots, inserted_weights),
               params, 3);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_THAT(inserted[k], Pointwise(DoubleNear(1e-12), half[k])) << k;
  }
}

// FindSpan and FindSpanFrom (from any hint) return the s in [p, n] with
// u_s <= u < u_{s+1}, and at the end of the domain the last non-empty span.
TEST(BSplineTest, FindSpanMatchesDefinition) {
  std::mt19937_64 rng(17);
  for (int p = 1; p <= 6; ++p) {
    for (bool clamped : {true, false}) {
      const int n = p + static_cast<int>(rng() % 8);
      const std::vector<double> knots = RandomKnots(rng, p, n, clamped);
      const double end = knots[static_cast<size_t>(n + 1)];
      for (double u : TestParameters(rng, p, n, knots)) {
        int expected = -1;
        for (int s = p; s <= n; ++s) {
          const double a = knots[static_cast<size_t>(s)];
          const double b = knots[static_cast<size_t>(s + 1)];
          if (u < end ? a <= u && u < b : a < b) expected = s;
        }
        EXPECT_EQ(FindSpan(n, p, u, knots), expected) << u;
        for (int hint = p - 2; hint <= n + 2; ++hint) {
          EXPECT_EQ(FindSpanFrom(hint, n, p, u, knots), expected) << hint;
        }
      }
    }
  }
}

// The single-point helpers agree with the Cox-de Boor definition for
// degrees 0..20 on clamped and unclamped knots with repeated knots; values
// are nonnegative and sum to 1, derivatives sum to 0.
TEST(BSplineTest, BasisFunctionsMatchCoxDeBoorDefinition) {
  std::mt19937_64 rng(23);
  for (int p = 0; p <= 20; ++p) {
    for (bool clamped : {true, false}) {
      const int n = p + static_cast<int>(rng() % 9);
      const std::vector<double> knots = RandomKnots(rng, p, n, clamped);
      const int max_order = p + 2;
      const size_t width = static_cast<size_t>(p) + 1;
      std::vector<double> values(width);
      std::vector<double> scratch(BasisScratchSize(p));
      std::vector<double> ders((max_order + 1) * width);
      std::vector<double> ders_scratch(BasisDerivativesScratchSize(p));
      for (double u : TestParameters(rng, p, n, knots)) {
        const int span = FindSpan(n, p, u, knots);
        BasisFunctions(span, u, p, knots, absl::MakeSpan(values),
                       absl::MakeSpan(scratch));
        BasisFunctionDerivatives(span, u, p, max_order, knots,
                                 absl::MakeSpan(ders),
                                 absl::MakeSpan(ders_scratch));
        const Table reference = ReferenceBasis(p, knots, u, max_order);
        for (int k = 0; k <= max_order; ++k) {
          const auto& expected = reference[static_cast<size_t>(k)];
          const double tolerance = static_cast<double>(
              1e-13L * (k + 1) * std::max(1.0L, MaxAbs(expected)));
          double sum = 0;
          for (size_t j = 0; j < width; ++j) {
            const double value = ders[k * width + j];
            EXPECT_NEAR(value, static_cast<double>(expected[span - p + j]),
                        tolerance)
                << "p=" << p << " k=" << k << " u=" << u << " j=" << j;
            if (k == 0) {
              EXPECT_EQ(value, values[j]);
              EXPECT_GE(value, 0.0);
            }
            sum += value;
          }
          EXPECT_NEAR(sum, k == 0 ? 1.0 : 0.0, tolerance);
        }
      }
    }
  }
}

// The dense basis is zero outside the support: N_{i,p}(u) = 0 unless
// u_i <= u < u_{i+p+1} (u_i < u <= u_{i+p+1} at the end of the domain),
// and equals the definition everywhere.
TEST(BSplineTest, DenseBasisHasLocalSupport) {
  std::mt19937_64 rng(29);
  for (int p = 1; p <= 20; p += 3) {
    for (bool clamped : {true, false}) {
      const int n = p + 1 + static_cast<int>(rng() % 8);
      const std::vector<double> knots = RandomKnots(rng, p, n, clamped);
      const std::vector<double> params = TestParameters(rng, p, n, knots);
      const auto dense = EvaluateBasis(p, knots, {}, params, 2);
      const double end = knots[static_cast<size_t>(n + 1)];
      const size_t count = static_cast<size_t>(n) + 1;
      for (size_t r = 0; r < params.size(); ++r) {
        const double u = params[r];
        const Table reference = ReferenceBasis(p, knots, u, 1);
        for (size_t i = 0; i < count; ++i) {
          const double a = knots[i];
          const double b = knots[i + static_cast<size_t>(p) + 1];
          const bool support = u < end ? a <= u && u < b : a < u && u <= b;
          if (!support) {
            EXPECT_EQ(dense[0][r * count + i], 0.0);
            EXPECT_EQ(dense[1][r * count + i], 0.0);
          }
          EXPECT_NEAR(dense[0][r * count + i],
                      static_cast<double>(reference[0][i]), 1e-13);
          EXPECT_NEAR(dense[1][r * count + i],
                      static_cast<double>(reference[1][i]),
                      1e-12 * static_cast<double>(MaxAbs(reference[1])));
        }
      }
    }
  }
}

// N'_{i,p} agrees with the central difference (N(u+h) - N(u-h)) / 2h
// inside the spans, for degrees 1..20.
TEST(BSplineTest, BasisDerivativeMatchesCentralDifference) {
  std::mt19937_64 rng(31);
  for (int p = 1; p <= 20; ++p) {
    const int n = p + static_cast<int>(rng() % 6);
    const std::vector<double> knots = RandomKnots(rng, p, n, p % 2 == 0);
    std::vector<double> params;
    std::vector<double> below;
    std::vector<double> above;
    for (int s = p; s <= n; ++s) {
      const double a = knots[static_cast<size_t>(s)];
      const double b = knots[static_cast<size_t>(s + 1)];
      if (!(a < b)) continue;
      const double u = a + 0.37 * (b - a);
      const double h = 1e-5 * (b - a);
      params.push_back(u);
      below.push_back(u - h);
      above.push_back(u + h);
    }
    const auto at = EvaluateBasis(p, knots, {}, params, 2);
    const auto lo = EvaluateBasis(p, knots, {}, below, 1)[0];
    const auto hi = EvaluateBasis(p, knots, {}, above, 1)[0];
    const size_t count = static_cast<size_t>(n) + 1;
    for (size_t r = 0; r < params.size(); ++r) {
      const double h = above[r] - params[r];
      const double scale = std::abs(*std::max_element(
          at[1].begin() + r * count, at[1].begin() + (r + 1) * count,
          [](double x, double y) { return std::abs(x) < std::abs(y); }));
      for (size_t i = 0; i < count; ++i) {
        const double difference =
            (hi[r * count + i] - lo[r * count + i]) / (2 * h);
        EXPECT_NEAR(at[1][r * count + i], difference, 1e-6 * (1 + scale))
            << "p=" << p << " i=" << i;
      }
    }
  }
}

// Expects the derivatives 0..orders-1 of the curve at `params` to equal
// sum_i N^(k)_i P_i from the definition (for a NURBS, the quotient rule on
// the homogeneous sums), up to rounding relative to sum_i |N^(k)_i|.
void ExpectCurveMatchesReference(const BSplineCurveView& curve,
                                 const std::vector<double>& points,
                                 const std::vector<double>& knots,
                                 const std::vector<double>& weights,
                                 const std::vector<double>& params,
                                 int orders) {
  const auto result = Evaluate(curve, params, orders);
  const size_t dimension = static_cast<size_t>(curve.control_points.dimension);
  for (size_t r = 0; r < params.size(); ++r) {
    const Table expected =
        ReferenceCurve(curve, points, knots, weights, params[r], orders - 1);
    const Table basis =
        ReferenceBasis(curve.degree, knots, params[r], orders - 1);
    for (size_t k = 0; k < static_cast<size_t>(orders); ++k) {
      long double bound = 0;
      for (long double value : basis[k]) bound += std::abs(value);
      // 16^k: the quotient rule's growth with weights in [1/4, 4].
      const double tolerance = static_cast<double>(1e-12L * std::pow(16.0L, k) *
                                                   std::max(1.0L, bound));
      for (size_t j = 0; j < dimension; ++j) {
        EXPECT_NEAR(result[k][r * dimension + j],
                    static_cast<double>(expected[k][j]), tolerance)
            << "p=" << curve.degree << " k=" << k << " u=" << params[r]
            << " rational=" << curve.rational() << " orders=" << orders;
      }
    }
  }
}

// Curve derivatives of orders up to 1, 2 and p + 1 (each path of the
// evaluator) match the definition for degrees 1..20, clamped and unclamped
// knots, with and without weights.
TEST(BSplineTest, CurveDerivativesMatchReference) {
  std::mt19937_64 rng(37);
  for (int p = 1; p <= 20; ++p) {
    for (bool clamped : {true, false}) {
      for (bool rational : {false, true}) {
        const int n = p + static_cast<int>(rng() % 9);
        const int dimension = 1 + p % 4;
        const std::vector<double> knots = RandomKnots(rng, p, n, clamped);
        const std::vector<double> points =
            RandomValues(rng, static_cast<size_t>((n + 1) * dimension));
        const std::vector<double> weights =
            rational ? RandomWeights(rng, static_cast<size_t>(n) + 1)
                     : std::vector<double>();
        const BSplineCurveView curve =
            Curve(p, points, dimension, knots, weights);
        const std::vector<double> params = TestParameters(rng, p, n, knots);
        for (int orders : {1, 2, std::min(p + 2, 5)}) {
          ExpectCurveMatchesReference(curve, points, knots, weights, params,
                                      orders);
        }
      }
    }
  }
}

// On the knots 0^(n+1) 1^(n+1) the B-spline basis is the Bernstein basis:
// the curve is the Bezier curve with the same control points (and weights).
TEST(BSplineTest, ClampedSingleSpanIsTheBezierCurve) {
  std::mt19937_64 rng(41);
  const std::vector<double> params = {0.0, 0.1, 0.37, 0.5, 0.81, 1.0};
  for (int n = 1; n <= 20; ++n) {
    for (bool rational : {false, true}) {
      const std::vector<double> points =
          RandomValues(rng, static_cast<size_t>(n + 1) * 3);
      const std::vector<double> weights =
          rational ? RandomWeights(rng, static_cast<size_t>(n) + 1)
                   : std::vector<double>();
      std::vector<double> knots(static_cast<size_t>(n) + 1, 0.0);
      knots.insert(knots.end(), static_cast<size_t>(n) + 1, 1.0);
      const auto spline =
          Evaluate(Curve(n, points, 3, knots, weights), params, 4);
      Output bezier(4, params.size(), 3);
      ASSERT_TRUE(
          EvaluateBezierCurve(
              {.control_points = {.dimension = 3, .coordinates = points},
               .weights = weights},
              params, bezier.spans)
              .ok());
      for (size_t k = 0; k < 4; ++k) {
        const double tolerance =
            1e-12 * std::pow(2.0 * n * (rational ? 16 : 1), k);
        EXPECT_THAT(spline[k],
                    Pointwise(DoubleNear(tolerance), bezier.buffers[k]))
            << "n=" << n << " k=" << k << " rational=" << rational;
      }
    }
  }
}

// Equal weights cancel: the NURBS is the non-rational B-spline.
TEST(BSplineTest, EqualWeightsGiveTheNonRationalCurve) {
  std::mt19937_64 rng(43);
  for (int p = 1; p <= 9; p += 2) {
    const int n = p + 5;
    const std::vector<double> knots = RandomKnots(rng, p, n, false);
    const std::vector<double> points =
        RandomValues(rng, static_cast<size_t>(n + 1) * 3);
    const std::vector<double> weights(static_cast<size_t>(n) + 1, 2.5);
    const std::vector<double> params = TestParameters(rng, p, n, knots);
    const auto plain = Evaluate(Curve(p, points, 3, knots), params, 4);
    const auto rational =
        Evaluate(Curve(p, points, 3, knots, weights), params, 4);
    for (size_t k = 0; k < 4; ++k) {
      double scale = 1;
      for (double value : plain[k]) scale = std::max(scale, std::abs(value));
      EXPECT_THAT(rational[k], Pointwise(DoubleNear(1e-12 * scale), plain[k]))
          << "p=" << p << " k=" << k;
    }
  }
}

// At an interior knot a value is the right-hand limit, at the end of the
// domain the left-hand limit. The polyline 0 -> 1 -> 3 on knots 0,0,1,2,2
// has slope 1, then 2; the quadratic on 0,0,0,1,1,2,2,2 passes through P2
// at the double knot u = 1 with a corner: C'(1-) = 2 (P2 - P1),
// C'(1+) = 2 (P3 - P2).
TEST(BSplineTest, RightHandLimitsAtKnotsLeftHandAtTheEnd) {
  const std::vector<double> polyline = {0, 1, 3};
  const auto line = Evaluate(Curve(1, polyline, 1, {0, 0, 1, 2, 2}),
                             {0.0, 0.5, 1.0, 1.5, 2.0}, 3);
  EXPECT_THAT(line[0], Pointwise(DoubleNear(1e-15),
                                 std::vector<double>{0, 0.5, 1, 2, 3}));
  EXPECT_THAT(line[1],
              Pointwise(DoubleNear(1e-15), std::vector<double>{1, 1, 2, 2, 2}));
  EXPECT_THAT(line[2], Pointwise(DoubleNear(0), std::vector<double>(5, 0)));

  const std::vector<double> points = {0, 1, 3, 4, 8};
  const auto corner = Evaluate(Curve(2, points, 1, {0, 0, 0, 1, 1, 2, 2, 2}),
                               {1.0, 1.0 - 1e-12, 2.0}, 2);
  EXPECT_NEAR(corner[0][0], 3.0, 1e-15);
  EXPECT_NEAR(corner[1][0], 2 * (4 - 3), 1e-14);
  EXPECT_NEAR(corner[1][1], 2 * (3 - 1), 1e-9);
  EXPECT_NEAR(corner[0][2], 8.0, 1e-15);
  EXPECT_NEAR(corner[1][2], 2 * (8 - 4), 1e-14);
}

// On the unclamped uniform knots 0..6 a quadratic lives on [u_2, u_4] =
// [2, 4] and passes through the midpoints of its control polygon at the
// knots (docs/references.md,
// 'Quadratic B-spline curves touch their control polygon').
TEST(BSplineTest, UnclampedDomain) {
  const std::vector<double> points = {0, 0, 2, 4, 6, 2, 8, 8};
  const std::vector<double> knots = {0, 1, 2, 3, 4, 5, 6};
  const BSplineCurveView curve = Curve(2, points, 2, knots);
  const ParameterDomain domain = BSplineDomain(curve);
  EXPECT_EQ(domain.start, 2);
  EXPECT_EQ(domain.end, 4);
  const auto result = Evaluate(curve, {2, 3, 4}, 1);
  EXPECT_THAT(result[0], Pointwise(DoubleNear(1e-15),
                                   std::vector<double>{1, 2, 4, 3, 7, 5}));
  std::vector<double> out(2);
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(out)};
  const absl::Status status =
      EvaluateBSplineCurve(curve, std::vector<double>{1.5}, output);
  EXPECT_EQ(FieldPathOf(status).value_or(""), "parameters[0]") << status;
}

// The rational basis R_i = w_i N_i / W sums to 1 (derivatives to 0),
// matches the quotient rule on the definition, and sum_i R_i P_i is the
// NURBS curve.
TEST(BSplineTest, RationalBasis) {
  std::mt19937_64 rng(47);
  for (int p = 1; p <= 7; ++p) {
    const int n = p + 4;
    const std::vector<double> knots = RandomKnots(rng, p, n, p % 2 == 1);
    const std::vector<double> weights =
        RandomWeights(rng, static_cast<size_t>(n) + 1);
    const std::vector<double> points =
        RandomValues(rng, static_cast<size_t>(n + 1) * 2);
    const std::vector<double> params = TestParameters(rng, p, n, knots);
    const int orders = 3;
    const auto basis = EvaluateBasis(p, knots, weights, params, orders);
    const auto curve =
        Evaluate(Curve(p, points, 2, knots, weights), params, orders);
    const size_t count = static_cast<size_t>(n) + 1;
    for (size_t r = 0; r < params.size(); ++r) {
      const Table plain = ReferenceBasis(p, knots, params[r], orders - 1);
      Table numerator(plain.size(), std::vector<long double>(count));
      std::vector<long double> weight(plain.size());
      for (size_t k = 0; k < plain.size(); ++k) {
        for (size_t i = 0; i < count; ++i) {
          numerator[k][i] = weights[i] * plain[k][i];
          weight[k] += numerator[k][i];
        }
      }
      const Table expected = Quotient(numerator, weight);
      for (size_t k = 0; k < static_cast<size_t>(orders); ++k) {
        const double tolerance =
            1e-12 * std::max(1.0, static_cast<double>(MaxAbs(expected[k])));
        double sum = 0;
        double combined[2] = {0, 0};
        for (size_t i = 0; i < count; ++i) {
          const double value = basis[k][r * count + i];
          EXPECT_NEAR(value, static_cast<double>(expected[k][i]), tolerance);
          sum += value;
          combined[0] += value * points[2 * i];
          combined[1] += value * points[2 * i + 1];
        }
        EXPECT_NEAR(sum, k == 0 ? 1.0 : 0.0, tolerance);
        EXPECT_NEAR(curve[k][2 * r], combined[0], 4 * tolerance);
        EXPECT_NEAR(curve[k][2 * r + 1], combined[1], 4 * tolerance);
      }
    }
  }
}

TEST(BSplineTest, PoolResultsEqualSerialResults) {
  std::mt19937_64 rng(53);
  const int p = 3;
  const int n = 99;
  const std::vector<double> knots = RandomKnots(rng, p, n, true);
  const std::vector<double> points =
      RandomValues(rng, static_cast<size_t>(n + 1) * 3);
  const std::vector<double> weights =
      RandomWeights(rng, static_cast<size_t>(n) + 1);
  const std::vector<double> params = Uniform(100'002);
  ThreadPool pool(4);
  const ExecutionContext context{.pool = &pool, .grain = 1000};
  for (const auto& w : {std::vector<double>(), weights}) {
    const BSplineCurveView curve = Curve(p, points, 3, knots, w);
    EXPECT_EQ(Evaluate(curve, params, 3), Evaluate(curve, params, 3, context));
  }
}

TEST(BSplineTest, CancelledTokenStopsTheBatch) {
  const std::vector<double> points = {0, 0, 1, 1, 2, 0};
  const std::vector<double> knots = {0, 0, 0, 1, 1, 1};
  const std::vector<double> params(50'000, 0.5);
  CancellationToken token;
  token.Cancel();
  ThreadPool pool(2);
  const ExecutionContext context{
      .pool = &pool, .cancellation = &token, .grain = 100};
  Output curve_out(1, params.size(), 2);
  EXPECT_EQ(EvaluateBSplineCurve(Curve(2, points, 2, knots), params,
                                 curve_out.spans, context)
                .code(),
            absl::StatusCode::kCancelled);
  Output basis_out(1, params.size(), 3);
  EXPECT_EQ(EvaluateBSplineBasis(2, knots, {}, params, basis_out.spans, context)
                .code(),
            absl::StatusCode::kCancelled);
}

// The parameters of a large batch are checked chunk by chunk on the pool
// (core/src/base/checked_chunks.h); the error still names the first offender
// of the whole batch, however the chunks were claimed, for B-spline and
// Bezier curves alike.
TEST(BSplineTest, LargeBatchOnThePoolNamesTheFirstBadParameter) {
  const std::vector<double> points = {0, 0, 1, 1, 2, 0, 3, 1};
  const std::vector<double> knots = {0, 0, 0, 0, 1, 1, 1, 1};
  ThreadPool pool(2);
  const ExecutionContext context{.pool = &pool, .grain = 100};
  const double nan = std::nan("");
  struct Bad {
    std::vector<std::pair<size_t, double>> values;
    std::string field;
  };
  const std::vector<Bad> cases = {
      {{{77'777, 1.5}}, "parameters[77777]"},
      {{{90'000, -0.5}, {5, nan}}, "parameters[5]"},
      {{{99'999, HUGE_VAL}, {60'000, 2.0}}, "parameters[60000]"},
      {{{0, -HUGE_VAL}}, "parameters[0]"}};
  for (const Bad& bad : cases) {
    std::vector<double> params = Uniform(100'000);
    for (const auto& [index, value] : bad.values) params[index] = value;
    Output out(2, params.size(), 2);
    const absl::Status bspline = EvaluateBSplineCurve(
        Curve(3, points, 2, knots), params, out.spans, context);
    EXPECT_EQ(bspline.code(), absl::StatusCode::kInvalidArgument) << bspline;
    EXPECT_EQ(FieldPathOf(bspline).value_or(""), bad.field) << bspline;
    const BezierCurveView bezier{
        .control_points = {.dimension = 2, .coordinates = points}};
    const absl::Status ladder =
        EvaluateBezierCurve(bezier, params, out.spans, context);
    EXPECT_EQ(FieldPathOf(ladder).value_or(""), bad.field) << ladder;
  }
}

struct InvalidCase {
  int degree;
  std::vector<double> coordinates;  // 2D
  std::vector<double> knots;
  std::vector<double> weights;
  std::vector<double> params;
  std::string field;
  int dimension = 2;
};

TEST(BSplineTest, InvalidCurveNamesTheField) {
  const double nan = std::nan("");
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> three = {0, 0, 1, 1, 2, 0};
  const std::vector<double> four = {0, 0, 1, 1, 2, 0, 3, 1};
  const std::vector<double> six = {0, 0, 1, 1, 2, 0, 3, 1, 4, 0, 5, 1};
  const std::vector<double> bezier2 = {0, 0, 0, 1, 1, 1};
  const std::vector<InvalidCase> cases = {
      {-1, three, bezier2, {}, {0.5}, "degree"},
      {3,
       three,
       {0, 0, 0, 0, 1, 1, 1},
       {},
       {0.5},
       "control_points.coordinates"},
      {2, {0, 0, 1, 1, 2}, bezier2, {}, {0.5}, "control_points.coordinates"},
      {2,
       {0, nan, 1, 1, 2, 0},
       bezier2,
       {},
       {0.5},
       "control_points.coordinates[1]"},
      {2, three, bezier2, {}, {0.5}, "control_points.dimension", 0},
      {2, three, {0, 0, 0, 1, 1}, {}, {0.5}, "knots"},
      {2, three, {0, 0, 0, 1, 1, 1, 1}, {}, {0.5}, "knots"},
      {2, four, {0, 0, 0, 0.6, 0.5, 1, 1}, {}, {0.5}, "knots[4]"},
      {2, four, {0, 0, nan, 0.5, 1, 1, 1}, {}, {0.5}, "knots[2]"},
      {2, four, {0, 0, 0, 0.5, 1, 1, inf}, {}, {0.5}, "knots[6]"},
      // An interior knot of multiplicity p + 1 (a discontinuity).
      {2, six, {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1}, {}, {0.5}, "knots[5]"},
      {1, four, {0, 0, 0.5, 0.5, 1, 1}, {}, {0.5}, "knots[3]"},
      // An end knot of multiplicity p + 2.
      {1, three, {0, 0, 0, 1, 1}, {}, {0.5}, "knots[2]"},
      // The empty domain [u_1, u_2] = [1, 1].
      {1, {0, 0, 1, 1}, {0, 1, 1, 2}, {}, {1}, "knots"},
      {2, three, bezier2, {1, 1}, {0.5}, "weights"},
      {2, three, bezier2, {1, -1, 1}, {0.5}, "weights[1]"},
      {2, three, bezier2, {1, nan, 1}, {0.5}, "weights[1]"},
      {2, three, bezier2, {1, inf, 1}, {0.5}, "weights[1]"},
      // Zero weights whose basis functions are the only nonzero ones at a
      // span end: at u = 0, at u = 1, at the double knot 1 of a C^0 curve,
      // and on the whole span [1, 2) of a polyline.
      {2, three, bezier2, {0, 1, 1}, {0.5}, "weights[0]"},
      {2, three, bezier2, {1, 1, 0}, {0.5}, "weights[2]"},
      {2,
       {0, 0, 1, 1, 2, 0, 3, 1, 4, 0},
       {0, 0, 0, 1, 1, 2, 2, 2},
       {1, 1, 0, 1, 1},
       {0.5},
       "weights[2]"},
      {1, four, {0, 0, 1, 2, 3, 3}, {1, 0, 0, 1}, {0.5}, "weights[1]"},
      {2, three, bezier2, {}, {0.5, 1.5}, "parameters[1]"},
      {2, three, bezier2, {}, {-0.1}, "parameters[0]"},
      {2, three, bezier2, {}, {nan}, "parameters[0]"},
      // Unclamped: the domain is [u_2, u_4] = [2, 4].
      {2, four, {0, 1, 2, 3, 4, 5, 6}, {}, {3, 4.5}, "parameters[1]"},
  };
  for (const InvalidCase& c : cases) {
    Output out(1, c.params.size(), 2);
    const absl::Status status = EvaluateBSplineCurve(
        Curve(c.degree, c.coordinates, c.dimension, c.knots, c.weights),
        c.params, out.spans);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << c.field;
    EXPECT_EQ(FieldPathOf(status).value_or(""), c.field) << status;
  }
}

TEST(BSplineTest, InvalidBasisNamesTheField) {
  EXPECT_TRUE(ValidateBSplineBasis(2, std::vector<double>{0, 0, 0, 1, 1, 1},
                                   std::vector<double>{1, 0, 1})
                  .ok());
  const std::vector<InvalidCase> cases = {
      {-1, {}, {0, 1}, {}, {0.5}, "degree"},
      {2, {}, {0, 0, 0, 1, 1}, {}, {0.5}, "knots"},
      {1, {}, {0, 0, 1, 0.5, 1}, {}, {0.5}, "knots[3]"},
      {1, {}, {0, 0, 0.5, 0.5, 1, 1}, {}, {0.5}, "knots[3]"},
      {1, {}, {0, 0, 1, 1}, {1, 1, 1}, {0.5}, "weights"},
      {1, {}, {0, 0, 1, 1}, {1, -2}, {0.5}, "weights[1]"},
      {1, {}, {0, 0, 1, 1}, {1, 0}, {0.5}, "weights[1]"},
      {1, {}, {0, 0, 1, 1}, {}, {2}, "parameters[0]"},
  };
  for (const InvalidCase& c : cases) {
    Output out(1, c.params.size(), 1);  // validated last
    const absl::Status status =
        EvaluateBSplineBasis(c.degree, c.knots, c.weights, c.params, out.spans);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << c.field;
    EXPECT_EQ(FieldPathOf(status).value_or(""), c.field) << status;
  }
}

TEST(BSplineTest, WronglySizedOutputIsRejected) {
  const std::vector<double> points = {0, 0, 1, 1};
  const std::vector<double> knots = {0, 0, 1, 1};
  const std::vector<double> params = {0.5};
  std::vector<double> out(3);
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(out)};
  const absl::Status curve_status =
      EvaluateBSplineCurve(Curve(1, points, 2, knots), params, output);
  EXPECT_EQ(curve_status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(curve_status.message(), HasSubstr("output[0]"));
  const absl::Status basis_status =
      EvaluateBSplineBasis(1, knots, {}, params, output);
  EXPECT_EQ(basis_status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(basis_status.message(), HasSubstr("output[0]"));
  EXPECT_EQ(EvaluateBSplineCurve(Curve(1, points, 2, knots), params, {}).code(),
            absl::StatusCode::kInvalidArgument);
}

// A constant rational curve is its point whatever its weights: with
// coordinates of 2.5e-155 and an end weight of 1e-300 the homogeneous
// point w P (6e-456) underflows, and the end evaluated to the origin (a
// fuzz finding of issue 30). EvaluateCurve and EvaluateSurface evaluate
// such geometry on a copy rescaled by powers of two and scale back
// exactly: the points, and the derivatives (0 here; for the scaled line
// below, the slope).
TEST(BSplineTest, TinyCoordinatesWithTinyWeightsKeepTheirPoints) {
  const double c = 2.5e-155;
  const std::vector<double> points(2 * 11, c);
  std::vector<double> weights(11, 1.0);
  weights.back() = 1e-300;
  std::vector<double> knots(7, 0.0);
  for (double k : {0.2, 0.4, 0.6, 0.8}) knots.push_back(k);
  knots.insert(knots.end(), 7, 1.0);
  const ::freeform::Curve constant =
      *BSplineCurve::Create({.degree = 6,
                             .control_points = {2, points},
                             .knots = knots,
                             .weights = weights});
  const std::vector<double> at = {0.0, 0.5, 1.0};
  std::vector<double> values(6), slopes(6);
  const absl::Span<double> output[] = {absl::MakeSpan(values),
                                       absl::MakeSpan(slopes)};
  ASSERT_TRUE(EvaluateCurve(constant, at, output).ok());
  for (size_t i = 0; i < values.size(); ++i) {
    EXPECT_NEAR(values[i], c, 4e-16 * c) << i;
    EXPECT_NEAR(slopes[i], 0.0, 1e-12 * c) << i;
  }
  // A line from 0 to 1e-160 with weights 1 and 1e-290, on knots [0, 4]:
  // its end is 1e-160, and its speed there, by the quotient rule, is
  // (w0 / w1) (P1 - P0) / 4 = 2.5e129 ... scaled by exactly the same powers.
  const std::vector<double> line = {0.0, 1e-160};
  const std::vector<double> line_weights = {1.0, 1e-290};
  const std::vector<double> line_knots = {0, 0, 4, 4};
  const ::freeform::Curve segment =
      *BSplineCurve::Create({.degree = 1,
                             .control_points = {1, line},
                             .knots = line_knots,
                             .weights = line_weights});
  const std::vector<double> end = {4.0};
  std::vector<double> point(1), speed(1);
  const absl::Span<double> end_output[] = {absl::MakeSpan(point),
                                           absl::MakeSpan(speed)};
  ASSERT_TRUE(EvaluateCurve(segment, end, end_output).ok());
  EXPECT_NEAR(point[0], 1e-160, 4e-16 * 1e-160);
  EXPECT_NEAR(speed[0], 1e-160 / 4 / 1e-290, 1e-14 * (1e-160 / 4 / 1e-290));

  // A bilinear patch of corners c with one corner weight 1e-300.
  const std::vector<double> net(3 * 4, c);
  const std::vector<double> net_weights = {1, 1, 1, 1e-300};
  const Surface patch = *BezierSurface::Create(
      {.control_net = {3, 2, 2, net}, .weights = net_weights});
  const std::vector<double> uv = {1.0, 1.0, 0.5, 0.5};
  std::vector<double> corner(6);
  const absl::Span<double> surface_output[] = {absl::MakeSpan(corner)};
  ASSERT_TRUE(
      EvaluateSurface(patch, SurfaceSamples::Pairs(uv), surface_output, {})
          .ok());
  for (size_t i = 0; i < corner.size(); ++i) {
    EXPECT_NEAR(corner[i], c, 4e-16 * c) << i;
  }
}

// A rational curve and patch whose x reaches -2.5e304 at weight 1e103
// while y stays in [1e25, 1e25 + 1e10], next to a weight of 1e203 (a fuzz
// finding's ranges): w x overflows, so they are evaluated on the rescaled
// copy, where with one power of two for both axes y became 2e-280 and
// w y (weight 6e-101 there) underflowed: points at (0, 0). Scaled per
// axis, the ends are their control points and every y lies in the y range
// of the control points (a convex combination of them: positive weights).
TEST(BSplineTest, HugeAxisKeepsTheDigitsOfAnother) {
  const std::vector<double> points = {0, 1e25, -2.5e304, 1e25 + 1e10, 1, 1e25};
  const std::vector<double> weights = {1e103, 1e103, 1e203};
  const ::freeform::Curve curve =
      *BezierCurve::Create({.control_points = {2, points}, .weights = weights});
  const std::vector<double> at = {0.0, 0.25, 0.5, 1.0};
  std::vector<double> values(8);
  const absl::Span<double> output[] = {absl::MakeSpan(values)};
  ASSERT_TRUE(EvaluateCurve(curve, at, output).ok());
  EXPECT_EQ(values[0], 0.0);
  EXPECT_NEAR(values[1], 1e25, 4e-16 * 1e25);
  EXPECT_NEAR(values[6], 1.0, 4e-16);
  EXPECT_NEAR(values[7], 1e25, 4e-16 * 1e25);
  for (size_t r = 0; r < at.size(); ++r) {
    EXPECT_GE(values[2 * r + 1], 1e25 * (1 - 4e-16)) << r;
    EXPECT_LE(values[2 * r + 1], (1e25 + 1e10) * (1 + 4e-16)) << r;
  }
  const std::vector<double> net = {0, 1e25, -2.5e304, 1e25 + 1e10,
                                   1, 1e25, 2,        1e25};
  const std::vector<double> net_weights = {1e103, 1e103, 1e203, 1e103};
  const Surface patch = *BezierSurface::Create(
      {.control_net = {2, 2, 2, net}, .weights = net_weights});
  const std::vector<double> uv = {0.0, 0.0, 1.0, 1.0, 0.5, 0.5};
  std::vector<double> samples(6);
  const absl::Span<double> surface_output[] = {absl::MakeSpan(samples)};
  ASSERT_TRUE(
      EvaluateSurface(patch, SurfaceSamples::Pairs(uv), surface_output, {})
          .ok());
  // (x of the corner (1, 1), 2 at weight 1e103, is 2^-1010 of its axis's
  // largest and still underflows in the copy: only y is checked there.)
  EXPECT_EQ(samples[0], 0.0);
  EXPECT_NEAR(samples[1], 1e25, 4e-16 * 1e25);
  EXPECT_NEAR(samples[3], 1e25, 4e-16 * 1e25);
  EXPECT_GE(samples[5], 1e25 * (1 - 4e-16));
  EXPECT_LE(samples[5], (1e25 + 1e10) * (1 + 4e-16));
}

}  // namespace
}  // namespace freeform
