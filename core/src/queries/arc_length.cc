#include "freeform/core/arc_length.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <numbers>
#include <utility>
#include <variant>
#include <vector>

#include "absl/strings/str_cat.h"
#include "base/binomial.h"
#include "base/scaled.h"
#include "base/tessellation_checks.h"
#include "freeform/core/curve_output.h"
#include "freeform/core/points.h"
#include "freeform/core/saturating.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "geometry/scaled_geometry.h"
#include "geometry/variant_dispatch.h"
#include "queries/bezier_net.h"
#include "queries/speed.h"
#include "queries/speed_minima.h"

namespace freeform {
namespace {

using internal::kRoundingAgreement;
using internal::Net;
using internal::SpeedIntegrator;
using internal::SpeedMinimaSearch;

// Newton steps of the inverse before it settles for the bracket.
constexpr int kMaxNewtonSteps = 100;
// Parameters solved per chunk of ParametersAtArcLengths.
constexpr size_t kSolveGrain = 64;
// No segment: a stretch that is a whole piece uses the piece's own net.
constexpr size_t kPieceNet = std::numeric_limits<size_t>::max();

// The curve as the Bezier pieces of its scaled copy (scaled_geometry.h),
// lifted, each rational one with its weights at most 1: every length is
// computed in the copy's units and every parameter in its parameters.
struct CurvePieces {
  internal::ScaledCurve scaled;
  std::vector<Net> nets;
  std::vector<double> breakpoints;
  bool rational = false;

