#include "freeform/core/bezier.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <condition_variable>
#include <mutex>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <thread>
#include <vector>

#include "freeform/core/bspline.h"
#include "freeform/core/status.h"
#include "test_util.h"

namespace freeform {
namespace {

using ::freeform::testing_util::RandomValues;

using ::testing::DoubleNear;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Pointwise;

// Evaluates with `orders` derivative buffers and returns them.
std::vector<std::vector<double>> Evaluate(
    const BezierCurveView& curve, const std::vector<double>& params, int orders,
    const ExecutionContext& context = {},
    BezierAlgorithm algorithm = BezierAlgorithm::kAuto) {
  std::vector<std::vector<double>> buffers(
      static_cast<size_t>(orders),
      std::vector<double>(params.size() *
                          static_cast<size_t>(curve.control_points.dimension)));
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  const absl::Status status =
      EvaluateBezierCurve(curve, params, output, context, algorithm);
  EXPECT_TRUE(status.ok()) << status;
  return buffers;
}

BezierCurveView View(const std::vector<double>& coordinates, int dimension,
                     const std::vector<double>& weights = {}) {
  return BezierCurveView{
      .control_points = {.dimension = dimension, .coordinates = coordinates},
      .weights = weights};
}

long double Binomial(int n, int k) {
  long double result = 1;
  for (int i = 1; i <= k; ++i) result = result * (n - k + i) / i;
  return result;
}

// Reference: the k-th derivative as the Bernstein sum of the k-th forward
// differences, n!/(n-k)! sum_i (Delta^k P)_i B(n-k, i, t), in long double
// with explicit binomials and powers (independent of de Casteljau).
std::vector<long double> ReferenceDerivative(const std::vector<double>& points,
                                             int dimension, int k, double t) {
  const int n = static_cast<int>(points.size()) / dimension - 1;
  std::vector<long double> result(static_cast<size_t>(dimension), 0.0L);
  if (k > n) return result;
  long double factor = 1;
  for (int q = 0; q < k; ++q) factor *= n - q;
  for (int i = 0; i <= n - k; ++i) {
    const long double basis = Binomial(n - k, i) *
                              std::pow(1.0L - t, n - k - i) *
                              std::pow(static_cast<long double>(t), i);
    for (int j = 0; j < dimension; ++j) {
      long double difference = 0;  // (Delta^k P)_i
      for (int r = 0; r <= k; ++r) {
        const long double sign = ((k - r) % 2 == 0) ? 1.0L : -1.0L;
        difference += sign * Binomial(k, r) *
                      points[static_cast<size_t>((i + r) * dimension + j)];
      }
      result[static_cast<size_t>(j)] += factor * difference * basis;
    }
  }
  return result;
}

// The cubic with control points (0,0), (1,2), (3,2), (4,0); see
// 'Worked example: the cubic Bezier curve (0,0), (1,2), (3,2), (4,0)' in
// docs/references.md.
TEST(BezierTest, CubicWorkedExample) {
  const std::vector<double> points = {0, 0, 1, 2, 3, 2, 4, 0};
  const auto result = Evaluate(View(points, 2), {0.0, 0.5, 1.0}, 3);
  EXPECT_THAT(result[0], ElementsAre(0, 0, 2, 1.5, 4, 0));
  // C'(0) = 3 (P1 - P0) = (3, 6); C'(1) = 3 (P3 - P2) = (3, -6);
  // C'(1/2) = 3 (P1 - P0 + 2 (P2 - P1) + P3 - P2) / 4 = (4.5, 0).
  EXPECT_THAT(result[1], ElementsAre(3, 6, 4.5, 0, 3, -6));
  // C''(t) = 6 ((1-t)(P2 - 2 P1 + P0) + t (P3 - 2 P2 + P1)).
  EXPECT_THAT(result[2], ElementsAre(6, -12, 0, -12, -6, -12));
}

TEST(BezierTest, LinearAndConstantCurves) {
  const std::vector<double> line = {1, 5};  // 1D: from 1 to 5
  const auto result = Evaluate(View(line, 1), {0.25}, 3);
  EXPECT_DOUBLE_EQ(result[0][0], 2.0);
  EXPECT_DOUBLE_EQ(result[1][0], 4.0);
  EXPECT_EQ(result[2][0], 0.0);
  const std::vector<double> point = {7, 8, 9};
  const auto constant = Evaluate(View(point, 3), {0.3}, 2);
  EXPECT_THAT(constant[0], ElementsAre(7, 8, 9));
  EXPECT_THAT(constant[1], ElementsAre(0, 0, 0));
}

constexpr BezierAlgorithm kAlgorithms[] = {BezierAlgorithm::kDeCasteljau,
                                           BezierAlgorithm::kHorner,
                                           BezierAlgorithm::kLadder};

// Derivatives by every scheme agree with the forward-difference Bernstein
// sum (the rule Q_i = n (P_{i+1} - P_i) applied k times) for degrees 1..20
// and dimensions 1..16.
TEST(BezierTest, DerivativesMatchHodographReference) {
  std::mt19937_64 rng(42);
  for (int n = 1; n <= 20; ++n) {
    const int dimension = 1 + (n * 5) % 16;
    const std::vector<double> points =
        RandomValues(rng, static_cast<size_t>((n + 1) * dimension));
    const std::vector<double> params = {0.0, 0.1, 0.37, 0.5, 0.81, 1.0};
    const int orders = std::min(n + 2, 6);
    for (BezierAlgorithm algorithm : kAlgorithms) {
      const auto result =
          Evaluate(View(points, dimension), params, orders, {}, algorithm);
      for (int k = 0; k < orders; ++k) {
        const double scale = std::pow(2.0 * n, k);  // derivative magnitude
        for (size_t r = 0; r < params.size(); ++r) {
          const auto expected =
              ReferenceDerivative(points, dimension, k, params[r]);
          for (int j = 0; j < dimension; ++j) {
            EXPECT_NEAR(result[static_cast<size_t>(k)][r * dimension + j],
                        static_cast<double>(expected[static_cast<size_t>(j)]),
                        1e-13 * scale)
                << "n=" << n << " k=" << k << " t=" << params[r]
                << " algorithm=" << static_cast<int>(algorithm);
          }
        }
      }
    }
  }
}

// The three schemes agree on rational curves too (homogeneous evaluation).
TEST(BezierTest, SchemesAgreeOnRationalCurves) {
  std::mt19937_64 rng(17);
  for (int n = 1; n <= 15; ++n) {
    const std::vector<double> points =
        RandomValues(rng, static_cast<size_t>((n + 1) * 2));
    std::vector<double> weights = RandomValues(rng, static_cast<size_t>(n + 1));
    for (double& weight : weights) weight = 1.5 + weight;  // in [0.5, 2.5]
    const std::vector<double> params = {0.0, 0.2, 0.5, 0.77, 1.0};
    const auto reference = Evaluate(View(points, 2, weights), params, 3, {},
                                    BezierAlgorithm::kDeCasteljau);
    for (BezierAlgorithm algorithm : kAlgorithms) {
      const auto result =
          Evaluate(View(points, 2, weights), params, 3, {}, algorithm);
      for (int k = 0; k < 3; ++k) {
        EXPECT_THAT(
            result[k],
            Pointwise(DoubleNear(1e-12 * std::pow(4.0 * n, k)), reference[k]))
            << "n=" << n << " k=" << k;
      }
    }
  }
}

TEST(BezierTest, AutoPicksTheLadderUpToTheMeasuredDegree) {
  EXPECT_EQ(ResolveBezierAlgorithm(BezierAlgorithm::kAuto, 3),
            BezierAlgorithm::kLadder);
  EXPECT_EQ(
      ResolveBezierAlgorithm(BezierAlgorithm::kAuto, kLinearMaxAutoDegree),
      BezierAlgorithm::kLadder);
  EXPECT_EQ(
      ResolveBezierAlgorithm(BezierAlgorithm::kAuto, kLinearMaxAutoDegree + 1),
      BezierAlgorithm::kDeCasteljau);
  EXPECT_EQ(ResolveBezierAlgorithm(BezierAlgorithm::kLadder, 3),
            BezierAlgorithm::kLadder);
}

TEST(BezierTest, EndpointInterpolationAndSymmetry) {
  std::mt19937_64 rng(7);
  for (int n = 1; n <= 20; ++n) {
    const int dimension = 3;
    std::vector<double> points =
        RandomValues(rng, static_cast<size_t>((n + 1) * dimension));
    const auto ends = Evaluate(View(points, dimension), {0.0, 1.0}, 1);
    for (int j = 0; j < dimension; ++j) {
      EXPECT_EQ(ends[0][j], points[j]);
      EXPECT_EQ(ends[0][dimension + j], points[n * dimension + j]);
    }
    // Reversing the control points reverses the parameter.
    std::vector<double> reversed(points.size());
    for (int i = 0; i <= n; ++i) {
      std::copy_n(points.begin() + (n - i) * dimension, dimension,
                  reversed.begin() + i * dimension);
    }
    const std::vector<double> params = {0.1, 0.25, 0.6, 0.9};
    std::vector<double> mirrored;
    for (double t : params) mirrored.push_back(1.0 - t);
    const auto forward = Evaluate(View(points, dimension), params, 1);
    const auto backward = Evaluate(View(reversed, dimension), mirrored, 1);
    EXPECT_THAT(forward[0], Pointwise(DoubleNear(1e-14), backward[0]));
  }
}

TEST(BezierTest, BernsteinBasisPartitionOfUnityAndSymmetry) {
  for (int n = 0; n <= 30; ++n) {
    std::vector<double> values(static_cast<size_t>(n + 1));
    std::vector<double> mirrored(static_cast<size_t>(n + 1));
    for (double t : {0.0, 0.13, 0.5, 0.77, 1.0}) {
      BernsteinBasis(n, t, absl::MakeSpan(values));
      BernsteinBasis(n, 1.0 - t, absl::MakeSpan(mirrored));
      double sum = 0;
      for (int i = 0; i <= n; ++i) {
        sum += values[static_cast<size_t>(i)];
        EXPECT_GE(values[static_cast<size_t>(i)], 0.0);
        EXPECT_NEAR(values[static_cast<size_t>(i)],
                    mirrored[static_cast<size_t>(n - i)], 1e-15);
        const long double explicit_value = Binomial(n, i) *
                                           std::pow(1.0L - t, n - i) *
                                           std::pow((long double)t, i);
        EXPECT_NEAR(values[static_cast<size_t>(i)],
                    static_cast<double>(explicit_value), 1e-15);
      }
      EXPECT_NEAR(sum, 1.0, 1e-14);
    }
  }
}

// The basis sum sum_i B(n,i,t) P_i and de Casteljau agree.
TEST(BezierTest, DeCasteljauAgreesWithBasisSum) {
  std::mt19937_64 rng(11);
  const int n = 12;
  const int dimension = 2;
  const std::vector<double> points =
      RandomValues(rng, static_cast<size_t>((n + 1) * dimension));
  std::vector<double> params;
  for (int r = 0; r <= 100; ++r) params.push_back(r / 100.0);
  const auto result = Evaluate(View(points, dimension), params, 1);
  std::vector<double> basis(n + 1);
  for (size_t r = 0; r < params.size(); ++r) {
    BernsteinBasis(n, params[r], absl::MakeSpan(basis));
    for (int j = 0; j < dimension; ++j) {
      double sum = 0;
      for (int i = 0; i <= n; ++i) sum += basis[i] * points[i * dimension + j];
      EXPECT_NEAR(result[0][r * dimension + j], sum, 1e-14);
    }
  }
}

// Affine invariance: mapping the control points maps the curve.
TEST(BezierTest, AffineInvariance) {
  std::mt19937_64 rng(5);
  const std::vector<double> points = RandomValues(rng, 8 * 2);
  std::vector<double> mapped(points.size());
  for (size_t i = 0; i < points.size(); i += 2) {
    mapped[i] = 2 * points[i] - 3 * points[i + 1] + 1;
    mapped[i + 1] = 0.5 * points[i] + points[i + 1] - 4;
  }
  const std::vector<double> params = {0.0, 0.2, 0.45, 0.7, 1.0};
  const auto original = Evaluate(View(points, 2), params, 1)[0];
  const auto image = Evaluate(View(mapped, 2), params, 1)[0];
  for (size_t i = 0; i < original.size(); i += 2) {
    EXPECT_NEAR(image[i], 2 * original[i] - 3 * original[i + 1] + 1, 1e-14);
    EXPECT_NEAR(image[i + 1], 0.5 * original[i] + original[i + 1] - 4, 1e-14);
  }
}

// A rational quadratic with weights (1, sqrt(2)/2, 1) is a quarter of the
// unit circle: points on the circle, C . C' = 0 and C' . C' + C . C'' = 0.
TEST(BezierTest, RationalQuarterCircle) {
  const std::vector<double> points = {1, 0, 1, 1, 0, 1};
  const std::vector<double> weights = {1, std::numbers::sqrt2 / 2, 1};
  std::vector<double> params;
  for (int r = 0; r <= 1000; ++r) params.push_back(r / 1000.0);
  const auto result = Evaluate(View(points, 2, weights), params, 3);
  for (size_t r = 0; r < params.size(); ++r) {
    const double* c = &result[0][2 * r];
    const double* d1 = &result[1][2 * r];
    const double* d2 = &result[2][2 * r];
    EXPECT_NEAR(std::hypot(c[0], c[1]), 1.0, 1e-15);
    EXPECT_NEAR(c[0] * d1[0] + c[1] * d1[1], 0.0, 1e-14);
    EXPECT_NEAR(d1[0] * d1[0] + d1[1] * d1[1] + c[0] * d2[0] + c[1] * d2[1],
                0.0, 1e-13);
  }
  // C'(0) = (w1 / w0) * 2 (P1 - P0) = sqrt(2) * (0, 1).
  EXPECT_NEAR(result[1][0], 0.0, 1e-15);
  EXPECT_NEAR(result[1][1], std::numbers::sqrt2, 1e-15);
}

// With all weights equal a rational curve is the polynomial one.
TEST(BezierTest, EqualWeightsGiveThePolynomialCurve) {
  std::mt19937_64 rng(3);
  const std::vector<double> points = RandomValues(rng, 6 * 3);
  const std::vector<double> weights(6, 2.5);
  const std::vector<double> params = {0.0, 0.3, 0.5, 0.99};
  const auto polynomial = Evaluate(View(points, 3), params, 4);
  const auto rational = Evaluate(View(points, 3, weights), params, 4);
  for (int k = 0; k < 4; ++k) {
    EXPECT_THAT(rational[k], Pointwise(DoubleNear(1e-11), polynomial[k]));
  }
}

TEST(BezierTest, PoolResultsEqualSerialResults) {
  std::mt19937_64 rng(9);
  const std::vector<double> points = RandomValues(rng, 10 * 4);
  std::vector<double> params(100'003);
  for (size_t r = 0; r < params.size(); ++r) {
    params[r] = static_cast<double>(r) / static_cast<double>(params.size() - 1);
  }
  ThreadPool pool(4);
  const auto serial = Evaluate(View(points, 4), params, 3);
  const auto parallel =
      Evaluate(View(points, 4), params, 3,
               ExecutionContext{.pool = &pool, .grain = 1000});
  EXPECT_EQ(serial, parallel);
}

TEST(BezierTest, CancelledTokenStopsTheBatch) {
  const std::vector<double> points = {0, 0, 1, 1, 2, 0};
  std::vector<double> params(50'000, 0.5);
  std::vector<double> out(params.size() * 2);
  std::vector<absl::Span<double>> output = {absl::MakeSpan(out)};
  CancellationToken token;
  token.Cancel();
  ThreadPool pool(2);
  const absl::Status status = EvaluateBezierCurve(
      View(points, 2), params, output,
      ExecutionContext{.pool = &pool, .cancellation = &token, .grain = 100});
  EXPECT_EQ(status.code(), absl::StatusCode::kCancelled);
}

struct InvalidCase {
  std::vector<double> coordinates;
  int dimension;
  std::vector<double> weights;
  std::vector<double> params;
  std::string field;
};

TEST(BezierTest, InvalidInputNamesTheField) {
  const double nan = std::nan("");
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<InvalidCase> cases = {
      {{0, 0, 1}, 2, {}, {0.5}, "control_points.coordinates"},
      {{}, 2, {}, {0.5}, "control_points.coordinates"},
      {{0, nan, 1, 1}, 2, {}, {0.5}, "control_points.coordinates[1]"},
      {{0, 0, 1, inf}, 2, {}, {0.5}, "control_points.coordinates[3]"},
      {{0, 0}, 0, {}, {0.5}, "control_points.dimension"},
      {{0, 0, 1, 1}, 2, {1}, {0.5}, "weights"},
      {{0, 0, 1, 1, 2, 2}, 2, {1, -1, 1}, {0.5}, "weights[1]"},
      {{0, 0, 1, 1, 2, 2}, 2, {1, nan, 1}, {0.5}, "weights[1]"},
      {{0, 0, 1, 1, 2, 2}, 2, {0, 1, 1}, {0.5}, "weights[0]"},
      {{0, 0, 1, 1, 2, 2}, 2, {1, 1, 0}, {0.5}, "weights[2]"},
      {{0, 0, 1, 1}, 2, {}, {0.5, 1.5}, "parameters[1]"},
      {{0, 0, 1, 1}, 2, {}, {nan}, "parameters[0]"},
  };
  for (const InvalidCase& c : cases) {
    std::vector<double> out(c.params.size() * std::max(c.dimension, 1));
    std::vector<absl::Span<double>> output = {absl::MakeSpan(out)};
    const absl::Status status = EvaluateBezierCurve(
        View(c.coordinates, c.dimension, c.weights), c.params, output);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << c.field;
    EXPECT_EQ(FieldPathOf(status).value_or(""), c.field) << status;
  }
}

// A zero interior weight is a point at infinity whose coordinates give its
// direction: the half circle with homogeneous points (1,0,1), (0,1,0),
// (-1,0,1) is the upper half of the unit circle (docs/references.md,
// 'Worked example: the half circle with a point at infinity').
TEST(BezierTest, ZeroInteriorWeightIsAPointAtInfinity) {
  const std::vector<double> points = {1, 0, 0, 1, -1, 0};
  const std::vector<double> weights = {1, 0, 1};
  std::vector<double> params;
  for (int r = 0; r <= 1000; ++r) params.push_back(r / 1000.0);
  const auto result = Evaluate(View(points, 2, weights), params, 2);
  for (size_t r = 0; r < params.size(); ++r) {
    const double* c = &result[0][2 * r];
    const double* d1 = &result[1][2 * r];
    EXPECT_NEAR(std::hypot(c[0], c[1]), 1.0, 1e-15);
    EXPECT_GE(c[1], 0.0);
    EXPECT_NEAR(c[0] * d1[0] + c[1] * d1[1], 0.0, 1e-14);
  }
  EXPECT_NEAR(result[0][1000], 0.0, 1e-15);  // C(1/2) = (0, 1)
  EXPECT_NEAR(result[0][1001], 1.0, 1e-15);
}

TEST(BezierTest, WronglySizedOutputIsRejected) {
  const std::vector<double> points = {0, 0, 1, 1};
  std::vector<double> out(3);
  std::vector<absl::Span<double>> output = {absl::MakeSpan(out)};
  const absl::Status status =
      EvaluateBezierCurve(View(points, 2), std::vector<double>{0.5}, output);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("output[0]"));
}

}  // namespace
}  // namespace freeform

namespace freeform {
namespace {

// The basis sum sum_i B(n,i,t) P_i, the third independent way.
std::vector<double> BasisSum(const std::vector<double>& points, int dimension,
                             const std::vector<double>& params) {
  const int n = static_cast<int>(points.size()) / dimension - 1;
  std::vector<double> basis(static_cast<size_t>(n + 1));
  std::vector<double> out(params.size() * dimension, 0.0);
  for (size_t r = 0; r < params.size(); ++r) {
    BernsteinBasis(n, params[r], absl::MakeSpan(basis));
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j < dimension; ++j) {
        out[r * dimension + j] += basis[i] * points[i * dimension + j];
      }
    }
  }
  return out;
}

// std::nullopt stands for the basis sum.
double MaxRelativeError(const std::vector<double>& points, int dimension,
                        const std::vector<double>& params,
                        std::optional<BezierAlgorithm> algorithm) {
  std::vector<double> out(params.size() * dimension);
  if (algorithm.has_value()) {
    std::vector<absl::Span<double>> output = {absl::MakeSpan(out)};
    EXPECT_TRUE(EvaluateBezierCurve(View(points, dimension), params, output, {},
                                    *algorithm)
                    .ok());
  } else {
    out = BasisSum(points, dimension, params);
  }
  double scale = 0;
  for (double value : points) scale = std::max(scale, std::abs(value));
  double worst = 0;
  for (size_t r = 0; r < params.size(); ++r) {
    const auto exact =
        testing_util::LongDoubleDeCasteljau(points, dimension, params[r]);
    for (int j = 0; j < dimension; ++j) {
      worst = std::max(
          worst,
          static_cast<double>(std::fabs(out[r * dimension + j] - exact[j])) /
              scale);
    }
  }
  return worst;
}

// Degrees 1..64 at 10^4 parameters against long double: de Casteljau,
// Horner, the ladder and the basis sum all stay within 1e-13 of the scale of
// the control points; the errors printed here are what kLinearMaxAutoDegree
// was chosen from.
TEST(BezierAccuracyTest, AlgorithmsMatchLongDoubleReference) {
  std::mt19937_64 rng(2024);
  std::vector<double> params(10'000);
  for (size_t r = 0; r < params.size(); ++r) {
    params[r] = static_cast<double>(r) / static_cast<double>(params.size() - 1);
  }
  for (int n : {1, 3, 5, 7, 10, 12, 15, 20, 25, 30, 40, 50, 64}) {
    const std::vector<double> points =
        RandomValues(rng, static_cast<size_t>(3 * (n + 1)));
    const double casteljau =
        MaxRelativeError(points, 3, params, BezierAlgorithm::kDeCasteljau);
    const double horner =
        MaxRelativeError(points, 3, params, BezierAlgorithm::kHorner);
    const double ladder =
        MaxRelativeError(points, 3, params, BezierAlgorithm::kLadder);
    const double automatic =
        MaxRelativeError(points, 3, params, BezierAlgorithm::kAuto);
    const double basis_sum = MaxRelativeError(points, 3, params, std::nullopt);
    std::printf(
        "degree %2d: de Casteljau %.2e  Horner %.2e  ladder %.2e  basis sum "
        "%.2e\n",
        n, casteljau, horner, ladder, basis_sum);
    EXPECT_LT(basis_sum, 1e-13) << n;
    EXPECT_LT(casteljau, 1e-13) << n;
    EXPECT_LT(automatic, 1e-13) << n;
    EXPECT_LT(horner, 1e-13) << n;
    EXPECT_LT(ladder, 1e-13) << n;
  }
}

}  // namespace
}  // namespace freeform

