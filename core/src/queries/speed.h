// The speed |C'(s)| of a lifted curve net (bezier_net.h) and its integral
// over an interval of the net's parameter by the 16-point Gauss-Legendre
// rule: the integrand of the arc-length queries. Internal to the core.
#ifndef FREEFORM_CORE_SRC_QUERIES_SPEED_H_
#define FREEFORM_CORE_SRC_QUERIES_SPEED_H_

#include <array>
#include <cstddef>
#include <limits>
#include <vector>

#include "queries/bezier_net.h"

namespace freeform::internal {

// Two quadrature rules whose values differ by at most this fraction of
// their value agree to rounding; the speed's polynomials are trusted to the
// same fraction of the products they sum (speed_minima.h).
inline constexpr double kRoundingAgreement =
    64 * std::numeric_limits<double>::epsilon();

// Points of the Gauss-Legendre rule of every quadrature step.
inline constexpr int kSpeedRulePoints = 16;

// Reduce runs de Casteljau at s over the first `count` points of `stride`
// values in `points` (overwritten) and returns the point it ends with.
const double* Reduce(double* points, int count, size_t stride, double s);

// Integrates the speed |C'(s)| of a curve net over intervals of its
// parameter with the 16-point rule. Keeps its buffers between calls: one
// per thread.
class SpeedIntegrator {
 public:
  // Integrate returns the rule's value over [a, b] of `net`.
  double Integrate(const Net& net, double a, double b);

  // Speed returns |C'(s)| of `net`: de Casteljau over the differences of
  // its (homogeneous) control points, so that a constant stretch has speed
  // 0 exactly, and for a rational net the quotient rule C' = (A' w - A w')
  // / w^2; the norm is scaled (scaled.h).
  double Speed(const Net& net, double s);

  // The parameters of the rule's nodes, or the speeds there.
  using Nodes = std::array<double, kSpeedRulePoints>;

  // Speeds writes the speeds of `net` at the nodes `s`, as Speed does.
  void Speeds(const Net& net, const Nodes& s, Nodes& speeds);

  // Work returns the arithmetic of one step over two halves, for
  // cancellation polls.
  static size_t Work(const Net& net) {
    return 3 * kSpeedRulePoints * net.values.size() * 8;
  }

 private:
  // ReduceNodes runs de Casteljau at every node s[j] over `count` points
  // of `stride` values, each value spread over the nodes (value x of point
  // i, node j at batch[(i * stride + x) * kSpeedRulePoints + j]).
  static void ReduceNodes(double* batch, int count, size_t stride,
                          const Nodes& s);

  std::vector<double> differences_, values_, gather_;
};

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_QUERIES_SPEED_H_
