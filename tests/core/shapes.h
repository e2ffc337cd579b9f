// Curves and surfaces with exactly known geometry that the query, mesh and
// service tests share, each owning its arrays: the NURBS circle, the twisted
// cubic, sphere and torus patches as rational surfaces of revolution, and
// the closed NURBS sphere and torus; and the evaluation helpers those tests
// use to check answers.
#ifndef FREEFORM_TESTS_CORE_SHAPES_H_
#define FREEFORM_TESTS_CORE_SHAPES_H_

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "absl/types/span.h"
#include "freeform/core/curve.h"
#include "freeform/core/geometry_data.h"
#include "freeform/core/surface.h"

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

// Revolve returns the NURBS surface swept by turning the profile (rho_i,
// z_i, weight w_i) on `profile_knots` a full turn about z with the
// nine-point quadratic circle (The NURBS Book, ex. 7.1 and section 8.5):
// P_ij = (rho_i x_j, rho_i y_j, z_i), w_ij = w_i c_j.
inline SurfaceData Revolve(const std::vector<std::array<double, 3>>& profile,
                           std::vector<double> profile_knots) {
  const BSplineCurveData circle = NurbsCircle(1.0);
  SurfaceData surface{.degree_u = 2,
                      .degree_v = 2,
                      .dimension = 3,
                      .count_u = static_cast<int>(profile.size()),
                      .count_v = 9};
  for (const auto& [rho, z, w] : profile) {
    for (size_t j = 0; j < 9; ++j) {
      surface.coordinates.insert(surface.coordinates.end(),
                                 {rho * circle.coordinates[2 * j],
                                  rho * circle.coordinates[2 * j + 1], z});
      surface.weights.push_back(w * circle.weights[j]);
    }
  }
  surface.knots_u = std::move(profile_knots);
  surface.knots_v = circle.knots;
  return surface;
}

// The sphere of `radius` about the origin: a half circle from the south to
// the north pole, turned a full turn. Both poles are collapsed rows.
inline SurfaceData NurbsSphere(double radius) {
  const double r = radius, s = std::sqrt(0.5);
  return Revolve({{0, -r, 1}, {r, -r, s}, {r, 0, 1}, {r, r, s}, {0, r, 1}},
                 {0, 0, 0, 0.5, 0.5, 1, 1, 1});
}

// The torus with major radius `major` and minor radius `minor`: the full
// tube circle (NurbsCircle about (major, 0)) turned a full turn, closed both
// ways.
inline SurfaceData NurbsTorus(double major, double minor) {
  const BSplineCurveData tube = NurbsCircle(minor, major, 0.0);
  std::vector<std::array<double, 3>> profile;
  for (size_t i = 0; i < tube.weights.size(); ++i) {
    profile.push_back({tube.coordinates[2 * i], tube.coordinates[2 * i + 1],
                       tube.weights[i]});
  }
  return Revolve(profile, tube.knots);
}

// The twisted cubic (t, t^2, t^3) on [0, 1] as a cubic Bezier curve.
inline BezierCurveData TwistedCubic() {
  return {.dimension = 3,
          .coordinates = {0, 0, 0, 1.0 / 3, 0, 0, 2.0 / 3, 1.0 / 3, 0, 1, 1, 1},
          .weights = {}};
}

// Revolution returns the biquadratic rational Bezier patch swept by the
// quarter circle profile (radial distance rho_i, height z_i, weights 1,
// sqrt(1/2), 1) turned by a quarter about the z axis from the x axis to the
// y axis: P_ij = (rho_i x_j, rho_i y_j, z_i), weights w_i w_j (The NURBS
// Book, section 8.5).
inline SurfaceData Revolution(const double rho[3], const double z[3]) {
  const double w = std::sqrt(0.5);
  const double x[3] = {1, 1, 0};
  const double y[3] = {0, 1, 1};
  const double weight[3] = {1, w, 1};
  SurfaceData patch{
      .degree_u = 2, .degree_v = 2, .dimension = 3, .count_u = 3, .count_v = 3};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      patch.coordinates.insert(patch.coordinates.end(),
                               {rho[i] * x[j], rho[i] * y[j], z[i]});
      patch.weights.push_back(weight[i] * weight[j]);
    }
  }
  return patch;
}

// A rational biquadratic Bezier patch of the sphere of `radius` about the
// origin, an octant: the quarter meridian from the equator (u = 0) to the
// north pole (u = 1, a collapsed row) turned by a quarter about z (v from
// the x axis to the y axis). S_u x S_v points into the sphere.
inline SurfaceData SpherePatch(double radius) {
  const double rho[3] = {radius, radius, 0};
  const double z[3] = {0, radius, radius};
  return Revolution(rho, z);
}

// A quarter of a quarter of the torus with major radius R and minor radius
// r: the tube's outer upper quarter (angle phi from 0 to pi/2 in u) turned
// by a quarter about z. Point (theta, phi): ((R + r cos phi) cos theta,
// (R + r cos phi) sin theta, r sin phi).
inline SurfaceData TorusPatch(double major, double minor) {
  const double rho[3] = {major + minor, major + minor, major};
  const double z[3] = {0, minor, minor};
  return Revolution(rho, z);
}

