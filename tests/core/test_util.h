// Small helpers shared by the core tests: random data and evenly spaced
// parameters.
#ifndef FREEFORM_TESTS_CORE_TEST_UTIL_H_
#define FREEFORM_TESTS_CORE_TEST_UTIL_H_

#include <cstddef>
#include <random>
#include <vector>

namespace freeform::testing_util {

// RandomValues returns `count` values drawn uniformly from [lo, hi).
inline std::vector<double> RandomValues(std::mt19937_64& rng, size_t count,
                                        double lo = -1.0, double hi = 1.0) {
  std::uniform_real_distribution<double> uniform(lo, hi);
  std::vector<double> values(count);
  for (double& value : values) value = uniform(rng);
  return values;
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

}  // namespace freeform::testing_util

#endif  // FREEFORM_TESTS_CORE_TEST_UTIL_H_