  double Width(size_t k) const { return breakpoints[k + 1] - breakpoints[k]; }
  // Parameter returns the copy's parameter at u in [0, 1] of piece k.
  double Parameter(size_t k, double u) const {
    if (u <= 0.0) return breakpoints[k];
    if (u >= 1.0) return breakpoints[k + 1];
    return std::clamp(breakpoints[k] + u * Width(k), breakpoints[k],
                      breakpoints[k + 1]);
  }
};

// CheckResolvable refuses, naming "tolerance", a tolerance below what
// double precision resolves on the pieces (tessellation_checks.h, in the
// curve's units): the speed is computed to the rounding of the
// coordinates, not of itself, so such a tolerance could only end at the
// interval limits with a sum no better than a coarser one. Straight
// polynomial pieces, whose speed is constant and whose rule is exact, meet
// any tolerance.
absl::Status CheckResolvable(const CurvePieces& pieces, double tolerance) {
  double largest = 0.0;
  bool straight = true;
  for (const Net& net : pieces.nets) {
    straight &= !net.rational && net.count_u <= 2;
    largest = std::max(largest, internal::LargestNetCoordinate(net));
  }
  if (straight) return absl::OkStatus();
  return internal::CheckResolvableAt(tolerance,
                                     pieces.scaled.scale().Length(largest));
}

// LiftCurvePieces decomposes the scaled copy of `curve` into its lifted
// Bezier pieces, and checks that `tolerance` is resolvable on them.
absl::StatusOr<CurvePieces> LiftCurvePieces(const Curve& curve,
                                            double tolerance,
                                            const CancellationToken* cancel) {
  CurvePieces pieces{.scaled = internal::ScaledCurve::Of(curve)};
  absl::StatusOr<BezierDecomposition> decomposition =
      DecomposeCurve(pieces.scaled.curve(), cancel);
  if (!decomposition.ok()) return decomposition.status();
  for (const BezierCurveData& segment : decomposition->segments) {
    pieces.nets.push_back(internal::LiftCurve(segment));
    internal::NormalizeWeights(pieces.nets.back());
    pieces.rational |= pieces.nets.back().rational;
  }
  pieces.breakpoints = std::move(decomposition->breakpoints);
  RETURN_IF_ERROR(CheckResolvable(pieces, tolerance));
  return pieces;
}

// SplitAt writes the parts [0, u] and [u, 1] of the curve net `net` (de
// Casteljau in homogeneous form); either may be null.
void SplitAt(const Net& net, double u, Net* low, Net* high) {
  const int n = net.count_u - 1;
  const size_t stride = static_cast<size_t>(net.stride());
  std::vector<double> work = net.values;
  for (Net* part : {low, high}) {
    if (part != nullptr) part->values.resize(work.size());
  }
  auto keep = [&](Net* part, int slot, int from) {
    if (part == nullptr) return;
    std::copy_n(work.data() + static_cast<size_t>(from) * stride, stride,
                part->values.data() + static_cast<size_t>(slot) * stride);
  };
  keep(low, 0, 0);
  keep(high, n, n);
  for (int r = 1; r <= n; ++r) {
    for (int i = 0; i + r <= n; ++i) {
      double* a = work.data() + static_cast<size_t>(i) * stride;
      const double* b = a + stride;
      for (size_t x = 0; x < stride; ++x) a[x] = (1.0 - u) * a[x] + u * b[x];
    }
    keep(low, r, 0);
    keep(high, n - r, n - r);
  }
  for (Net* part : {low, high}) {
    if (part == nullptr) continue;
    part->dimension = net.dimension;
    part->rational = net.rational;
    part->count_u = net.count_u;
    part->count_v = 1;
  }
}

// Clip returns the part [u0, u1] of a curve net.
Net Clip(const Net& net, double u0, double u1) {
  Net low = net;
  if (u1 < 1.0) SplitAt(net, u1, &low, nullptr);
  internal::NormalizeWeights(low);
  if (u0 <= 0.0) return low;
  Net part;
  SplitAt(low, u0 / u1, nullptr, &part);
  internal::NormalizeWeights(part);
  return part;
}

// WeightsAreModerate returns true when a net's weights are positive and
// within kModerateWeights of each other (always for a polynomial net).
constexpr double kModerateWeights = 4.0;
bool WeightsAreModerate(const Net& net) {
  if (!net.rational) return true;
  double lo = std::numeric_limits<double>::infinity();
  double hi = 0.0;
  const size_t stride = static_cast<size_t>(net.stride());
  for (size_t k = static_cast<size_t>(net.dimension); k < net.values.size();
       k += stride) {
    lo = std::min(lo, net.values[k]);
    hi = std::max(hi, net.values[k]);
  }
  return lo > 0.0 && hi <= kModerateWeights * lo;
}

// A stretch of piece `piece` over [u_a, u_b] of the piece's parameter,
// integrated in its own parameter s in [0, 1], and its kept intervals
// [first, end) of the table. `net` indexes the table's nets (a clipped or
// halved stretch, when the table keeps them), or is kPieceNet for a whole
// piece (and for every stretch of a table that keeps no nets, which only
// sums lengths).
struct Segment {
  size_t piece = 0;
  double u_a = 0.0;
  double u_b = 1.0;
  size_t net = kPieceNet;
  size_t first = 0;
  size_t end = 0;
};

// The kept intervals of the adaptive quadrature in curve order: interval k
// is [lo[k], hi[k]] of segment segment_of[k]; cumulative[k] is the length
// from the start to its start (cumulative.back() the whole length), in the
// scaled copy's units.
struct LengthTable {
  double start = 0.0;  // the copy's parameters of the integrated interval
  double end = 0.0;
  std::vector<Segment> segments;
  std::vector<Net> nets;
  std::vector<size_t> segment_of;
  std::vector<double> lo, hi;
  std::vector<double> cumulative = {0.0};

