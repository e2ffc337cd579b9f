#include "freeform/core/arc_length.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <vector>

#include "absl/strings/str_cat.h"
#include "freeform/core/curve_output.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"

namespace freeform {
namespace {

// Points of the Gauss-Legendre rule of every quadrature step.
constexpr int kRulePoints = 16;
// Newton steps of the inverse before it settles for the bracket.
constexpr int kMaxNewtonSteps = 100;
// Parameters solved per chunk of ParametersAtArcLengths.
constexpr size_t kSolveGrain = 64;

// Two quadrature rules whose values differ by at most this fraction of
// their value agree to rounding.
constexpr double kRoundingAgreement =
    64 * std::numeric_limits<double>::epsilon();

struct Rule {
  std::array<double, kRulePoints> nodes;
  std::array<double, kRulePoints> weights;
};

const Rule& SixteenPointRule() {
  static const Rule rule = [] {
    Rule r;
    GaussLegendreRule(kRulePoints, absl::MakeSpan(r.nodes),
                      absl::MakeSpan(r.weights));
    return r;
  }();
  return rule;
}

// Integrates the speed |C'| of one curve over intervals with the 16-point
// rule. Keeps its buffers between calls: one per thread.
class SpeedIntegrator {
 public:
  explicit SpeedIntegrator(const Curve& curve)
      : curve_(curve), dimension_(DimensionOf(curve)) {}

  // Integrate writes the rule's value over [ends[k], ends[k + 1]] into
  // sums[k] for every consecutive pair of `ends`.
  absl::Status Integrate(absl::Span<const double> ends, double* sums) {
    parameters_.clear();
    for (size_t k = 0; k + 1 < ends.size(); ++k) AddNodes(ends[k], ends[k + 1]);
    if (absl::Status status = Speeds(); !status.ok()) return status;
    for (size_t k = 0; k + 1 < ends.size(); ++k) {
      sums[k] = RuleSum(ends[k], ends[k + 1], k * kRulePoints);
    }
    return absl::OkStatus();
  }

  // LengthAndSpeed writes the rule's value over [a, t] and |C'(t)|.
  absl::Status LengthAndSpeed(double a, double t, double& length,
                              double& speed) {
    parameters_.clear();
    AddNodes(a, t);
    parameters_.push_back(t);
    if (absl::Status status = Speeds(); !status.ok()) return status;
    length = RuleSum(a, t, 0);
    speed = speeds_[kRulePoints];
    return absl::OkStatus();
  }

  // Work returns the arithmetic of one Integrate step over two intervals,
  // for cancellation polls.
  size_t Work() const {
    return 2 * kRulePoints * static_cast<size_t>(dimension_ + 1) * 16;
  }

 private:
  void AddNodes(double a, double b) {
    const Rule& rule = SixteenPointRule();
    const double mid = 0.5 * (a + b);
    const double half = 0.5 * (b - a);
    for (const double x : rule.nodes) {
      parameters_.push_back(std::clamp(mid + half * x, a, b));
    }
  }

  double RuleSum(double a, double b, size_t first) const {
    const Rule& rule = SixteenPointRule();
    double sum = 0.0;
    for (int i = 0; i < kRulePoints; ++i) {
      sum += rule.weights[i] * speeds_[first + static_cast<size_t>(i)];
    }
    return 0.5 * (b - a) * sum;
  }

  absl::Status Speeds() {
    const size_t size = parameters_.size() * static_cast<size_t>(dimension_);
    points_.resize(size);
    derivatives_.resize(size);
    const absl::Span<double> output[] = {absl::MakeSpan(points_),
                                         absl::MakeSpan(derivatives_)};
    if (absl::Status status = EvaluateCurve(curve_, parameters_, output);
        !status.ok()) {
      return status;
    }
    speeds_.resize(parameters_.size());
    for (size_t r = 0; r < parameters_.size(); ++r) {
      double sum = 0.0;
      for (int j = 0; j < dimension_; ++j) {
        const double d = derivatives_[r * static_cast<size_t>(dimension_) + j];
        sum += d * d;
      }
      speeds_[r] = std::sqrt(sum);
    }
    return absl::OkStatus();
  }

  const Curve& curve_;
  const int dimension_;
  std::vector<double> parameters_, points_, derivatives_, speeds_;
};

// The arc length from ends[0] to every ends[k]: the ends of the intervals
// the adaptive quadrature kept, in increasing order.
struct LengthTable {
  std::vector<double> ends;
  std::vector<double> cumulative;

