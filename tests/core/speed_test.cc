// The speed of curve nets and the cuts of the arc-length quadrature at its
// sharp minima (queries/speed.h, queries/speed_minima.h), against direct
// evaluation and dense sampling.
#include "queries/speed.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "queries/bezier_net.h"
#include "queries/speed_minima.h"

namespace freeform::internal {
namespace {

// The net of the polynomial Bezier curve with control points `points`
// (`dimension` values each).
Net PolynomialNet(int dimension, std::vector<double> points) {
  const int count = static_cast<int>(points.size()) / dimension;
  return Net{.dimension = dimension,
             .rational = false,
             .count_u = count,
             .values = std::move(points)};
}

// SampledSpeed returns |C'(s)| of a polynomial net by the power form of
// the Bernstein derivative: n sum_i (P_{i+1} - P_i) B_i^{n-1}(s).
double SampledSpeed(const Net& net, double s) {
  const int n = net.count_u - 1;
  std::vector<double> derivative(static_cast<size_t>(net.dimension), 0.0);
  for (int i = 0; i < n; ++i) {
    const double basis = std::tgamma(n) /
                         (std::tgamma(i + 1) * std::tgamma(n - i)) *
                         std::pow(s, i) * std::pow(1.0 - s, n - 1 - i);
    for (int x = 0; x < net.dimension; ++x) {
      derivative[x] += n * basis *
                       (net.values[(i + 1) * net.dimension + x] -
                        net.values[i * net.dimension + x]);
    }
  }
  double squared = 0.0;
  for (const double v : derivative) squared += v * v;
  return std::sqrt(squared);
}

TEST(SpeedTest, BatchedSpeedsAreTheSingleSpeeds) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> value(-2.0, 2.0);
  std::uniform_real_distribution<double> weight(0.25, 4.0);
  for (const bool rational : {false, true}) {
    for (int count = 1; count <= 7; ++count) {
      Net net{.dimension = 3, .rational = rational, .count_u = count};
      for (int i = 0; i < count; ++i) {
        const double w = rational ? weight(random) : 1.0;
        for (int x = 0; x < 3; ++x) net.values.push_back(w * value(random));
        if (rational) net.values.push_back(w);
      }
      SpeedIntegrator integrator;
      SpeedIntegrator::Nodes s;
      for (size_t k = 0; k < s.size(); ++k)
        s[k] = (static_cast<double>(k) + 0.5) / kSpeedRulePoints;
      SpeedIntegrator::Nodes speeds;
      integrator.Speeds(net, s, speeds);
      for (size_t k = 0; k < s.size(); ++k) {
        EXPECT_EQ(speeds[k], integrator.Speed(net, s[k]))
            << "count " << count << " rational " << rational << " node " << k;
      }
    }
  }
}

TEST(SpeedTest, SpeedIsTheDerivativesNorm) {
  // x = (s - 1/2)^3, y = s / 100: x' = 3 (s - 1/2)^2, y' = 1/100.
  const Net net = PolynomialNet(
      2, {-0.125, 0.0, 0.125, 1.0 / 300, -0.125, 2.0 / 300, 0.125, 0.01});
  SpeedIntegrator integrator;
  for (const double s : {0.0, 0.1, 0.5, 0.75, 1.0}) {
    const double x = 3 * (s - 0.5) * (s - 0.5);
    EXPECT_NEAR(integrator.Speed(net, s), std::hypot(x, 0.01), 1e-15) << s;
    EXPECT_NEAR(integrator.Speed(net, s), SampledSpeed(net, s), 1e-14) << s;
  }
}

TEST(SpeedMinimaTest, CutsAtTheSharpMinimumOfAnInflectingCubic) {
  // The speed hypot(3 (s - 1/2)^2, 1/100) falls to 1/100 at s = 1/2, far
  // below a quarter of its bound (3 max |P_{i+1} - P_i| = 0.75).
  const Net net = PolynomialNet(
      2, {-0.125, 0.0, 0.125, 1.0 / 300, -0.125, 2.0 / 300, 0.125, 0.01});
  SpeedIntegrator integrator;
  SpeedMinimaSearch search;
  const absl::Span<const double> cuts = search.Cuts(net, integrator);
  ASSERT_EQ(cuts.size(), 3u);
  EXPECT_EQ(cuts[0], 0.0);
  EXPECT_NEAR(cuts[1], 0.5, std::ldexp(1.0, -30));
  EXPECT_EQ(cuts[2], 1.0);
}

TEST(SpeedMinimaTest, AStraightOrGentleCurveIsNotCut) {
  SpeedIntegrator integrator;
  SpeedMinimaSearch search;
  // A line, and a quarter-circle-like arc whose speed varies by 10%.
  for (const Net& net : {PolynomialNet(2, {0, 0, 1, 1, 2, 2, 3, 3}),
                         PolynomialNet(2, {1, 0, 1, 0.55, 0.55, 1, 0, 1})}) {
    const absl::Span<const double> cuts = search.Cuts(net, integrator);
    EXPECT_EQ(std::vector<double>(cuts.begin(), cuts.end()),
              (std::vector<double>{0.0, 1.0}));
  }
}

// Every local minimum of the speed, sampled densely, that falls below a
// quarter of the hodograph's bound (with a margin for the sampling) has a
// cut near it; every cut is at a speed below that quarter.
TEST(SpeedMinimaTest, EverySharpSampledMinimumHasACut) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  constexpr int kSamples = 4000;
  SpeedIntegrator integrator;
  SpeedMinimaSearch search;
  int sharp_minima = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int count = 3 + trial % 5;
    std::vector<double> points;
    for (int i = 0; i < 2 * count; ++i) points.push_back(value(random));
    const Net net = PolynomialNet(2, points);
    double bound = 0.0;
    for (int i = 0; i + 1 < count; ++i) {
      bound =
          std::max(bound, std::hypot(points[2 * i + 2] - points[2 * i],
                                     points[2 * i + 3] - points[2 * i + 1]));
    }
    bound *= count - 1;
    const absl::Span<const double> cuts = search.Cuts(net, integrator);
    for (size_t k = 1; k + 1 < cuts.size(); ++k) {
      EXPECT_LT(SampledSpeed(net, cuts[k]), 0.25 * bound * (1 + 1e-9));
    }
    std::vector<double> speeds(kSamples + 1);
    for (int j = 0; j <= kSamples; ++j) {
      speeds[j] = SampledSpeed(net, static_cast<double>(j) / kSamples);
    }
    for (int j = 1; j < kSamples; ++j) {
      if (!(speeds[j] < speeds[j - 1] && speeds[j] <= speeds[j + 1])) continue;
      if (speeds[j] > 0.24 * bound) continue;
      ++sharp_minima;
      const double s = static_cast<double>(j) / kSamples;
      const bool cut =
          std::any_of(cuts.begin() + 1, cuts.end() - 1,
                      [s](double c) { return std::abs(c - s) <= 1e-3; });
      EXPECT_TRUE(cut) << "trial " << trial << " minimum at " << s;
    }
  }
  EXPECT_GT(sharp_minima, 50);
}

}  // namespace
}  // namespace freeform::internal