  double total() const { return cumulative.back(); }
  const Net& NetOf(const Segment& segment, const CurvePieces& pieces) const {
    return segment.net == kPieceNet ? pieces.nets[segment.piece]
                                    : nets[segment.net];
  }
  void Keep(double a, double b, double length) {
    segment_of.push_back(segments.size() - 1);
    lo.push_back(a);
    hi.push_back(b);
    cumulative.push_back(cumulative.back() + length);
  }
};

// The interval [a, b] of a segment still to be integrated, with the rule's
// value on it.
struct Pending {
  double a;
  double b;
  double whole;
  int depth;
};

// SpeedRounding returns the size of the speed |C'(s)| of a curve net as
// its rounding sees it: its degree times its largest projected coordinate
// (the derivative of a rational net subtracts products of the coordinates'
// size, so its rounding is that of the coordinates, not of the speed; a
// stretch where the curve stands still has a speed far below it).
double SpeedRounding(const Net& net) {
  return (net.count_u - 1) * internal::LargestNetCoordinate(net);
}

// The integrator and the search for the speed's minima of one table.
struct TableWorkspace {
  SpeedIntegrator integrator;
  SpeedMinimaSearch minima;
};

// AddSegment integrates the last segment of `table` (whose net is `net`)
// adaptively, from its parts between the speed's minima (speed_minima.h), with
// the share budget * (b - a) of every kept interval [a, b] of its
// parameter.
absl::Status AddSegment(const Net& net, double budget,
                        TableWorkspace& workspace, CancellationPoll& poll,
                        LengthTable& table) {
  SpeedIntegrator& integrator = workspace.integrator;
  table.segments.back().first = table.lo.size();
  const double speed_rounding = SpeedRounding(net);
  // The parts between the speed's minima, the first on top.
  const absl::Span<const double> cuts = workspace.minima.Cuts(net, integrator);
  std::vector<Pending> stack;
  for (size_t k = cuts.size() - 1; k > 0; --k) {
    stack.push_back({cuts[k - 1], cuts[k],
                     integrator.Integrate(net, cuts[k - 1], cuts[k]), 0});
  }
  size_t kept = 0;
  while (!stack.empty()) {
    const Pending top = stack.back();
    stack.pop_back();
    const double mid = 0.5 * (top.a + top.b);
    const double halves[] = {integrator.Integrate(net, top.a, mid),
                             integrator.Integrate(net, mid, top.b)};
    RETURN_IF_ERROR(poll.Done(SpeedIntegrator::Work(net)));
    // Rules that agree to rounding of their value cannot do better (a
    // tolerance below what double precision resolves would otherwise
    // halve every interval kMaxArcLengthDepth times, 2^40 intervals), nor
    // can rules that overflowed.
    const double sum = halves[0] + halves[1];
    const double difference = std::abs(top.whole - sum);
    const bool settled =
        difference <= budget * (top.b - top.a) ||
        difference <=
            kRoundingAgreement * (sum + speed_rounding * (top.b - top.a)) ||
        !std::isfinite(sum) || top.depth >= kMaxArcLengthDepth ||
        kept + 2 * stack.size() + 2 >= kMaxArcLengthIntervals ||
        !(top.a < mid && mid < top.b);
    if (settled) {
      kept += 2;
      table.Keep(top.a, mid, halves[0]);
      table.Keep(mid, top.b, halves[1]);
      continue;
    }
    stack.push_back({mid, top.b, halves[1], top.depth + 1});
    stack.push_back({top.a, mid, halves[0], top.depth + 1});
  }
  table.segments.back().end = table.lo.size();
  return absl::OkStatus();
}

// A stretch of a piece waiting to be integrated or halved for its weights.
struct Stretch {
  Net net;
  double u_a;
  double u_b;
  double budget;
  int depth;
};

absl::Status WeightsError(absl::string_view why) {
  return InvalidFieldError(
      "weights",
      absl::StrCat("the weights vary too much for the arc length: ", why,
                   " (docs/references.md, 'Arc length of rational curves')"));
}

// PolygonLength returns the length of a curve net's control polygon (its
// projected points; infinity when a weight is not positive), which bounds
// the length of the curve: de Casteljau cuts its corners.
double PolygonLength(const Net& net) {
  std::vector<double> points;
  if (!internal::Project(net, points)) {
    return std::numeric_limits<double>::infinity();
  }
  double length = 0.0;
  double unused = 0.0;
  internal::PolygonLengths(points, net.dimension, net.count_u, 1, length,
                           unused);
  return length;
}

// LengthShare returns the share of a stretch's tolerance that its first
// half `low` gets: the mean of its share of the parameter (1/2) and its
// part of the two halves' polygon lengths. By parameter alone, the half of
// a corner with weight 1e20 that holds almost all of the length got 2^-66
// of the tolerance; by length alone, a half where the curve stands still
// got less than the rounding of its speed (which is that of the
// coordinates, not of the speed). Either half keeps at least half of
// either share. One half when the lengths are not finite or both 0.
double LengthShare(const Net& low, const Net& high) {
  const double a = PolygonLength(low);
  const double b = PolygonLength(high);
  const double sum = a + b;
  if (!(sum > 0.0) || !std::isfinite(sum)) return 0.5;
  return 0.5 * (0.5 + a / sum);
}

// AddPiece integrates the part [u0, u1] of piece k into `table` within
// `budget` (absolute, in the copy's units). A rational part whose weights
// are not moderate is first halved (de Casteljau) until every stretch's
// are: each halving roughly halves the spread of the weights where the
// speed concentrates, so a spread of 2^m takes about m halvings there, and
// then the speed is as smooth as a polynomial's.
absl::Status AddPiece(const CurvePieces& pieces, size_t k, double u0, double u1,
                      double budget, bool keep_nets, TableWorkspace& workspace,
                      CancellationPoll& poll, LengthTable& table) {
  const Net& whole = pieces.nets[k];
  const bool clipped = u0 > 0.0 || u1 < 1.0;
  if (!clipped && WeightsAreModerate(whole)) {
    table.segments.push_back({.piece = k});
    return AddSegment(whole, budget, workspace, poll, table);
  }
  size_t held = 0;  // values of the stack and the kept nets
  std::vector<Stretch> stack;
  stack.push_back({clipped ? Clip(whole, u0, u1) : whole, u0, u1, budget, 0});
  while (!stack.empty()) {
    Stretch top = std::move(stack.back());
    stack.pop_back();
    held -= std::min(held, top.net.values.size());
    if (WeightsAreModerate(top.net)) {
      table.segments.push_back({.piece = k, .u_a = top.u_a, .u_b = top.u_b});
      RETURN_IF_ERROR(AddSegment(top.net, top.budget, workspace, poll, table));
      if (keep_nets) {
        held += top.net.values.size();
        table.segments.back().net = table.nets.size();
        table.nets.push_back(std::move(top.net));
      }
      continue;
    }
    if (top.depth >= kMaxArcLengthWeightHalvings) {
      return WeightsError(absl::StrCat(
          "more than ", kMaxArcLengthWeightHalvings, " halvings of one piece"));
    }
    RETURN_IF_ERROR(poll.Done(top.net.values.size() * 4));
    Stretch low{.net = {},
                .u_a = top.u_a,
                .u_b = 0.5 * (top.u_a + top.u_b),
                .budget = 0.5 * top.budget,
                .depth = top.depth + 1};
    Stretch high{.net = {},
                 .u_a = low.u_b,
                 .u_b = top.u_b,
                 .budget = low.budget,
                 .depth = low.depth};
    internal::Halve(top.net, true, low.net, high.net);
    // Halves far from the largest weight would square weights that
    // underflow: each keeps its weights at most 1 (scaled.h).
    internal::NormalizeWeights(low.net);
    internal::NormalizeWeights(high.net);
    const double low_share = LengthShare(low.net, high.net);
    low.budget = low_share * top.budget;
    high.budget = (1.0 - low_share) * top.budget;
    held += low.net.values.size() + high.net.values.size();
    if (held > kMaxArcLengthWeightValues) {
      return WeightsError(
          absl::StrCat("its halved pieces would hold more than ",
                       kMaxArcLengthWeightValues, " values"));
    }
    stack.push_back(std::move(high));
    stack.push_back(std::move(low));
  }
  return absl::OkStatus();
}

// BuildTable integrates [start, end] (the copy's parameters) piece by
// piece within `tolerance` in all, each piece's share its width's.
absl::StatusOr<LengthTable> BuildTable(const CurvePieces& pieces, double start,
                                       double end, double tolerance,
                                       bool keep_nets,
                                       const CancellationToken* cancel) {
  LengthTable table{.start = start, .end = end};
  if (!(start < end)) return table;
  const std::vector<double>& breaks = pieces.breakpoints;
  size_t k = static_cast<size_t>(
      std::upper_bound(breaks.begin(), breaks.end(), start) - breaks.begin());
  k = k == 0 ? 0 : k - 1;
  TableWorkspace workspace;
  CancellationPoll poll(cancel);
  for (; k < pieces.nets.size() && breaks[k] < end; ++k) {
    const double width = pieces.Width(k);
    if (!(width > 0.0) || breaks[k + 1] <= start) continue;
    const double u0 = start > breaks[k] ? (start - breaks[k]) / width : 0.0;
    const double u1 = end < breaks[k + 1] ? (end - breaks[k]) / width : 1.0;
    if (!(u0 < u1)) continue;
    const double share =
        (std::min(end, breaks[k + 1]) - std::max(start, breaks[k])) /
        (end - start);
    RETURN_IF_ERROR(AddPiece(pieces, k, std::clamp(u0, 0.0, 1.0),
                             std::clamp(u1, 0.0, 1.0), tolerance * share,
                             keep_nets, workspace, poll, table));
  }
  return table;
}

// The parameter of the copy at s of a segment.
double SegmentParameter(const CurvePieces& pieces, const Segment& segment,
                        double s) {
  const double u = s <= 0.0   ? segment.u_a
                   : s >= 1.0 ? segment.u_b
                              : segment.u_a + s * (segment.u_b - segment.u_a);
  return pieces.Parameter(segment.piece, u);
}

// A table and the pieces it was built on, with the integrator of one
// thread.
struct TableReader {
  const CurvePieces& pieces;
  const LengthTable& table;
  SpeedIntegrator& integrator;

