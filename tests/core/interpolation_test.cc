#include "freeform/core/interpolation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "freeform/core/bspline.h"
#include "freeform/core/lagrange.h"
#include "freeform/core/status.h"
#include "freeform/core/tensor_surface.h"

namespace freeform {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr Parameterization kParameterizations[] = {
    Parameterization::kUniform, Parameterization::kChordLength,
    Parameterization::kCentripetal, Parameterization::kUniversal};

// Evaluates derivatives 0..orders-1 of `curve` at `params`.
std::vector<std::vector<double>> Evaluate(const BSplineCurveData& curve,
                                          const std::vector<double>& params,
                                          int orders) {
  std::vector<std::vector<double>> buffers(
      static_cast<size_t>(orders),
      std::vector<double>(params.size() *
                          static_cast<size_t>(curve.dimension)));
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  const absl::Status status =
      EvaluateBSplineCurve(curve.view(), params, output);
  EXPECT_TRUE(status.ok()) << status;
  return buffers;
}

double MaxAbs(const std::vector<double>& values) {
  double max = 1.0;
  for (double value : values) max = std::max(max, std::abs(value));
  return max;
}

double MaxDifference(const std::vector<double>& a,
                     const std::vector<double>& b) {
  EXPECT_EQ(a.size(), b.size());
  double max = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    max = std::max(max, std::abs(a[i] - b[i]));
  }
  return max;
}

// The largest deviation |C(t_k) - Q_k| relative to the data's size.
double RelativeMiss(const BSplineCurveData& curve,
                    const std::vector<double>& params,
                    const std::vector<double>& points) {
  return MaxDifference(Evaluate(curve, params, 1)[0], points) / MaxAbs(points);
}

std::vector<double> Random(std::mt19937_64& rng, size_t count) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<double> values(count);
  for (double& value : values) value = uniform(rng);
  return values;
}

// Points along a smooth curve with small noise, so consecutive chords are
// nearly equal (Schoenberg-Whitney then holds for uniform knots too); with
// `closed` they go once around.
std::vector<double> SmoothPoints(std::mt19937_64& rng, int count, int dimension,
                                 bool closed) {
  std::vector<double> points;
  const std::vector<double> noise =
      Random(rng, static_cast<size_t>(count * dimension));
  const double step = 2 * std::numbers::pi / count;
  for (int k = 0; k < count; ++k) {
    for (int j = 0; j < dimension; ++j) {
      const double angle = step * k;
      double value = 0;
      if (dimension == 1) {
        value = closed ? std::cos(angle) : k;
      } else if (j % 2 == 0) {
        value = (3 + j) * std::cos(angle + 0.1 * j);
      } else {
        value = (3 + j) * std::sin(angle + 0.1 * j);
      }
      points.push_back(value +
                       0.01 * noise[static_cast<size_t>(k * dimension + j)]);
    }
  }
  return points;
}

// ----------------------------------------------- five planar points --
// docs/references.md,
// 'Worked example: a cubic B-spline through five planar points'.

const std::vector<double> kExercise5 = {0, 0, 3, 4, -1, 4, -4, 0, -4, -3};

TEST(InterpolateCurveTest, Exercise5ChordLength) {
  absl::StatusOr<CurveInterpolation> result = InterpolateCurve(
      {.dimension = 2, .coordinates = kExercise5}, CurveInterpolationOptions{});
  ASSERT_TRUE(result.ok()) << result.status();
  const std::vector<double> expected = {0, 5.0 / 17, 9.0 / 17, 14.0 / 17, 1};
  EXPECT_LT(MaxDifference(result->parameters, expected), 1e-15);
  const std::vector<double> knots = {0, 0, 0, 0, 28.0 / 51, 1, 1, 1, 1};
  EXPECT_LT(MaxDifference(result->curve.knots, knots), 1e-15);
  EXPECT_LT(RelativeMiss(result->curve, expected, kExercise5), 1e-12);
  EXPECT_LT(result->max_residual, 1e-12);
}

TEST(InterpolateCurveTest, Exercise5UniversalUsesBasisMaxima) {
  absl::StatusOr<CurveInterpolation> result =
      InterpolateCurve({.dimension = 2, .coordinates = kExercise5},
                       {.parameterization = Parameterization::kUniversal});
  ASSERT_TRUE(result.ok()) << result.status();
  const std::vector<double> knots = {0, 0, 0, 0, 0.5, 1, 1, 1, 1};
  EXPECT_EQ(result->curve.knots, knots);
  const std::vector<double>& t = result->parameters;
  ASSERT_EQ(t.size(), 5u);
  EXPECT_EQ(t[0], 0.0);
  EXPECT_NEAR(t[1], 0.226541, 1e-6);  // (3 - sqrt(2)) / 7, not 1/3
  EXPECT_NEAR(t[2], 0.5, 1e-15);
  EXPECT_NEAR(t[3], 0.773459, 1e-6);
  EXPECT_NEAR(t[1] + t[3], 1.0, 1e-15);  // symmetric knots
  EXPECT_EQ(t[4], 1.0);
  // t_i is where N_{i,3} peaks: N'_{i,3}(t_i) = 0 and N'' < 0.
  std::vector<double> values(25), first(25), second(25);
  const std::vector<absl::Span<double>> output = {
      absl::MakeSpan(values), absl::MakeSpan(first), absl::MakeSpan(second)};
  ASSERT_TRUE(EvaluateBSplineBasis(3, knots, {}, t, output).ok());
  for (int i = 1; i <= 3; ++i) {
    EXPECT_NEAR(first[static_cast<size_t>(i * 5 + i)], 0.0, 1e-13) << i;
    EXPECT_LT(second[static_cast<size_t>(i * 5 + i)], 0.0) << i;
  }
  EXPECT_LT(RelativeMiss(result->curve, t, kExercise5), 1e-12);
}

TEST(InterpolationParametersTest, ChordCentripetalUniform) {
  const PointsView points{.dimension = 2, .coordinates = kExercise5};
  EXPECT_THAT(*InterpolationParameters(points, 3, Parameterization::kUniform),
              ElementsAre(0, 0.25, 0.5, 0.75, 1));
  // Chords 5, 4, 5, 3: square roots over their sum.
  const double sum = 2 * std::sqrt(5.0) + 2 + std::sqrt(3.0);
  const std::vector<double> centripetal =
      *InterpolationParameters(points, 3, Parameterization::kCentripetal);
  const std::vector<double> expected = {0, std::sqrt(5.0) / sum,
                                        (std::sqrt(5.0) + 2) / sum,
                                        (2 * std::sqrt(5.0) + 2) / sum, 1};
  EXPECT_LT(MaxDifference(centripetal, expected), 1e-15);
}

TEST(InterpolationParametersTest, UniversalParametersAreBasisMaxima) {
  for (int p = 1; p <= 6; ++p) {
    for (int count : {p + 1, p + 2, 2 * p + 3, 20}) {
      const std::vector<double> coordinates(static_cast<size_t>(count), 0.0);
      const std::vector<double> t =
          *InterpolationParameters({.dimension = 1, .coordinates = coordinates},
                                   p, Parameterization::kUniversal);
      std::vector<double> knots(static_cast<size_t>(p) + 1, 0.0);
      for (int j = 1; j < count - p; ++j)
        knots.push_back(1.0 * j / (count - p));
      knots.insert(knots.end(), static_cast<size_t>(p) + 1, 1.0);
      // N_{i,p} at t_i is not below its value at nearby points.
      for (int i = 0; i < count; ++i) {
        const double ti = t[static_cast<size_t>(i)];
        std::vector<double> samples = {ti};
        for (double h : {-1e-7, 1e-7, -1e-3, 1e-3}) {
          samples.push_back(std::clamp(ti + h, 0.0, 1.0));
        }
        std::vector<double> values(samples.size() * static_cast<size_t>(count));
        const std::vector<absl::Span<double>> output = {absl::MakeSpan(values)};
        ASSERT_TRUE(EvaluateBSplineBasis(p, knots, {}, samples, output).ok());
        for (size_t s = 1; s < samples.size(); ++s) {
          EXPECT_GE(
              values[static_cast<size_t>(i)] + 1e-15,
              values[s * static_cast<size_t>(count) + static_cast<size_t>(i)])
              << "p=" << p << " count=" << count << " i=" << i;
        }
      }
    }
  }
}

