// Arc length of curves: the length over a parameter interval, its inverse
// (the parameter at a given length) and samples at equal arc-length
// spacing, for every curve kind of curve.h in any dimension.
//
// The length of C over [a, b] is the integral of the speed |C'(t)|. The
// curve is cut into its Bezier pieces (DecomposeCurve) between the
// breakpoints, where the speed is smooth; each piece is cut at the local
// minima of its speed (the roots of the derivative of |C'|^2, from its
// Bernstein form, located to 2^-32), where a speed that almost vanishes
// has a kink that no rule's error estimate sees; and each part is
// integrated in its piece's parameter s in [0, 1] by adaptive
// Gauss-Legendre quadrature
// (docs/references.md, 'Arc length by adaptive Gauss-Legendre
// quadrature'): an interval's 16-point rule is compared with the sum of the
// rules on its two halves; when they differ by at most the interval's share
// of the tolerance (the tolerance times the piece's share of the width of
// [a, b], times the interval's share of the piece) the halves' sum is kept,
// otherwise each half is refined the same way. The difference estimates the
// error of the coarser rule, so the kept sums are far more accurate than
// the tolerance for smooth speeds. An interval whose rules agree to rounding
// (64 epsilon of their value plus the rounding of the speed, which is that
// of the coordinates times the degree: a stretch where the curve stands
// still cannot do better) is kept as it is, and a piece is not split
// beyond kMaxArcLengthDepth halvings or kMaxArcLengthIntervals intervals.
// A tolerance below what double precision resolves on the curve, 2^-48
// times its largest control point coordinate (the speed is computed to the
// rounding of the coordinates), is refused at once naming "tolerance",
// as Tessellate refuses it, unless every piece is a straight polynomial
// segment (whose rule is exact).
//
// Extreme weights: a rational piece whose weights differ by a large factor
// moves almost all of its way in a tiny part of its parameter (the corner
// (1,0), (1,1), (0,1) with weights 1, 1e10, 1 runs from one end to the
// corner for t < 1e-10), which a quadrature rule's nodes step over. Such a
// piece is first halved by de Casteljau, in homogeneous form and without
// evaluating it at parameters, until the weights of every stretch are
// within a factor 4 of each other (a stretch's spread of 2^m takes about m
// halvings, kMaxArcLengthWeightHalvings at most; each half gets the mean
// of its share of the parameter and its share of the two halves' control
// polygon lengths of the stretch's tolerance, so that the half where the
// curve runs gets most of it); then its speed is as
// smooth as a polynomial's and the quadrature above applies in the
// stretch's own parameter (docs/references.md, 'Arc length of rational
// curves').
//
// Extreme scale: the curve is integrated as its copy rescaled by powers of
// two (coordinates at most 1, weights at most 1, domain width about 1;
// exact), so squared norms neither underflow nor overflow for curves of
// size 1e-300 or 1e300 or knots 1e170 apart, and lengths are scaled back.
//
// The inverse solves L(start, t) = s for t by Newton's method, whose
// derivative is the speed, safeguarded by bisection on the interval of the
// quadrature table that holds s (the length is monotone in t). Where the
// curve stands still (zero speed over an interval) every parameter of that
// interval has the same length; the one returned lies inside it. A
// returned parameter is a double: where the curve moves more than the
// tolerance between adjacent doubles of t (weights so extreme that a whole
// stretch lies within one unit in the last place of t) no parameter has
// the length asked for within the tolerance, and the call fails with
// INVALID_ARGUMENT naming "weights" (or, for a polynomial curve, whose
// knots would have to be as extreme, "tolerance") and saying by how much
// the best parameter misses.
//
// Errors name their field: "start", "end", "tolerance", "lengths[i]",
// "count", "weights". Output buffers have a size known before any work (the
// number of lengths, or `count`); a wrongly sized buffer is INVALID_ARGUMENT.
//
// All functions are thread-safe and allocate per call or per chunk.
#ifndef FREEFORM_CORE_ARC_LENGTH_H_
#define FREEFORM_CORE_ARC_LENGTH_H_

#include <cstddef>
#include <cstdint>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/curve.h"
#include "freeform/core/thread_pool.h"

