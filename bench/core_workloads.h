// The workloads' curve W1 and surface W3 (docs/benchmarks.md) as the core's
// owning geometry (freeform/core/geometry_data.h), for the benchmark
// programs that call the core; the data comes from workloads.h.
#ifndef FREEFORM_BENCH_CORE_WORKLOADS_H_
#define FREEFORM_BENCH_CORE_WORKLOADS_H_

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

}  // namespace freeform::bench

#endif  // FREEFORM_BENCH_CORE_WORKLOADS_H_
