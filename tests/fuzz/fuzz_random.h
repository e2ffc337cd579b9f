// FuzzRandom: the random choices of the structure-aware mutator
// (request_mutator.h), drawn from a std::mt19937_64 seeded with libFuzzer's
// seed, so that a mutation is a function of the input and the seed. The
// draws use only the engine's raw output (no std distribution, whose
// results differ between standard libraries). Not thread-safe.
#ifndef FREEFORM_TESTS_FUZZ_FUZZ_RANDOM_H_
#define FREEFORM_TESTS_FUZZ_FUZZ_RANDOM_H_

#include <cstddef>
#include <cstdint>
#include <random>

#include "absl/types/span.h"

namespace freeform::fuzz {

class FuzzRandom {
 public:
  explicit FuzzRandom(uint64_t seed) : engine_(seed) {}

  uint64_t Next() { return engine_(); }

  // Below returns a value in [0, n), or 0 when n is 0.
  size_t Below(size_t n) {
    return n == 0 ? 0 : static_cast<size_t>(engine_() % n);
  }

  // Between returns a value in [lo, hi] (lo <= hi).
  int64_t Between(int64_t lo, int64_t hi) {
    return lo + static_cast<int64_t>(
                    Below(static_cast<size_t>(hi - lo) + size_t{1}));
  }

  // OneIn is true with probability 1 / n.
  bool OneIn(size_t n) { return Below(n) == 0; }

  // Unit returns a value in [0, 1) with 53 random bits.
  double Unit() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  // Pick returns one element of a non-empty span.
  template <typename T>
  const T& Pick(absl::Span<const T> values) {
    return values[Below(values.size())];
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace freeform::fuzz

#endif  // FREEFORM_TESTS_FUZZ_FUZZ_RANDOM_H_
