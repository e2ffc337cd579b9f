// CoreFuzzInput: what the core fuzzers share. It reads the parts of a
// geometry (sizes, knot vectors, coordinates, weights, parameters) from
// libFuzzer's bytes and remembers whether any value was "wild" (NaN,
// infinity, or any bit pattern at all): such geometry must be refused or
// handled without a crash, while geometry of moderate values must also
// give answers that are finite and right (partition of unity, ...). The
// checks abort() so libFuzzer records the input.
#ifndef FREEFORM_TESTS_FUZZ_CORE_FUZZ_INPUT_H_
#define FREEFORM_TESTS_FUZZ_CORE_FUZZ_INPUT_H_

#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "freeform/core/status.h"

namespace freeform::fuzz {

[[noreturn]] inline void Fail(absl::string_view what) {
  std::fprintf(stderr, "\ncore fuzzer: %s\n", std::string(what).c_str());
  std::abort();
}

inline void Check(bool condition, absl::string_view what) {
  if (!condition) Fail(what);
}

// CheckRefusal checks that a refused geometry is INVALID_ARGUMENT naming
// the field at fault.
inline void CheckRefusal(const absl::Status& status, absl::string_view what) {
  Check(status.code() == absl::StatusCode::kInvalidArgument,
        absl::StrCat(what, " refused with ", status.ToString()));
  const std::optional<std::string> field = FieldPathOf(status);
  Check(
      field.has_value() && !field->empty(),
      absl::StrCat(what, " refused without a field path: ", status.ToString()));
}

// CheckNear checks |actual - expected| <= tolerance * scale.
inline void CheckNear(double actual, double expected, double scale,
                      absl::string_view what, double tolerance = 1e-8) {
  Check(std::abs(actual - expected) <= tolerance * std::max(1.0, scale),
        absl::StrCat(what, ": ", actual, " instead of ", expected, " (scale ",
                     scale, ")"));
}

inline void CheckFinite(absl::Span<const double> values,
                        absl::string_view what) {
  for (size_t i = 0; i < values.size(); ++i) {
    Check(std::isfinite(values[i]),
          absl::StrCat(what, "[", i, "] is ", values[i]));
  }
}

// OutputBuffers holds the buffers of an evaluation: one per derivative
// order (curves) or partial (surfaces), each of `values` doubles.
struct OutputBuffers {
  OutputBuffers(size_t buffers, size_t values)
      : storage(buffers, std::vector<double>(values)) {
    for (std::vector<double>& buffer : storage) {
      spans.push_back(absl::MakeSpan(buffer));
    }
  }
  OutputBuffers(const OutputBuffers&) = delete;
  OutputBuffers& operator=(const OutputBuffers&) = delete;

  std::vector<std::vector<double>> storage;
  std::vector<absl::Span<double>> spans;
};

// CheckSumsTo checks that the `functions` values at each of `count`
// points (values[r * functions + i]) sum to `expected`, to a tolerance
// relative to the sum of their magnitudes or to `scale_floor`, the size of
// the terms the values were computed from, when that is larger.
inline void CheckSumsTo(absl::Span<const double> values, size_t count,
                        size_t functions, double expected,
                        absl::string_view what, double scale_floor = 0) {
  for (size_t r = 0; r < count; ++r) {
    double sum = 0;
    double scale = scale_floor;
    for (size_t i = 0; i < functions; ++i) {
      sum += values[r * functions + i];
      scale += std::abs(values[r * functions + i]);
    }
    CheckNear(sum, expected, scale, absl::StrCat(what, " at point ", r));
  }
}

// CheckBasisTimesPoints checks that `result` (count points of `dimension`)
// is the basis values (count x functions) times the points (functions x
// dimension), to a tolerance relative to the terms' magnitudes or to
// `basis_scale_floor` (as in CheckSumsTo) times the largest coordinate.
inline void CheckBasisTimesPoints(absl::Span<const double> result,
                                  absl::Span<const double> basis,
                                  absl::Span<const double> points,
                                  int dimension, size_t count, size_t functions,
                                  absl::string_view what,
                                  double basis_scale_floor = 0) {
  const size_t d = static_cast<size_t>(dimension);
  double largest_coordinate = 0;
  for (const double coordinate : points) {
    largest_coordinate = std::max(largest_coordinate, std::abs(coordinate));
  }
  for (size_t r = 0; r < count; ++r) {
    for (size_t j = 0; j < d; ++j) {
      double sum = 0;
      double scale = basis_scale_floor * largest_coordinate;
      for (size_t i = 0; i < functions; ++i) {
        const double term = basis[r * functions + i] * points[i * d + j];
        sum += term;
        scale += std::abs(term);
      }
      CheckNear(result[r * d + j], sum, scale,
                absl::StrCat(what, " at point ", r, ", coordinate ", j));
    }
  }
}

class CoreFuzzInput {
 public:
  CoreFuzzInput(const uint8_t* data, size_t size) : provider_(data, size) {}