  double total() const { return cumulative.back(); }
};

// The interval [a, b] still to be integrated, with the rule's value on it.
struct Pending {
  double a;
  double b;
  double whole;
  int depth;
};

// AddPiece integrates [a, b] (one smooth piece) adaptively into `table`
// with the share tolerance * (b' - a') / width of every kept interval
// [a', b'].
absl::Status AddPiece(double a, double b, double tolerance, double width,
                      SpeedIntegrator& integrator, CancellationPoll& poll,
                      LengthTable& table) {
  double whole = 0.0;
  const double piece[] = {a, b};
  if (absl::Status status = integrator.Integrate(piece, &whole); !status.ok()) {
    return status;
  }
  std::vector<Pending> stack = {{a, b, whole, 0}};
  size_t kept = 0;
  while (!stack.empty()) {
    const Pending top = stack.back();
    stack.pop_back();
    const double mid = 0.5 * (top.a + top.b);
    const double halves_ends[] = {top.a, mid, top.b};
    double halves[2];
    if (absl::Status status = integrator.Integrate(halves_ends, halves);
        !status.ok()) {
      return status;
    }
    if (absl::Status status = poll.Done(integrator.Work()); !status.ok()) {
      return status;
    }
    // Rules that agree to rounding of their value cannot do better (a
    // tolerance below what double precision resolves would otherwise
    // halve every interval kMaxArcLengthDepth times, 2^40 intervals), nor
    // can rules that overflowed.
    const double sum = halves[0] + halves[1];
    const double difference = std::abs(top.whole - sum);
    const bool settled =
        difference <= tolerance * (top.b - top.a) / width ||
        difference <= kRoundingAgreement * sum || !std::isfinite(sum) ||
        top.depth >= kMaxArcLengthDepth ||
        kept + 2 * stack.size() + 2 >= kMaxArcLengthIntervals ||
        !(top.a < mid && mid < top.b);
    if (settled) {
      kept += 2;
      table.ends.push_back(mid);
      table.cumulative.push_back(table.total() + halves[0]);
      table.ends.push_back(top.b);
      table.cumulative.push_back(table.total() + halves[1]);
      continue;
    }
    stack.push_back({mid, top.b, halves[1], top.depth + 1});
    stack.push_back({top.a, mid, halves[0], top.depth + 1});
  }
  return absl::OkStatus();
}

// BuildTable integrates [start, end] piece by piece between the curve's
// breakpoints, within `tolerance` in all.
absl::StatusOr<LengthTable> BuildTable(const Curve& curve, double start,
                                       double end, double tolerance,
                                       const CancellationToken* cancel) {
  LengthTable table{.ends = {start}, .cumulative = {0.0}};
  if (!(start < end)) return table;
  std::vector<double> cuts = {start};
  for (const double breakpoint : CurveBreakpoints(curve)) {
    if (breakpoint > start && breakpoint < end) cuts.push_back(breakpoint);
  }
  cuts.push_back(end);
  SpeedIntegrator integrator(curve);
  CancellationPoll poll(cancel);
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    if (absl::Status status = AddPiece(cuts[k], cuts[k + 1], tolerance,
                                       end - start, integrator, poll, table);
        !status.ok()) {
      return status;
    }
  }
  return table;
}

// Solve returns the parameter whose length from table.ends[0] is `length`
// (0 <= length <= table.total()) within `tolerance`: Newton's method with
// bisection on the kept interval that holds it.
absl::StatusOr<double> Solve(const LengthTable& table, double length,
                             double tolerance, SpeedIntegrator& integrator) {
  const std::vector<double>& cumulative = table.cumulative;
  if (length >= table.total()) return table.ends.back();
  const size_t k = static_cast<size_t>(
      std::upper_bound(cumulative.begin(), cumulative.end(), length) -
      cumulative.begin() - 1);
  const double a = table.ends[k];
  const double base = cumulative[k];
  const double span = cumulative[k + 1] - base;
  double lo = a;
  double hi = table.ends[k + 1];
  double t = span > 0.0 ? a + (length - base) / span * (hi - a) : a;
  for (int step = 0; step < kMaxNewtonSteps; ++step) {
    double partial = 0.0;
    double speed = 0.0;
    if (absl::Status status = integrator.LengthAndSpeed(a, t, partial, speed);
        !status.ok()) {
      return status;
    }
    const double residual = base + partial - length;
    if (std::abs(residual) <= tolerance) return t;
    (residual < 0.0 ? lo : hi) = t;
    double next = speed > 0.0 ? t - residual / speed : lo;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == t || !(lo < hi)) return t;
    t = next;
  }
  return t;
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
  const ParameterDomain domain = DomainOf(curve);
  if (absl::Status status = CheckParameter(start, domain, "start");
      !status.ok()) {
    return status;
  }
  if (absl::Status status = CheckParameter(end, domain, "end"); !status.ok()) {
    return status;
  }
  if (end < start) return InvalidFieldError("end", "must not be below start");
  return ValidatePositive(tolerance, "tolerance");
}

