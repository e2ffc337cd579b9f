// What the curve fit and the gridded surface fit share to refine a
// least-squares fit until it meets a tolerance (fitting.h;
// docs/references.md, 'Least-squares fitting to a tolerance'): the
// single-span start, the knot placement rule and the error when the
// refinement cannot go on. Internal to the core.
#ifndef FREEFORM_CORE_SRC_CONSTRUCT_TOLERANCE_REFINEMENT_H_
#define FREEFORM_CORE_SRC_CONSTRUCT_TOLERANCE_REFINEMENT_H_

#include <cstddef>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"

namespace freeform::internal {

// SingleSpanKnots returns p + 1 copies of `start` and p + 1 of `end`: the
// Bezier basis on [start, end].
std::vector<double> SingleSpanKnots(int p, double start, double end);

// The fewest parameters a knot span keeps when it is split: one per span
// would keep Schoenberg-Whitney, but near-interpolating systems of odd
// degree with one parameter mid-span are badly conditioned (the
// collocation at span midpoints degenerates), and normal equations square
// that; two per span keep the least-squares systems well conditioned.
inline constexpr size_t kMinSpanParameters = 2;

// SplitFailingSpans returns the sorted knots to insert into the clamped
// `knots` of degree p: one in each knot span whose largest error over the
// sorted parameters t_k inside it (errors[k]) exceeds `tolerance` and which
// holds c >= 2 kMinSpanParameters parameters t_a..t_{a+c-1}, halfway
// between t_{a+c/2-1} and t_{a+c/2}. Every span keeps kMinSpanParameters
// parameters, strictly inside it; with at most as many control points as
// parameters (the caller's `capacity` ensures it) the Schoenberg-Whitney
// condition then holds. When more than `capacity` spans qualify, those with
// the largest errors are split.
std::vector<double> SplitFailingSpans(int p, absl::Span<const double> knots,
                                      absl::Span<const double> t,
                                      absl::Span<const double> errors,
                                      double tolerance, size_t capacity);

// SpansHoldData returns whether every non-empty knot span of `knots`
// (degree p) holds at least kMinSpanParameters of the sorted parameters
// `t`, none of them on an interior knot: the invariant of
// SplitFailingSpans.
bool SpansHoldData(int p, absl::Span<const double> knots,
                   absl::Span<const double> t);

// WithKnots returns the sorted `knots` with the sorted `inserted` merged in.
std::vector<double> WithKnots(absl::Span<const double> knots,
                              absl::Span<const double> inserted);

// ToleranceNotMet returns RESOURCE_EXHAUSTED on "tolerance" for a fit that
// stopped with max residual `achieved`: at the cap `cap_field` = `cap` when
// `cap_reached`, else because every failing span holds fewer than
// 2 kMinSpanParameters parameters.
absl::Status ToleranceNotMet(double achieved, double tolerance,
                             bool cap_reached, absl::string_view cap_field,
                             int cap);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_CONSTRUCT_TOLERANCE_REFINEMENT_H_
