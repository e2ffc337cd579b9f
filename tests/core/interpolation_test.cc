#include "freeform/core/interpolation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "freeform/core/bspline.h"
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

}  // namespace
}  // namespace freeform
