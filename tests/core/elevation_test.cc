#include "freeform/core/elevation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "freeform/core/status.h"
#include "test_util.h"

namespace freeform {
namespace {

using ::freeform::testing_util::MaxAbs;
using ::freeform::testing_util::MaxDifference;

using ::freeform::testing_util::EvenlySpaced;
using ::freeform::testing_util::RandomValues;

using ::testing::ElementsAre;
using ::testing::ElementsAreArray;
using ::testing::Optional;

using Buffers = std::vector<std::vector<double>>;

Buffers MakeBuffers(size_t orders, size_t size) {
  return Buffers(orders, std::vector<double>(size));
}

Buffers EvaluateBezier(const BezierCurveView& curve,
                       const std::vector<double>& parameters, int orders) {
  Buffers buffers =
      MakeBuffers(orders, parameters.size() * curve.control_points.dimension);
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  EXPECT_TRUE(EvaluateBezierCurve(curve, parameters, output).ok());
  return buffers;
}

Buffers EvaluateBSpline(const BSplineCurveView& curve,
                        const std::vector<double>& parameters, int orders) {
  Buffers buffers =
      MakeBuffers(orders, parameters.size() * curve.control_points.dimension);
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  const absl::Status status = EvaluateBSplineCurve(curve, parameters, output);
  EXPECT_TRUE(status.ok()) << status;
  return buffers;
}

// Expects every derivative buffer of `actual` within `relative` of
// `expected`, relative to max(scale, largest value of that order).
void ExpectSameDerivatives(const Buffers& expected, const Buffers& actual,
                           double scale, double relative,
                           const std::string& label) {
  ASSERT_EQ(expected.size(), actual.size());
  for (size_t k = 0; k < expected.size(); ++k) {
    const double tolerance =
        relative * std::max(scale, k == 0 ? 0.0 : MaxAbs(expected[k]));
    EXPECT_LE(MaxDifference(expected[k], actual[k]), tolerance)
        << label << " order " << k;
  }
}

BezierCurveView BezierView(const std::vector<double>& coordinates,
                           int dimension,
                           const std::vector<double>& weights = {}) {
  return {
      .control_points = {.dimension = dimension, .coordinates = coordinates},
      .weights = weights};
}

TEST(ElevateBezierCurve, SeedQuadraticToCubicExample) {
  // Q1 is 2/3 of the way from P0 to P1, Q2 1/3 of the way from P1 to P2; see
  // 'Worked example: a quadratic Bezier curve elevated to a cubic' in
  // docs/references.md.
  const std::vector<double> points = {0, 0, 3, 6, 9, -3};
  const absl::StatusOr<BezierCurveData> cubic =
      ElevateBezierCurve(BezierView(points, 2), 1);
  ASSERT_TRUE(cubic.ok()) << cubic.status();
  EXPECT_EQ(cubic->dimension, 2);
  EXPECT_TRUE(cubic->weights.empty());
  const double q1x = 0 + 2.0 / 3.0 * (3 - 0), q1y = 0 + 2.0 / 3.0 * (6 - 0);
  const double q2x = 3 + 1.0 / 3.0 * (9 - 3), q2y = 6 + 1.0 / 3.0 * (-3 - 6);
  EXPECT_THAT(cubic->coordinates,
              ElementsAre(0, 0, testing::DoubleNear(q1x, 1e-15),
                          testing::DoubleNear(q1y, 1e-15),
                          testing::DoubleNear(q2x, 1e-15),
                          testing::DoubleNear(q2y, 1e-15), 9, -3));
}

TEST(ElevateBezierCurve, HalfCircleWithPointAtInfinity) {
  // The half circle (1,0), direction (0,1) with weight 0, (-1,0): the
  // elevated weights are 1, 1/3, 1/3, 1 (eq. 5.36 on the homogeneous points)
  // and the curve stays on the unit circle.
  const std::vector<double> points = {1, 0, 0, 1, -1, 0};
  const std::vector<double> weights = {1, 0, 1};
  const absl::StatusOr<BezierCurveData> cubic =
      ElevateBezierCurve(BezierView(points, 2, weights), 1);
  ASSERT_TRUE(cubic.ok());
  EXPECT_THAT(cubic->weights, ElementsAre(1, testing::DoubleEq(1.0 / 3),
                                          testing::DoubleEq(1.0 / 3), 1));
  const std::vector<double> parameters = EvenlySpaced(0, 1, 101);
  const Buffers values = EvaluateBezier(cubic->view(), parameters, 1);
  for (size_t i = 0; i < parameters.size(); ++i) {
    EXPECT_NEAR(std::hypot(values[0][2 * i], values[0][2 * i + 1]), 1.0, 1e-14);
  }
}

TEST(ElevateBezierCurve, ProjectsHomogeneousPoints) {
  // Homogeneous (2,0,1), (0,8,2); the middle point is their average
  // (1,4,1.5), i.e. weight 1.5 at (1/1.5, 4/1.5).
  const std::vector<double> points = {2, 0, 0, 4};
  const std::vector<double> weights = {1, 2};
  const absl::StatusOr<BezierCurveData> quadratic =
      ElevateBezierCurve(BezierView(points, 2, weights), 1);
  ASSERT_TRUE(quadratic.ok());
  EXPECT_THAT(quadratic->weights, ElementsAre(1, 1.5, 2));
  EXPECT_THAT(quadratic->coordinates,
              ElementsAre(2, 0, testing::DoubleEq(1 / 1.5),
                          testing::DoubleEq(4 / 1.5), 0, 4));
}

TEST(ElevateBezierCurve, ZeroWeightResultKeepsDirection) {
  // Weights 1,0,0,0,1: Q_2 = 2/5 P_1 + 3/5 P_2 combines two points at
  // infinity, so it is one too, with direction 2/5 (1,0) + 3/5 (0,1).
  const std::vector<double> points = {0, 0, 1, 0, 0, 1, 1, 1, 2, 2};
  const std::vector<double> weights = {1, 0, 0, 0, 1};
  const BezierCurveView curve = BezierView(points, 2, weights);
  const absl::StatusOr<BezierCurveData> elevated = ElevateBezierCurve(curve, 1);
  ASSERT_TRUE(elevated.ok());
  EXPECT_EQ(elevated->weights[2], 0.0);
  EXPECT_DOUBLE_EQ(elevated->coordinates[4], 0.4);
  EXPECT_DOUBLE_EQ(elevated->coordinates[5], 0.6);
  const std::vector<double> parameters = EvenlySpaced(0, 1, 1001);
  ExpectSameDerivatives(EvaluateBezier(curve, parameters, 2),
                        EvaluateBezier(elevated->view(), parameters, 2), 2.0,
                        1e-12, "zero weights");
}

TEST(ElevateBezierCurve, EvaluatesUnchangedForAllDegrees) {
  std::mt19937_64 rng(11);
  const std::vector<double> parameters = EvenlySpaced(0, 1, 10000);
  for (int n = 1; n <= 20; ++n) {
    for (int rational = 0; rational < 2; ++rational) {
      const std::vector<double> points = RandomValues(rng, 3 * (n + 1));
      const std::vector<double> weights =
          rational ? RandomValues(rng, n + 1, 0.5, 2.0) : std::vector<double>{};
      const BezierCurveView curve = BezierView(points, 3, weights);
      const Buffers expected = EvaluateBezier(curve, parameters, 3);
      for (int by = 1; by <= 5; ++by) {
        const absl::StatusOr<BezierCurveData> elevated =
            ElevateBezierCurve(curve, by);
        ASSERT_TRUE(elevated.ok());
        ASSERT_EQ(elevated->coordinates.size(), 3u * (n + 1 + by));
        ASSERT_EQ(elevated->weights.size(), rational ? n + 1u + by : 0u);
        const Buffers actual = EvaluateBezier(elevated->view(), parameters, 3);
        const std::string label = "n=" + std::to_string(n) +
                                  " by=" + std::to_string(by) +
                                  " rational=" + std::to_string(rational);
        ExpectSameDerivatives(expected, actual, MaxAbs(points), 1e-12, label);
      }
    }
  }
}

TEST(ElevateBezierCurve, OneStepEqualsRepeatedSingleSteps) {
  std::mt19937_64 rng(12);
  for (int n = 1; n <= 20; ++n) {
    for (int rational = 0; rational < 2; ++rational) {
      const std::vector<double> points = RandomValues(rng, 2 * (n + 1));
      const std::vector<double> weights =
          rational ? RandomValues(rng, n + 1, 0.5, 2.0) : std::vector<double>{};
      for (int by = 2; by <= 5; ++by) {
        const absl::StatusOr<BezierCurveData> direct =
            ElevateBezierCurve(BezierView(points, 2, weights), by);
        ASSERT_TRUE(direct.ok());
        BezierCurveData stepped{2, points, weights};
        for (int step = 0; step < by; ++step) {
          absl::StatusOr<BezierCurveData> next =
              ElevateBezierCurve(stepped.view(), 1);
          ASSERT_TRUE(next.ok());
          stepped = *std::move(next);
        }
        EXPECT_LE(MaxDifference(direct->coordinates, stepped.coordinates),
                  1e-13)
            << n << " " << by;
        EXPECT_LE(MaxDifference(direct->weights, stepped.weights), 1e-13);
      }
    }
  }
}

TEST(ElevateBezierCurve, RejectsNonPositiveBy) {
  const std::vector<double> points = {0, 1, 2};
  for (int by : {0, -1}) {
    const absl::StatusOr<BezierCurveData> result =
        ElevateBezierCurve(BezierView(points, 1), by);
    EXPECT_EQ(result.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(FieldPathOf(result.status()), Optional(std::string("by")));
  }
}

BSplineCurveView BSplineView(int degree, const std::vector<double>& points,
                             int dimension, const std::vector<double>& knots,
                             const std::vector<double>& weights = {}) {
  return {.degree = degree,
          .control_points = {.dimension = dimension, .coordinates = points},
          .knots = knots,
          .weights = weights};
}

// Distinct knot values and their multiplicities.
std::vector<std::pair<double, int>> Runs(const std::vector<double>& knots) {
  std::vector<std::pair<double, int>> runs;
  for (double knot : knots) {
    if (!runs.empty() && runs.back().first == knot) {
      ++runs.back().second;
    } else {
      runs.emplace_back(knot, 1);
    }
  }
  return runs;
}

// A clamped knot vector on [0, 1] for degree p with interior knots of
// random multiplicities 1..p; the control point count follows.
std::vector<double> RandomClampedKnots(std::mt19937_64& rng, int p,
                                       int interior) {
  std::vector<double> values = RandomValues(rng, interior, 0.05, 0.95);
  std::sort(values.begin(), values.end());
  std::uniform_int_distribution<int> multiplicity(1, p);
  std::vector<double> knots(p + 1, 0.0);
  for (double value : values)
    knots.insert(knots.end(), multiplicity(rng), value);
  knots.insert(knots.end(), p + 1, 1.0);
  return knots;
}

// The curve reversed in parameter: u -> -u. Its right-hand limits at -x are
// the original's left-hand limits at x (derivative k times (-1)^k).
BSplineCurveData Reversed(const BSplineCurveData& curve) {
  BSplineCurveData result = curve;
  const size_t count = curve.coordinates.size() / curve.dimension;
  for (size_t i = 0; i < count; ++i) {
    std::copy_n(&curve.coordinates[(count - 1 - i) * curve.dimension],
                curve.dimension, &result.coordinates[i * curve.dimension]);
  }
  std::reverse(result.weights.begin(), result.weights.end());
  for (size_t i = 0; i < curve.knots.size(); ++i) {
    result.knots[i] = -curve.knots[curve.knots.size() - 1 - i];
  }
  return result;
}

// Expects the left and right derivatives of orders 0..p-m to agree at every
// interior knot of `elevated`, m being that knot's multiplicity in
// `original` (degree p).
void ExpectContinuityKept(const BSplineCurveView& original,
                          const BSplineCurveData& elevated) {
  const std::vector<double> knots(original.knots.begin(), original.knots.end());
  const BSplineCurveData reversed = Reversed(elevated);
  const auto runs = Runs(knots);
  for (size_t r = 1; r + 1 < runs.size(); ++r) {
    const auto [knot, multiplicity] = runs[r];
    const int orders = original.degree - multiplicity + 1;
    const Buffers right = EvaluateBSpline(elevated.view(), {knot}, orders);
    const Buffers left = EvaluateBSpline(reversed.view(), {-knot}, orders);
    for (int k = 0; k < orders; ++k) {
      const double sign = k % 2 == 0 ? 1.0 : -1.0;
      for (size_t x = 0; x < right[k].size(); ++x) {
        EXPECT_NEAR(right[k][x], sign * left[k][x],
                    1e-9 * (1.0 + std::abs(right[k][x])))
            << "knot " << knot << " order " << k;
      }
    }
  }
}

void ExpectElevatedKnots(const std::vector<double>& original, int p, int by,
                         const std::vector<double>& elevated) {
  auto expected = Runs(original);
  expected.front().second = p + by + 1;
  expected.back().second = p + by + 1;
  for (size_t r = 1; r + 1 < expected.size(); ++r) expected[r].second += by;
  EXPECT_THAT(Runs(elevated), ElementsAreArray(expected));
}

void ExpectBSplineElevationExact(const BSplineCurveView& curve, int by,
                                 const std::string& label,
                                 double relative = 1e-12) {
  const absl::StatusOr<BSplineCurveData> elevated =
      ElevateBSplineCurve(curve, by);
  ASSERT_TRUE(elevated.ok()) << elevated.status();
  EXPECT_EQ(elevated->degree, curve.degree + by);
  ASSERT_TRUE(ValidateBSplineCurve(elevated->view()).ok()) << label;
  const std::vector<double> knots(curve.knots.begin(), curve.knots.end());
  const int n = static_cast<int>(curve.control_points.size()) - 1;
  const std::vector<double> parameters =
      EvenlySpaced(knots[curve.degree], knots[n + 1], 10000);
  const Buffers expected = EvaluateBSpline(curve, parameters, 2);
  const Buffers actual = EvaluateBSpline(elevated->view(), parameters, 2);
  ExpectSameDerivatives(
      expected, actual,
      MaxAbs(std::vector<double>(curve.control_points.coordinates.begin(),
                                 curve.control_points.coordinates.end())),
      relative, label);
}

TEST(ElevateBSplineCurve, RandomClampedCurvesKeepShapeKnotsAndContinuity) {
  std::mt19937_64 rng(21);
  std::uniform_int_distribution<int> interior(0, 6);
  for (int p = 1; p <= 12; ++p) {
    const int trials = p <= 7 ? 6 : 2;
    for (int trial = 0; trial < trials; ++trial) {
      const bool rational = trial % 2 == 1;
      const std::vector<double> knots =
          RandomClampedKnots(rng, p, interior(rng));
      const int count = static_cast<int>(knots.size()) - p - 1;
      const std::vector<double> points = RandomValues(rng, 3 * count);
      const std::vector<double> weights =
          rational ? RandomValues(rng, count, 0.5, 2.0) : std::vector<double>{};
      const BSplineCurveView curve = BSplineView(p, points, 3, knots, weights);
      ASSERT_TRUE(ValidateBSplineCurve(curve).ok());
      for (int by = 1; by <= 3; ++by) {
        const std::string label = "p=" + std::to_string(p) +
                                  " by=" + std::to_string(by) +
                                  " trial=" + std::to_string(trial);
        // At degrees 11-12 on random knots (some spans tiny) the two curves
        // evaluate up to 1.5e-11 apart; uniform high degrees keep 1e-12
        // (HighDegreeUniformKnotsExact).
        ExpectBSplineElevationExact(curve, by, label, p <= 7 ? 1e-12 : 1e-10);
        const absl::StatusOr<BSplineCurveData> elevated =
            ElevateBSplineCurve(curve, by);
        ASSERT_TRUE(elevated.ok());
        ExpectElevatedKnots(knots, p, by, elevated->knots);
        ExpectContinuityKept(curve, *elevated);
      }
    }
  }
}

// The benchmark workloads' LCG (bench/workloads.h): rnd() in [-1, 1).
std::vector<double> LcgPoints(uint64_t seed, size_t count) {
  uint64_t state = seed;
  std::vector<double> points(count);
  for (double& value : points) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    value = 2.0 * (static_cast<double>(state >> 11) * 0x1.0p-53) - 1.0;
  }
  return points;
}

std::vector<double> ClampedUniformKnots(int count, int degree) {
  std::vector<double> knots(degree + 1, 0.0);
  for (int i = 1; i < count - degree; ++i) {
    knots.push_back(static_cast<double>(i) / (count - degree));
  }
  knots.insert(knots.end(), degree + 1, 1.0);
  return knots;
}

TEST(ElevateBSplineCurve, HighDegreeUniformKnotsExact) {
  std::mt19937_64 rng(22);
  for (int p = 8; p <= 12; ++p) {
    const std::vector<double> knots = ClampedUniformKnots(3 * p, p);
    const std::vector<double> points = RandomValues(rng, 3 * 3 * p);
    for (int by = 1; by <= 3; ++by) {
      ExpectBSplineElevationExact(BSplineView(p, points, 3, knots), by,
                                  "uniform p=" + std::to_string(p));
    }
  }
}

TEST(ElevateBSplineCurve, W1CubicGets197ControlPoints) {
  const std::vector<double> points = LcgPoints(1, 300);
  const std::vector<double> knots = ClampedUniformKnots(100, 3);
  const BSplineCurveView curve = BSplineView(3, points, 3, knots);
  const absl::StatusOr<BSplineCurveData> elevated =
      ElevateBSplineCurve(curve, 1);
  ASSERT_TRUE(elevated.ok());
  EXPECT_EQ(elevated->coordinates.size(), 3u * 197);
  ExpectElevatedKnots(knots, 3, 1, elevated->knots);
  ExpectBSplineElevationExact(curve, 1, "W1");
}

// Elevating by 1 takes the mean of p + 1 leave-one-out blossoms; by 2 or
// more builds the average over subsets one argument at a time. Two steps of
// the first give the same spline as one of the second. From degree 8 on,
// random knots (repeated up to p times, some spans 1e-3 wide) make the
// control points themselves ill-conditioned: both algorithms then agree
// only to about 1e-8 while their curves agree to 1e-10
// (RandomClampedCurvesKeepShapeKnotsAndContinuity), so degrees 8 to 12 run
// on uniform knots.
TEST(ElevateBSplineCurve, ByOneTwiceEqualsByTwoOnce) {
  std::mt19937_64 rng(23);
  std::uniform_int_distribution<int> interior(0, 8);
  for (int p = 1; p <= 12; ++p) {
    // 3 and 4 run the compiled point sizes, 2 and 5 the run-time ones.
    for (int dimension : {2, 3, 4, 5}) {
      const bool rational = (p + dimension) % 2 == 0;
      const std::vector<double> knots =
          p <= 7 ? RandomClampedKnots(rng, p, interior(rng))
                 : ClampedUniformKnots(3 * p, p);
      const int count = static_cast<int>(knots.size()) - p - 1;
      const std::vector<double> points = RandomValues(rng, dimension * count);
      const std::vector<double> weights =
          rational ? RandomValues(rng, count, 0.5, 2.0) : std::vector<double>{};
      const BSplineCurveView curve =
          BSplineView(p, points, dimension, knots, weights);
      const std::string label =
          "p=" + std::to_string(p) + " dimension=" + std::to_string(dimension);
      const absl::StatusOr<BSplineCurveData> once =
          ElevateBSplineCurve(curve, 1);
      ASSERT_TRUE(once.ok()) << label;
      const absl::StatusOr<BSplineCurveData> twice =
          ElevateBSplineCurve(once->view(), 1);
      const absl::StatusOr<BSplineCurveData> by_two =
          ElevateBSplineCurve(curve, 2);
      ASSERT_TRUE(twice.ok() && by_two.ok()) << label;
      EXPECT_EQ(twice->degree, p + 2);
      EXPECT_EQ(twice->knots, by_two->knots) << label;
      EXPECT_LE(MaxDifference(twice->coordinates, by_two->coordinates),
                1e-13 * MaxAbs(points))
          << label;
      EXPECT_LE(MaxDifference(twice->weights, by_two->weights), 1e-13) << label;
    }
  }
}

TEST(ElevateBSplineCurve, UnclampedKnotVectors) {
  // Uniform unclamped cubic on [3, 8] (knots 0..11, 8 control points).
  std::vector<double> uniform(12);
  for (int i = 0; i < 12; ++i) uniform[i] = i;
  std::mt19937_64 rng(31);
  const std::vector<double> points = RandomValues(rng, 2 * 8);
  for (int by = 1; by <= 3; ++by) {
    const BSplineCurveView curve = BSplineView(3, points, 2, uniform);
    ExpectBSplineElevationExact(curve, by, "uniform");
    const absl::StatusOr<BSplineCurveData> elevated =
        ElevateBSplineCurve(curve, by);
    ASSERT_TRUE(elevated.ok());
    // Clamped at the domain ends; knots outside the domain dropped.
    std::vector<double> inside = {3, 3, 3, 3, 4, 5, 6, 7, 8, 8, 8, 8};
    ExpectElevatedKnots(inside, 3, by, elevated->knots);
  }
  // Random knots (partly repeated, a repeated domain start) and weights.
  for (int trial = 0; trial < 20; ++trial) {
    const int p = 1 + trial % 5;
    const int count = p + 1 + trial % 4;
    std::vector<double> knots = RandomValues(rng, count + p + 1, 0.0, 1.0);
    std::sort(knots.begin(), knots.end());
    if (trial % 3 == 0 && p >= 2) knots[p - 1] = knots[p];
    const std::vector<double> curve_points = RandomValues(rng, 2 * count);
    const std::vector<double> weights =
        trial % 2 ? RandomValues(rng, count, 0.5, 2.0) : std::vector<double>{};
    const BSplineCurveView curve =
        BSplineView(p, curve_points, 2, knots, weights);
    ASSERT_TRUE(ValidateBSplineCurve(curve).ok());
    ExpectBSplineElevationExact(curve, 1 + trial % 3,
                                "trial " + std::to_string(trial));
  }
}

TEST(ElevateBSplineCurve, DegreeZeroAndNurbsCircleQuadrant) {
  const std::vector<double> constant = {1, 2};
  const std::vector<double> knots01 = {0, 1};
  const absl::StatusOr<BSplineCurveData> line =
      ElevateBSplineCurve(BSplineView(0, constant, 2, knots01), 2);
  ASSERT_TRUE(line.ok());
  EXPECT_EQ(line->degree, 2);
  EXPECT_THAT(line->knots, ElementsAre(0, 0, 0, 1, 1, 1));
  EXPECT_THAT(line->coordinates, ElementsAre(1, 2, 1, 2, 1, 2));
  // The half circle with a point at infinity as a NURBS.
  const std::vector<double> points = {1, 0, 0, 1, -1, 0};
  const std::vector<double> weights = {1, 0, 1};
  const std::vector<double> knots = {0, 0, 0, 1, 1, 1};
  ExpectBSplineElevationExact(BSplineView(2, points, 2, knots, weights), 2,
                              "half circle");
}

TEST(ElevateBSplineCurve, RejectsNonPositiveBy) {
  const std::vector<double> points = {0, 1};
  const std::vector<double> knots = {0, 0, 1, 1};
  const absl::StatusOr<BSplineCurveData> result =
      ElevateBSplineCurve(BSplineView(1, points, 1, knots), 0);
  EXPECT_EQ(result.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(FieldPathOf(result.status()), Optional(std::string("by")));
}

TEST(ReduceBezierCurve, RecoversElevatedCurvesExactly) {
  std::mt19937_64 rng(41);
  for (int m = 0; m <= 10; ++m) {
    for (int by = 1; by <= 4; ++by) {
      const std::vector<double> points = RandomValues(rng, 3 * (m + 1));
      const absl::StatusOr<BezierCurveData> elevated =
          ElevateBezierCurve(BezierView(points, 3), by);
      ASSERT_TRUE(elevated.ok());
      const absl::StatusOr<ReducedBezierCurve> reduced =
          ReduceBezierCurve(elevated->view(), by);
      ASSERT_TRUE(reduced.ok()) << reduced.status();
      EXPECT_LE(MaxDifference(reduced->curve.coordinates, points), 1e-12)
          << m << " " << by;
      EXPECT_LE(reduced->error_bound, 1e-12);
      EXPECT_TRUE(reduced->curve.weights.empty());
    }
  }
}

// The largest distance between the two curves at 10^4 parameters.
double MeasuredDistance(const BezierCurveView& a, const BezierCurveView& b) {
  const std::vector<double> parameters = EvenlySpaced(0, 1, 10000);
  const Buffers x = EvaluateBezier(a, parameters, 1);
  const Buffers y = EvaluateBezier(b, parameters, 1);
  const int dim = a.control_points.dimension;
  double result = 0.0;
  for (size_t i = 0; i < parameters.size(); ++i) {
    double norm = 0.0;
    for (int j = 0; j < dim; ++j) {
      norm = std::hypot(norm, x[0][i * dim + j] - y[0][i * dim + j]);
    }
    result = std::max(result, norm);
  }
  return result;
}

TEST(ReduceBezierCurve, ErrorBoundHoldsAndIsTight) {
  std::mt19937_64 rng(42);
  for (int trial = 0; trial < 50; ++trial) {
    const std::vector<double> points = RandomValues(rng, 3 * 4);
    const BezierCurveView cubic = BezierView(points, 3);
    const absl::StatusOr<ReducedBezierCurve> reduced =
        ReduceBezierCurve(cubic, 1);
    ASSERT_TRUE(reduced.ok());
    const double distance = MeasuredDistance(cubic, reduced->curve.view());
    EXPECT_GE(reduced->error_bound, distance * (1 - 1e-12));
    EXPECT_LE(reduced->error_bound, 10 * distance);
    // End points are kept.
    EXPECT_THAT(std::vector<double>(reduced->curve.coordinates.begin(),
                                    reduced->curve.coordinates.begin() + 3),
                ElementsAreArray(points.begin(), points.begin() + 3));
  }
  for (int n = 1; n <= 12; ++n) {
    for (int by = 1; by <= n; ++by) {
      const std::vector<double> points = RandomValues(rng, 2 * (n + 1));
      const BezierCurveView curve = BezierView(points, 2);
      const absl::StatusOr<ReducedBezierCurve> reduced =
          ReduceBezierCurve(curve, by);
      ASSERT_TRUE(reduced.ok());
      EXPECT_EQ(reduced->curve.coordinates.size(), 2u * (n - by + 1));
      EXPECT_GE(reduced->error_bound * (1 + 1e-12) + 1e-15,
                MeasuredDistance(curve, reduced->curve.view()))
          << n << " " << by;
    }
  }
}

TEST(ReduceBezierCurve, RejectsBadByAndRationalCurves) {
  const std::vector<double> points = {0, 1, 3};
  for (int by : {0, -1, 3}) {
    const absl::StatusOr<ReducedBezierCurve> result =
        ReduceBezierCurve(BezierView(points, 1), by);
    EXPECT_EQ(result.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(FieldPathOf(result.status()), Optional(std::string("by")));
  }
  const std::vector<double> weights = {1, 2, 1};
  const absl::StatusOr<ReducedBezierCurve> rational =
      ReduceBezierCurve(BezierView(points, 1, weights), 1);
  EXPECT_EQ(rational.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(FieldPathOf(rational.status()), Optional(std::string("weights")));
}

// Evaluates positions and first partials on a 50 x 50 grid.
Buffers EvaluateSurface(const BezierSurfaceView* bezier,
                        const BSplineSurfaceView* bspline, SurfaceDomain domain,
                        int dimension) {
  const std::vector<double> u = EvenlySpaced(domain.u_start, domain.u_end, 50);
  const std::vector<double> v = EvenlySpaced(domain.v_start, domain.v_end, 50);
  Buffers buffers = MakeBuffers(PartialCount(1), 50 * 50 * dimension);
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  const SurfaceSamples samples = SurfaceSamples::Grid(u, v);
  const absl::Status status =
      bezier ? EvaluateBezierSurface(*bezier, samples, output)
             : EvaluateBSplineSurface(*bspline, samples, output);
  EXPECT_TRUE(status.ok()) << status;
  return buffers;
}

TEST(ElevateBezierSurface, EvaluatesUnchanged) {
  std::mt19937_64 rng(51);
  for (int rational = 0; rational < 2; ++rational) {
    const std::vector<double> net = RandomValues(rng, 4 * 5 * 3);
    const std::vector<double> weights =
        rational ? RandomValues(rng, 20, 0.5, 2.0) : std::vector<double>{};
    const BezierSurfaceView surface{.control_net = {.dimension = 3,
                                                    .count_u = 4,
                                                    .count_v = 5,
                                                    .coordinates = net},
                                    .weights = weights};
    const Buffers expected =
        EvaluateSurface(&surface, nullptr, BezierSurfaceDomain(), 3);
    for (const auto& [by_u, by_v] : {std::pair{1, 0}, {0, 2}, {2, 3}}) {
      const absl::StatusOr<SurfaceData> elevated =
          ElevateBezierSurface(surface, by_u, by_v);
      ASSERT_TRUE(elevated.ok());
      EXPECT_EQ(elevated->count_u, 4 + by_u);
      EXPECT_EQ(elevated->count_v, 5 + by_v);
      EXPECT_EQ(elevated->degree_u, 3 + by_u);
      EXPECT_EQ(elevated->degree_v, 4 + by_v);
      EXPECT_TRUE(elevated->knots_u.empty());
      const BezierSurfaceView view = elevated->bezier_view();
      ASSERT_TRUE(ValidateBezierSurface(view).ok());
      const Buffers actual =
          EvaluateSurface(&view, nullptr, BezierSurfaceDomain(), 3);
      ExpectSameDerivatives(
          expected, actual, MaxAbs(net), 1e-12,
          "bezier " + std::to_string(by_u) + "," + std::to_string(by_v));
    }
  }
}

TEST(ElevateBSplineSurface, EvaluatesUnchanged) {
  std::mt19937_64 rng(52);
  const std::vector<double> knots_u = {0, 0, 0, 0, 0.3, 0.3, 0.6, 1, 1, 1, 1};
  const std::vector<double> knots_v = {0, 0, 0, 0.5, 2, 2, 2};
  for (int rational = 0; rational < 2; ++rational) {
    const std::vector<double> net = RandomValues(rng, 7 * 4 * 3);
    const std::vector<double> weights =
        rational ? RandomValues(rng, 28, 0.5, 2.0) : std::vector<double>{};
    const BSplineSurfaceView surface{.degree_u = 3,
                                     .degree_v = 2,
                                     .control_net = {.dimension = 3,
                                                     .count_u = 7,
                                                     .count_v = 4,
                                                     .coordinates = net},
                                     .knots_u = knots_u,
                                     .knots_v = knots_v,
                                     .weights = weights};
    ASSERT_TRUE(ValidateBSplineSurface(surface).ok());
    const SurfaceDomain domain = BSplineSurfaceDomain(surface);
    const Buffers expected = EvaluateSurface(nullptr, &surface, domain, 3);
    for (const auto& [by_u, by_v] : {std::pair{1, 0}, {0, 2}, {2, 1}}) {
      const absl::StatusOr<SurfaceData> elevated =
          ElevateBSplineSurface(surface, by_u, by_v);
      ASSERT_TRUE(elevated.ok());
      EXPECT_EQ(elevated->degree_u, 3 + by_u);
      EXPECT_EQ(elevated->degree_v, 2 + by_v);
      // u: 3 segments, v: 2 segments.
      EXPECT_EQ(elevated->count_u, 7 + 3 * by_u);
      EXPECT_EQ(elevated->count_v, 4 + 2 * by_v);
      const BSplineSurfaceView view = elevated->bspline_view();
      ASSERT_TRUE(ValidateBSplineSurface(view).ok());
      const Buffers actual = EvaluateSurface(nullptr, &view, domain, 3);
      ExpectSameDerivatives(
          expected, actual, MaxAbs(net), 1e-12,
          "bspline " + std::to_string(by_u) + "," + std::to_string(by_v));
    }
  }
}

TEST(ElevateSurfaces, RejectBadBy) {
  const std::vector<double> net = {0, 1, 2, 3};
  const BezierSurfaceView bezier{.control_net = {.dimension = 1,
                                                 .count_u = 2,
                                                 .count_v = 2,
                                                 .coordinates = net},
                                 .weights = {}};
  const std::vector<double> knots = {0, 0, 1, 1};
  const BSplineSurfaceView bspline{.degree_u = 1,
                                   .degree_v = 1,
                                   .control_net = bezier.control_net,
                                   .knots_u = knots,
                                   .knots_v = knots,
                                   .weights = {}};
  const std::vector<std::pair<std::pair<int, int>, std::string>> cases = {
      {{0, 0}, "by_u"}, {{-1, 1}, "by_u"}, {{1, -1}, "by_v"}};
  for (const auto& [by, field] : cases) {
    EXPECT_THAT(
        FieldPathOf(ElevateBezierSurface(bezier, by.first, by.second).status()),
        Optional(field));
    EXPECT_THAT(
        FieldPathOf(
            ElevateBSplineSurface(bspline, by.first, by.second).status()),
        Optional(field));
  }
}

TEST(ElevateTriangularPatch, LinearToQuadraticByHand) {
  // P100 = A, P010 = B, P001 = C: Q200 = A, Q110 = (A+B)/2, Q101 = (A+C)/2,
  // Q020 = B, Q011 = (B+C)/2, Q002 = C in storage order.
  const std::vector<double> points = {0, 0, 4, 0, 0, 2};
  const std::vector<double> triangle = {0, 0, 1, 0, 0, 1};
  const TriangularPatchView patch{
      .degree = 1,
      .control_points = {.dimension = 2, .coordinates = points},
      .weights = {},
      .domain_triangle = triangle};
  const absl::StatusOr<TriangularPatchData> quadratic =
      ElevateTriangularPatch(patch, 1);
  ASSERT_TRUE(quadratic.ok());
  EXPECT_EQ(quadratic->degree, 2);
  EXPECT_THAT(quadratic->coordinates,
              ElementsAre(0, 0, 2, 0, 0, 1, 4, 0, 2, 1, 0, 2));
  EXPECT_THAT(quadratic->domain_triangle, ElementsAreArray(triangle));
}

TEST(ElevateTriangularPatch, EvaluatesUnchanged) {
  std::mt19937_64 rng(61);
  std::vector<double> uv;
  for (int i = 0; i < 300; ++i) {
    std::vector<double> pair = RandomValues(rng, 2, 0.0, 1.0);
    if (pair[0] + pair[1] > 1) pair = {1 - pair[0], 1 - pair[1]};
    uv.insert(uv.end(), pair.begin(), pair.end());
  }
  uv.insert(uv.end(), {1, 0, 0, 1, 0, 0});
  for (int n = 1; n <= 8; ++n) {
    for (int rational = 0; rational < 2; ++rational) {
      const size_t count = TriangularPointCount(n);
      const std::vector<double> points = RandomValues(rng, 3 * count);
      const std::vector<double> weights =
          rational ? RandomValues(rng, count, 0.5, 2.0) : std::vector<double>{};
      const TriangularPatchView patch{
          .degree = n,
          .control_points = {.dimension = 3, .coordinates = points},
          .weights = weights,
          .domain_triangle = {}};
      Buffers expected = MakeBuffers(PartialCount(1), uv.size() / 2 * 3);
      std::vector<absl::Span<double>> out(expected.begin(), expected.end());
      ASSERT_TRUE(EvaluateTriangularPatch(patch, uv, out).ok());
      for (int by = 1; by <= 4; ++by) {
        const absl::StatusOr<TriangularPatchData> elevated =
            ElevateTriangularPatch(patch, by);
        ASSERT_TRUE(elevated.ok());
        ASSERT_TRUE(ValidateTriangularPatch(elevated->view()).ok());
        Buffers actual = MakeBuffers(PartialCount(1), uv.size() / 2 * 3);
        std::vector<absl::Span<double>> out2(actual.begin(), actual.end());
        ASSERT_TRUE(EvaluateTriangularPatch(elevated->view(), uv, out2).ok());
        ExpectSameDerivatives(
            expected, actual, MaxAbs(points), 1e-12,
            "triangular n=" + std::to_string(n) + " by=" + std::to_string(by));
      }
    }
  }
}

TEST(ElevateTriangularPatch, RejectsNonPositiveBy) {
  const std::vector<double> points = {0, 1, 2};
  const TriangularPatchView patch{
      .degree = 1,
      .control_points = {.dimension = 1, .coordinates = points},
      .weights = {},
      .domain_triangle = {}};
  EXPECT_THAT(FieldPathOf(ElevateTriangularPatch(patch, 0).status()),
              Optional(std::string("by")));
}

}  // namespace
}  // namespace freeform