// ------------------------------------------------------------- random --

TEST(InterpolateCurveTest, RandomDataAllDegreesParameterizationsKnotRules) {
  std::mt19937_64 rng(1);
  for (int p = 1; p <= 7; ++p) {
    for (int dimension = 1; dimension <= 5; ++dimension) {
      for (Parameterization parameterization : kParameterizations) {
        for (KnotRule rule : {KnotRule::kAveraging, KnotRule::kUniform}) {
          for (bool derivatives : {false, true}) {
            if (derivatives && p == 1) continue;
            const int count = p + 1 + static_cast<int>(rng() % 25);
            // Fully random data for averaging knots (always solvable);
            // evenly spaced data for uniform knots (Schoenberg-Whitney).
            const std::vector<double> points =
                rule == KnotRule::kAveraging
                    ? Random(rng, static_cast<size_t>(count * dimension))
                    : SmoothPoints(rng, count, dimension, false);
            const std::vector<double> start =
                Random(rng, static_cast<size_t>(dimension));
            const std::vector<double> end =
                Random(rng, static_cast<size_t>(dimension));
            CurveInterpolationOptions options{
                .degree = p,
                .parameterization = parameterization,
                .knot_rule = rule};
            if (derivatives) {
              options.start_derivative = start;
              options.end_derivative = end;
            }
            absl::StatusOr<CurveInterpolation> result = InterpolateCurve(
                {.dimension = dimension, .coordinates = points}, options);
            ASSERT_TRUE(result.ok())
                << result.status() << " p=" << p << " d=" << dimension;
            const auto& t = result->parameters;
            ASSERT_EQ(t.size(), static_cast<size_t>(count));
            EXPECT_TRUE(std::is_sorted(t.begin(), t.end()));
            EXPECT_EQ(result->curve.coordinates.size(),
                      points.size() + (derivatives ? 2u * dimension : 0u));
            // Uniform knots on non-uniform parameters can be badly
            // conditioned (docs/references.md, 'Global B-spline
            // interpolation'; control points up to 1e7 here): a
            // backward-stable solve then misses by eps |A| |P|, so measure
            // relative to the control points too.
            const double scale =
                rule == KnotRule::kAveraging
                    ? 1.0
                    : std::max(1.0, MaxAbs(result->curve.coordinates) /
                                        MaxAbs(points));
            EXPECT_LT(RelativeMiss(result->curve, t, points), 1e-12 * scale)
                << "p=" << p << " d=" << dimension << " count=" << count;
            if (derivatives) {
              const auto d =
                  Evaluate(result->curve, {t.front(), t.back()}, 2)[1];
              for (int j = 0; j < dimension; ++j) {
                EXPECT_NEAR(d[static_cast<size_t>(j)],
                            start[static_cast<size_t>(j)], 1e-11);
                EXPECT_NEAR(d[static_cast<size_t>(dimension + j)],
                            end[static_cast<size_t>(j)], 1e-11);
              }
            }
          }
        }
      }
    }
  }
}

TEST(InterpolateCurveTest, ExplicitParametersAreUsed) {
  std::mt19937_64 rng(2);
  const std::vector<double> points = Random(rng, 18);
  const std::vector<double> t = {-1, 0.5, 2, 2.5, 4, 7};
  absl::StatusOr<CurveInterpolation> result = InterpolateCurve(
      {.dimension = 3, .coordinates = points}, {.degree = 2, .parameters = t});
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_EQ(result->parameters, t);
  EXPECT_EQ(result->curve.knots.front(), -1);
  EXPECT_EQ(result->curve.knots.back(), 7);
  EXPECT_LT(RelativeMiss(result->curve, t, points), 1e-12);
}

TEST(InterpolateCurveTest, ClosedCurvesArePeriodic) {
  std::mt19937_64 rng(3);
  for (int p = 1; p <= 7; ++p) {
    for (int dimension = 2; dimension <= 5; ++dimension) {
      for (int count : {p + 1, p + 2, 3 * p + 3, 30}) {
        for (Parameterization parameterization : kParameterizations) {
          for (KnotRule rule : {KnotRule::kAveraging, KnotRule::kUniform}) {
            const std::vector<double> points =
                SmoothPoints(rng, count, dimension, true);
            absl::StatusOr<CurveInterpolation> result = InterpolateCurve(
                {.dimension = dimension, .coordinates = points},
                {.degree = p,
                 .parameterization = parameterization,
                 .knot_rule = rule,
                 .closed = true});
            ASSERT_TRUE(result.ok())
                << result.status() << " p=" << p << " count=" << count;
            const BSplineCurveData& curve = result->curve;
            EXPECT_EQ(curve.coordinates.size(),
                      points.size() + static_cast<size_t>(p * dimension));
            EXPECT_LT(RelativeMiss(curve, result->parameters, points), 1e-12)
                << "p=" << p << " d=" << dimension << " count=" << count;
            // C^(p-1) across the seam: the right limit at the domain start
            // equals the left limit at its end.
            const double a = curve.knots[static_cast<size_t>(p)];
            const double b =
                curve.knots[curve.knots.size() - 1 - static_cast<size_t>(p)];
            const auto ends = Evaluate(curve, {a, b}, p);
            for (int k = 0; k < p; ++k) {
              const auto& v = ends[static_cast<size_t>(k)];
              const size_t d = static_cast<size_t>(dimension);
              const std::vector<double> left(v.begin(), v.begin() + d);
              const std::vector<double> right(v.begin() + d, v.end());
              EXPECT_LT(MaxDifference(left, right), 1e-9 * MaxAbs(v))
                  << "order " << k << " p=" << p << " count=" << count;
            }
          }
        }
      }
    }
  }
}

TEST(InterpolateCurveTest, LargeCubicPassesThroughEveryPoint) {
  constexpr int kCount = 1000000;
  std::mt19937_64 rng(4);
  std::vector<double> points = Random(rng, 3 * static_cast<size_t>(kCount));
  for (int i = 0; i < kCount; ++i) {
    const size_t at = 3 * static_cast<size_t>(i);
    points[at] = 10 * std::cos(0.01 * i) + 0.1 * points[at];
    points[at + 1] = 10 * std::sin(0.01 * i) + 0.1 * points[at + 1];
    points[at + 2] = 0.01 * i + 0.1 * points[at + 2];
  }
  absl::StatusOr<CurveInterpolation> result =
      InterpolateCurve({.dimension = 3, .coordinates = points}, {});
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_LT(RelativeMiss(result->curve, result->parameters, points), 1e-12);
}

// ------------------------------------------------------- cubic splines --

// A vector-valued cubic y(x) = (1 - 2x + x^2/3 - x^3/7, 2 + x^3) and its
// derivatives.
std::vector<double> Cubic(double x, int order) {
  switch (order) {
    case 0:
      return {1 - 2 * x + x * x / 3 - x * x * x / 7, 2 + x * x * x};
    case 1:
      return {-2 + 2 * x / 3 - 3 * x * x / 7, 3 * x * x};
    default:
      return {2.0 / 3 - 6 * x / 7, 6 * x};
  }
}

