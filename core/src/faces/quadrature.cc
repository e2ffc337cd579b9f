#include "faces/quadrature.h"

#include <array>
#include <cmath>
#include <queue>
#include <vector>

#include "absl/status/status.h"
#include "freeform/core/status_macros.h"

namespace freeform::internal {
namespace {

// The 15-point Kronrod nodes on [-1, 1] (ascending) and weights, and the
// 7-point Gauss weights at the odd nodes (QUADPACK's qk15).
constexpr std::array<double, 8> kAbscissae = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
constexpr std::array<double, 8> kKronrodWeights = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr std::array<double, 4> kGaussWeights = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

// Node k of 0..14 on [-1, 1] and its weights.
double Abscissa(int k) { return k < 7 ? -kAbscissae[k] : kAbscissae[14 - k]; }
double KronrodWeight(int k) { return kKronrodWeights[k < 7 ? k : 14 - k]; }
double GaussWeight(int k) {
  if (k % 2 == 0) return 0.0;
  const int m = k < 7 ? k : 14 - k;
  return kGaussWeights[m / 2];
}

struct Interval {
  PartInterval where;
  Estimate estimate;
  bool operator<(const Interval& other) const {
    return estimate.error < other.estimate.error;
  }
};

}  // namespace

double KronrodNode(double a, double b, int k) {
  const double centre = 0.5 * (a + b);
  const double half = 0.5 * (b - a);
  return centre + half * Abscissa(k);
}

Estimate KronrodInterval(double a, double b, const Estimate* values) {
  const double half = 0.5 * (b - a);
  double kronrod = 0.0, gauss = 0.0, inherited = 0.0;
  for (int k = 0; k < kKronrodPoints; ++k) {
    kronrod += KronrodWeight(k) * values[k].value;
    gauss += GaussWeight(k) * values[k].value;
    inherited += KronrodWeight(k) * values[k].error;
  }
  return {.value = half * kronrod,
          .error = std::abs(half) * (std::abs(kronrod - gauss) + inherited)};
}

uint64_t IntegrateAdaptiveBytes(uint64_t max_intervals) {
  // One more than the limit may be pushed before the loop stops.
  return 2 * (max_intervals + 2) * sizeof(Interval);
}

absl::StatusOr<Estimate> IntegrateAdaptive(KronrodIntegrand integrand,
                                           absl::Span<const PartInterval> parts,
                                           double tolerance,
                                           size_t max_intervals,
                                           const CancellationToken* cancel) {
  std::array<Estimate, kKronrodPoints> values;
  const auto measure =
      [&](const PartInterval& where) -> absl::StatusOr<Interval> {
    RETURN_IF_ERROR(integrand(where.part, where.a, where.b, values.data()));
    return Interval{where, KronrodInterval(where.a, where.b, values.data())};
  };
  std::priority_queue<Interval> heap;
  Estimate total;
  CancellationPoll poll(cancel, 64);
  for (const PartInterval& where : parts) {
    ASSIGN_OR_RETURN(Interval interval, measure(where));
    total.value += interval.estimate.value;
    total.error += interval.estimate.error;
    heap.push(interval);
    RETURN_IF_ERROR(poll.Done(1));
  }
  while (!heap.empty() && total.error > tolerance &&
         heap.size() < max_intervals) {
    const Interval worst = heap.top();
    const PartInterval& w = worst.where;
    const double middle = 0.5 * (w.a + w.b);
    if (!(middle > w.a && middle < w.b)) break;
    heap.pop();
    ASSIGN_OR_RETURN(Interval left, measure({w.part, w.a, middle}));
    ASSIGN_OR_RETURN(Interval right, measure({w.part, middle, w.b}));
    total.value +=
        left.estimate.value + right.estimate.value - worst.estimate.value;
    total.error +=
        left.estimate.error + right.estimate.error - worst.estimate.error;
    heap.push(left);
    heap.push(right);
    RETURN_IF_ERROR(poll.Done(2));
  }
  // The running sums drift by rounding: add the intervals up again.
  total = {};
  while (!heap.empty()) {
    total.value += heap.top().estimate.value;
    total.error += heap.top().estimate.error;
    heap.pop();
  }
  return total;
}

absl::StatusOr<Estimate> IntegrateAdaptive(KronrodIntegrand integrand, double a,
                                           double b, double tolerance,
                                           size_t max_intervals,
                                           const CancellationToken* cancel) {
  const PartInterval whole[] = {{.part = 0, .a = a, .b = b}};
  return IntegrateAdaptive(integrand, whole, tolerance, max_intervals, cancel);
}

}  // namespace freeform::internal
