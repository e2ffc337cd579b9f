// Structure-aware mutations of the freeform.v1 geometry inside a request
// (request_mutator.h): changes that keep a curve, surface, basis or
// parameter set consistent, so the request reaches the work behind the
// validation, where byte mutations almost never get:
//   - a B-spline curve or basis gets another degree (0 included) with its
//     knot vector made for it (count + degree + 1 knots: clamped, uniform,
//     multiple or distorted knots), more control points when the degree
//     needs them;
//   - the control points of a curve (with its weights, knots, nodes,
//     tangents) or the rows or columns of a net (with the weights and the
//     knot vector of that direction) grow or shrink together;
//   - a triangular patch changes degree with (n + 1)(n + 2) / 2 points;
//   - weights become extreme (1e+-300, 0, a ramp) with their count kept;
//     control points become equal, collinear, planar, huge or tiny;
//   - a curve or surface becomes another kind made of the same points (a
//     Bezier curve a B-spline with clamped knots, a net a bicubic patch);
//   - parameters switch between a list and a range, surface parameters
//     between pairs and a grid;
//   - every point set and net of the request changes dimension together.
// Deterministic given the FuzzRandom. Not thread-safe.
#ifndef FREEFORM_TESTS_FUZZ_GEOMETRY_MUTATIONS_H_
#define FREEFORM_TESTS_FUZZ_GEOMETRY_MUTATIONS_H_

#include "field_mutations.h"
#include "fuzz_random.h"
#include "google/protobuf/message.h"

namespace freeform::fuzz {

// MutateGeometry applies one of the mutations above to one geometry
// message found anywhere in `message` (a generated freeform.v1 message).
// Returns false when `message` holds no geometry or nothing changed.
bool MutateGeometry(google::protobuf::Message& message,
                    const MutationLimits& limits, FuzzRandom& random);

}  // namespace freeform::fuzz

#endif  // FREEFORM_TESTS_FUZZ_GEOMETRY_MUTATIONS_H_