std::vector<double> SortedAbscissas(std::mt19937_64& rng, int count) {
  std::vector<double> x = Random(rng, static_cast<size_t>(count));
  for (double& value : x) value *= 3;
  std::sort(x.begin(), x.end());
  return x;
}

std::vector<double> Samples(const std::vector<double>& x, int per_interval) {
  std::vector<double> samples;
  for (size_t i = 0; i + 1 < x.size(); ++i) {
    for (int s = 0; s < per_interval; ++s) {
      samples.push_back(x[i] + (x[i + 1] - x[i]) * s / per_interval);
    }
  }
  samples.push_back(x.back());
  return samples;
}

std::vector<double> CubicAt(const std::vector<double>& x, int order) {
  std::vector<double> values;
  for (double value : x) {
    const std::vector<double> y = Cubic(value, order);
    values.insert(values.end(), y.begin(), y.end());
  }
  return values;
}

TEST(CubicSplineTest, ClampedAndNotAKnotReproduceCubics) {
  std::mt19937_64 rng(5);
  for (int count : {2, 3, 4, 5, 9, 30}) {
    const std::vector<double> x = SortedAbscissas(rng, count);
    const std::vector<double> y = CubicAt(x, 0);
    const std::vector<double> start = Cubic(x.front(), 1);
    const std::vector<double> end = Cubic(x.back(), 1);
    const std::vector<double> samples = Samples(x, 7);
    const std::vector<double> expected = CubicAt(samples, 0);
    absl::StatusOr<CurveInterpolation> clamped = InterpolateCubicSpline(
        {.dimension = 2, .coordinates = y}, x, SplineEnd::kClamped, start, end);
    ASSERT_TRUE(clamped.ok()) << clamped.status();
    EXPECT_LT(MaxDifference(Evaluate(clamped->curve, samples, 1)[0], expected),
              1e-11 * MaxAbs(expected))
        << count;
    if (count < 4) continue;
    absl::StatusOr<CurveInterpolation> not_a_knot = InterpolateCubicSpline(
        {.dimension = 2, .coordinates = y}, x, SplineEnd::kNotAKnot, {}, {});
    ASSERT_TRUE(not_a_knot.ok()) << not_a_knot.status();
    EXPECT_LT(
        MaxDifference(Evaluate(not_a_knot->curve, samples, 1)[0], expected),
        1e-11 * MaxAbs(expected))
        << count;
    // Knots at every abscissa, as for the other end conditions.
    EXPECT_EQ(not_a_knot->curve.knots, clamped->curve.knots);
  }
}

TEST(CubicSplineTest, NotAKnotHasContinuousThirdDerivativeAtX1AndXnm1) {
  // s''' is constant on each interval of a cubic spline; not-a-knot makes
  // it the same on both sides of x_1 and of x_{n-1}, the knots that the
  // spline is solved without and that knot insertion puts back.
  std::mt19937_64 rng(11);
  for (int count : {4, 5, 9, 30}) {
    const std::vector<double> x = SortedAbscissas(rng, count);
    std::vector<double> y;
    for (double value : x) y.insert(y.end(), {std::sin(3 * value), value});
    absl::StatusOr<CurveInterpolation> spline = InterpolateCubicSpline(
        {.dimension = 2, .coordinates = y}, x, SplineEnd::kNotAKnot, {}, {});
    ASSERT_TRUE(spline.ok()) << spline.status();
    std::vector<double> midpoints;
    for (size_t i = 0; i + 1 < x.size(); ++i) {
      midpoints.push_back(0.5 * (x[i] + x[i + 1]));
    }
    const std::vector<double> third = Evaluate(spline->curve, midpoints, 4)[3];
    const double scale = MaxAbs(third);
    const size_t last = midpoints.size() - 1;
    for (const auto& [left, right] :
         {std::pair<size_t, size_t>{0, 1}, {last - 1, last}}) {
      EXPECT_NEAR(third[2 * left], third[2 * right], 1e-9 * scale)
          << count << " at interval " << left;
    }
    EXPECT_LT(MaxDifference(Evaluate(spline->curve, x, 1)[0], y),
              1e-12 * MaxAbs(y))
        << count;
  }
}

TEST(CubicSplineTest, NotAKnotWithThreePointsIsTheParabola) {
  const std::vector<double> x = {0, 1, 3};
  const std::vector<double> y = {1, 2, 10};  // y = 1 + x^2
  absl::StatusOr<CurveInterpolation> result = InterpolateCubicSpline(
      {.dimension = 1, .coordinates = y}, x, SplineEnd::kNotAKnot, {}, {});
  ASSERT_TRUE(result.ok()) << result.status();
  const std::vector<double> samples = {0, 0.5, 2, 2.5, 3};
  EXPECT_LT(MaxDifference(Evaluate(result->curve, samples, 1)[0],
                          {1, 1.25, 5, 7.25, 10}),
            1e-13);
}

