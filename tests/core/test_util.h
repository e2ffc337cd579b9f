// Small helpers shared by the core tests (and a few service tests):
// random data, random knot vectors, evenly spaced parameters, a long-double
// Bezier reference and distances to power curves.
#ifndef FREEFORM_TESTS_CORE_TEST_UTIL_H_
#define FREEFORM_TESTS_CORE_TEST_UTIL_H_

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

namespace freeform::testing_util {

// DistanceToPowerCurve bounds the distance from (x, y) to the curve
// (s, s^power) from above: the distance to its point nearest after Newton
// steps on the squared distance from s = x.
inline double DistanceToPowerCurve(double x, double y, int power) {
  double s = x;
  for (int step = 0; step < 8; ++step) {
    const double f = std::pow(s, power);
    const double df = power * std::pow(s, power - 1);
    const double ddf = power * (power - 1) * std::pow(s, power - 2);
    const double gradient = (s - x) + (f - y) * df;
    const double curvature = 1 + df * df + (f - y) * ddf;
    if (!(curvature > 0)) break;
    s -= gradient / curvature;
  }
  return std::min(std::hypot(s - x, std::pow(s, power) - y),
                  std::fabs(y - std::pow(x, power)));
}

// RandomValues returns `count` values drawn uniformly from [lo, hi).
inline std::vector<double> RandomValues(std::mt19937_64& rng, size_t count,
                                        double lo = -1.0, double hi = 1.0) {
  std::uniform_real_distribution<double> uniform(lo, hi);
  std::vector<double> values(count);
  for (double& value : values) value = uniform(rng);
  return values;
}

// MaxAbs returns the largest magnitude in `values` (0 when empty).
inline double MaxAbs(const std::vector<double>& values) {
  double result = 0.0;
  for (const double value : values) result = std::max(result, std::fabs(value));
  return result;
}

// MaxDifference returns the largest |a[i] - b[i]|, or infinity when the
// sizes differ (so that a check against a bound fails).
inline double MaxDifference(const std::vector<double>& a,
                            const std::vector<double>& b) {
  if (a.size() != b.size()) return INFINITY;
  double result = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    result = std::max(result, std::fabs(a[i] - b[i]));
  }
  return result;
}

// EvenlySpaced returns `count` >= 2 values from `start` to `end`, both
// included exactly.
inline std::vector<double> EvenlySpaced(double start, double end,
                                        size_t count) {
  std::vector<double> values(count);
  for (size_t i = 0; i < count; ++i) {
    values[i] = start + (end - start) * static_cast<double>(i) /
                            static_cast<double>(count - 1);
  }
  values.back() = end;
  return values;
}

// Lengths of runs of equal knots adding up to `count`: mostly simple
// knots, some repeated up to p times.
inline std::vector<int> RandomRuns(std::mt19937_64& rng, int p, int count) {
  std::vector<int> runs;
  std::bernoulli_distribution repeat(0.3);
  for (int left = count; left > 0;) {
    int run = 1;
    if (p > 1 && repeat(rng)) {
      run = std::uniform_int_distribution<int>(2, p)(rng);
    }
    run = std::min(run, left);
    runs.push_back(run);
    left -= run;
  }
  return runs;
}

// n + p + 2 knots with spans of comparable length and interior knots
// repeated up to p times. Clamped: p + 1 zeros and p + 1 ones at the ends.
// Unclamped: every knot drawn, the domain [u_p, u_{n+1}] somewhere inside.
inline std::vector<double> RandomKnots(std::mt19937_64& rng, int p, int n,
                                       bool clamped) {
  const int m = n + p + 2;
  std::uniform_real_distribution<double> gap(0.2, 1.0);
  while (true) {
    const std::vector<int> runs = RandomRuns(rng, p, clamped ? n - p : m);
    std::vector<double> values;
    double position = clamped ? 0.0 : -gap(rng);
    for (size_t r = 0; r <= runs.size(); ++r) {
      position += gap(rng);
      values.push_back(position);
    }
    std::vector<double> knots;
    if (clamped) knots.assign(static_cast<size_t>(p) + 1, 0.0);
    for (size_t r = 0; r < runs.size(); ++r) {
      const double value = clamped ? values[r] / values.back() : values[r];
      knots.insert(knots.end(), static_cast<size_t>(runs[r]), value);
    }
    if (clamped) knots.insert(knots.end(), static_cast<size_t>(p) + 1, 1.0);
    if (knots[static_cast<size_t>(p)] < knots[static_cast<size_t>(n + 1)]) {
      return knots;
    }
  }
}

// LongDoubleDeCasteljau returns the point at t of the Bezier curve with
// control points `points`, by de Casteljau in long double: the reference for
// accuracy.
inline std::vector<long double> LongDoubleDeCasteljau(
    const std::vector<double>& points, int dimension, long double t) {
  std::vector<long double> levels(points.begin(), points.end());
  const int n = static_cast<int>(points.size()) / dimension - 1;
  for (int m = n; m > 0; --m) {
    for (int x = 0; x < m * dimension; ++x) {
      levels[x] = (1.0L - t) * levels[x] + t * levels[x + dimension];
    }
  }
  levels.resize(static_cast<size_t>(dimension));
  return levels;
}

}  // namespace freeform::testing_util

#endif  // FREEFORM_TESTS_CORE_TEST_UTIL_H_