  const Net& NetOf(size_t segment) const {
    return table.NetOf(table.segments[segment], pieces);
  }

  // LengthIn returns the length from the start to s of segment `index`.
  double LengthIn(size_t index, double s) const {
    const Segment& segment = table.segments[index];
    if (segment.first == segment.end) return table.cumulative[segment.first];
    const auto hi_begin =
        table.hi.begin() + static_cast<ptrdiff_t>(segment.first);
    const auto hi_end = table.hi.begin() + static_cast<ptrdiff_t>(segment.end);
    const size_t k =
        std::min(static_cast<size_t>(std::lower_bound(hi_begin, hi_end, s) -
                                     table.hi.begin()),
                 segment.end - 1);
    if (s <= table.lo[k]) return table.cumulative[k];
    return table.cumulative[k] +
           integrator.Integrate(NetOf(index), table.lo[k], s);
  }

  // LengthRangeAt returns the least and largest length from the start to
  // parameter t of the copy: one value, unless the stretch at t is finer
  // than the parameters' doubles (a whole segment at a single t).
  std::pair<double, double> LengthRangeAt(double t) const {
    double lowest = std::numeric_limits<double>::infinity();
    double highest = -lowest;
    const std::vector<Segment>& segments = table.segments;
    // The segments are in curve order: skip those that end before t.
    const auto first = std::partition_point(
        segments.begin(), segments.end(), [&](const Segment& segment) {
          return SegmentParameter(pieces, segment, 1.0) < t;
        });
    for (size_t i = static_cast<size_t>(first - segments.begin());
         i < segments.size(); ++i) {
      const Segment& segment = segments[i];
      const double t_a = SegmentParameter(pieces, segment, 0.0);
      const double t_b = SegmentParameter(pieces, segment, 1.0);
      if (t < t_a) break;
      double least = table.cumulative[segment.first];
      double largest = table.cumulative[segment.end];
      if (t_a < t_b) {
        const double width = pieces.Width(segment.piece);
        const double u = (t - pieces.breakpoints[segment.piece]) / width;
        const double s = std::clamp(
            (u - segment.u_a) / (segment.u_b - segment.u_a), 0.0, 1.0);
        least = largest = LengthIn(i, s);
      }
      lowest = std::min(lowest, least);
      highest = std::max(highest, largest);
    }
    if (lowest > highest) return {table.total(), table.total()};
    return {lowest, highest};
  }
};

// ResolutionError reports a length no double parameter reaches within the
// tolerance.
absl::Status ResolutionError(const CurvePieces& pieces, double original_t,
                             double missed, double tolerance) {
  const std::string rule = absl::StrCat(
      "no double-precision parameter has its arc length within the tolerance ",
      pieces.scaled.scale().Length(tolerance), ": at t = ", original_t,
      " it is off by ", pieces.scaled.scale().Length(missed),
      " because the curve moves that far between adjacent parameters there");
  if (pieces.rational) {
    return InvalidFieldError(
        "weights", absl::StrCat(rule, " (its weights vary that steeply)"));
  }
  return InvalidFieldError("tolerance", rule);
}

// Solve returns the copy's parameter whose length from the table's start is
// `length` (0 <= length <= table.total()) within `tolerance`: Newton's
// method with bisection on the kept interval that holds it. Fails with
// ResolutionError when no double parameter has that length.
absl::StatusOr<double> Solve(const TableReader& reader, double length,
                             double tolerance) {
  const LengthTable& table = reader.table;
  const std::vector<double>& cumulative = table.cumulative;
  if (table.segments.empty()) return table.start;
  if (length >= table.total()) return table.end;
  const size_t k = static_cast<size_t>(
      std::upper_bound(cumulative.begin(), cumulative.end(), length) -
      cumulative.begin() - 1);
  const size_t index = table.segment_of[k];
  const Net& net = reader.NetOf(index);
  const double a = table.lo[k];
  const double base = cumulative[k];
  const double span = cumulative[k + 1] - base;
  double lo = a;
  double hi = table.hi[k];
  double s = span > 0.0 ? a + (length - base) / span * (hi - a) : a;
  double speed = 0.0;
  for (int step = 0; step < kMaxNewtonSteps; ++step) {
    const double partial = reader.integrator.Integrate(net, a, s);
    speed = reader.integrator.Speed(net, s);
    const double residual = base + partial - length;
    if (std::abs(residual) <= tolerance) break;
    (residual < 0.0 ? lo : hi) = s;
    double next = speed > 0.0 ? s - residual / speed : lo;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == s || !(lo < hi)) break;
    s = next;
    speed = -1.0;  // not yet at the new s
  }
  if (speed < 0.0) speed = reader.integrator.Speed(net, s);
  const Segment& segment = table.segments[index];
  // Within the table's interval: a piece's parameter start + u width
  // rounds, and may fall an ulp before the table's start.
  const double t = std::clamp(SegmentParameter(reader.pieces, segment, s),
                              table.start, table.end);
  // The double t stands for s only to its rounding: check the length at t
  // itself unless that rounding moves it by far less than the tolerance.
  const double width =
      reader.pieces.Width(segment.piece) * (segment.u_b - segment.u_a);
  const double moved =
      width > 0.0
          ? speed * std::abs(t) * std::numeric_limits<double>::epsilon() / width
          : std::numeric_limits<double>::infinity();
  if (moved <= 0.25 * tolerance) return t;
  const auto [least, largest] = reader.LengthRangeAt(t);
  const double missed =
      std::max(std::abs(least - length), std::abs(largest - length));
  if (missed <= tolerance) return t;
  return ResolutionError(reader.pieces, reader.pieces.scaled.ToOriginal(t),
                         missed, tolerance);
}

absl::Status CheckParameter(double value, const ParameterDomain& domain,
                            absl::string_view field) {
  if (std::isfinite(value) && value >= domain.start && value <= domain.end) {
    return absl::OkStatus();
  }
  return InvalidFieldError(
      field, absl::StrCat(value, " is not in the domain [", domain.start, ", ",
                          domain.end, "]"));
}

absl::Status CheckInterval(const Curve& curve, double start, double end,
                           double tolerance) {
  RETURN_IF_ERROR(ValidateArcLengthInterval(curve, start, end));
  return ValidatePositive(tolerance, "tolerance");
}

absl::Status CheckOutputSize(absl::Span<double> parameters, size_t expected) {
  if (parameters.size() == expected) return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrCat(
      "parameters holds ", parameters.size(), " values, expected ", expected));
}

