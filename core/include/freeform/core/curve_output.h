// CurveOutput: where batch curve evaluations write their results.
//
// Every curve evaluator takes one buffer per derivative order: output[k]
// receives the k-th derivative at every parameter, count * dimension doubles
// (derivative k at parameter r, coordinate j, is output[k][r * dimension + j]).
// A caller can hand in the final storage (a response message's arrays), so
// nothing is copied. Thread-safe.
#ifndef FREEFORM_CORE_CURVE_OUTPUT_H_
#define FREEFORM_CORE_CURVE_OUTPUT_H_

#include <cstddef>

#include "absl/status/status.h"
#include "absl/types/span.h"

namespace freeform {

// Per-order output buffers of a batch evaluation: output[k] receives the
// k-th derivative at every parameter (count * dimension doubles).
using CurveOutput = absl::Span<const absl::Span<double>>;

// ValidateCurveOutput checks that `output` has at least one buffer (the
// positions) and that every buffer holds count * dimension doubles.
absl::Status ValidateCurveOutput(CurveOutput output, size_t count,
                                 int dimension);

// ValidateBatch checks what every batch evaluator gets besides its curve:
// parameters finite and inside [start, end] ("parameters[i]"), and output
// buffers of count * values_per_point doubles.
absl::Status ValidateBatch(absl::Span<const double> parameters, double start,
                           double end, CurveOutput output,
                           int values_per_point);

}  // namespace freeform

#endif  // FREEFORM_CORE_CURVE_OUTPUT_H_
