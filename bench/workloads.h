// The data of the benchmark workloads (docs/benchmarks.md): the LCG,
// uniform parameters, clamped uniform knots, random splines and query
// points, so every benchmark program computes exactly the geometry the peers
// (OpenCASCADE, scipy, Eigen; bench/peers/) do.
#ifndef FREEFORM_BENCH_WORKLOADS_H_
#define FREEFORM_BENCH_WORKLOADS_H_

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace freeform::bench {

// The workloads' LCG: Next() is rnd() in [-1, 1).
class Lcg {
 public:
  explicit Lcg(uint64_t seed) : state_(seed) {}
  double Next() {
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    const double unit = static_cast<double>(state_ >> 11) * 0x1.0p-53;
    return 2.0 * unit - 1.0;
  }

 private:
  uint64_t state_;
};

// `count` points of `dimension` coordinates drawn from seed `seed`.
inline std::vector<double> RandomPoints(uint64_t seed, size_t count,
                                        int dimension) {
  Lcg lcg(seed);
  std::vector<double> points(count * static_cast<size_t>(dimension));
  for (double& value : points) value = lcg.Next();
  return points;
}

// t_k = k / (N - 1), k = 0..N-1.
inline std::vector<double> UniformParameters(size_t count) {
  std::vector<double> parameters(count);
  for (size_t k = 0; k < count; ++k) {
    parameters[k] = static_cast<double>(k) / static_cast<double>(count - 1);
  }
  return parameters;
}

// p + 1 zeros, i / (n - p) for i = 1..n-p-1, p + 1 ones (n control points).
inline std::vector<double> ClampedUniformKnots(int count, int degree) {
  std::vector<double> knots(static_cast<size_t>(degree) + 1, 0.0);
  for (int i = 1; i < count - degree; ++i) {
    knots.push_back(static_cast<double>(i) / (count - degree));
  }
  knots.insert(knots.end(), static_cast<size_t>(degree) + 1, 1.0);
  return knots;
}

// A clamped B-spline curve's data (polynomial).
struct SplineData {
  int degree = 3;
  int dimension = 3;
  std::vector<double> points;  // `dimension` coordinates each
  std::vector<double> knots;
};

// RandomSpline returns the clamped B-spline of `degree` on clamped uniform
// knots whose `count` control points of `dimension` coordinates are drawn
// from LCG seed `seed` (W1: seed 1, 100 points, 3D, cubic).
inline SplineData RandomSpline(uint64_t seed, int count, int dimension,
                               int degree = 3) {
  return {.degree = degree,
          .dimension = dimension,
          .points = RandomPoints(seed, static_cast<size_t>(count), dimension),
          .knots = ClampedUniformKnots(count, degree)};
}

// PointsInBox returns `count` points drawn from LCG seed `seed`, uniform in
// the bounding box of `points` (of `dimension` coordinates) scaled about its
// centre by `scale` (1.1: inflated by 10%).
inline std::vector<double> PointsInBox(const std::vector<double>& points,
                                       int dimension, double scale,
                                       uint64_t seed, size_t count) {
  const size_t dim = static_cast<size_t>(dimension);
  std::vector<double> lo(dim, std::numeric_limits<double>::infinity());
  std::vector<double> hi(dim, -std::numeric_limits<double>::infinity());
  for (size_t k = 0; k < points.size(); ++k) {
    lo[k % dim] = std::min(lo[k % dim], points[k]);
    hi[k % dim] = std::max(hi[k % dim], points[k]);
  }
  Lcg lcg(seed);
  std::vector<double> result(count * dim);
  for (size_t k = 0; k < result.size(); ++k) {
    const double centre = 0.5 * (lo[k % dim] + hi[k % dim]);
    const double half = 0.5 * scale * (hi[k % dim] - lo[k % dim]);
    result[k] = centre + half * lcg.Next();
  }
  return result;
}

// W5Points returns W5's `count` points P_i = (10 cos(0.01 i) + 0.1 r1,
// 10 sin(0.01 i) + 0.1 r2, 0.01 i + 0.1 r3), with r1, r2, r3 drawn in that
// order from LCG seed 4 for each i (3 coordinates a point).
inline std::vector<double> W5Points(size_t count) {
  Lcg lcg(4);
  std::vector<double> points;
  points.reserve(3 * count);
  for (size_t i = 0; i < count; ++i) {
    const double t = 0.01 * static_cast<double>(i);
    const double r1 = lcg.Next();
    const double r2 = lcg.Next();
    const double r3 = lcg.Next();
    points.push_back(10 * std::cos(t) + 0.1 * r1);
    points.push_back(10 * std::sin(t) + 0.1 * r2);
    points.push_back(t + 0.1 * r3);
  }
  return points;
}

}  // namespace freeform::bench

#endif  // FREEFORM_BENCH_WORKLOADS_H_