// ScaledTolerance returns a tolerance in the copy's units (at most the
// largest double).
double ScaledTolerance(const CurvePieces& pieces, double tolerance) {
  return std::min(pieces.scaled.scale().Unlength(tolerance),
                  std::numeric_limits<double>::max());
}

// ForEachChunk runs chunk(begin, end) over chunks of [0, count) on the
// context's pool (small chunks: each item is a whole integration) and
// returns the first failure of a chunk, or the token's CANCELLED /
// DEADLINE_EXCEEDED.
template <typename Chunk>
absl::Status ForEachChunk(size_t count, const ExecutionContext& context,
                          Chunk chunk) {
  ExecutionContext chunks = context;
  chunks.grain = std::min(context.grain, kSolveGrain);
  std::mutex mutex;
  absl::Status failure;
  absl::Status status = ParallelFor(count, chunks, [&](size_t b, size_t e) {
    if (absl::Status result = chunk(b, e); !result.ok()) {
      const std::lock_guard<std::mutex> lock(mutex);
      failure.Update(result);
    }
  });
  return status.ok() ? failure : status;
}

// What the inverse solves in: the pieces, their table from start to end
// (keeping the stretches' nets), the tolerance of each solve, half the
// call's, in the copy's units, and [start, end] in the original parameters.
struct Inverse {
  CurvePieces pieces;
  LengthTable table;
  double tolerance = 0.0;
  double start = 0.0;
  double end = 0.0;
};