  // wild is true once any value came from raw bits.
  bool wild() const { return wild_; }

  int Int(int lo, int hi) { return provider_.ConsumeIntegralInRange(lo, hi); }
  bool Bool() { return provider_.ConsumeBool(); }
  double Probability() { return provider_.ConsumeProbability<double>(); }

  // Count returns `exact` most of the time, else any count in [0, max]: a
  // size that may not match the structure.
  int Count(int exact, int max) {
    return provider_.ConsumeIntegralInRange(0, 7) != 0 ? exact : Int(0, max);
  }

  // Value returns a moderate number (small multiples of 1/4 up to +-64, or
  // values up to +-1e6), or, rarely, a wild one.
  double Value() {
    switch (provider_.ConsumeIntegralInRange(0, 15)) {
      case 0:
        return Wild();
      case 1:
        return provider_.ConsumeFloatingPointInRange(-1e6, 1e6);
      default:
        return provider_.ConsumeIntegralInRange(-256, 256) / 4.0;
    }
  }

  // Weight returns a moderate weight (0 sometimes) or, rarely, a wild one.
  double Weight() {
    static constexpr double kWeights[] = {0, 0.25, 0.5, 1, 1, 1, 2, 4};
    const int pick = provider_.ConsumeIntegralInRange(0, 8);
    return pick == 8 ? Wild() : kWeights[pick];
  }

  // Values returns `count` Value()s.
  std::vector<double> Values(int count) {
    std::vector<double> values(static_cast<size_t>(std::max(0, count)));
    for (double& value : values) value = Value();
    return values;
  }

  // Weights returns none (polynomial) or Count(count, ...) weights.
  std::vector<double> Weights(int count) {
    if (Bool()) return {};
    std::vector<double> weights(static_cast<size_t>(Count(count, count + 2)));
    for (double& weight : weights) weight = Weight();
    return weights;
  }

  // Knots returns `count` knots: mostly non-decreasing with steps of
  // moderate sizes (0 often, for multiplicities), sometimes with a step
  // back or a wild value.
  std::vector<double> Knots(int count) {
    static constexpr double kSteps[] = {0, 0, 0, 1, 1, 0.5, 0.25, 2, 1e-3, 10};
    std::vector<double> knots(static_cast<size_t>(std::max(0, count)));
    double knot = provider_.ConsumeIntegralInRange(-8, 8) / 2.0;
    for (double& value : knots) {
      const int pick = provider_.ConsumeIntegralInRange(0, 11);
      if (pick == 10) {
        knot -= 1;
      } else if (pick == 11) {
        knot = Wild();
      } else {
        knot += kSteps[pick];
      }
      value = knot;
    }
    return knots;
  }

  // Parameter returns a point of [start, end]: an end or a fraction of the
  // way (exactly inside, whatever the rounding).
  double Parameter(double start, double end) {
    switch (provider_.ConsumeIntegralInRange(0, 3)) {
      case 0:
        return start;
      case 1:
        return end;
      default: {
        const double f = Probability();
        return std::clamp(start * (1 - f) + end * f, start, end);
      }
    }
  }

 private:
  double Wild() {
    wild_ = true;
    const uint64_t bits = provider_.ConsumeIntegral<uint64_t>();
    double value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }

  FuzzedDataProvider provider_;
  bool wild_ = false;
};

}  // namespace freeform::fuzz

#endif  // FREEFORM_TESTS_FUZZ_CORE_FUZZ_INPUT_H_
