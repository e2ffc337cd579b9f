// Adaptive Gauss-Kronrod (7-15) quadrature of integrands that may carry
// their own error (an inner integral), for the face's areas. Internal to
// the core; thread-safe.
#ifndef FREEFORM_CORE_SRC_FACES_QUADRATURE_H_
#define FREEFORM_CORE_SRC_FACES_QUADRATURE_H_

#include <cstddef>
#include <cstdint>

#include "absl/functional/function_ref.h"
#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"

namespace freeform::internal {

// A value with a bound of its error.
struct Estimate {
  double value = 0.0;
  double error = 0.0;
};

// The points of the Kronrod rule; the Gauss rule uses every odd one.
inline constexpr int kKronrodPoints = 15;

// KronrodNode returns node k (0..14, ascending) of the 15-point rule on
// [a, b].
double KronrodNode(double a, double b, int k);

// KronrodInterval integrates over [a, b] from the integrand's values at the
// 15 KronrodNode points: value the Kronrod sum, error |K15 - G7| plus the
// integrand's own errors weighted by the Kronrod weights.
Estimate KronrodInterval(double a, double b, const Estimate* values);

// An integrand of batches: values[k] at KronrodNode(a, b, k) for k in
// 0..14, of the integrand numbered `part`.
using KronrodIntegrand = absl::FunctionRef<absl::Status(
    size_t part, double a, double b, Estimate* values)>;

// One interval of one integrand.
struct PartInterval {
  size_t part = 0;
  double a = 0.0;
  double b = 0.0;
};

// IntegrateAdaptiveBytes bounds the memory of IntegrateAdaptive with
// `max_intervals` intervals (its heap, grown by doubling).
uint64_t IntegrateAdaptiveBytes(uint64_t max_intervals);

// IntegrateAdaptive integrates over every interval of `parts` (each of its
// own integrand `part`) together, halving the interval of largest error
// until the errors add up to at most `tolerance` or `max_intervals`
// intervals are in use; returns the sum and its error bound.
absl::StatusOr<Estimate> IntegrateAdaptive(KronrodIntegrand integrand,
                                           absl::Span<const PartInterval> parts,
                                           double tolerance,
                                           size_t max_intervals,
                                           const CancellationToken* cancel);

// IntegrateAdaptive over the one interval [a, b] of integrand 0.
absl::StatusOr<Estimate> IntegrateAdaptive(KronrodIntegrand integrand, double a,
                                           double b, double tolerance,
                                           size_t max_intervals,
                                           const CancellationToken* cancel);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_FACES_QUADRATURE_H_
