#include "freeform/core/differential_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "freeform/core/status.h"
#include "shapes.h"
#include "test_util.h"

namespace freeform {
namespace {

using testing_util::EvenlySpaced;
using testing_util::NurbsCircle;
using testing_util::RandomKnots;
using testing_util::RandomValues;
using testing_util::SpherePatch;
using testing_util::TwistedCubic;

// Owned buffers of a FrenetFrameOutput.
struct Frenet {
  Frenet(int dimension, size_t count) {
    const FrenetFrameSizes sizes = FrenetSizes(dimension, count);
    tangents.resize(sizes.tangents);
    normals.resize(sizes.normals);
    binormals.resize(sizes.binormals);
    curvatures.resize(sizes.curvatures);
    torsions.resize(sizes.torsions);
    statuses.resize(sizes.statuses);
  }
  FrenetFrameOutput output() {
    return {.tangents = absl::MakeSpan(tangents),
            .normals = absl::MakeSpan(normals),
            .binormals = absl::MakeSpan(binormals),
            .curvatures = absl::MakeSpan(curvatures),
            .torsions = absl::MakeSpan(torsions),
            .statuses = absl::MakeSpan(statuses)};
  }
  std::vector<double> tangents, normals, binormals, curvatures, torsions;
  std::vector<CurvePointStatus> statuses;
};

std::vector<double> Derivatives(const Curve& curve,
                                const std::vector<double>& parameters,
                                int order) {
  const size_t size = parameters.size() * DimensionOf(curve);
  std::vector<std::vector<double>> buffers(order + 1,
                                           std::vector<double>(size));
  std::vector<absl::Span<double>> output;
  for (auto& buffer : buffers) output.push_back(absl::MakeSpan(buffer));
  EXPECT_TRUE(EvaluateCurve(curve, parameters, output).ok());
  return buffers[order];
}

double Dot(const double* a, const double* b, int d) {
  double sum = 0.0;
  for (int j = 0; j < d; ++j) sum += a[j] * b[j];
  return sum;
}

TEST(FrenetFrames, CircleHasCurvatureOneOverRadiusTowardsItsCentre) {
  const double radius = 2.5;
  const BSplineCurveData data = NurbsCircle(radius, 1.0, -2.0);
  const Curve circle = *BSplineCurve::Create(data.view());
  const std::vector<double> t = EvenlySpaced(0.0, 1.0, 201);
  Frenet frenet(2, t.size());
  ASSERT_TRUE(EvaluateFrenetFrames(circle, t, frenet.output()).ok());
  const std::vector<double> points = Derivatives(circle, t, 0);
  for (size_t r = 0; r < t.size(); ++r) {
    EXPECT_EQ(frenet.statuses[r], CurvePointStatus::kRegular);
    EXPECT_NEAR(frenet.curvatures[r], 1.0 / radius, 1e-14) << t[r];
    // The centre of curvature is the circle's centre.
    EXPECT_NEAR(points[2 * r] + radius * frenet.normals[2 * r], 1.0, 1e-13);
    EXPECT_NEAR(points[2 * r + 1] + radius * frenet.normals[2 * r + 1], -2.0,
                1e-13);
    EXPECT_NEAR(Dot(&frenet.tangents[2 * r], &frenet.normals[2 * r], 2), 0.0,
                1e-15);
  }
}

// kappa = |r' x r''| / |r'|^3 and tau = 3 / (9t^4 + 9t^2 + 1) for
// (t, t^2, t^3): r' x r'' = (6t^2, -6t, 2), (r' x r'') . r''' = 12.
TEST(FrenetFrames, TwistedCubicTorsionAndCurvature) {
  const BezierCurveData data = TwistedCubic();
  const Curve cubic = *BezierCurve::Create(data.view());
  const std::vector<double> t = EvenlySpaced(0.0, 1.0, 101);
  Frenet frenet(3, t.size());
  ASSERT_TRUE(EvaluateFrenetFrames(cubic, t, frenet.output()).ok());
  for (size_t r = 0; r < t.size(); ++r) {
    const double s = t[r];
    const double t2 = s * s;
    EXPECT_EQ(frenet.statuses[r], CurvePointStatus::kRegular);
    EXPECT_NEAR(frenet.torsions[r], 3.0 / (9 * t2 * t2 + 9 * t2 + 1), 1e-13)
        << s;
    const double cross = std::sqrt(36 * t2 * t2 + 36 * t2 + 4);
    const double speed = std::sqrt(1 + 4 * t2 + 9 * t2 * t2);
    EXPECT_NEAR(frenet.curvatures[r], cross / (speed * speed * speed), 1e-13);
    // B = (r' x r'') / |r' x r''|.
    EXPECT_NEAR(frenet.binormals[3 * r], 6 * t2 / cross, 1e-14);
    EXPECT_NEAR(frenet.binormals[3 * r + 1], -6 * s / cross, 1e-14);
    EXPECT_NEAR(frenet.binormals[3 * r + 2], 2 / cross, 1e-14);
  }
}

// The circle of radius r has curvature 1/r towards its centre whatever the
// scale of r and of its knots: squared derivatives of 1e-200 underflowed
// (a SINGULAR point of curvature 0), and on knots 1e170 apart the second
// derivative itself did.
TEST(FrenetFrames, CircleCurvatureAtEveryScale) {
  for (int k = -300; k <= 300; k += 50) {
    const double radius = std::pow(10.0, k);
    for (const double knots : {1e-300, 1.0, 1e170, 1e300}) {
      BSplineCurveData data = NurbsCircle(radius);
      for (double& knot : data.knots) knot *= knots;
      const Curve circle = *BSplineCurve::Create(data.view());
      const std::vector<double> t = {0.1 * knots, 0.3 * knots, 0.6 * knots};
      Frenet frenet(2, t.size());
      ASSERT_TRUE(EvaluateFrenetFrames(circle, t, frenet.output()).ok());
      const std::vector<double> points = Derivatives(circle, t, 0);
      for (size_t r = 0; r < t.size(); ++r) {
        EXPECT_EQ(frenet.statuses[r], CurvePointStatus::kRegular)
            << "r = " << radius << ", knots " << knots;
        EXPECT_NEAR(frenet.curvatures[r] * radius, 1.0, 1e-12)
            << "r = " << radius << ", knots " << knots;
        for (int j = 0; j < 2; ++j) {  // the normal points to the centre
          EXPECT_NEAR(frenet.normals[2 * r + j], -points[2 * r + j] / radius,
                      1e-12);
        }
      }
    }
  }
}

// The twisted cubic (t, t^2, t^3) scaled by S has at t = 0 the curvature
// 2 / S and the torsion 3 / S (TwistedCubicTorsionAndCurvature), at every
// scale.
TEST(FrenetFrames, TwistedCubicTorsionAtEveryScale) {
  for (int k = -300; k <= 300; k += 50) {
    const double scale = std::pow(10.0, k);
    BezierCurveData data = TwistedCubic();
    for (double& x : data.coordinates) x *= scale;
    const Curve cubic = *BezierCurve::Create(data.view());
    const std::vector<double> t = {0.0};
    Frenet frenet(3, 1);
    ASSERT_TRUE(EvaluateFrenetFrames(cubic, t, frenet.output()).ok());
    EXPECT_EQ(frenet.statuses[0], CurvePointStatus::kRegular) << scale;
    EXPECT_NEAR(frenet.curvatures[0] * scale, 2.0, 1e-12) << scale;
    EXPECT_NEAR(frenet.torsions[0] * scale, 3.0, 1e-12) << scale;
  }
}

// kappa = |dT/ds|: central differences of the unit tangent over a free-form
// spline in 4-D, from first derivatives only.
TEST(FrenetFrames, CurvatureMatchesDifferencesOfTheTangent) {
  std::mt19937_64 rng(3);
  const std::vector<double> points = RandomValues(rng, 8 * 4);
  const std::vector<double> knots = RandomKnots(rng, 3, 7, true);
  const Curve curve = *BSplineCurve::Create(
      {.degree = 3, .control_points = {4, points}, .knots = knots});
  constexpr double kStep = 1e-5;
  std::vector<double> t;
  for (size_t s = 3; s < 8; ++s) {
    if (knots[s] < knots[s + 1]) {
      for (const double f : {0.3, 0.5, 0.7}) {
        t.push_back(knots[s] + f * (knots[s + 1] - knots[s]));
      }
    }
  }
  Frenet frenet(4, t.size());
  ASSERT_TRUE(EvaluateFrenetFrames(curve, t, frenet.output()).ok());
  for (size_t r = 0; r < t.size(); ++r) {
    const std::vector<double> d1 =
        Derivatives(curve, {t[r] - kStep, t[r], t[r] + kStep}, 1);
    double unit[3][4];
    for (int k = 0; k < 3; ++k) {
      const double speed = std::sqrt(Dot(&d1[4 * k], &d1[4 * k], 4));
      for (int j = 0; j < 4; ++j) unit[k][j] = d1[4 * k + j] / speed;
    }
    double change = 0.0;
    for (int j = 0; j < 4; ++j) {
      change += std::pow((unit[2][j] - unit[0][j]) / (2 * kStep), 2);
    }
    const double speed = std::sqrt(Dot(&d1[4], &d1[4], 4));
    const double kappa = std::sqrt(change) / speed;
    EXPECT_NEAR(frenet.curvatures[r], kappa, 1e-6 * kappa) << t[r];
  }
}

// A quarter circle of radius 3 in the plane of two orthonormal vectors of
// R^4: curvature 1/3, no binormal or torsion outside 3-D.
TEST(FrenetFrames, CircleInFourDimensions) {
  const double e1[4] = {0.5, 0.5, 0.5, 0.5};
  const double e2[4] = {0.5, -0.5, 0.5, -0.5};
  const double unit[3][2] = {{1, 0}, {1, 1}, {0, 1}};
  std::vector<double> net;
  for (const auto& p : unit) {
    for (int j = 0; j < 4; ++j)
      net.push_back(3 * (p[0] * e1[j] + p[1] * e2[j]));
  }
  const std::vector<double> weights = {1, std::sqrt(0.5), 1};
  const Curve arc =
      *BezierCurve::Create({.control_points = {4, net}, .weights = weights});
  const std::vector<double> t = EvenlySpaced(0.0, 1.0, 11);
  Frenet frenet(4, t.size());
  EXPECT_TRUE(frenet.binormals.empty());
  EXPECT_TRUE(frenet.torsions.empty());
  ASSERT_TRUE(EvaluateFrenetFrames(arc, t, frenet.output()).ok());
  for (const double kappa : frenet.curvatures)
    EXPECT_NEAR(kappa, 1.0 / 3, 1e-14);
  std::vector<double> binormals(3 * t.size());
  FrenetFrameOutput output = frenet.output();
  output.binormals = absl::MakeSpan(binormals);
  EXPECT_EQ(EvaluateFrenetFrames(arc, t, output).code(),
            absl::StatusCode::kInvalidArgument);
}

TEST(FrenetFrames, DegeneratePointsAreNamedAndFinite) {
  // P0 = P1: r'(0) = 0. The line: no bending anywhere.
  const std::vector<double> cusp = {0, 0, 0, 0, 1, 1, 2, 0};
  const std::vector<double> line = {0, 0, 1, 2, 3, 6};
  const Curve stationary = *BezierCurve::Create({.control_points = {2, cusp}});
  const Curve straight = *BezierCurve::Create({.control_points = {2, line}});
  const std::vector<double> t = {0.0, 0.5};
  Frenet frenet(2, 2);
  ASSERT_TRUE(EvaluateFrenetFrames(stationary, t, frenet.output()).ok());
  EXPECT_EQ(frenet.statuses[0], CurvePointStatus::kSingular);
  EXPECT_EQ(frenet.statuses[1], CurvePointStatus::kRegular);
  EXPECT_EQ(frenet.curvatures[0], 0.0);
  EXPECT_EQ(frenet.tangents[0], 0.0);
  ASSERT_TRUE(EvaluateFrenetFrames(straight, t, frenet.output()).ok());
  for (size_t r = 0; r < 2; ++r) {
    EXPECT_EQ(frenet.statuses[r], CurvePointStatus::kStraight);
    EXPECT_EQ(frenet.curvatures[r], 0.0);
    EXPECT_EQ(frenet.normals[2 * r], 0.0);
    EXPECT_NEAR(frenet.tangents[2 * r], 1 / std::sqrt(5.0), 1e-15);
  }
  const std::vector<double> outside = {0.5, 1.5};
  EXPECT_EQ(
      FieldPathOf(EvaluateFrenetFrames(straight, outside, frenet.output())),
      "parameters[1]");
}

TEST(FrenetFrames, PoolGivesTheSameNumbers) {
  const BezierCurveData data = TwistedCubic();
  const Curve cubic = *BezierCurve::Create(data.view());
  const std::vector<double> t = EvenlySpaced(0.0, 1.0, 5000);
  Frenet serial(3, t.size()), parallel(3, t.size());
  ASSERT_TRUE(EvaluateFrenetFrames(cubic, t, serial.output()).ok());
  ThreadPool pool(2);
  ASSERT_TRUE(EvaluateFrenetFrames(cubic, t, parallel.output(),
                                   {.pool = &pool, .grain = 256})
                  .ok());
  EXPECT_EQ(serial.torsions, parallel.torsions);
  EXPECT_EQ(serial.normals, parallel.normals);
}

// Owned buffers of a RotationMinimizingFrameOutput.
struct Frames {
  Frames(int dimension, size_t count) {
    const RotationMinimizingFrameSizes sizes =
        RotationMinimizingSizes(dimension, count);
    tangents.resize(sizes.tangents);
    references.resize(sizes.references);
    third.resize(sizes.third);
  }
  RotationMinimizingFrameOutput output() {
    return {.tangents = absl::MakeSpan(tangents),
            .references = absl::MakeSpan(references),
            .third = absl::MakeSpan(third)};
  }
  std::vector<double> tangents, references, third;
};

// Along a curve in the plane z = 2 the rotation-minimizing frame keeps its
// angle to the plane: r = c e_z + s (e_z x t) with c and s fixed by the
// first frame (the in-plane part turns with the tangent, the normal part
// stays).
TEST(RotationMinimizingFrames, PlanarCurveKeepsItsAngleToThePlane) {
  const std::vector<double> net = {0, 0, 2, 1, 3, 2, 3, -1, 2, 4, 0, 2};
  const Curve curve = *BezierCurve::Create({.control_points = {3, net}});
  const std::vector<double> t = EvenlySpaced(0.0, 1.0, 50);
  Frames frames(3, t.size());
  const std::vector<double> tilted = {0.0, 1.5, 1.0};
  ASSERT_TRUE(
      EvaluateRotationMinimizingFrames(curve, t, tilted, frames.output()).ok());
  const auto in_plane = [&](size_t r) {
    const double* tangent = &frames.tangents[3 * r];
    return std::vector<double>{-tangent[1], tangent[0], 0.0};  // e_z x t
  };
  const double c = frames.references[2];
  const double s = Dot(frames.references.data(), in_plane(0).data(), 3);
  EXPECT_GT(std::abs(s), 0.1);
  for (size_t r = 0; r < t.size(); ++r) {
    const std::vector<double> side = in_plane(r);
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(frames.references[3 * r + j],
                  (j == 2 ? c : 0.0) + s * side[j], 1e-14)
          << t[r];
    }
  }
}

// Along a circle of radius r in the plane z = 0 of 3-D space the frame
// started at e_z stays e_z at every scale of r (and of the given initial
// reference): at r = 1e-200 the squared tangent underflowed, so every
// point "stood still", and the reflections were skipped between points
// closer than 1e-154.
TEST(RotationMinimizingFrames, PlanarCircleAtEveryScale) {
  for (int k = -300; k <= 300; k += 50) {
    const double radius = std::pow(10.0, k);
    const BSplineCurveData flat = NurbsCircle(radius);
    BSplineCurveData circle = flat;
    circle.dimension = 3;
    circle.coordinates.clear();
    for (size_t i = 0; i < flat.weights.size(); ++i) {
      circle.coordinates.insert(
          circle.coordinates.end(),
          {flat.coordinates[2 * i], flat.coordinates[2 * i + 1], 0.0});
    }
    const Curve curve = *BSplineCurve::Create(circle.view());
    const std::vector<double> t = EvenlySpaced(0.0, 1.0, 33);
    for (const double size : {1e-300, 1.0, 1e300}) {
      Frames frames(3, t.size());
      const std::vector<double> up = {0.0, 0.0, size};
      ASSERT_TRUE(
          EvaluateRotationMinimizingFrames(curve, t, up, frames.output()).ok())
          << radius;
      for (size_t r = 0; r < t.size(); ++r) {
        EXPECT_NEAR(frames.references[3 * r + 2], 1.0, 1e-12) << radius;
      }
    }
  }
}

// Along the twisted cubic the frame turns against the Frenet frame by
// theta(t) = -integral of tau |r'| (r = cos theta N + sin theta B makes
// r' parallel to T only then); the integral by Simpson's rule.
TEST(RotationMinimizingFrames, TwistedCubicTurnsByTheIntegralOfTorsion) {
  const BezierCurveData data = TwistedCubic();
  const Curve cubic = *BezierCurve::Create(data.view());
  const std::vector<double> t = EvenlySpaced(0.0, 1.0, 401);
  Frames frames(3, t.size());
  ASSERT_TRUE(
      EvaluateRotationMinimizingFrames(cubic, t, {}, frames.output()).ok());
  Frenet frenet(3, t.size());
  ASSERT_TRUE(EvaluateFrenetFrames(cubic, t, frenet.output()).ok());
  const auto twist = [](double s) {
    const double s2 = s * s;
    return 3.0 / (9 * s2 * s2 + 9 * s2 + 1) *
           std::sqrt(1 + 4 * s2 + 9 * s2 * s2);
  };
  double theta = 0.0;
  for (size_t r = 0; r < t.size(); ++r) {
    if (r > 0) {
      const double a = t[r - 1], b = t[r];
      theta -= (b - a) / 6 * (twist(a) + 4 * twist(0.5 * (a + b)) + twist(b));
    }
    const double* ref = &frames.references[3 * r];
    const double angle = std::atan2(Dot(ref, &frenet.binormals[3 * r], 3),
                                    Dot(ref, &frenet.normals[3 * r], 3));
    EXPECT_NEAR(angle, theta, 1e-9) << t[r];
    EXPECT_NEAR(Dot(ref, &frames.tangents[3 * r], 3), 0.0, 1e-15);
    EXPECT_NEAR(Dot(ref, ref, 3), 1.0, 1e-15);
  }
}

TEST(RotationMinimizingFrames, ErrorsNameTheirField) {
  // P0 = P1: the tangent at 0 is undefined.
  const std::vector<double> cusp = {0, 0, 0, 0, 0, 0, 1, 1, 0, 2, 0, 0};
  const Curve curve = *BezierCurve::Create({.control_points = {3, cusp}});
  Frames frames(3, 3);
  EXPECT_EQ(
      FieldPathOf(EvaluateRotationMinimizingFrames(
          curve, std::vector<double>{0.5, 0.7, 0.0}, {}, frames.output())),
      "parameters[2]");
  EXPECT_EQ(FieldPathOf(EvaluateRotationMinimizingFrames(
                curve, std::vector<double>{0.5, 0.7, 0.9},
                std::vector<double>{3.0, 1.0, 0.0}, frames.output())),
            "initial_reference");
  const std::vector<double> scalar = {0, 1, 3};
  const Curve line = *BezierCurve::Create({.control_points = {1, scalar}});
  Frames one(1, 1);
  EXPECT_EQ(FieldPathOf(EvaluateRotationMinimizingFrames(
                line, std::vector<double>{0.5}, {}, one.output())),
            "dimension");
}

// Owned buffers of a SurfaceCurvatureOutput.
struct Curvatures {
  explicit Curvatures(size_t count) {
    const SurfaceCurvatureSizes sizes = CurvatureSizes(count);
    normals.resize(sizes.normals);
    gaussian.resize(sizes.gaussian);
    mean.resize(sizes.mean);
    principal.resize(sizes.principal_curvatures);
    directions.resize(sizes.principal_directions);
    statuses.resize(sizes.statuses);
  }
  SurfaceCurvatureOutput output() {
    return {.normals = absl::MakeSpan(normals),
            .gaussian = absl::MakeSpan(gaussian),
            .mean = absl::MakeSpan(mean),
            .principal_curvatures = absl::MakeSpan(principal),
            .principal_directions = absl::MakeSpan(directions),
            .statuses = absl::MakeSpan(statuses)};
  }
  std::vector<double> normals, gaussian, mean, principal, directions;
  std::vector<SurfacePointStatus> statuses;
};

// S_u x S_v of the patch points into the sphere, so H = +1/r.
TEST(SurfaceCurvatures, SpherePatchHasGaussianOneOverRSquared) {
  const double radius = 2.0;
  const SurfaceData data = SpherePatch(radius);
  const Surface sphere = *BezierSurface::Create(data.bezier_view());
  const std::vector<double> u = EvenlySpaced(0.0, 0.95, 12);
  const std::vector<double> v = EvenlySpaced(0.0, 1.0, 9);
  const SurfaceSamples samples = SurfaceSamples::Grid(u, v);
  Curvatures curvatures(samples.size());
  ASSERT_TRUE(
      EvaluateSurfaceCurvatures(sphere, samples, curvatures.output()).ok());
  std::vector<double> points(3 * samples.size());
  const absl::Span<double> output[] = {absl::MakeSpan(points)};
  ASSERT_TRUE(EvaluateSurface(sphere, samples, output, {}).ok());
  for (size_t r = 0; r < samples.size(); ++r) {
    EXPECT_EQ(curvatures.statuses[r], SurfacePointStatus::kUmbilic);
    EXPECT_NEAR(curvatures.gaussian[r], 1.0 / (radius * radius), 1e-13);
    EXPECT_NEAR(curvatures.mean[r], 1.0 / radius, 1e-13);
    EXPECT_NEAR(curvatures.principal[2 * r], 1.0 / radius, 1e-7);
    EXPECT_NEAR(curvatures.principal[2 * r + 1], 1.0 / radius, 1e-7);
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(curvatures.normals[3 * r + j], -points[3 * r + j] / radius,
                  1e-14);
    }
  }
  // The pole (u = 1) is a collapsed row: singular, with finite outputs.
  const std::vector<double> pole = {1.0, 0.5};
  Curvatures at_pole(1);
  ASSERT_TRUE(EvaluateSurfaceCurvatures(sphere, SurfaceSamples::Pairs(pole),
                                        at_pole.output())
                  .ok());
  EXPECT_EQ(at_pole.statuses[0], SurfacePointStatus::kSingular);
  EXPECT_EQ(at_pole.gaussian[0], 0.0);
  EXPECT_NEAR(at_pole.normals[2], -1.0, 1e-12);  // the limit: inwards
}

