// Trim loops and planes with known geometry for the trimmed-face tests and
// benchmark: the unit square as a plane, circles of either orientation
// (the NURBS circle), squares, polylines and a flower-shaped B-spline loop,
// each owning its arrays; LoopOf wraps them as a TrimLoop of views.
#ifndef FREEFORM_TESTS_CORE_TRIM_SHAPES_H_
#define FREEFORM_TESTS_CORE_TRIM_SHAPES_H_

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "freeform/core/curve.h"
#include "freeform/core/geometry_data.h"
#include "freeform/core/surface.h"
#include "freeform/core/trimmed_surface.h"
#include "shapes.h"

namespace freeform::trim_testing {

// S(u, v) = (u, v, 0) on [0, 1]^2 as a bilinear Bezier patch.
inline SurfaceData BilinearPlane() {
  return {.degree_u = 1,
          .degree_v = 1,
          .dimension = 3,
          .count_u = 2,
          .count_v = 2,
          .coordinates = {0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0}};
}

// The same plane as a bilinear B-spline with knots at u = 0.5, v = 0.5.
inline SurfaceData KnottedPlane() {
  SurfaceData plane{
      .degree_u = 1, .degree_v = 1, .dimension = 3, .count_u = 3, .count_v = 3};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      plane.coordinates.insert(plane.coordinates.end(),
                               {0.5 * i, 0.5 * j, 0.0});
    }
  }
  plane.knots_u = {0, 0, 0.5, 1, 1};
  plane.knots_v = {0, 0, 0.5, 1, 1};
  return plane;
}

// The quarter cylinder of `radius` about the z axis as a rational Bezier
// patch: u around it from +x to +y (the rational quadratic arc), v along it
// from z = 0 to `height`.
inline SurfaceData QuarterCylinder(double radius, double height) {
  const double w = std::sqrt(0.5);
  const double arc[3][2] = {{1, 0}, {1, 1}, {0, 1}};
  SurfaceData cylinder{
      .degree_u = 2, .degree_v = 1, .dimension = 3, .count_u = 3, .count_v = 2};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 2; ++j) {
      cylinder.coordinates.insert(
          cylinder.coordinates.end(),
          {radius * arc[i][0], radius * arc[i][1], height * j});
      cylinder.weights.push_back(i == 1 ? w : 1.0);
    }
  }
  return cylinder;
}

// Reversed returns the curve run backwards (its knots mirrored).
inline BSplineCurveData Reversed(const BSplineCurveData& curve) {
  BSplineCurveData reversed = curve;
  const size_t n = curve.coordinates.size() / 2;
  for (size_t i = 0; i < n; ++i) {
    reversed.coordinates[2 * i] = curve.coordinates[2 * (n - 1 - i)];
    reversed.coordinates[2 * i + 1] = curve.coordinates[2 * (n - 1 - i) + 1];
  }
  reversed.weights.assign(curve.weights.rbegin(), curve.weights.rend());
  const double ends = curve.knots.front() + curve.knots.back();
  for (size_t i = 0; i < curve.knots.size(); ++i) {
    reversed.knots[i] = ends - curve.knots[curve.knots.size() - 1 - i];
  }
  return reversed;
}

// The circle of radius r about (cu, cv), clockwise: a hole.
inline BSplineCurveData ClockwiseCircle(double r, double cu, double cv) {
  return Reversed(testing_util::NurbsCircle(r, cu, cv));
}

// Turned returns the curve turned by `angle` about (cu, cv).
inline BSplineCurveData Turned(BSplineCurveData curve, double cu, double cv,
                               double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  for (size_t i = 0; i + 1 < curve.coordinates.size(); i += 2) {
    const double x = curve.coordinates[i] - cu;
    const double y = curve.coordinates[i + 1] - cv;
    curve.coordinates[i] = cu + c * x - s * y;
    curve.coordinates[i + 1] = cv + s * x + c * y;
  }
  return curve;
}

// BrokenLine returns the segments between consecutive points.
inline std::vector<BezierCurveData> BrokenLine(
    const std::vector<std::array<double, 2>>& points) {
  std::vector<BezierCurveData> segments;
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    segments.push_back({.dimension = 2,
                        .coordinates = {points[i][0], points[i][1],
                                        points[i + 1][0], points[i + 1][1]},
                        .weights = {}});
  }
  return segments;
}

// The rectangle [u0, u1] x [v0, v1], counter-clockwise.
inline std::vector<BezierCurveData> Square(double u0, double v0, double u1,
                                           double v1) {
  return BrokenLine({{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}, {u0, v0}});
}

// Reversed returns a chain of segments run backwards.
inline std::vector<BezierCurveData> Reversed(
    const std::vector<BezierCurveData>& chain) {
  std::vector<BezierCurveData> reversed;
  for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
    BezierCurveData segment = *it;
    const size_t n = segment.coordinates.size() / 2;
    for (size_t i = 0; i < n; ++i) {
      segment.coordinates[2 * i] = it->coordinates[2 * (n - 1 - i)];
      segment.coordinates[2 * i + 1] = it->coordinates[2 * (n - 1 - i) + 1];
    }
    reversed.push_back(segment);
  }
  return reversed;
}

