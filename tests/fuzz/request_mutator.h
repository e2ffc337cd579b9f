// The structure-aware mutator of the RPC fuzzers (rpc_fuzzer.cc defines
// libFuzzer's LLVMFuzzerCustomMutator and LLVMFuzzerCustomCrossOver with
// it): the input is parsed as the target's request message, changed
// through protobuf reflection and serialized again, so that most mutants
// are requests of a different, still consistent structure, where byte
// mutations almost never make one (a degree-0 spline with its knots).
//
// Each call draws from a std::mt19937_64 seeded with libFuzzer's seed, so
// a mutation depends on the input and the seed only. It applies one to
// four changes, each a geometry mutation (geometry_mutations.h: degrees
// with their knots, counts with their arrays, extreme weights, kinds
// converted) or a field mutation (field_mutations.h: boundary numbers,
// enums, repeated fields grown and shrunk, oneofs switched, submessages
// cleared). One call in kByteMutationOneIn, and every input that does not
// parse, gets the byte mutator instead (libFuzzer's LLVMFuzzerMutate), so
// the bytes-level paths (truncated and malformed requests) stay covered.
// A mutant is never larger than `max_size`: a larger one is dropped for
// another try, and after a few the byte mutator answers.
//
// Thread-compatible: no shared state.
#ifndef FREEFORM_TESTS_FUZZ_REQUEST_MUTATOR_H_
#define FREEFORM_TESTS_FUZZ_REQUEST_MUTATOR_H_

#include <cstddef>
#include <cstdint>

#include "field_mutations.h"
#include "google/protobuf/message.h"

namespace freeform::fuzz {

// libFuzzer's byte mutator (LLVMFuzzerMutate): mutates data[0, size) in
// place, returns the new size, at most max_size.
using ByteMutator = size_t (*)(uint8_t* data, size_t size, size_t max_size);

// One call in this many is a byte mutation.
inline constexpr size_t kByteMutationOneIn = 5;

// MutateRequest mutates the serialized `prototype`-typed request in
// data[0, size) in place (data holds max_size bytes) and returns its new
// size (at most max_size).
size_t MutateRequest(const google::protobuf::Message& prototype, uint8_t* data,
                     size_t size, size_t max_size, uint64_t seed,
                     ByteMutator byte_mutator,
                     const MutationLimits& limits = {});

// CrossOverRequests writes into out (max_out_size bytes) a request made of
// two: one submessage of the first replaced by a submessage of the same
// type from the second (a curve, a point set, the options), or each top
// field taken from either. Returns its size, or 0 when either does not
// parse or the result does not fit.
size_t CrossOverRequests(const google::protobuf::Message& prototype,
                         const uint8_t* data1, size_t size1,
                         const uint8_t* data2, size_t size2, uint8_t* out,
                         size_t max_out_size, uint64_t seed);

}  // namespace freeform::fuzz

#endif  // FREEFORM_TESTS_FUZZ_REQUEST_MUTATOR_H_