absl::StatusOr<Inverse> BuildInverse(const Curve& curve, double start,
                                     double end, double tolerance,
                                     const CancellationToken* cancel) {
  absl::StatusOr<CurvePieces> pieces =
      LiftCurvePieces(curve, tolerance, cancel);
  if (!pieces.ok()) return pieces.status();
  const double half = 0.5 * ScaledTolerance(*pieces, tolerance);
  absl::StatusOr<LengthTable> table =
      BuildTable(*pieces, pieces->scaled.ToScaled(start),
                 pieces->scaled.ToScaled(end), half, true, cancel);
  if (!table.ok()) return table.status();
  return Inverse{.pieces = *std::move(pieces),
                 .table = *std::move(table),
                 .tolerance = half,
                 .start = start,
                 .end = end};
}

// SolveAll writes the original parameter of Solve(targets(i)) into
// parameters[i] for i < count, in chunks on the context's pool, clamped to
// the inverse's [start, end]: mapped back from the scaled copy, a parameter
// of a domain of 1e170 may round past a start of 1e-300.
template <typename Targets>
absl::Status SolveAll(const Inverse& inverse, size_t count, Targets targets,
                      double* parameters, const ExecutionContext& context) {
  return ForEachChunk(count, context, [&](size_t b, size_t e) {
    SpeedIntegrator integrator;
    const TableReader reader{inverse.pieces, inverse.table, integrator};
    for (size_t i = b; i < e; ++i) {
      absl::StatusOr<double> t = Solve(reader, targets(i), inverse.tolerance);
      if (!t.ok()) return t.status();
      parameters[i] = std::clamp(inverse.pieces.scaled.ToOriginal(*t),
                                 inverse.start, inverse.end);
    }
    return absl::OkStatus();
  });
}