// A quarter of the cylinder of radius r about the z axis (the straight
// profile from z = 0 to 2r turned by a quarter), as a rational Bezier patch
// and as a B-spline patch on knots of any scale: S_u x S_v points inwards,
// so k1 = 1/r around it, k2 = 0 along it, K = 0 and H = 1/(2r), at every
// scale (past 1e77 the squares of S_u x S_v overflowed: UMBILIC with
// curvatures 0).
TEST(SurfaceCurvatures, CylinderAtEveryScale) {
  for (int k = -300; k <= 300; k += 50) {
    const double radius = std::pow(10.0, k);
    const double rho[3] = {radius, radius, radius};
    const double z[3] = {0.0, radius, 2.0 * radius};
    SurfaceData data = testing_util::Revolution(rho, z);
    for (const double knots : {0.0, 1e-300, 1.0, 1e300}) {
      std::vector<double> uv = {0.3, 0.6};
      Surface surface = *BezierSurface::Create(data.bezier_view());
      if (knots > 0.0) {
        data.knots_u = data.knots_v = {0, 0, 0, knots, knots, knots};
        surface = *BSplineSurface::Create(data.bspline_view());
        uv = {0.3 * knots, 0.6 * knots};
      }
      Curvatures curvatures(1);
      ASSERT_TRUE(EvaluateSurfaceCurvatures(surface, SurfaceSamples::Pairs(uv),
                                            curvatures.output())
                      .ok());
      EXPECT_EQ(curvatures.statuses[0], SurfacePointStatus::kRegular)
          << "r = " << radius << ", knots " << knots;
      EXPECT_NEAR(curvatures.principal[0] * radius, 1.0, 1e-12) << radius;
      EXPECT_NEAR(curvatures.principal[1] * radius, 0.0, 1e-12) << radius;
      EXPECT_EQ(curvatures.gaussian[0], 0.0) << radius;
      EXPECT_NEAR(curvatures.mean[0] * radius, 0.5, 1e-12) << radius;
      EXPECT_NEAR(curvatures.normals[2], 0.0, 1e-12);  // across the axis
    }
  }
}

