// Owning geometry: the results of operations that build new curves and
// surfaces (degree elevation, knot insertion, interpolation, ...). Each type
// owns its arrays and hands out the matching read-only view of bezier.h,
// bspline.h or tensor_surface.h. Value types: copyable, movable, not
// synchronized.
#ifndef FREEFORM_CORE_GEOMETRY_DATA_H_
#define FREEFORM_CORE_GEOMETRY_DATA_H_

#include <vector>

#include "freeform/core/bezier.h"
#include "freeform/core/bspline.h"
#include "freeform/core/tensor_surface.h"

namespace freeform {

// A Bezier curve (rational when `weights` is not empty).
struct BezierCurveData {
  int dimension = 0;
  std::vector<double> coordinates;
  std::vector<double> weights;

  BezierCurveView view() const {
    return {.control_points = {dimension, coordinates}, .weights = weights};
  }
};

// A B-spline curve (NURBS when `weights` is not empty).
struct BSplineCurveData {
  int degree = 0;
  int dimension = 0;
  std::vector<double> coordinates;
  std::vector<double> knots;
  std::vector<double> weights;

  BSplineCurveView view() const {
    return {.degree = degree,
            .control_points = {dimension, coordinates},
            .knots = knots,
            .weights = weights};
  }
};

// A tensor-product B-spline (NURBS) surface; a Bezier surface when both
// knot vectors are empty.
struct SurfaceData {
  int degree_u = 0;
  int degree_v = 0;
  int dimension = 0;
  int count_u = 0;
  int count_v = 0;
  std::vector<double> coordinates;
  std::vector<double> knots_u;
  std::vector<double> knots_v;
  std::vector<double> weights;

  ControlNetView net() const {
    return {.dimension = dimension,
            .count_u = count_u,
            .count_v = count_v,
            .coordinates = coordinates};
  }
  BezierSurfaceView bezier_view() const {
    return {.control_net = net(), .weights = weights};
  }
  BSplineSurfaceView bspline_view() const {
    return {.degree_u = degree_u,
            .degree_v = degree_v,
            .control_net = net(),
            .knots_u = knots_u,
            .knots_v = knots_v,
            .weights = weights};
  }
};

}  // namespace freeform

#endif  // FREEFORM_CORE_GEOMETRY_DATA_H_