namespace freeform {
namespace {

// The cubic Bezier geometry matrix (docs/references.md, 'The Bezier geometry
// matrix') turns control points into power coefficients; PowerToBezier
// undoes it.
TEST(PowerFormTest, CubicGeometryMatrixOfTheSlides) {
  const double geometry[4][4] = {
      {1, 0, 0, 0}, {-3, 3, 0, 0}, {3, -6, 3, 0}, {-1, 3, -3, 1}};
  const std::vector<double> control = {0, 0, 1, 2, 3, 2, 4, 0};
  const std::vector<double> power = BezierToPower({2, control});
  for (int j = 0; j < 4; ++j) {
    for (int x = 0; x < 2; ++x) {
      double expected = 0;
      for (int i = 0; i < 4; ++i)
        expected += geometry[j][i] * control[2 * i + x];
      EXPECT_DOUBLE_EQ(power[2 * j + x], expected);
    }
  }
  EXPECT_THAT(PowerToBezier({2, power}), Pointwise(DoubleNear(1e-15), control));
}

TEST(PowerFormTest, ConvertedCurveEvaluatesThePolynomial) {
  std::mt19937_64 rng(8);
  for (int n = 0; n <= 8; ++n) {
    const std::vector<double> coefficients =
        RandomValues(rng, static_cast<size_t>(n + 1));
    const std::vector<double> control = PowerToBezier({1, coefficients});
    const std::vector<double> params = {0, 0.3, 0.5, 0.9, 1};
    const auto result = Evaluate(View(control, 1), params, 2);
    for (size_t r = 0; r < params.size(); ++r) {
      double value = 0, derivative = 0;
      for (int j = n; j >= 0; --j) {
        derivative = derivative * params[r] + value;
        value = value * params[r] + coefficients[j];
      }
      EXPECT_NEAR(result[0][r], value, 1e-14) << n;
      EXPECT_NEAR(result[1][r], derivative, 1e-13) << n;
    }
  }
}

TEST(BernsteinBasisTest, DenseValuesDerivativesAndRationalBasis) {
  const std::vector<double> params = {0, 0.25, 0.5, 1};
  std::vector<std::vector<double>> buffers(2, std::vector<double>(3 * 4));
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  ASSERT_TRUE(EvaluateBernsteinBasis(2, {}, params, output).ok());
  for (size_t r = 0; r < params.size(); ++r) {
    const double t = params[r];
    EXPECT_NEAR(buffers[0][3 * r + 0], (1 - t) * (1 - t), 1e-15);
    EXPECT_NEAR(buffers[0][3 * r + 1], 2 * t * (1 - t), 1e-15);
    EXPECT_NEAR(buffers[0][3 * r + 2], t * t, 1e-15);
    EXPECT_NEAR(buffers[1][3 * r + 0], -2 * (1 - t), 1e-14);
    EXPECT_NEAR(buffers[1][3 * r + 1], 2 - 4 * t, 1e-14);
    EXPECT_NEAR(buffers[1][3 * r + 2], 2 * t, 1e-14);
  }
  // Rational basis of the quarter circle (weights 1, 1, 2): sums to one.
  const std::vector<double> weights = {1, 1, 2};
  ASSERT_TRUE(EvaluateBernsteinBasis(2, weights, params, output).ok());
  for (size_t r = 0; r < params.size(); ++r) {
    const double t = params[r];
    const double w = (1 - t) * (1 - t) + 2 * t * (1 - t) + 2 * t * t;
    EXPECT_NEAR(buffers[0][3 * r + 2], 2 * t * t / w, 1e-15);
    EXPECT_NEAR(
        buffers[0][3 * r] + buffers[0][3 * r + 1] + buffers[0][3 * r + 2], 1.0,
        1e-15);
    EXPECT_NEAR(
        buffers[1][3 * r] + buffers[1][3 * r + 1] + buffers[1][3 * r + 2], 0.0,
        1e-14);
  }
}

}  // namespace
}  // namespace freeform

