// Legal requests whose work is far longer than any test deadline, shared
// by the service and integration tests of deadlines and call-time limits.
#ifndef FREEFORM_TESTS_LONG_REQUESTS_H_
#define FREEFORM_TESTS_LONG_REQUESTS_H_

#include <algorithm>
#include <cmath>

#include "freeform/v1/curve_service.pb.h"

namespace freeform {

// LongElevation is a degree-10 B-spline of 16,000 points in 4-D elevated
// by 54: about 10^10 operations for an answer under every limit.
inline v1::ElevateCurveDegreeRequest LongElevation() {
  v1::ElevateCurveDegreeRequest request;
  v1::BSplineCurve* curve = request.mutable_curve()->mutable_bspline();
  constexpr int kCount = 16'000, kDegree = 10;
  curve->set_degree(kDegree);
  curve->mutable_control_points()->set_dimension(4);
  for (int i = 0; i < 4 * kCount; ++i) {
    curve->mutable_control_points()->add_coordinates(std::cos(i));
  }
  for (int k = 0; k < kCount + kDegree + 1; ++k) {
    curve->add_knots(std::clamp(k - kDegree, 0, kCount - kDegree));
  }
  request.set_by(54);
  return request;
}

}  // namespace freeform

#endif  // FREEFORM_TESTS_LONG_REQUESTS_H_