absl::Status CheckOutputSize(absl::Span<double> parameters, size_t expected) {
  if (parameters.size() == expected) return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrCat(
      "parameters holds ", parameters.size(), " values, expected ", expected));
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

// SolveAll writes Solve(targets(i)) into parameters[first + i] for
// i < count, in chunks on the context's pool.
template <typename Targets>
absl::Status SolveAll(const Curve& curve, const LengthTable& table,
                      size_t count, Targets targets, double tolerance,
                      double* parameters, const ExecutionContext& context) {
  return ForEachChunk(count, context, [&](size_t b, size_t e) {
    SpeedIntegrator integrator(curve);
    for (size_t i = b; i < e; ++i) {
      absl::StatusOr<double> t =
          Solve(table, targets(i), tolerance, integrator);
      if (!t.ok()) return t.status();
      parameters[i] = *t;
    }
    return absl::OkStatus();
  });
}

}  // namespace

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

absl::StatusOr<double> ArcLength(const Curve& curve, double start, double end,
                                 double tolerance,
                                 const CancellationToken* cancel) {
  if (absl::Status status = CheckInterval(curve, start, end, tolerance);
      !status.ok()) {
    return status;
  }
  absl::StatusOr<LengthTable> table =
      BuildTable(curve, start, end, tolerance, cancel);
  if (!table.ok()) return table.status();
  return table->total();
}

absl::Status ArcLengths(const Curve& curve, absl::Span<const double> intervals,
                        double tolerance, absl::Span<double> lengths,
                        const ExecutionContext& context) {
  if (intervals.size() % 2 != 0) {
    return InvalidFieldError("intervals", "must hold (start, end) pairs");
  }
  const size_t count = intervals.size() / 2;
  if (absl::Status status = CheckOutputSize(lengths, count); !status.ok()) {
    return status;
  }
  if (absl::Status status = ValidatePositive(tolerance, "tolerance");
      !status.ok()) {
    return status;
  }
  for (size_t i = 0; i < count; ++i) {
    if (absl::Status status = CheckInterval(curve, intervals[2 * i],
                                            intervals[2 * i + 1], tolerance);
        !status.ok()) {
      return PrefixFieldPath(status, IndexedField("intervals", i));
    }
  }
  return ForEachChunk(count, context, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      absl::StatusOr<LengthTable> table =
          BuildTable(curve, intervals[2 * i], intervals[2 * i + 1], tolerance,
                     context.cancellation);
      if (!table.ok()) return table.status();
      lengths[i] = table->total();
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
  if (absl::Status status = CheckInterval(curve, start, end, tolerance);
      !status.ok()) {
    return status;
  }
  if (absl::Status status = CheckOutputSize(parameters, lengths.size());
      !status.ok()) {
    return status;
  }
  if (absl::Status status = ValidateInRange(
          lengths, 0.0, std::numeric_limits<double>::max(), "lengths");
      !status.ok()) {
    return status;
  }
  absl::StatusOr<LengthTable> table =
      BuildTable(curve, start, end, 0.5 * tolerance, context.cancellation);
  if (!table.ok()) return table.status();
  for (size_t i = 0; i < lengths.size(); ++i) {
    if (lengths[i] > table->total() + tolerance) {
      return InvalidFieldError(
          IndexedField("lengths", i),
          absl::StrCat(lengths[i], " is beyond the curve's length ",
                       table->total(), " from start"));
    }
  }
  return SolveAll(
      curve, *table, lengths.size(),
      [&](size_t i) { return std::min(lengths[i], table->total()); },
      0.5 * tolerance, parameters.data(), context);
}

absl::Status EqualArcLengthParameters(const Curve& curve, double start,
                                      double end, size_t count,
                                      double tolerance,
                                      absl::Span<double> parameters,
                                      const ExecutionContext& context) {
  if (absl::Status status = CheckInterval(curve, start, end, tolerance);
      !status.ok()) {
    return status;
  }
  if (count < 2) return InvalidFieldError("count", "must be at least 2");
  if (absl::Status status = CheckOutputSize(parameters, count); !status.ok()) {
    return status;
  }
  absl::StatusOr<LengthTable> table =
      BuildTable(curve, start, end, 0.5 * tolerance, context.cancellation);
  if (!table.ok()) return table.status();
  const double last = static_cast<double>(count - 1);
  parameters.front() = start;
  parameters.back() = end;
  if (!(table->total() > 0.0)) {
    for (size_t k = 1; k + 1 < count; ++k) {
      parameters[k] = start + (end - start) * (static_cast<double>(k) / last);
    }
    return absl::OkStatus();
  }
  return SolveAll(
      curve, *table, count - 2,
      [&](size_t i) {
        return table->total() * (static_cast<double>(i + 1) / last);
      },
      0.5 * tolerance, parameters.data() + 1, context);
}

}  // namespace freeform
