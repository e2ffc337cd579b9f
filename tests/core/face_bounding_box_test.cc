// The tight bounding box of a trimmed face (trimmed_surface.h,
// FaceBoundingBox): planes whose extremes lie on a circular trim or at the
// domain's corners, in closed form, and a trimmed NURBS sphere against a
// dense sampling of the face.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "freeform/core/trimmed_surface.h"
#include "shapes.h"
#include "test_util.h"
#include "trim_shapes.h"

namespace freeform {
namespace {

using trim_testing::BilinearPlane;
using trim_testing::ClockwiseCircle;
using trim_testing::LoopOf;

TEST(FaceBoundingBox, APlaneDiskIsBoxedByItsCircle) {
  const SurfaceData plane = BilinearPlane();
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  const BSplineCurveData disk = testing_util::NurbsCircle(0.3, 0.5, 0.45);
  absl::StatusOr<TrimmedSurface> face = TrimmedSurface::Create(
      {.surface = surface, .outer = LoopOf(disk), .holes = {}}, 1e-9);
  ASSERT_TRUE(face.ok()) << face.status();
  const double tolerance = 1e-6;
  absl::StatusOr<BoundingBox> box = FaceBoundingBox(*face, tolerance);
  ASSERT_TRUE(box.ok()) << box.status();
  const double lower[] = {0.2, 0.15, 0.0}, upper[] = {0.8, 0.75, 0.0};
  for (int j = 0; j < 3; ++j) {
    EXPECT_LE(box->lower[j], lower[j]);
    EXPECT_GE(box->upper[j], upper[j]);
    EXPECT_NEAR(box->lower[j], lower[j], tolerance + 1e-13) << j;
    EXPECT_NEAR(box->upper[j], upper[j], tolerance + 1e-13) << j;
  }
}

TEST(FaceBoundingBox, APlaneWithAHoleIsBoxedByTheDomain) {
  const trim_testing::PlaneWithHole shape(0.2, 0.5, 0.5);
  ASSERT_TRUE(shape.face.ok()) << shape.face.status();
  absl::StatusOr<BoundingBox> box = FaceBoundingBox(*shape.face, 1e-9);
  ASSERT_TRUE(box.ok()) << box.status();
  for (int j = 0; j < 2; ++j) {
    EXPECT_NEAR(box->lower[j], 0.0, 1e-13);
    EXPECT_NEAR(box->upper[j], 1.0, 1e-13);
  }
}

TEST(FaceBoundingBox, ATrimmedSphereHoldsEverySampleOfTheFace) {
  const SurfaceData data = testing_util::NurbsSphere(2.0);
  const Surface sphere = *BSplineSurface::Create(data.bspline_view());
  const std::vector<BezierCurveData> window =
      trim_testing::Square(0.1, 0.02, 0.9, 0.6);
  const BSplineCurveData hole = ClockwiseCircle(0.15, 0.45, 0.3);
  absl::StatusOr<TrimmedSurface> face = TrimmedSurface::Create(
      {.surface = sphere, .outer = LoopOf(window), .holes = {LoopOf(hole)}},
      1e-9);
  ASSERT_TRUE(face.ok()) << face.status();
  const double tolerance = 1e-5;
  absl::StatusOr<BoundingBox> box = FaceBoundingBox(*face, tolerance);
  ASSERT_TRUE(box.ok()) << box.status();
  // Samples: a 300 x 300 grid of the window kept where the face is, and
  // 4000 points of every trim curve.
  std::vector<double> uv;
  for (int a = 0; a <= 300; ++a) {
    for (int b = 0; b <= 300; ++b) {
      uv.push_back(0.1 + 0.8 * a / 300.0);
      uv.push_back(0.02 + 0.58 * b / 300.0);
    }
  }
  absl::StatusOr<std::vector<PointLocation>> at =
      ClassifyPoints(*face, uv, 0.0);
  ASSERT_TRUE(at.ok());
  std::vector<double> kept;
  for (size_t k = 0; k < at->size(); ++k) {
    if ((*at)[k] == PointLocation::kOutside) continue;
    kept.insert(kept.end(), {uv[2 * k], uv[2 * k + 1]});
  }
  for (const TrimLoop* loop : {&*face->outer(), &face->holes()[0]}) {
    for (const Curve& curve : loop->curves) {
      const ParameterDomain d = DomainOf(curve);
      const std::vector<double> points = testing_util::CurvePoints(
          curve, testing_util::EvenlySpaced(d.start, d.end, 4000));
      kept.insert(kept.end(), points.begin(), points.end());
    }
  }
  const std::vector<double> points =
      testing_util::SurfacePoints(sphere, SurfaceSamples::Pairs(kept));
  for (int j = 0; j < 3; ++j) {
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = j; i < points.size(); i += 3) {
      lo = std::min(lo, points[i]);
      hi = std::max(hi, points[i]);
    }
    EXPECT_LE(box->lower[j], lo) << j;
    EXPECT_GE(box->upper[j], hi) << j;
    // The samples are 0.003 apart in (u, v): within about 1e-4 of the
    // face's extremes on a sphere of radius 2.
    EXPECT_NEAR(box->lower[j], lo, tolerance + 2e-4) << j;
    EXPECT_NEAR(box->upper[j], hi, tolerance + 2e-4) << j;
  }
}

}  // namespace
}  // namespace freeform