namespace freeform {
namespace {

// A 10^6-parameter batch on a pool gives exactly the serial numbers, and
// every pool thread takes part: the token's poll, asked before each chunk on
// the thread that runs it, holds each thread until all five (the caller and
// four workers) have arrived, so the batch can only finish if all took work.
TEST(BezierBatchTest, MillionParametersUseEveryThreadAndMatchSerial) {
  std::mt19937_64 rng(99);
  const std::vector<double> points = RandomValues(rng, 8 * 3);
  std::vector<double> params(1'000'000);
  for (size_t r = 0; r < params.size(); ++r) {
    params[r] = static_cast<double>(r) / static_cast<double>(params.size() - 1);
  }
  constexpr size_t kWorkers = 4;
  ThreadPool pool(kWorkers);
  std::mutex mutex;
  std::condition_variable arrived;
  std::set<std::thread::id> threads;
  CancellationToken token;
  token.SetPoll([&] {
    std::unique_lock<std::mutex> lock(mutex);
    threads.insert(std::this_thread::get_id());
    arrived.notify_all();
    arrived.wait_for(lock, std::chrono::seconds(20),
                     [&] { return threads.size() >= kWorkers + 1; });
    return false;
  });
  const auto serial = Evaluate(View(points, 3), params, 2);
  const auto parallel = Evaluate(View(points, 3), params, 2,
                                 ExecutionContext{.pool = &pool,
                                                  .cancellation = &token,
                                                  .grain = 4096,
                                                  .max_helpers = kWorkers});
  EXPECT_EQ(serial, parallel);
  EXPECT_EQ(threads.size(), kWorkers + 1);
}

// The Bernstein basis of degree n is the B-spline basis on n + 1 zeros and
// n + 1 ones: Cox-de Boor (A2.3) against the Bernstein triangle, with and
// without weights, to degree 64 and third derivatives.
TEST(BernsteinBasisTest, EqualsTheBSplineBasisOnBezierKnots) {
  const std::vector<double> params = {0, 0.1, 0.37, 0.5, 0.93, 1};
  for (int n : {0, 1, 5, 17, 64}) {
    std::vector<double> knots(static_cast<size_t>(n) + 1, 0.0);
    knots.insert(knots.end(), static_cast<size_t>(n) + 1, 1.0);
    std::vector<double> weights(static_cast<size_t>(n) + 1);
    for (int i = 0; i <= n; ++i) weights[i] = 1.0 + 0.5 * std::sin(i);
    for (const std::vector<double>& w : {std::vector<double>{}, weights}) {
      const size_t size = params.size() * (static_cast<size_t>(n) + 1);
      std::vector<std::vector<double>> bernstein(4, std::vector<double>(size));
      std::vector<std::vector<double>> bspline(4, std::vector<double>(size));
      std::vector<absl::Span<double>> out_bernstein(bernstein.begin(),
                                                    bernstein.end());
      std::vector<absl::Span<double>> out_bspline(bspline.begin(),
                                                  bspline.end());
      ASSERT_TRUE(EvaluateBernsteinBasis(n, w, params, out_bernstein).ok());
      ASSERT_TRUE(EvaluateBSplineBasis(n, knots, w, params, out_bspline).ok());
      for (int k = 0; k <= 3; ++k) {
        // Derivative k of degree n grows like n^k.
        const double scale = std::pow(std::max(n, 1), k);
        for (size_t i = 0; i < size; ++i) {
          EXPECT_NEAR(bernstein[k][i], bspline[k][i], 1e-12 * scale)
              << "degree " << n << " order " << k << " value " << i
              << (w.empty() ? "" : " rational");
        }
      }
    }
  }
}

}  // namespace
}  // namespace freeform