// The rational quadratic corner (1,0), (1,1), (0,1) with weights 1, w, 1:
// a hyperbola for w > 1 that hugs the polyline through (1,1) as w grows
// (it runs from (1,0) to near the corner for t < 1/w and from there to
// (0,1) for t > 1 - 1/w), so its length tends to 2 from below (a convex arc
// inside the triangle of its chord).
inline BezierCurveData RationalCorner(double weight) {
  return {.dimension = 2,
          .coordinates = {1, 0, 1, 1, 0, 1},
          .weights = {1, weight, 1}};
}

// CornerSpeed returns |C'(t)| of RationalCorner(w) from the closed form of
// C = (N_x, N_y) / D, in long double.
inline long double CornerSpeed(long double w, long double t) {
  const long double s = 1 - t;
  const long double d = s * s + 2 * w * t * s + t * t;
  const long double dd = 2 * (w - 1) * (1 - 2 * t);
  const long double nx = s * s + 2 * w * t * s;
  const long double dnx = -2 * s + 2 * w * (1 - 2 * t);
  const long double ny = 2 * w * t * s + t * t;
  const long double dny = 2 * w * (1 - 2 * t) + 2 * t;
  return std::hypot((dnx * d - nx * dd) / (d * d),
                    (dny * d - ny * dd) / (d * d));
}

// CornerLength returns the arc length of RationalCorner(w) over [0, t],
// independently of the library: for t <= 1/2 the speed integrated by
// composite Simpson in x = ln t (where the motion near t = 1/w is a smooth
// step of about one unit of x) from t = 1e-30 / w (the part left out is
// below 1e-29), in long double, accurate to about 1e-12; for t > 1/2 the
// whole length less the length over [0, 1 - t], by the curve's symmetry.
inline long double CornerLength(long double w, double t) {
  if (t > 0.5) return 2 * CornerLength(w, 0.5) - CornerLength(w, 1.0 - t);
  const long double from = std::log(1e-30L / w);
  const long double to = std::log(static_cast<long double>(t));
  if (!(to > from)) return 0;
  const int steps = 2 * static_cast<int>((to - from) / 0.004L + 1);
  const long double h = (to - from) / steps;
  long double sum = 0;
  for (int k = 0; k <= steps; ++k) {
    const long double x = from + k * h;
    const long double f = CornerSpeed(w, std::exp(x)) * std::exp(x);
    sum += (k == 0 || k == steps ? 1 : (k % 2 == 1 ? 4 : 2)) * f;
  }
  return sum * h / 3;
}

// A segment from (-2, -2) to (2, 0) on the knot span [origin + 0.25,
// origin + 0.375] (degree 1, then constant at (2, 0) to origin + 0.75),
// extruded along z from -1 to 1 (u in [0, 1]): a surface crossed by the
// plane x = 0, or by a line in it, at v = origin + 0.3125. At origin 1e15
// the span is two ulps of its position and no double is that v: the nearest
// doubles are the span's ends, where the surface is 2 from the crossing.
inline SurfaceData ShortSpanWall(double origin) {
  SurfaceData wall{.degree_u = 1,
                   .degree_v = 1,
                   .dimension = 3,
                   .count_u = 2,
                   .count_v = 4,
                   .knots_u = {0, 0, 1, 1}};
  for (const double z : {-1.0, 1.0}) {
    for (const auto& [x, y] :
         {std::pair{-2.0, -2.0}, {2.0, 0.0}, {2.0, 0.0}, {2.0, 0.0}}) {
      wall.coordinates.insert(wall.coordinates.end(), {x, y, z});
    }
  }
  for (const double knot : {0.0, 0.25, 0.375, 0.625, 0.75, 1.0}) {
    wall.knots_v.push_back(origin + knot);
  }
  return wall;
}

// CurvePoints returns the curve's points at `parameters`.
inline std::vector<double> CurvePoints(const Curve& curve,
                                       const std::vector<double>& parameters) {
  std::vector<double> points(parameters.size() * DimensionOf(curve));
  const absl::Span<double> output[] = {absl::MakeSpan(points)};
  EXPECT_TRUE(EvaluateCurve(curve, parameters, output).ok());
  return points;
}

// SurfacePoints returns the surface's points at `samples`.
inline std::vector<double> SurfacePoints(const Surface& surface,
                                         const SurfaceSamples& samples) {
  std::vector<double> points(samples.size() * DimensionOf(surface));
  const absl::Span<double> output[] = {absl::MakeSpan(points)};
  EXPECT_TRUE(EvaluateSurface(surface, samples, output, {}).ok());
  return points;
}

// PointDistance returns |a - b|.
inline double PointDistance(const double* a, const double* b, int dimension) {
  double sum = 0.0;
  for (int x = 0; x < dimension; ++x) sum += (a[x] - b[x]) * (a[x] - b[x]);
  return std::sqrt(sum);
}

}  // namespace freeform::testing_util

#endif  // FREEFORM_TESTS_CORE_SHAPES_H_
