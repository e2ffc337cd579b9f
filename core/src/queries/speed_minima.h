// The parameters where the arc-length quadrature cuts a curve net: the
// sharp local minima of its speed |C'|, where the speed has a kink that the
// 16-point rule integrates badly, and badly alike on an interval and on its
// halves. Internal to the core.
#ifndef FREEFORM_CORE_SRC_QUERIES_SPEED_MINIMA_H_
#define FREEFORM_CORE_SRC_QUERIES_SPEED_MINIMA_H_

#include <vector>

#include "absl/types/span.h"
#include "queries/bezier_net.h"
#include "queries/speed.h"

namespace freeform::internal {

// Finds the cuts of curve nets. Keeps its buffers between calls: one per
// thread.
class SpeedMinimaSearch {
 public:
  // Cuts returns 0, the parameters in (0, 1) where the speed of `net` has a
  // sharp local minimum, and 1, in increasing order; the span is valid
  // until the next call.
  absl::Span<const double> Cuts(const Net& net, SpeedIntegrator& integrator);

 private:
  bool PolynomialSlope(const Net& net, double sharp);
  void RationalSlope(const Net& net);
  void AppendMinima(int depth, double lo, double hi);
  double BisectRoot(const double* slope, int steps);
  void KeepSharpMinima(const Net& net, double sharp,
                       SpeedIntegrator& integrator);

  // The slope polynomial's coefficients (a polynomial of the sign of the
  // derivative of |C'|^2), and what rounding may put in them.
  std::vector<double> slope_;
  double noise_ = 0.0;
  // Halvings of the slope left for this net.
  int halvings_ = 0;
  // Per depth of the halving, the part being searched and its upper half
  // waiting, each slope_.size() values.
  std::vector<double> parts_, waiting_, scratch_;
  std::vector<double> hodograph_, squared_speed_, binomials_;
  std::vector<double> cuts_;
};

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_QUERIES_SPEED_MINIMA_H_