// The graph z = f(u, v) = a u^2 + b u v + c v^2 over the unit square as a
// biquadratic Bezier patch, against the Monge-patch formulas
// K = (f_uu f_vv - f_uv^2) / W^4, H = ((1 + f_v^2) f_uu - 2 f_u f_v f_uv +
// (1 + f_u^2) f_vv) / (2 W^3), W = sqrt(1 + f_u^2 + f_v^2); the normal
// curvature along a principal direction (du, dv) is
// II / I = (f_uu du^2 + 2 f_uv du dv + f_vv dv^2) / W /
// (du^2 + dv^2 + (f_u du + f_v dv)^2).
TEST(SurfaceCurvatures, GraphPatchMatchesMongeFormulas) {
  const double a = 0.7, b = -1.1, c = 0.4;
  std::vector<double> net;
  // x = u and y = v have Bezier coefficients 0, 1/2, 1; u^2 has 0, 0, 1 and
  // u v has (i / 2)(j / 2).
  const double half[3] = {0, 0.5, 1};
  const double square[3] = {0, 0, 1};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      net.insert(net.end(),
                 {half[i], half[j],
                  a * square[i] + b * half[i] * half[j] + c * square[j]});
    }
  }
  const Surface graph = *BezierSurface::Create(
      {.control_net = {
           .dimension = 3, .count_u = 3, .count_v = 3, .coordinates = net}});
  const std::vector<double> uv = {0.1, 0.2, 0.5, 0.5, 0.9, 0.3, 0.0, 1.0};
  Curvatures curvatures(4);
  ASSERT_TRUE(EvaluateSurfaceCurvatures(graph, SurfaceSamples::Pairs(uv),
                                        curvatures.output())
                  .ok());
  for (size_t r = 0; r < 4; ++r) {
    const double u = uv[2 * r], v = uv[2 * r + 1];
    const double fu = 2 * a * u + b * v, fv = b * u + 2 * c * v;
    const double fuu = 2 * a, fuv = b, fvv = 2 * c;
    const double w = std::sqrt(1 + fu * fu + fv * fv);
    EXPECT_EQ(curvatures.statuses[r], SurfacePointStatus::kRegular);
    EXPECT_NEAR(curvatures.gaussian[r],
                (fuu * fvv - fuv * fuv) / std::pow(w, 4), 1e-14);
    EXPECT_NEAR(
        curvatures.mean[r],
        ((1 + fv * fv) * fuu - 2 * fu * fv * fuv + (1 + fu * fu) * fvv) /
            (2 * w * w * w),
        1e-14);
    EXPECT_NEAR(curvatures.normals[3 * r + 2], 1 / w, 1e-15);
    EXPECT_GE(curvatures.principal[2 * r], curvatures.principal[2 * r + 1]);
    for (int k = 0; k < 2; ++k) {
      const double* d = &curvatures.directions[6 * r + 3 * k];
      const double du = d[0], dv = d[1];
      const double second =
          (fuu * du * du + 2 * fuv * du * dv + fvv * dv * dv) / w;
      const double first = du * du + dv * dv + std::pow(fu * du + fv * dv, 2);
      EXPECT_NEAR(second / first, curvatures.principal[2 * r + k], 1e-14);
      EXPECT_NEAR(Dot(d, &curvatures.normals[3 * r], 3), 0.0, 1e-15);
      EXPECT_NEAR(Dot(d, d, 3), 1.0, 1e-15);
    }
  }
}

TEST(SurfaceCurvatures, RefusesSurfacesOutsideThreeDimensions) {
  const std::vector<double> net = {0, 0, 1, 0, 0, 1, 1, 1};
  const Surface flat = *BezierSurface::Create(
      {.control_net = {
           .dimension = 2, .count_u = 2, .count_v = 2, .coordinates = net}});
  const std::vector<double> uv = {0.5, 0.5};
  Curvatures curvatures(1);
  EXPECT_EQ(FieldPathOf(EvaluateSurfaceCurvatures(
                flat, SurfaceSamples::Pairs(uv), curvatures.output())),
            "control_net.dimension");
}

}  // namespace
}  // namespace freeform
