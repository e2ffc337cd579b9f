// Oracles of the query RPCs: cheap checks, independent of the query code,
// that an OK answer is right, so that a silently wrong answer is a finding
// of the RPC fuzzers (rpc_fuzzer.cc) like a crash:
//   - ClosestPoint (curve, surface): each minimum's point is the geometry
//     evaluated at its parameters; its distance to the query lies between
//     the reported distance and that plus the tolerance; the certified
//     lower bound is below the distance of every sample of the geometry
//     (17 x 17 per surface, 65 and the breakpoints per curve) and, for a
//     complete answer, within the tolerance of the distance;
//   - Intersect, IntersectCurve: each point's two inputs, evaluated at its
//     parameters, are within the tolerance of each other, and the point is
//     the first input's; so are the ends of each overlap;
//   - Section: every vertex is within the tolerance of the plane and of
//     the surface at its parameters, a closed polyline ends where it
//     starts, and the vertices are within max_points;
//   - ArcLength, ParametersAtArcLength: a length is at least that of an
//     inscribed polyline (the chord and finer), and of a polynomial curve
//     at most the control polygons of the pieces it spans; returned points
//     are the curve at their parameters;
//   - SampleByArcLength: the samples run from start to end, their
//     parameters never decrease, and each point is the curve there;
//   - BoundingBox (curve, surface): every sample of the geometry is inside
//     the box, and, with positive weights, the box is within the tolerance
//     of the control points' box.
// Every comparison allows the request's tolerance (or its documented
// default) plus a rounding margin (kRoundingMargin times the geometry's
// scale, kAbsoluteMargin) and, where the answer names parameters, the
// slack of their rounding (oracle_geometry.h). Thread-compatible.
#ifndef FREEFORM_TESTS_FUZZ_QUERY_ORACLES_H_
#define FREEFORM_TESTS_FUZZ_QUERY_ORACLES_H_

#include <limits>
#include <optional>
#include <string>

#include "google/protobuf/descriptor.h"
#include "google/protobuf/message.h"
#include "service_limits.h"

namespace freeform::fuzz {

// The rounding margin of a value a query computed, relative to the
// geometry's scale (oracle_geometry.h). One evaluation of a piece of
// degree <= 16 (the fuzz server's limit) by de Casteljau or de Boor rounds
// by at most about 2 * 16 * 2^-53 = 3.6e-15 of the control points'
// magnitude (positive weights keep a rational one within the same bound:
// numerator and denominator are sums of positive terms), a decomposition
// into pieces adds as much, and a distance or a polyline of up to 4096
// segments sums such errors. 1e-10 is above 4096 * 4 * 3.6e-15 = 6e-11, so
// a right answer never trips it, while the wrong answers the oracles look
// for (issue 30: 0.2 to 1 off at scale 1) are far beyond it. A point that
// an answer places at parameters gets their slack on top
// (kParameterRounding).
inline constexpr double kRoundingMargin = 1e-10;

// In the subnormal range rounding is absolute, half of 2^-1074 per
// operation: 1024 of them.
inline constexpr double kAbsoluteMargin =
    1024 * std::numeric_limits<double>::denorm_min();

// CheckQueryAnswer checks the OK `answer` of `method` to `request` (both
// of the method's types) and returns what is wrong with it, or nullopt
// when every check holds or the method has no oracle. `limits` are the
// server's, so that the geometry is prepared as it was.
std::optional<std::string> CheckQueryAnswer(
    const google::protobuf::MethodDescriptor& method,
    const google::protobuf::Message& request,
    const google::protobuf::Message& answer,
    const server::ServiceLimits& limits);

}  // namespace freeform::fuzz

#endif  // FREEFORM_TESTS_FUZZ_QUERY_ORACLES_H_