// LengthOf integrates [start, end] of `curve` (original parameters) and
// returns its length in the curve's units.
absl::StatusOr<double> LengthOf(const CurvePieces& pieces, double start,
                                double end, double tolerance,
                                const CancellationToken* cancel) {
  absl::StatusOr<LengthTable> table = BuildTable(
      pieces, pieces.scaled.ToScaled(start), pieces.scaled.ToScaled(end),
      ScaledTolerance(pieces, tolerance), false, cancel);
  if (!table.ok()) return table.status();
  return pieces.scaled.scale().Length(table->total());
}

bool IsRational(const Curve& curve) {
  return std::visit(
      internal::Overloaded{
          [](const BezierCurve& bezier) { return bezier.view().rational(); },
          [](const BSplineCurve& bspline) { return bspline.view().rational(); },
          [](const LagrangeCurve&) { return false; },
          [](const HermiteCurve&) { return false; }},
      curve);
}

}  // namespace

uint64_t ArcLengthWorkValues(const Curve& curve, size_t tables) {
  const uint64_t pieces = CurveBreakpoints(curve).size();
  const uint64_t per_table =
      SaturatingSum(SaturatingProduct(pieces, 48),
                    IsRational(curve) ? kMaxArcLengthWeightValues : 0);
  return SaturatingSum(SaturatingProduct(DecomposedCurveValues(curve), 3),
                       SaturatingProduct(per_table, tables));
}

void GaussLegendreRule(int points, absl::Span<double> nodes,
                       absl::Span<double> weights) {
  const int n = points;
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double derivative = 0.0;
    for (int step = 0; step < 100; ++step) {
      // P_n(x) and P_{n-1}(x) by the three-term recurrence.
      double p0 = 1.0;
      double p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / derivative;
      x -= dx;
      if (std::abs(dx) <= 1e-16) break;
    }
    nodes[static_cast<size_t>(n - 1 - i)] = x;
    weights[static_cast<size_t>(n - 1 - i)] =
        2.0 / ((1.0 - x * x) * derivative * derivative);
  }
}

absl::Status ValidateArcLengthInterval(const Curve& curve, double start,
                                       double end) {
  const ParameterDomain domain = DomainOf(curve);
  RETURN_IF_ERROR(CheckParameter(start, domain, "start"));
  RETURN_IF_ERROR(CheckParameter(end, domain, "end"));
  if (end < start) return InvalidFieldError("end", "must not be below start");
  return absl::OkStatus();
}

