// The workloads' curve W1, surface W3 and mesh torus M1 (docs/benchmarks.md)
// as the core's owning geometry (freeform/core/geometry_data.h), for the
// benchmark programs, the core's and the peers'; the data comes from
// workloads.h.
#ifndef FREEFORM_BENCH_CORE_WORKLOADS_H_
#define FREEFORM_BENCH_CORE_WORKLOADS_H_

#include <numbers>

#include "freeform/core/geometry_data.h"
#include "workloads.h"

namespace freeform::bench {

// W1: cubic clamped B-spline, 100 3D control points from LCG seed 1,
// clamped uniform knots.
inline BSplineCurveData W1Curve() {
  return {.degree = 3,
          .dimension = 3,
          .coordinates = RandomPoints(1, 100, 3),
          .knots = ClampedUniformKnots(100, 3),
          .weights = {}};
}

// W3: bicubic clamped B-spline surface, 20 x 20 control points from LCG
// seed 2 (row-major, u the row index), clamped uniform knots both ways.
inline SurfaceData W3Surface() {
  return {.degree_u = 3,
          .degree_v = 3,
          .dimension = 3,
          .count_u = 20,
          .count_v = 20,
          .coordinates = RandomPoints(2, 20 * 20, 3),
          .knots_u = ClampedUniformKnots(20, 3),
          .knots_v = ClampedUniformKnots(20, 3),
          .weights = {}};
}

// M1: the NURBS torus, the tube circle (radius `minor` about (major, 0))
// turned a full turn about z: nine-point quadratic circles both ways.
inline SurfaceData NurbsTorus(double major, double minor) {
  const double s = std::numbers::sqrt2 / 2;
  const double cx[9] = {1, 1, 0, -1, -1, -1, 0, 1, 1};
  const double cy[9] = {0, 1, 1, 1, 0, -1, -1, -1, 0};
  const double cw[9] = {1, s, 1, s, 1, s, 1, s, 1};
  SurfaceData torus{
      .degree_u = 2, .degree_v = 2, .dimension = 3, .count_u = 9, .count_v = 9};
  for (int i = 0; i < 9; ++i) {
    const double rho = major + minor * cx[i], z = minor * cy[i];
    for (int j = 0; j < 9; ++j) {
      torus.coordinates.insert(torus.coordinates.end(),
                               {rho * cx[j], rho * cy[j], z});
      torus.weights.push_back(cw[i] * cw[j]);
    }
  }
  torus.knots_u = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
  torus.knots_v = torus.knots_u;
  return torus;
}

}  // namespace freeform::bench

#endif  // FREEFORM_BENCH_CORE_WORKLOADS_H_
