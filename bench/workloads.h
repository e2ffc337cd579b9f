// The data of the benchmark workloads (docs/benchmarks.md): the LCG,
// uniform parameters and clamped uniform knots, so every benchmark program
// computes exactly the geometry the peers (OpenCASCADE, scipy, Eigen) do.
#ifndef FREEFORM_BENCH_WORKLOADS_H_
#define FREEFORM_BENCH_WORKLOADS_H_

#include <cstddef>
#include <cstdint>
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

}  // namespace freeform::bench

#endif  // FREEFORM_BENCH_WORKLOADS_H_