absl::StatusOr<double> ArcLength(const Curve& curve, double start, double end,
                                 double tolerance,
                                 const CancellationToken* cancel) {
  RETURN_IF_ERROR(CheckInterval(curve, start, end, tolerance));
  absl::StatusOr<CurvePieces> pieces =
      LiftCurvePieces(curve, tolerance, cancel);
  if (!pieces.ok()) return pieces.status();
  return LengthOf(*pieces, start, end, tolerance, cancel);
}

absl::Status ArcLengths(const Curve& curve, absl::Span<const double> intervals,
                        double tolerance, absl::Span<double> lengths,
                        const ExecutionContext& context) {
  if (intervals.size() % 2 != 0) {
    return InvalidFieldError("intervals", "must hold (start, end) pairs");
  }
  const size_t count = intervals.size() / 2;
  RETURN_IF_ERROR(CheckOutputSize(lengths, count));
  RETURN_IF_ERROR(ValidatePositive(tolerance, "tolerance"));
  for (size_t i = 0; i < count; ++i) {
    if (absl::Status status = CheckInterval(curve, intervals[2 * i],
                                            intervals[2 * i + 1], tolerance);
        !status.ok()) {
      return PrefixFieldPath(status, IndexedField("intervals", i));
    }
  }
  absl::StatusOr<CurvePieces> pieces =
      LiftCurvePieces(curve, tolerance, context.cancellation);
  if (!pieces.ok()) return pieces.status();
  return ForEachChunk(count, context, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      absl::StatusOr<double> length =
          LengthOf(*pieces, intervals[2 * i], intervals[2 * i + 1], tolerance,
                   context.cancellation);
      if (!length.ok()) return length.status();
      lengths[i] = *length;
    }
    return absl::OkStatus();
  });
}

absl::Status ParametersAtArcLengths(const Curve& curve, double start,
                                    absl::Span<const double> lengths,
                                    double tolerance,
                                    absl::Span<double> parameters,
                                    const ExecutionContext& context) {
  const double end = DomainOf(curve).end;
  RETURN_IF_ERROR(CheckInterval(curve, start, end, tolerance));
  RETURN_IF_ERROR(CheckOutputSize(parameters, lengths.size()));
  RETURN_IF_ERROR(ValidateInRange(
      lengths, 0.0, std::numeric_limits<double>::max(), "lengths"));
  absl::StatusOr<Inverse> inverse =
      BuildInverse(curve, start, end, tolerance, context.cancellation);
  if (!inverse.ok()) return inverse.status();
  const internal::ScaledValues& scale = inverse->pieces.scaled.scale();
  const double total = inverse->table.total();
  for (size_t i = 0; i < lengths.size(); ++i) {
    if (scale.Unlength(lengths[i]) > total + 2 * inverse->tolerance) {
      return InvalidFieldError(
          IndexedField("lengths", i),
          absl::StrCat(lengths[i], " is beyond the curve's length ",
                       scale.Length(total), " from start"));
    }
  }
  return SolveAll(
      *inverse, lengths.size(),
      [&](size_t i) { return std::min(scale.Unlength(lengths[i]), total); },
      parameters.data(), context);
}

absl::Status EqualArcLengthParameters(const Curve& curve, double start,
                                      double end, size_t count,
                                      double tolerance,
                                      absl::Span<double> parameters,
                                      const ExecutionContext& context) {
  RETURN_IF_ERROR(CheckInterval(curve, start, end, tolerance));
  if (count < 2) return InvalidFieldError("count", "must be at least 2");
  RETURN_IF_ERROR(CheckOutputSize(parameters, count));
  absl::StatusOr<Inverse> inverse =
      BuildInverse(curve, start, end, tolerance, context.cancellation);
  if (!inverse.ok()) return inverse.status();
  const double last = static_cast<double>(count - 1);
  const double total = inverse->table.total();
  parameters.front() = start;
  parameters.back() = end;
  if (!(total > 0.0)) {
    for (size_t k = 1; k + 1 < count; ++k) {
      parameters[k] = start + (end - start) * (static_cast<double>(k) / last);
    }
    return absl::OkStatus();
  }
  return SolveAll(
      *inverse, count - 2,
      [&](size_t i) { return total * (static_cast<double>(i + 1) / last); },
      parameters.data() + 1, context);
}

}  // namespace freeform