// The classic natural spline: second derivatives M_i from the dense
// tridiagonal system h_{i-1} M_{i-1} + 2 (h_{i-1} + h_i) M_i + h_i M_{i+1} =
// 6 (d_i - d_{i-1}), M_0 = M_n = 0, then the piecewise cubic formula.
std::vector<double> NaturalReference(const std::vector<double>& x,
                                     const std::vector<double>& y,
                                     const std::vector<double>& samples) {
  const size_t n = x.size() - 1;
  std::vector<double> m(n + 1, 0.0);
  if (n >= 2) {
    const size_t size = n - 1;
    std::vector<std::vector<double>> a(size, std::vector<double>(size + 1));
    for (size_t i = 1; i < n; ++i) {
      const double h0 = x[i] - x[i - 1], h1 = x[i + 1] - x[i];
      if (i > 1) a[i - 1][i - 2] = h0;
      a[i - 1][i - 1] = 2 * (h0 + h1);
      if (i + 1 < n) a[i - 1][i] = h1;
      a[i - 1][size] = 6 * ((y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0);
    }
    for (size_t k = 0; k < size; ++k) {  // Gauss-Jordan, no pivoting needed
      for (size_t i = 0; i < size; ++i) {
        if (i == k) continue;
        const double f = a[i][k] / a[k][k];
        for (size_t j = k; j <= size; ++j) a[i][j] -= f * a[k][j];
      }
    }
    for (size_t i = 0; i < size; ++i) m[i + 1] = a[i][size] / a[i][i];
  }
  std::vector<double> values;
  for (double s : samples) {
    size_t i = 0;
    while (i + 1 < n && s >= x[i + 1]) ++i;
    const double h = x[i + 1] - x[i], l = x[i + 1] - s, r = s - x[i];
    values.push_back(
        m[i] * l * l * l / (6 * h) + m[i + 1] * r * r * r / (6 * h) +
        (y[i] / h - m[i] * h / 6) * l + (y[i + 1] / h - m[i + 1] * h / 6) * r);
  }
  return values;
}

TEST(CubicSplineTest, NaturalMatchesTridiagonalReference) {
  std::mt19937_64 rng(6);
  for (int count : {2, 3, 4, 7, 25}) {
    const std::vector<double> x = SortedAbscissas(rng, count);
    const std::vector<double> y = Random(rng, static_cast<size_t>(count));
    absl::StatusOr<CurveInterpolation> result = InterpolateCubicSpline(
        {.dimension = 1, .coordinates = y}, x, SplineEnd::kNatural, {}, {});
    ASSERT_TRUE(result.ok()) << result.status();
    const std::vector<double> samples = Samples(x, 5);
    EXPECT_LT(MaxDifference(Evaluate(result->curve, samples, 1)[0],
                            NaturalReference(x, y, samples)),
              1e-11)
        << count;
    const auto second = Evaluate(result->curve, {x.front(), x.back()}, 3)[2];
    EXPECT_NEAR(second[0], 0.0, 1e-9);
    EXPECT_NEAR(second[1], 0.0, 1e-9);
  }
}

TEST(CubicSplineTest, PeriodicIsC2Periodic) {
  std::mt19937_64 rng(7);
  for (int count : {3, 4, 5, 8, 12, 40}) {
    std::vector<double> x = SortedAbscissas(rng, count);
    const double period = x.back() - x.front();
    std::vector<double> y;
    for (double value : x) {
      const double angle = 2 * std::numbers::pi * (value - x.front()) / period;
      y.insert(y.end(), {std::cos(angle), std::sin(2 * angle) + 0.3, 2.0});
    }
    std::copy_n(y.begin(), 3, y.end() - 3);  // exact closure
    absl::StatusOr<CurveInterpolation> result = InterpolateCubicSpline(
        {.dimension = 3, .coordinates = y}, x, SplineEnd::kPeriodic, {}, {});
    ASSERT_TRUE(result.ok()) << result.status() << count;
    const BSplineCurveData& curve = result->curve;
    EXPECT_EQ(curve.knots[3], x.front());
    EXPECT_EQ(curve.knots[curve.knots.size() - 4], x.back());
    EXPECT_LT(RelativeMiss(curve, x, y), 1e-12);
    const auto ends = Evaluate(curve, {x.front(), x.back()}, 3);
    for (int order = 0; order < 3; ++order) {
      const auto& v = ends[static_cast<size_t>(order)];
      EXPECT_LT(
          MaxDifference({v.begin(), v.begin() + 3}, {v.begin() + 3, v.end()}),
          1e-12 * MaxAbs(v))
          << "order " << order << " count " << count;
    }
  }
}

// -------------------------------------------------------- least squares --

TEST(LeastSquaresTest, AllControlPointsInterpolate) {
  std::mt19937_64 rng(8);
  for (int p = 1; p <= 4; ++p) {
    const std::vector<double> points = SmoothPoints(rng, 12, 3, false);
    absl::StatusOr<CurveApproximation> result =
        ApproximateCurve({.dimension = 3, .coordinates = points}, p, 12,
                         Parameterization::kChordLength, {});
    ASSERT_TRUE(result.ok()) << result.status();
    EXPECT_LT(RelativeMiss(result->curve, result->parameters, points), 1e-10);
  }
}

TEST(LeastSquaresTest, FewerControlPointsBeatSampledControlPoints) {
  std::mt19937_64 rng(9);
  for (int p = 1; p <= 5; ++p) {
    for (int n : {p + 1, p + 3, 15}) {
      const int count = 40;
      const std::vector<double> points = SmoothPoints(rng, count, 2, false);
      absl::StatusOr<CurveApproximation> result =
          ApproximateCurve({.dimension = 2, .coordinates = points}, p, n,
                           Parameterization::kCentripetal, {});
      ASSERT_TRUE(result.ok()) << result.status();
      const auto& t = result->parameters;
      const auto values = Evaluate(result->curve, t, 1)[0];
      // End points interpolated.
      EXPECT_NEAR(values[0], points[0], 1e-13);
      EXPECT_NEAR(values[1], points[1], 1e-13);
      EXPECT_NEAR(values[values.size() - 1], points.back(), 1e-13);
      double max = 0, sum = 0;
      for (int k = 0; k < count; ++k) {
        const double dx = values[2 * k] - points[2 * k];
        const double dy = values[2 * k + 1] - points[2 * k + 1];
        max = std::max(max, std::hypot(dx, dy));
        sum += dx * dx + dy * dy;
      }
      EXPECT_NEAR(result->max_residual, max, 1e-14);
      EXPECT_NEAR(result->rms_residual, std::sqrt(sum / count), 1e-14);
      // An alternative on the same knots: control points sampled from the
      // data (evenly by index, ends kept).
      BSplineCurveData sampled = result->curve;
      for (int i = 0; i < n; ++i) {
        const int k =
            static_cast<int>(std::lround(1.0 * i * (count - 1) / (n - 1)));
        sampled.coordinates[2 * i] = points[2 * k];
        sampled.coordinates[2 * i + 1] = points[2 * k + 1];
      }
      const auto other = Evaluate(sampled, t, 1)[0];
      double other_sum = 0;
      for (size_t i = 0; i < other.size(); ++i) {
        other_sum += (other[i] - points[i]) * (other[i] - points[i]);
      }
      EXPECT_LE(result->rms_residual, std::sqrt(other_sum / count) + 1e-15);
    }
  }
}

// -------------------------------------------------------------- surface --

TEST(InterpolateSurfaceTest, PassesThroughGrid) {
  std::mt19937_64 rng(10);
  for (int p = 1; p <= 3; ++p) {
    for (int q = 1; q <= 3; ++q) {
      for (Parameterization parameterization : kParameterizations) {
        for (KnotRule rule : {KnotRule::kAveraging, KnotRule::kUniform}) {
          const int nu = p + 1 + static_cast<int>(rng() % 6);
          const int nv = q + 1 + static_cast<int>(rng() % 6);
          std::vector<double> grid;
          const std::vector<double> noise =
              Random(rng, static_cast<size_t>(3 * nu * nv));
          for (int k = 0; k < nu; ++k) {
            for (int l = 0; l < nv; ++l) {
              const size_t at = static_cast<size_t>(3 * (k * nv + l));
              grid.insert(grid.end(),
                          {k + 0.05 * noise[at], l + 0.05 * noise[at + 1],
                           noise[at + 2]});
            }
          }
          const ControlNetView net{.dimension = 3,
                                   .count_u = nu,
                                   .count_v = nv,
                                   .coordinates = grid};
          absl::StatusOr<SurfaceInterpolation> result =
              InterpolateSurface(net, p, q, parameterization, rule);
          ASSERT_TRUE(result.ok()) << result.status();
          std::vector<double> values(grid.size());
          const std::vector<absl::Span<double>> output = {
              absl::MakeSpan(values)};
          ASSERT_TRUE(
              EvaluateBSplineSurface(result->surface.bspline_view(),
                                     SurfaceSamples::Grid(result->parameters_u,
                                                          result->parameters_v),
                                     output)
                  .ok());
          EXPECT_LT(MaxDifference(values, grid), 1e-12 * MaxAbs(grid))
              << p << " " << q;
          EXPECT_LT(result->max_residual, 1e-12 * MaxAbs(grid));
        }
      }
    }
  }
}

// --------------------------------------------------------------- errors --

void ExpectField(const absl::Status& status, const std::string& field) {
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << status;
  EXPECT_EQ(FieldPathOf(status).value_or(""), field) << status;
}

TEST(InterpolateCurveTest, Errors) {
  const std::vector<double> repeated = {0, 0, 1, 1, 1, 1, 2, 0, 3, 1};
  ExpectField(
      InterpolateCurve({.dimension = 2, .coordinates = repeated}, {}).status(),
      "points.coordinates[4]");
  ExpectField(
      InterpolateCurve({.dimension = 2, .coordinates = repeated},
                       {.parameterization = Parameterization::kCentripetal})
          .status(),
      "points.coordinates[4]");
  EXPECT_TRUE(InterpolateCurve({.dimension = 2, .coordinates = repeated},
                               {.parameterization = Parameterization::kUniform})
                  .ok());
  const std::vector<double> three = {0, 0, 1, 1, 2, 0};
  ExpectField(
      InterpolateCurve({.dimension = 2, .coordinates = three}, {}).status(),
      "points.coordinates");
  ExpectField(
      InterpolateCurve({.dimension = 2, .coordinates = three}, {.degree = 0})
          .status(),
      "degree");
  const std::vector<double> bad_t = {0, 0.5, 0.5};
  ExpectField(InterpolateCurve({.dimension = 2, .coordinates = three},
                               {.degree = 2, .parameters = bad_t})
                  .status(),
              "parameters[2]");
  const std::vector<double> short_t = {0, 1};
  ExpectField(InterpolateCurve({.dimension = 2, .coordinates = three},
                               {.degree = 2, .parameters = short_t})
                  .status(),
              "parameters");
  const std::vector<double> one = {1};
  ExpectField(InterpolateCurve({.dimension = 2, .coordinates = three},
                               {.degree = 2, .start_derivative = one})
                  .status(),
              "start_derivative");
  ExpectField(InterpolateCurve({.dimension = 2, .coordinates = three},
                               {.degree = 2, .end_derivative = one})
                  .status(),
              "end_derivative");
  const std::vector<double> two = {1, 0};
  ExpectField(InterpolateCurve({.dimension = 2, .coordinates = three},
                               {.degree = 1, .start_derivative = two})
                  .status(),
              "start_derivative");
  // A closed curve must not repeat its first point.
  const std::vector<double> loop = {0, 0, 1, 0, 1, 1, 0, 0};
  ExpectField(InterpolateCurve({.dimension = 2, .coordinates = loop},
                               {.degree = 2, .closed = true})
                  .status(),
              "points.coordinates[6]");
}

TEST(CubicSplineTest, Errors) {
  const std::vector<double> y = {0, 1, 0, 1};
  const std::vector<double> x = {0, 1, 2, 3};
  const PointsView values{.dimension = 1, .coordinates = y};
  ExpectField(
      InterpolateCubicSpline(values, x, SplineEnd::kPeriodic, {}, {}).status(),
      "points");
  const std::vector<double> bad_x = {0, 1, 1, 3};
  ExpectField(InterpolateCubicSpline(values, bad_x, SplineEnd::kNatural, {}, {})
                  .status(),
              "parameters[2]");
  ExpectField(
      InterpolateCubicSpline(values, {0, 1, 2}, SplineEnd::kNatural, {}, {})
          .status(),
      "parameters");
  const std::vector<double> d = {1};
  ExpectField(
      InterpolateCubicSpline(values, x, SplineEnd::kClamped, {}, d).status(),
      "start_derivative");
  ExpectField(
      InterpolateCubicSpline(values, x, SplineEnd::kClamped, d, {}).status(),
      "end_derivative");
  ExpectField(
      InterpolateCubicSpline(values, x, SplineEnd::kNatural, d, {}).status(),
      "start_derivative");
  const std::vector<double> single = {1};
  ExpectField(InterpolateCubicSpline({.dimension = 1, .coordinates = single},
                                     single, SplineEnd::kNatural, {}, {})
                  .status(),
              "points.coordinates");
}

TEST(LeastSquaresTest, Errors) {
  std::mt19937_64 rng(11);
  const std::vector<double> points = Random(rng, 20);
  const PointsView view{.dimension = 2, .coordinates = points};
  ExpectField(
      ApproximateCurve(view, 3, 3, Parameterization::kChordLength, {}).status(),
      "control_point_count");
  ExpectField(ApproximateCurve(view, 3, 11, Parameterization::kChordLength, {})
                  .status(),
              "control_point_count");
  ExpectField(
      ApproximateCurve(view, 0, 5, Parameterization::kChordLength, {}).status(),
      "degree");
  EXPECT_TRUE(
      ApproximateCurve(view, 3, 4, Parameterization::kChordLength, {}).ok());
}

TEST(InterpolateSurfaceTest, Errors) {
  const std::vector<double> grid(2 * 3 * 3, 0.0);
  const ControlNetView net{
      .dimension = 3, .count_u = 2, .count_v = 3, .coordinates = grid};
  ExpectField(InterpolateSurface(net, 0, 1, Parameterization::kUniform,
                                 KnotRule::kAveraging)
                  .status(),
              "degree_u");
  ExpectField(InterpolateSurface(net, 2, 1, Parameterization::kUniform,
                                 KnotRule::kAveraging)
                  .status(),
              "points.count_u");
  ExpectField(InterpolateSurface(net, 1, 1, Parameterization::kChordLength,
                                 KnotRule::kAveraging)
                  .status(),
              "points");
}

// ------------------------------- knots at the parameters (OpenCASCADE) --
// docs/references.md,
// 'Interpolation with knots at the parameters (OpenCASCADE rule)'.

#include "occt_interpolate_reference.inc"

// The derivative at x of the polynomial through (nodes[i], values[i]), by
// the product rule on the Lagrange basis: sum_i values[i] sum_{k != i}
// 1 / (t_i - t_k) prod_{j != i, k} (x - t_j) / (t_i - t_j).
double LagrangeDerivative(const std::vector<double>& nodes,
                          const std::vector<double>& values, double x) {
  double derivative = 0;
  for (size_t i = 0; i < nodes.size(); ++i) {
    double basis = 0;
    for (size_t k = 0; k < nodes.size(); ++k) {
      if (k == i) continue;
      double product = 1 / (nodes[i] - nodes[k]);
      for (size_t j = 0; j < nodes.size(); ++j) {
        if (j != i && j != k) product *= (x - nodes[j]) / (nodes[i] - nodes[j]);
      }
      basis += product;
    }
    derivative += basis * values[i];
  }
  return derivative;
}

// LagrangeSlope differentiates, coordinate by coordinate, the polynomial
// through the points first..first+count-1 at their parameters.
std::vector<double> LagrangeSlope(const std::vector<double>& points,
                                  const std::vector<double>& t, int dimension,
                                  size_t first, size_t count, double x) {
  const std::vector<double> nodes(
      t.begin() + static_cast<ptrdiff_t>(first),
      t.begin() + static_cast<ptrdiff_t>(first + count));
  std::vector<double> slope;
  for (int c = 0; c < dimension; ++c) {
    std::vector<double> values;
    for (size_t k = first; k < first + count; ++k) {
      values.push_back(
          points[k * static_cast<size_t>(dimension) + static_cast<size_t>(c)]);
    }
    slope.push_back(LagrangeDerivative(nodes, values, x));
  }
  return slope;
}

std::vector<double> Times(double factor, std::vector<double> values) {
  for (double& value : values) value *= factor;
  return values;
}

// The control points `count` to the end of `curve` (flat).
std::vector<double> LastPoles(const BSplineCurveData& curve, size_t count) {
  const size_t d = static_cast<size_t>(curve.dimension);
  return std::vector<double>(
      curve.coordinates.end() - static_cast<ptrdiff_t>(count * d),
      curve.coordinates.end());
}

// Runs InterpolateCurve on a reference case as a caller migrating from
// GeomAPI_Interpolate would: the same points and parameters (chord lengths
// normalized to [0, 1] when OpenCASCADE computed them, so an unscaled
// tangent D becomes L D, L the polygon's length = OpenCASCADE's last knot).
absl::StatusOr<CurveInterpolation> InterpolateReferenceCase(
    const OcctInterpolateCase& c, std::vector<double>& start,
    std::vector<double>& end) {
  const double length =
      c.parameters.empty() ? c.knots.back() - c.knots.front() : 1.0;
  const double factor = c.scale ? 1.0 : length;
  start = Times(factor, c.start_tangent);
  end = Times(factor, c.end_tangent);
  return InterpolateCurve({.dimension = c.dimension, .coordinates = c.points},
                          {.degree = c.degree,
                           .parameters = c.parameters,
                           .knot_rule = KnotRule::kAtParameters,
                           .start_derivative = start,
                           .end_derivative = end,
                           .scale_end_derivatives = c.scale,
                           .closed = c.closed});
}

TEST(AtParametersTest, ReproducesOpenCascade) {
  ASSERT_EQ(OcctInterpolateCases().size(), 90u);
  double worst_pole = 0, worst_knot = 0;
  for (const OcctInterpolateCase& c : OcctInterpolateCases()) {
    SCOPED_TRACE(c.name);
    std::vector<double> start, end;
    absl::StatusOr<CurveInterpolation> result =
        InterpolateReferenceCase(c, start, end);
    ASSERT_TRUE(result.ok()) << result.status();
    const BSplineCurveData& curve = result->curve;
    EXPECT_EQ(curve.degree, c.degree);
    // A closed curve repeats its first degree - multiplicity(t_0) + 1
    // poles (2 for the cubic, 1 for the polygon).
    const size_t d = static_cast<size_t>(c.dimension);
    const size_t repeats =
        c.closed ? static_cast<size_t>(c.degree + 1 - c.multiplicities[0]) : 0;
    ASSERT_EQ(curve.coordinates.size(), c.poles.size() + repeats * d);
    std::vector<double> poles = c.poles;
    poles.insert(poles.end(), c.poles.begin(),
                 c.poles.begin() + static_cast<ptrdiff_t>(repeats * d));
    const double pole_error =
        MaxDifference(curve.coordinates, poles) / MaxAbs(c.poles);
    EXPECT_LT(pole_error, 1e-9);
    worst_pole = std::max(worst_pole, pole_error);
    // Knots: OpenCASCADE's are ours mapped affinely from our domain
    // [u_p, u_{n+1}] to its (the identity for given parameters).
    ASSERT_EQ(curve.knots.size(), c.flat_knots.size());
    const size_t p = static_cast<size_t>(c.degree);
    const size_t last = curve.knots.size() - 1 - p;
    const double scale = (c.flat_knots[last] - c.flat_knots[p]) /
                         (curve.knots[last] - curve.knots[p]);
    std::vector<double> mapped;
    for (double knot : curve.knots) {
      mapped.push_back(c.flat_knots[p] + scale * (knot - curve.knots[p]));
    }
    const double knot_error =
        MaxDifference(mapped, c.flat_knots) / MaxAbs(c.flat_knots);
    EXPECT_LT(knot_error, 1e-9);
    worst_knot = std::max(worst_knot, knot_error);
    EXPECT_LT(result->max_residual, 1e-9 * MaxAbs(c.points));
  }
  std::printf("worst relative pole difference %.3g, knot difference %.3g\n",
              worst_pole, worst_knot);
}

// The kAtParameters curve through `points` at the parameters t.
absl::StatusOr<CurveInterpolation> AtParameters(
    const std::vector<double>& points, int dimension,
    const std::vector<double>& t, absl::Span<const double> start,
    absl::Span<const double> end, bool scale) {
  return InterpolateCurve({.dimension = dimension, .coordinates = points},
                          {.parameters = t,
                           .knot_rule = KnotRule::kAtParameters,
                           .start_derivative = start,
                           .end_derivative = end,
                           .scale_end_derivatives = scale});
}

// The five planar points of 'Worked example: a cubic B-spline through five
// planar points' at OpenCASCADE's parameters, their chord lengths 0, 5, 9,
// 14, 17: the estimated end tangents are the derivatives of the Lagrange
// cubics through the first and the last four points, worked by hand in
// docs/references.md.
TEST(AtParametersTest, FivePlanarPointsWorkedExample) {
  const std::vector<double> t = {0, 5, 9, 14, 17};
  absl::StatusOr<CurveInterpolation> given =
      InterpolateCurve({.dimension = 2, .coordinates = kExercise5},
                       {.parameters = t, .knot_rule = KnotRule::kAtParameters});
  ASSERT_TRUE(given.ok()) << given.status();
  EXPECT_THAT(given->curve.knots,
              ElementsAre(0, 0, 0, 0, 5, 9, 14, 17, 17, 17, 17));
  ASSERT_EQ(given->curve.coordinates.size(), 14u);
  const std::vector<double> start = {694.0 / 315, 56.0 / 45};
  const std::vector<double> end = {103.0 / 360, -341.0 / 360};
  // The hand values agree with the product-rule derivative.
  EXPECT_LT(MaxDifference(LagrangeSlope(kExercise5, t, 2, 0, 4, 0), start),
            1e-15);
  EXPECT_LT(MaxDifference(LagrangeSlope(kExercise5, t, 2, 1, 4, 17), end),
            1e-15);
  const std::vector<std::vector<double>> derivatives =
      Evaluate(given->curve, {0, 17}, 2);
  EXPECT_LT(MaxDifference(derivatives[1], {start[0], start[1], end[0], end[1]}),
            1e-14);
  // P_1 = Q_0 + (5/3) C'(0), P_5 = Q_4 - (3/3) C'(17); P_2..P_4 solve the
  // rows C(5) = Q_1, C(9) = Q_2, C(14) = Q_3 (exact fractions in
  // docs/references.md).
  // clang-format off
  const std::vector<double> poles = {
      0, 0,
      694.0 / 189, 56.0 / 27,
      37961681.0 / 8633520, 5461219.0 / 1233360,
      -16594429.0 / 8633520, 5691449.0 / 1233360,
      -2245282.0 / 539595, 55202.0 / 77085,
      -1543.0 / 360, -739.0 / 360,
      -4, -3};
  // clang-format on
  EXPECT_LT(MaxDifference(given->curve.coordinates, poles), 1e-14);
  EXPECT_LT(given->max_residual, 1e-14);

  // Chord length normalized by L = 17: knots / 17, the same poles.
  absl::StatusOr<CurveInterpolation> normalized =
      InterpolateCurve({.dimension = 2, .coordinates = kExercise5},
                       {.knot_rule = KnotRule::kAtParameters});
  ASSERT_TRUE(normalized.ok()) << normalized.status();
  EXPECT_LT(MaxDifference(normalized->curve.knots,
                          Times(1.0 / 17, given->curve.knots)),
            1e-15);
  EXPECT_LT(
      MaxDifference(normalized->curve.coordinates, given->curve.coordinates),
      1e-13);
}

// With four points both estimated tangents are derivatives of the one
// cubic through them, which then satisfies every condition: the rule
// returns that cubic (compared with Neville's algorithm everywhere).
TEST(AtParametersTest, FourPointsGiveTheLagrangeCubic) {
  std::mt19937_64 rng(41);
  for (int dimension : {1, 2, 3}) {
    const std::vector<double> points = SmoothPoints(rng, 4, dimension, false);
    absl::StatusOr<CurveInterpolation> result =
        InterpolateCurve({.dimension = dimension, .coordinates = points},
                         {.knot_rule = KnotRule::kAtParameters});
    ASSERT_TRUE(result.ok()) << result.status();
    std::vector<double> samples;
    for (int k = 0; k <= 40; ++k) samples.push_back(k / 40.0);
    const std::vector<double> values = Evaluate(result->curve, samples, 1)[0];
    std::vector<double> cubic(values.size()), scratch(points.size());
    for (size_t k = 0; k < samples.size(); ++k) {
      NevilleEvaluate(
          {.dimension = dimension, .coordinates = points}, result->parameters,
          samples[k], absl::MakeSpan(scratch),
          absl::MakeSpan(cubic).subspan(k * static_cast<size_t>(dimension),
                                        static_cast<size_t>(dimension)));
    }
    EXPECT_LT(MaxDifference(values, cubic) / MaxAbs(points), 1e-13);
  }
}

// Three points without tangents: the parabola (one Bezier segment) with
// C(s) = Q_1 at s = (t_1 - t_0) / (t_2 - t_0), whose middle control point
// is P_1 = (Q_1 - (1 - s)^2 Q_0 - s^2 Q_2) / (2 s (1 - s)).
TEST(AtParametersTest, ThreePointsGiveTheParabola) {
  const std::vector<double> points = {0, 0, 3, 4, 7, 1};  // chords 5, 5
  absl::StatusOr<CurveInterpolation> result =
      InterpolateCurve({.dimension = 2, .coordinates = points},
                       {.degree = 2, .knot_rule = KnotRule::kAtParameters});
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_THAT(result->curve.knots, ElementsAre(0, 0, 0, 1, 1, 1));
  // s = 1/2: P_1 = 2 Q_1 - (Q_0 + Q_2) / 2 = (2.5, 7.5).
  EXPECT_LT(MaxDifference(result->curve.coordinates, {0, 0, 2.5, 7.5, 7, 1}),
            1e-14);
  const std::vector<double> t = {1, 2, 5};  // s = 1/4
  result = InterpolateCurve(
      {.dimension = 2, .coordinates = points},
      {.degree = 2, .parameters = t, .knot_rule = KnotRule::kAtParameters});
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_THAT(result->curve.knots, ElementsAre(1, 1, 1, 5, 5, 5));
  // (Q_1 - (9/16) Q_0 - (1/16) Q_2) / (3/8) = (41/16, 63/16) (8/3)
  // = (41/6, 21/2).
  EXPECT_LT(MaxDifference(result->curve.coordinates,
                          {0, 0, 41.0 / 6, 21.0 / 2, 7, 1}),
            1e-14);
}

// Two points: the segment, or with tangents the Hermite cubic
// Q_0, Q_0 + h D_0 / 3, Q_1 - h D_1 / 3, Q_1 (h = t_1 - t_0 = 5). Scaled
// tangents get the length of the chord's slope (3, 4) / 5 in the 1-norm:
// |(0.6, 0.8, 0)|_1 / |D|_1 = 1.4 / 3.5 = 0.4 for both.
TEST(AtParametersTest, TwoPointsGiveTheSegmentOrTheHermiteCubic) {
  const std::vector<double> points = {0, 0, 0, 3, 4, 0};
  const std::vector<double> t = {0, 5};
  absl::StatusOr<CurveInterpolation> line = InterpolateCurve(
      {.dimension = 3, .coordinates = points},
      {.degree = 1, .parameters = t, .knot_rule = KnotRule::kAtParameters});
  ASSERT_TRUE(line.ok()) << line.status();
  EXPECT_THAT(line->curve.knots, ElementsAre(0, 0, 5, 5));
  EXPECT_EQ(line->curve.coordinates, points);
  const std::vector<double> d0 = {1, 2, -0.5}, d1 = {-2, 0.5, 1};
  for (bool scale : {false, true}) {
    absl::StatusOr<CurveInterpolation> hermite =
        AtParameters(points, 3, t, d0, d1, scale);
    ASSERT_TRUE(hermite.ok()) << hermite.status();
    EXPECT_THAT(hermite->curve.knots, ElementsAre(0, 0, 0, 0, 5, 5, 5, 5));
    const std::vector<double> expected =
        scale ? std::vector<double>{0,        0,        0,        2.0 / 3,
                                    4.0 / 3,  -1.0 / 3, 13.0 / 3, 11.0 / 3,
                                    -2.0 / 3, 3,        4,        0}
              : std::vector<double>{0,        0,        0,        5.0 / 3,
                                    10.0 / 3, -5.0 / 6, 19.0 / 3, 19.0 / 6,
                                    -5.0 / 3, 3,        4,        0};
    EXPECT_LT(MaxDifference(hermite->curve.coordinates, expected), 1e-14);
  }
  // One tangent given: the other is the chord's slope (3, 4, 0) / 5.
  absl::StatusOr<CurveInterpolation> one_sided =
      AtParameters(points, 3, t, d0, {}, false);
  ASSERT_TRUE(one_sided.ok()) << one_sided.status();
  EXPECT_LT(
      MaxDifference(LastPoles(one_sided->curve, 2), {2, 8.0 / 3, 0, 3, 4, 0}),
      1e-14);
}

// OpenCASCADE scales both tangents with the parabola through the FIRST three
// points: (0,0), (1,1), (2,4) at 0, 1, 2 lie on (t, t^2), slope (1, 2t),
// |.|_1 = 1 at t = 0 and 9 at the end t = 4 (not the parabola through the
// last three points, whose slope there is (1, -3.5)). So D_0 = (0, 2)
// becomes (0, 1) and D_1 = (3, -1) becomes (9/4)(3, -1).
TEST(AtParametersTest, ScaledTangentsUseTheFirstThreePoints) {
  const std::vector<double> points = {0, 0, 1, 1, 2, 4, 3, 5, 4, 3};
  const std::vector<double> t = {0, 1, 2, 3, 4};
  const std::vector<double> d0 = {0, 2}, d1 = {3, -1};
  for (bool scale : {false, true}) {
    absl::StatusOr<CurveInterpolation> result =
        AtParameters(points, 2, t, d0, d1, scale);
    ASSERT_TRUE(result.ok()) << result.status();
    const std::vector<double> expected =
        scale ? std::vector<double>{0, 1, 27.0 / 4, -9.0 / 4}
              : std::vector<double>{0, 2, 3, -1};
    EXPECT_LT(MaxDifference(Evaluate(result->curve, {0, 4}, 2)[1], expected),
              1e-13);
  }
}

// Random data, every parameterization the rule takes: the knots are the
// parameters (t_0 and t_{N-1} four times), N + 2 poles, the curve passes
// through every point at its parameter, and its end derivatives are the
// given ones or the slopes of the Lagrange cubics through the end points.
TEST(AtParametersTest, KnotsAreTheParametersAndEndsAreMatched) {
  std::mt19937_64 rng(43);
  for (int count : {4, 5, 10, 50, 500}) {
    for (int dimension : {1, 2, 3}) {
      for (Parameterization parameterization :
           {Parameterization::kChordLength, Parameterization::kCentripetal,
            Parameterization::kUniform}) {
        for (bool given : {false, true}) {
          SCOPED_TRACE(testing::Message()
                       << count << " points, dimension " << dimension << ", "
                       << static_cast<int>(parameterization) << ", " << given);
          const std::vector<double> points =
              SmoothPoints(rng, count, dimension, false);
          const std::vector<double> d0 =
              given ? Random(rng, static_cast<size_t>(dimension))
                    : std::vector<double>();
          const std::vector<double> d1 =
              given ? Random(rng, static_cast<size_t>(dimension))
                    : std::vector<double>();
          absl::StatusOr<CurveInterpolation> result =
              InterpolateCurve({.dimension = dimension, .coordinates = points},
                               {.parameterization = parameterization,
                                .knot_rule = KnotRule::kAtParameters,
                                .start_derivative = d0,
                                .end_derivative = d1});
          ASSERT_TRUE(result.ok()) << result.status();
          const std::vector<double>& t = result->parameters;
          std::vector<double> knots(3, t.front());
          knots.insert(knots.end(), t.begin(), t.end());
          knots.insert(knots.end(), 3, t.back());
          EXPECT_EQ(result->curve.knots, knots);
          EXPECT_EQ(result->curve.coordinates.size(),
                    static_cast<size_t>((count + 2) * dimension));
          EXPECT_LT(RelativeMiss(result->curve, t, points), 1e-12);
          const size_t n = static_cast<size_t>(count);
          std::vector<double> ends =
              given ? d0 : LagrangeSlope(points, t, dimension, 0, 4, 0.0);
          const std::vector<double> end =
              given ? d1 : LagrangeSlope(points, t, dimension, n - 4, 4, 1.0);
          ends.insert(ends.end(), end.begin(), end.end());
          const std::vector<double> slopes =
              Evaluate(result->curve, {0.0, 1.0}, 2)[1];
          EXPECT_LT(MaxDifference(slopes, ends) / MaxAbs(ends), 1e-10);
        }
      }
    }
  }
}

// The same data at its unnormalized chord lengths (OpenCASCADE's
// parameters) and normalized to [0, 1]: scaled and estimated tangents give
// the same poles without conversion, and the knots differ by the factor L.
TEST(AtParametersTest, NormalizingTheParametersKeepsThePoles) {
  std::mt19937_64 rng(47);
  const std::vector<double> points = SmoothPoints(rng, 12, 3, false);
  std::vector<double> lengths = {0};
  for (size_t k = 1; k < 12; ++k) {
    double square = 0;
    for (size_t c = 0; c < 3; ++c) {
      const double step = points[3 * k + c] - points[3 * k + c - 3];
      square += step * step;
    }
    lengths.push_back(lengths.back() + std::sqrt(square));
  }
  const std::vector<double> d0 = {1, -1, 0.5};
  for (bool scale : {false, true}) {
    const std::vector<double> start = scale ? d0 : std::vector<double>();
    absl::StatusOr<CurveInterpolation> raw =
        InterpolateCurve({.dimension = 3, .coordinates = points},
                         {.parameters = lengths,
                          .knot_rule = KnotRule::kAtParameters,
                          .start_derivative = start,
                          .scale_end_derivatives = scale});
    absl::StatusOr<CurveInterpolation> normalized =
        InterpolateCurve({.dimension = 3, .coordinates = points},
                         {.knot_rule = KnotRule::kAtParameters,
                          .start_derivative = start,
                          .scale_end_derivatives = scale});
    ASSERT_TRUE(raw.ok()) << raw.status();
    ASSERT_TRUE(normalized.ok()) << normalized.status();
    EXPECT_LT(
        MaxDifference(raw->curve.coordinates, normalized->curve.coordinates) /
            MaxAbs(points),
        1e-13);
    EXPECT_LT(MaxDifference(raw->curve.knots,
                            Times(lengths.back(), normalized->curve.knots)),
              1e-12);
  }
}

// Closed curves: knots t_{N-2} - T, t_{N-1} - T, t_0, t_0, t_1, ...,
// t_{N-1}, t_N, t_N, t_1 + T, t_2 + T, the first two poles repeated at the
// end (a periodic B-spline), every point interpolated, and where the curve
// closes it returns to Q_0 with the same first derivative (the given one,
// or the slope of the cubic through the first four points).
TEST(AtParametersTest, ClosedCurvesAreC1WhereTheyClose) {
  std::mt19937_64 rng(53);
  for (int count : {3, 4, 5, 12, 100}) {
    for (int dimension : {2, 3}) {
      for (bool given : {false, true}) {
        SCOPED_TRACE(testing::Message() << count << " points, dimension "
                                        << dimension << ", " << given);
        const std::vector<double> points =
            SmoothPoints(rng, count, dimension, true);
        const std::vector<double> d0 =
            given ? Random(rng, static_cast<size_t>(dimension))
                  : std::vector<double>();
        absl::StatusOr<CurveInterpolation> result =
            InterpolateCurve({.dimension = dimension, .coordinates = points},
                             {.knot_rule = KnotRule::kAtParameters,
                              .start_derivative = d0,
                              .closed = true});
        ASSERT_TRUE(result.ok()) << result.status();
        const std::vector<double>& t = result->parameters;
        const size_t n = static_cast<size_t>(count);
        ASSERT_EQ(t.size(), n);
        std::vector<double> knots = {t[n - 2] - 1, t[n - 1] - 1, 0};
        knots.insert(knots.end(), t.begin(), t.end());
        knots.insert(knots.end(), {1, 1, 1 + t[1], 1 + t[2]});
        EXPECT_LT(MaxDifference(result->curve.knots, knots), 1e-15);
        const size_t d = static_cast<size_t>(dimension);
        ASSERT_EQ(result->curve.coordinates.size(), (n + 3) * d);
        EXPECT_EQ(LastPoles(result->curve, 2),
                  std::vector<double>(result->curve.coordinates.begin(),
                                      result->curve.coordinates.begin() +
                                          static_cast<ptrdiff_t>(2 * d)));
        EXPECT_LT(RelativeMiss(result->curve, t, points), 1e-12);
        const std::vector<std::vector<double>> seam =
            Evaluate(result->curve, {0.0, 1.0}, 2);
        std::vector<double> twice(points.begin(),
                                  points.begin() + static_cast<ptrdiff_t>(d));
        twice.insert(twice.end(), twice.begin(), twice.end());
        EXPECT_LT(MaxDifference(seam[0], twice) / MaxAbs(points), 1e-12);
        std::vector<double> slope =
            given ? d0
                  : LagrangeSlope(points, t, dimension, 0,
                                  std::min<size_t>(n, 4), 0.0);
        slope.insert(slope.end(), slope.begin(), slope.end());
        EXPECT_LT(MaxDifference(seam[1], slope) / MaxAbs(slope), 1e-10);
      }
    }
  }
  // Two points: the closed polygon Q_0, Q_1, Q_0 of degree 1.
  const std::vector<double> two = {0, 0, 3, 4};
  absl::StatusOr<CurveInterpolation> polygon = InterpolateCurve(
      {.dimension = 2, .coordinates = two},
      {.degree = 1, .knot_rule = KnotRule::kAtParameters, .closed = true});
  ASSERT_TRUE(polygon.ok()) << polygon.status();
  EXPECT_THAT(polygon->curve.knots, ElementsAre(-0.5, 0, 0.5, 1, 1.5));
  EXPECT_THAT(polygon->curve.coordinates, ElementsAre(0, 0, 3, 4, 0, 0));
}

TEST(AtParametersTest, Errors) {
  const std::vector<double> four = {0, 0, 1, 1, 2, 0, 3, 1};
  const PointsView points{.dimension = 2, .coordinates = four};
  const CurveInterpolationOptions rule{.knot_rule = KnotRule::kAtParameters};
  CurveInterpolationOptions options = rule;
  options.degree = 2;
  ExpectField(InterpolateCurve(points, options).status(), "degree");
  const PointsView three{.dimension = 2,
                         .coordinates = absl::MakeSpan(four).subspan(0, 6)};
  ExpectField(InterpolateCurve(three, rule).status(), "degree");  // needs 2
  const PointsView one{.dimension = 2,
                       .coordinates = absl::MakeSpan(four).subspan(0, 2)};
  ExpectField(InterpolateCurve(one, rule).status(), "points.coordinates");
  options = rule;
  options.parameterization = Parameterization::kUniversal;
  ExpectField(InterpolateCurve(points, options).status(), "parameterization");
  const std::vector<double> d = {1, 0}, zero = {0, 0}, short_d = {1};
  options = rule;
  options.closed = true;
  options.end_derivative = d;
  ExpectField(InterpolateCurve(points, options).status(), "end_derivative");
  options = rule;
  options.start_derivative = short_d;
  ExpectField(InterpolateCurve(points, options).status(), "start_derivative");
  options = rule;
  options.end_derivative = zero;
  EXPECT_TRUE(InterpolateCurve(points, options).ok());  // a zero derivative
  options.scale_end_derivatives = true;  // has no direction to scale
  ExpectField(InterpolateCurve(points, options).status(), "end_derivative");
  options = CurveInterpolationOptions{};
  options.scale_end_derivatives = true;
  ExpectField(InterpolateCurve(points, options).status(),
              "scale_end_derivatives");
  const std::vector<double> bad_t = {0, 1, 1, 2};
  options = rule;
  options.parameters = bad_t;
  ExpectField(InterpolateCurve(points, options).status(), "parameters[2]");
  const std::vector<double> grid(3 * 4 * 4, 1.0);
  ExpectField(
      InterpolateSurface(
          {.dimension = 3, .count_u = 4, .count_v = 4, .coordinates = grid}, 3,
          3, Parameterization::kUniform, KnotRule::kAtParameters)
          .status(),
      "knot_rule");
}

}  // namespace
}  // namespace freeform