namespace freeform {

// The largest number of halvings of a piece of the curve between two
// breakpoints, and the most intervals one piece is cut into: together they
// bound the work of a tolerance the piece cannot meet (a speed with a
// corner finer than double precision resolves, a huge curve).
inline constexpr int kMaxArcLengthDepth = 40;
inline constexpr size_t kMaxArcLengthIntervals = 1024;

// A rational piece is halved for its weights (see the file comment) at
// most this many times along one path, and holds at most this many values
// of halved stretches at once: beyond either the call fails with
// INVALID_ARGUMENT naming "weights".
inline constexpr int kMaxArcLengthWeightHalvings = 1100;
inline constexpr size_t kMaxArcLengthWeightValues = size_t{1} << 18;

// ValidateArcLengthInterval checks an interval [start, end] of `curve`'s
// parameters as every function here checks it: INVALID_ARGUMENT naming
// "start" or "end" when one is not finite or outside the domain, and "end"
// when end < start. A caller that names the ends in a larger request (the
// server's prepare step) checks them with it before any work.
absl::Status ValidateArcLengthInterval(const Curve& curve, double start,
                                       double end);

// ArcLength returns the length of `curve` over [start, end] within
// `tolerance` (absolute, in the curve's units; see the file comment).
// start <= end, both in the domain. Fails with INVALID_ARGUMENT "start" or
// "end" (not finite, outside the domain, end < start) or "tolerance" (not
// positive and finite), and with the token's CANCELLED / DEADLINE_EXCEEDED.
absl::StatusOr<double> ArcLength(const Curve& curve, double start, double end,
                                 double tolerance,
                                 const CancellationToken* cancel = nullptr);

// ArcLengths writes into lengths[i] the length of `curve` over the interval
// [intervals[2 i], intervals[2 i + 1]] within `tolerance`, for every pair of
// `intervals` (an even number of values), in chunks on the context's pool.
// `lengths` holds intervals.size() / 2 values. Every interval is checked
// before any work: errors name "intervals[i].start", "intervals[i].end"
// (as ArcLength's "start" and "end") or "tolerance"; and the context
// token's CANCELLED / DEADLINE_EXCEEDED.
absl::Status ArcLengths(const Curve& curve, absl::Span<const double> intervals,
                        double tolerance, absl::Span<double> lengths,
                        const ExecutionContext& context = {});

// ParametersAtArcLengths writes into parameters[i] the parameter t >= start
// with |L(start, t) - lengths[i]| <= tolerance. Every length must lie in
// [0, L(start, domain end)] (one within the tolerance above that gives the
// end of the domain). The lengths are integrated once from `start` to the
// end of the domain, then the parameters are solved in chunks on the
// context's pool. `parameters` holds lengths.size() values. Fails like
// ArcLength ("start", "tolerance"), with "lengths[i]" for a length not
// finite, negative or beyond the curve, and with the context token's
// CANCELLED / DEADLINE_EXCEEDED.
absl::Status ParametersAtArcLengths(const Curve& curve, double start,
                                    absl::Span<const double> lengths,
                                    double tolerance,
                                    absl::Span<double> parameters,
                                    const ExecutionContext& context = {});

// EqualArcLengthParameters writes `count` >= 2 parameters t_0 = start,
// ..., t_{count-1} = end such that L(start, t_k) = k L(start, end) /
// (count - 1) within `tolerance`, so consecutive samples are equally far
// apart along the curve (each arc between them is L / (count - 1) within
// 2 tolerance; the parameters increase whenever that spacing exceeds
// 2 tolerance). A curve of zero length over [start, end] gets evenly
// spaced parameters. `parameters` holds `count` values. Fails like
// ArcLength, with "count" when count < 2.
absl::Status EqualArcLengthParameters(const Curve& curve, double start,
                                      double end, size_t count,
                                      double tolerance,
                                      absl::Span<double> parameters,
                                      const ExecutionContext& context = {});

// ArcLengthWorkValues returns an estimate, known before any work, of the
// doubles a call on `curve` holds besides its answer when `tables` length
// tables are built at once (one per thread of ArcLengths; one for the
// inverse): three copies of the curve's Bezier pieces (DecomposedCurveValues:
// the decomposition, its lifted nets and the rescaled copy of the curve),
// and per table 48 values per piece (a kept interval holds 4, a piece keeps
// a few at tolerances it resolves, up to kMaxArcLengthIntervals below
// them) and, for a rational curve, kMaxArcLengthWeightValues. Saturates at
// UINT64_MAX.
uint64_t ArcLengthWorkValues(const Curve& curve, size_t tables);

// GaussLegendreRule returns the `points` >= 1 nodes (ascending) and weights
// of the Gauss-Legendre rule on [-1, 1], which integrates polynomials of
// degree up to 2 points - 1 exactly: the nodes are the roots of the
// Legendre polynomial P_points, found by Newton's method from
// cos(pi (i + 3/4) / (points + 1/2)), and w_i = 2 / ((1 - x_i^2)
// P'_points(x_i)^2).
void GaussLegendreRule(int points, absl::Span<double> nodes,
                       absl::Span<double> weights);

}  // namespace freeform

#endif  // FREEFORM_CORE_ARC_LENGTH_H_