// A closed clamped cubic B-spline whose `count` control points lie on
// r(theta) = radius + amplitude cos(petals theta) about (cu, cv),
// counter-clockwise, the first repeated as the last.
inline BSplineCurveData Flower(double cu, double cv, double radius,
                               double amplitude, int petals, int count = 40) {
  BSplineCurveData flower{.degree = 3, .dimension = 2};
  for (int i = 0; i <= count; ++i) {
    const double theta = 2 * std::numbers::pi * (i % count) / count;
    const double r = radius + amplitude * std::cos(petals * theta);
    flower.coordinates.push_back(cu + r * std::cos(theta));
    flower.coordinates.push_back(cv + r * std::sin(theta));
  }
  const int n = count + 1;
  for (int k = 0; k < n + 4; ++k) {
    flower.knots.push_back(std::clamp(k - 3, 0, n - 3) / double(n - 3));
  }
  return flower;
}

// The circles of radius r about the centres of a side x side grid of
// cells of the unit square, clockwise: holes.
inline std::vector<BSplineCurveData> GridOfHoles(int side, double r) {
  std::vector<BSplineCurveData> circles;
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      circles.push_back(ClockwiseCircle(r, (i + 0.5) / side, (j + 0.5) / side));
    }
  }
  return circles;
}

// PolygonVertex returns vertex k (taken modulo n) of the regular n-gon of
// `radius` about (cu, cv), vertex 0 on the +u axis.
inline std::array<double, 2> PolygonVertex(int n, double radius, double cu,
                                           double cv, int k) {
  const double theta = 2 * std::numbers::pi * (k % n) / n;
  return {cu + radius * std::cos(theta), cv + radius * std::sin(theta)};
}

// The regular n-gon as one degree-1 B-spline, counter-clockwise (n linear
// segments, the first vertex repeated as the last).
inline BSplineCurveData RegularPolygon(int n, double radius, double cu,
                                       double cv) {
  BSplineCurveData polygon{.degree = 1, .dimension = 2};
  polygon.knots.push_back(0.0);
  for (int k = 0; k <= n; ++k) {
    const std::array<double, 2> p = PolygonVertex(n, radius, cu, cv, k);
    polygon.coordinates.insert(polygon.coordinates.end(), {p[0], p[1]});
    polygon.knots.push_back(static_cast<double>(k) / n);
  }
  polygon.knots.push_back(1.0);
  return polygon;
}

inline TrimLoop LoopOf(const BSplineCurveData& curve) {
  return TrimLoop{{*BSplineCurve::Create(curve.view())}};
}

inline TrimLoop LoopOf(const std::vector<BezierCurveData>& chain) {
  TrimLoop loop;
  for (const BezierCurveData& piece : chain) {
    loop.curves.push_back(*BezierCurve::Create(piece.view()));
  }
  return loop;
}

// LoopsOf returns one loop per curve.
inline std::vector<TrimLoop> LoopsOf(
    const std::vector<BSplineCurveData>& curves) {
  std::vector<TrimLoop> loops;
  for (const BSplineCurveData& curve : curves) loops.push_back(LoopOf(curve));
  return loops;
}

// The unit plane less the disk of radius r about (cu, cv), validated at
// 1e-9; the data outlives the face.
struct PlaneWithHole {
  PlaneWithHole(double r, double cu, double cv)
      : plane(BilinearPlane()),
        surface(*BezierSurface::Create(plane.bezier_view())),
        hole(ClockwiseCircle(r, cu, cv)),
        face(TrimmedSurface::Create({.surface = surface,
                                     .outer = std::nullopt,
                                     .holes = {LoopOf(hole)}},
                                    1e-9)) {}

  SurfaceData plane;
  Surface surface;
  BSplineCurveData hole;
  absl::StatusOr<TrimmedSurface> face;
};

// `surface` trimmed to the window [0.1, 0.9] x [0.02, 0.6] less the disk
// of radius 0.15 about (0.45, 0.3), validated at 1e-9; the surface's data
// must outlive it.
struct WindowWithHole {
  explicit WindowWithHole(const Surface& surface)
      : window(Square(0.1, 0.02, 0.9, 0.6)),
        hole(ClockwiseCircle(0.15, 0.45, 0.3)),
        face(TrimmedSurface::Create({.surface = surface,
                                     .outer = LoopOf(window),
                                     .holes = {LoopOf(hole)}},
                                    1e-9)) {}

  std::vector<BezierCurveData> window;
  BSplineCurveData hole;
  absl::StatusOr<TrimmedSurface> face;
};

}  // namespace freeform::trim_testing

#endif  // FREEFORM_TESTS_CORE_TRIM_SHAPES_H_
