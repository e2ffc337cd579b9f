// Curves and surfaces with known geometry that the query tests (arc
// length, differential geometry, bounding boxes) share: the NURBS circle,
// the twisted cubic and a rational sphere patch, each owning its arrays.
#ifndef FREEFORM_TESTS_CORE_SHAPES_H_
#define FREEFORM_TESTS_CORE_SHAPES_H_

#include <cmath>
#include <vector>

#include "freeform/core/geometry_data.h"

namespace freeform::testing_util {

// The full circle of `radius` about (cx, cy) as a quadratic NURBS curve of
// nine control points on knots 0,0,0, 1/4,1/4, 1/2,1/2, 3/4,3/4, 1,1,1
// (The NURBS Book, ex. 7.1): one quarter per span, not at constant speed.
inline BSplineCurveData NurbsCircle(double radius, double cx = 0.0,
                                    double cy = 0.0) {
  const double w = std::sqrt(0.5);
  const double unit[9][2] = {{1, 0},   {1, 1},  {0, 1},  {-1, 1}, {-1, 0},
                             {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
  BSplineCurveData circle{.degree = 2, .dimension = 2};
  for (const auto& p : unit) {
    circle.coordinates.push_back(cx + radius * p[0]);
    circle.coordinates.push_back(cy + radius * p[1]);
  }
  circle.weights = {1, w, 1, w, 1, w, 1, w, 1};
  circle.knots = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
  return circle;
}

// The twisted cubic (t, t^2, t^3) on [0, 1] as a cubic Bezier curve.
inline BezierCurveData TwistedCubic() {
  return {.dimension = 3,
          .coordinates = {0, 0, 0, 1.0 / 3, 0, 0, 2.0 / 3, 1.0 / 3, 0, 1, 1, 1},
          .weights = {}};
}

// A rational biquadratic Bezier patch of the sphere of `radius` about the
// origin: the quarter meridian from the equator (u = 0) to the north pole
// (u = 1, a collapsed row) turned by a quarter about z (v from the x axis
// to the y axis). It is the surface of revolution (rho(u) X(v), rho(u)
// Y(v), z(u)) of two rational quarter circles, so its net is P_ij =
// (rho_i x_j, rho_i y_j, z_i) with weights w_i w_j. S_u x S_v points into
// the sphere.
inline SurfaceData SpherePatch(double radius) {
  const double w = std::sqrt(0.5);
  const double rho[3] = {radius, radius, 0};
  const double z[3] = {0, radius, radius};
  const double x[3] = {1, 1, 0};
  const double y[3] = {0, 1, 1};
  const double weight[3] = {1, w, 1};
  SurfaceData sphere{
      .degree_u = 2, .degree_v = 2, .dimension = 3, .count_u = 3, .count_v = 3};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      sphere.coordinates.insert(sphere.coordinates.end(),
                                {rho[i] * x[j], rho[i] * y[j], z[i]});
      sphere.weights.push_back(weight[i] * weight[j]);
    }
  }
  return sphere;
}

}  // namespace freeform::testing_util

#endif  // FREEFORM_TESTS_CORE_SHAPES_H_
