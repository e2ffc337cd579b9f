// Trim curves sampled under a 3D chord bound (trimmed_surface.h,
// SampleTrimCurve): the 3D curve between consecutive samples, evaluated
// densely, against the chord, on a plane (a circle of known sagitta), a
// rational cylinder and a NURBS sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <optional>
#include <vector>

#include "freeform/core/status.h"
#include "freeform/core/trimmed_surface.h"
#include "shapes.h"
#include "trim_shapes.h"

namespace freeform {
namespace {

using trim_testing::BilinearPlane;
using trim_testing::ClockwiseCircle;
using trim_testing::LoopOf;

constexpr double kPi = std::numbers::pi;

double DistanceToSegment3(const double* p, const double* a, const double* b) {
  double ab[3], ap[3], ab2 = 0, t = 0;
  for (int j = 0; j < 3; ++j) {
    ab[j] = b[j] - a[j];
    ap[j] = p[j] - a[j];
    ab2 += ab[j] * ab[j];
    t += ap[j] * ab[j];
  }
  t = ab2 > 0 ? std::clamp(t / ab2, 0.0, 1.0) : 0.0;
  double d2 = 0;
  for (int j = 0; j < 3; ++j) {
    const double e = ap[j] - t * ab[j];
    d2 += e * e;
  }
  return std::sqrt(d2);
}

// LargestChordDeviation returns the largest distance, over 64 points
// between every two consecutive samples, from S(c(t)) to the chord of the
// samples' 3D points; it also checks that the samples lie on the curve.
double LargestChordDeviation(const Surface& surface, const Curve& curve,
                             const TrimSamples& samples) {
  const std::vector<double> uv_on_curve =
      testing_util::CurvePoints(curve, samples.parameters);
  for (size_t k = 0; k < uv_on_curve.size(); ++k) {
    EXPECT_NEAR(uv_on_curve[k], samples.uv[k], 1e-15);
  }
  const std::vector<double> ends =
      testing_util::SurfacePoints(surface, SurfaceSamples::Pairs(samples.uv));
  double largest = 0.0;
  for (size_t k = 0; k + 1 < samples.parameters.size(); ++k) {
    std::vector<double> t;
    for (int j = 1; j < 64; ++j) {
      t.push_back(samples.parameters[k] +
                  (samples.parameters[k + 1] - samples.parameters[k]) * j /
                      64.0);
    }
    const std::vector<double> uv = testing_util::CurvePoints(curve, t);
    const std::vector<double> points =
        testing_util::SurfacePoints(surface, SurfaceSamples::Pairs(uv));
    for (size_t j = 0; j < t.size(); ++j) {
      largest = std::max(
          largest,
          DistanceToSegment3(&points[3 * j], &ends[3 * k], &ends[3 * k + 3]));
    }
  }
  return largest;
}

TEST(SampleTrimCurve, ACircleOnAPlaneStaysWithinItsSagitta) {
  const SurfaceData plane = BilinearPlane();
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  const double r = 0.3;
  const BSplineCurveData hole = ClockwiseCircle(r, 0.5, 0.5);
  absl::StatusOr<TrimmedSurface> face = TrimmedSurface::Create(
      {.surface = surface, .outer = std::nullopt, .holes = {LoopOf(hole)}},
      1e-9);
  ASSERT_TRUE(face.ok()) << face.status();
  for (const double tolerance : {1e-2, 1e-4, 1e-6}) {
    absl::StatusOr<TrimSamples> samples =
        SampleTrimCurve(*face, 0, 0, tolerance);
    ASSERT_TRUE(samples.ok()) << samples.status();
    EXPECT_EQ(samples->parameters.front(), 0.0);
    EXPECT_EQ(samples->parameters.back(), 1.0);
    const Curve curve = face->holes()[0].curves[0];
    EXPECT_LE(LargestChordDeviation(surface, curve, *samples), tolerance);
    // The fewest chords of a circle within the tolerance: 2 pi over the
    // angle whose sagitta r (1 - cos(angle / 2)) is the tolerance. The
    // bound from control points costs a few times more.
    const double fewest = 2 * kPi / (2 * std::acos(1 - tolerance / r));
    EXPECT_LE(samples->parameters.size(), 8 * fewest + 8) << tolerance;
    std::cout << "tolerance " << tolerance << ": "
              << samples->parameters.size() - 1 << " chords, fewest "
              << std::ceil(fewest) << "\n";
  }
}

TEST(SampleTrimCurve, TrimsOnARationalCylinderAndSphereStayWithinTolerance) {
  const SurfaceData cylinder_data = testing_util::Revolve(
      {{1.5, 0, 1}, {1.5, 1, 1}, {1.5, 2, 1}}, {0, 0, 0, 1, 1, 1});
  const SurfaceData sphere_data = testing_util::NurbsSphere(2.0);
  for (const SurfaceData* data : {&cylinder_data, &sphere_data}) {
    const Surface surface = *BSplineSurface::Create(data->bspline_view());
    const trim_testing::WindowWithHole shape(surface);
    const absl::StatusOr<TrimmedSurface>& face = shape.face;
    ASSERT_TRUE(face.ok()) << face.status();
    for (const double tolerance : {1e-3, 1e-5}) {
      for (const auto& [hole_index, curve_index] :
           {std::pair{0, 0}, {-1, 0}, {-1, 1}, {-1, 2}}) {
        absl::StatusOr<TrimSamples> samples =
            SampleTrimCurve(*face, hole_index, curve_index, tolerance);
        ASSERT_TRUE(samples.ok()) << samples.status();
        const Curve curve = hole_index < 0
                                ? face->outer()->curves[curve_index]
                                : face->holes()[hole_index].curves[curve_index];
        EXPECT_LE(LargestChordDeviation(surface, curve, *samples), tolerance)
            << hole_index << " " << curve_index;
      }
    }
  }
}

TEST(SampleTrimCurve, BadArgumentsAreNamed) {
  const trim_testing::PlaneWithHole shape(0.2, 0.5, 0.5);
  ASSERT_TRUE(shape.face.ok()) << shape.face.status();
  const TrimmedSurface& face = *shape.face;
  EXPECT_EQ(FieldPathOf(SampleTrimCurve(face, -1, 0, 1e-3).status()), "hole");
  EXPECT_EQ(FieldPathOf(SampleTrimCurve(face, 1, 0, 1e-3).status()), "hole");
  EXPECT_EQ(FieldPathOf(SampleTrimCurve(face, 0, 1, 1e-3).status()), "curve");
  EXPECT_EQ(FieldPathOf(SampleTrimCurve(face, 0, 0, 0.0).status()),
            "tolerance");
  absl::StatusOr<TrimSamples> too_many = SampleTrimCurve(face, 0, 0, 1e-9, 10);
  EXPECT_EQ(too_many.status().code(), absl::StatusCode::kResourceExhausted);
  EXPECT_EQ(FieldPathOf(too_many.status()), "max_samples");
}

}  // namespace
}  // namespace freeform
