// Field mutations of the structure-aware mutator (request_mutator.h): one
// change to one field of a protobuf message, chosen anywhere in it through
// reflection, and the value mutations they share with the geometry
// mutations (geometry_mutations.h).
//
// Numbers go towards the boundaries (0, +-1, 2^31, 2^32, 2^63, INT64_MIN,
// NaN, +-Inf, 1e+-300, denormals, -0.0), are perturbed by an ulp or a
// relative 1e-15..1e-3, scaled by powers of ten or copied from elsewhere in
// the message (a knot as a parameter, a control point as a query); enums
// take every value and unknown ones; repeated fields grow (duplicated
// elements) and shrink (dropped, truncated to 0 or 1), are sorted, reversed
// or made equal; oneofs switch members; submessages are cleared or
// created. Growth is capped by MutationLimits. Deterministic given the
// FuzzRandom. Not thread-safe (it changes the message).
#ifndef FREEFORM_TESTS_FUZZ_FIELD_MUTATIONS_H_
#define FREEFORM_TESTS_FUZZ_FIELD_MUTATIONS_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "absl/types/span.h"
#include "fuzz_random.h"
#include "google/protobuf/message.h"

namespace freeform::fuzz {

// Bounds on what one mutation may add.
struct MutationLimits {
  // The most elements a repeated field is grown to (a repeated field that
  // is already longer is only shrunk or changed in place).
  int max_repeated = 4096;
  // The most elements one mutation adds to a repeated field.
  int max_growth = 64;
  // The largest degree a geometry mutation picks: a little above the fuzz
  // server's limit (16), so that the refusal is exercised too.
  int max_degree = 18;
};

// BoundaryDouble returns one of the boundary values of a double: 0, -0.0,
// +-1, 2, 2^31 - 1, 2^31, -2^31, 2^32, 2^53, 2^63, 1e+-10..1e+-308,
// DBL_MAX, DBL_MIN, denormals down to 5e-324, NaN, +-Inf.
double BoundaryDouble(FuzzRandom& random);

// ExtremePowerOfTen returns 10^k for k drawn from exponents where double
// arithmetic changes behaviour (squares overflow past 1e154, ...), with
// either sign of k.
double ExtremePowerOfTen(FuzzRandom& random);

// MutateDouble returns a mutation of `value`: a boundary value, a tiny
// perturbation, a scaling, its negation, a value of `pool` (the message's
// other doubles, maybe empty) or a small random number.
double MutateDouble(double value, absl::Span<const double> pool,
                    FuzzRandom& random);

// MutateInteger returns a mutation of `value` as 64 bits: a boundary
// (0, 1, 2, -1, INT32_MAX, 2^31, 2^32 - 1, 2^32, INT64_MIN, 2^63, the fuzz
// server's limits 16, 1024, 8192 and their neighbours, ...), value +- a
// small step, or a small random number. The caller casts it to the field's
// type (unsigned fields wrap, so -1 is their largest value).
uint64_t MutateInteger(uint64_t value, FuzzRandom& random);

// CollectDoubles returns up to `cap` of the double values anywhere in
// `message`, in field order.
std::vector<double> CollectDoubles(const google::protobuf::Message& message,
                                   size_t cap);

// MutateRandomField changes one field of `message` or of a message inside
// it (any depth), chosen uniformly among them, set or not. Returns false
// when nothing was changed.
bool MutateRandomField(google::protobuf::Message& message,
                       const MutationLimits& limits, FuzzRandom& random);

// MutateDoubles changes one element of `values` (MutateDouble), grows or
// shrinks it (duplicating or dropping elements, truncating to 0 or 1)
// within `limits`, or reorders it (sorted, reversed, all equal). Returns
// false when nothing was changed.
bool MutateDoubles(std::vector<double>& values, absl::Span<const double> pool,
                   const MutationLimits& limits, FuzzRandom& random);

}  // namespace freeform::fuzz

#endif  // FREEFORM_TESTS_FUZZ_FIELD_MUTATIONS_H_
