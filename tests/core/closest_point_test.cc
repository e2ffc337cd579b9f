#include "freeform/core/closest_point.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "freeform/core/rational.h"
#include "freeform/core/status.h"
#include "shapes.h"
#include "teapot.h"
#include "test_util.h"

namespace freeform {
namespace {

using testing_util::CurvePoints;
using testing_util::RandomValues;
using testing_util::SurfacePoints;
constexpr auto Distance = testing_util::PointDistance;

// Grid returns n + 1 parameters from lo to hi, both ends exact.
std::vector<double> Grid(double lo, double hi, int n) {
  return testing_util::EvenlySpaced(lo, hi, static_cast<size_t>(n) + 1);
}

// The reference distance of a curve to q: the best of 4001 samples, then
// three rounds of 41 samples within a step of the best one.
double CurveReference(const Curve& curve, const std::vector<double>& samples,
                      const std::vector<double>& points, const double* q) {
  const int dim = DimensionOf(curve);
  const ParameterDomain domain = DomainOf(curve);
  size_t best = 0;
  double distance = INFINITY;
  for (size_t k = 0; k < samples.size(); ++k) {
    const double d = Distance(points.data() + k * dim, q, dim);
    if (d < distance) distance = d, best = k;
  }
  double t = samples[best];
  double step = samples[1] - samples[0];
  for (int round = 0; round < 3; ++round) {
    const std::vector<double> local = Grid(std::max(domain.start, t - step),
                                           std::min(domain.end, t + step), 40);
    const std::vector<double> near = CurvePoints(curve, local);
    for (size_t k = 0; k < local.size(); ++k) {
      const double d = Distance(near.data() + k * dim, q, dim);
      if (d < distance) distance = d, t = local[k];
    }
    step = (local[1] - local[0]) * 1.01;
  }
  return distance;
}

// ParameterOf maps (s, t) of the unit square onto the surface's parameters
// (a triangular patch by (s, (1 - s) t)).
std::vector<double> SquareToSurface(const Surface& surface, double s,
                                    double t) {
  if (IsTriangular(surface)) return {s, (1.0 - s) * t};
  const SurfaceDomain d = DomainOf(surface);
  return {d.u_start + s * (d.u_end - d.u_start),
          d.v_start + t * (d.v_end - d.v_start)};
}

// The reference distance of a surface to q: the best of a 41 x 41 grid of
// the unit square, then six rounds of 9 x 9 samples within a step.
struct SurfaceReference {
  const Surface& surface;
  std::vector<double> grid_points;
  std::vector<double> square;

  explicit SurfaceReference(const Surface& s) : surface(s) {
    const std::vector<double> g = Grid(0.0, 1.0, 40);
    std::vector<double> uv;
    for (double a : g) {
      for (double b : g) {
        square.insert(square.end(), {a, b});
        const std::vector<double> p = SquareToSurface(surface, a, b);
        uv.insert(uv.end(), p.begin(), p.end());
      }
    }
    grid_points = SurfacePoints(surface, SurfaceSamples::Pairs(uv));
  }

  double Nearest(const double* q) const {
    const int dim = DimensionOf(surface);
    double distance = INFINITY;
    double s = 0.0, t = 0.0;
    for (size_t k = 0; k < square.size() / 2; ++k) {
      const double d = Distance(grid_points.data() + k * dim, q, dim);
      if (d < distance) distance = d, s = square[2 * k], t = square[2 * k + 1];
    }
    double step = 1.0 / 40;
    for (int round = 0; round < 6; ++round) {
      const std::vector<double> gs =
          Grid(std::max(0.0, s - step), std::min(1.0, s + step), 8);
      const std::vector<double> gt =
          Grid(std::max(0.0, t - step), std::min(1.0, t + step), 8);
      std::vector<double> uv;
      for (double a : gs) {
        for (double b : gt) {
          const std::vector<double> p = SquareToSurface(surface, a, b);
          uv.insert(uv.end(), p.begin(), p.end());
        }
      }
      const std::vector<double> near =
          SurfacePoints(surface, SurfaceSamples::Pairs(uv));
      for (size_t k = 0; k < uv.size() / 2; ++k) {
        const double d = Distance(near.data() + k * dim, q, dim);
        if (d < distance) {
          distance = d, s = gs[k / gt.size()], t = gt[k % gt.size()];
        }
      }
      step *= 0.25 * 1.01;
    }
    return distance;
  }
};

// CheckAnswer checks that every returned minimum is the geometry's point
// at its parameters, at the returned distance from its query.
void CheckCurveAnswer(const Curve& curve, const PointsView& queries,
                      const ClosestPoints& answer) {
  const int dim = DimensionOf(curve);
  for (size_t r = 0; r < queries.size(); ++r) {
    ASSERT_GE(answer.counts[r], 1);
    for (int k = 0; k < answer.counts[r]; ++k) {
      const size_t slot = r * answer.max_minima + k;
      const std::vector<double> point =
          CurvePoints(curve, {answer.parameters[slot]});
      const double* returned = answer.points.data() + slot * dim;
      ASSERT_LE(Distance(point.data(), returned, dim), 1e-12);
      ASSERT_NEAR(Distance(returned, queries.point(r), dim),
                  answer.distances[r], 1e-9);
    }
    ASSERT_LE(answer.lower_bounds[r], answer.distances[r]);
    // Certified: nothing closer than the tolerance below the distance.
    if (answer.complete[r]) {
      ASSERT_GE(answer.lower_bounds[r], answer.distances[r] - 1e-9 - 1e-14);
    }
  }
}

struct CurveCase {
  std::string name;
  absl::StatusOr<Curve> curve;
};

// Owned data of the curve cases.
struct CurveData {
  std::vector<std::vector<double>> arrays;
  const std::vector<double>& Keep(std::vector<double> values) {
    arrays.push_back(std::move(values));
    return arrays.back();
  }
};

std::vector<CurveCase> CurveCases(std::mt19937_64& rng, CurveData& data) {
  data.arrays.reserve(64);
  std::vector<CurveCase> cases;
  auto points = [&](size_t count, int dim) -> const std::vector<double>& {
    return data.Keep(RandomValues(rng, count * dim));
  };
  cases.push_back(
      {"bezier cubic 2D", BezierCurve::Create({{2, points(4, 2)}, {}})});
  cases.push_back(
      {"bezier degree 6 3D", BezierCurve::Create({{3, points(7, 3)}, {}})});
  cases.push_back(
      {"rational bezier 2D",
       BezierCurve::Create(
           {{2, points(5, 2)}, data.Keep(RandomValues(rng, 5, 0.3, 3.0))})});
  cases.push_back(
      {"power form 2D", BezierCurve::FromPowerForm({2, points(4, 2)})});
  cases.push_back(
      {"lagrange 3D", LagrangeCurve::Create({{3, points(5, 3)}, {}})});
  cases.push_back(
      {"hermite 2D", HermiteCurve::Create({{2, points(4, 2)},
                                           {2, points(4, 2)},
                                           data.Keep({0.0, 0.5, 2.0, 3.0})})});
  cases.push_back({"bspline cubic 2D",
                   BSplineCurve::Create({3,
                                         {2, points(10, 2)},
                                         data.Keep({0, 0, 0, 0, 0.1, 0.3, 0.3,
                                                    0.5, 0.8, 0.9, 1, 1, 1, 1}),
                                         {}})});
  cases.push_back({"nurbs unclamped 3D",
                   BSplineCurve::Create(
                       {2,
                        {3, points(8, 3)},
                        data.Keep(testing_util::RandomKnots(rng, 2, 7, false)),
                        data.Keep(RandomValues(rng, 8, 0.3, 3.0))})});
  cases.push_back(
      {"bspline 1D",
       BSplineCurve::Create({3,
                             {1, points(6, 1)},
                             data.Keep({0, 0, 0, 0, 0.4, 0.6, 1, 1, 1, 1}),
                             {}})});
  return cases;
}

TEST(ClosestPointTest, CurvesNeverFartherThanDenseReference) {
  std::mt19937_64 rng(12);
  CurveData data;
  for (const CurveCase& c : CurveCases(rng, data)) {
    ASSERT_TRUE(c.curve.ok()) << c.name << ": " << c.curve.status();
    const Curve& curve = *c.curve;
    const int dim = DimensionOf(curve);
    const std::vector<double> queries =
        RandomValues(rng, 1000 * dim, -1.5, 1.5);
    const PointsView view{dim, queries};
    const auto start = std::chrono::steady_clock::now();
    const absl::StatusOr<ClosestPoints> answer =
        CurveClosestPoints(curve, view);
    const double ms = std::chrono::duration<double, std::milli>(
                          std::chrono::steady_clock::now() - start)
                          .count();
    ASSERT_TRUE(answer.ok()) << c.name << ": " << answer.status();
    CheckCurveAnswer(curve, view, *answer);
    const ParameterDomain domain = DomainOf(curve);
    const std::vector<double> samples = Grid(domain.start, domain.end, 4000);
    const std::vector<double> points = CurvePoints(curve, samples);
    double worst = -INFINITY;
    int incomplete = 0;
    for (size_t r = 0; r < view.size(); ++r) {
      const double reference =
          CurveReference(curve, samples, points, view.point(r));
      worst = std::max(worst, answer->distances[r] - reference);
      incomplete += answer->complete[r] ? 0 : 1;
      EXPECT_LE(answer->distances[r], reference + 1e-9) << c.name << " " << r;
    }
    EXPECT_EQ(incomplete, 0) << c.name;
    std::printf("%s: 1000 queries %.1f ms, worst excess over reference %.2e\n",
                c.name.c_str(), ms, worst);
  }
}

// A cubic clamped B-spline of 100 random control points (97 spans, the
// benchmark's W1 shape): queries around it, far from it and on it.
TEST(ClosestPointTest, ManySpansMatchTheDenseReference) {
  std::mt19937_64 rng(19);
  const std::vector<double> control = RandomValues(rng, 3 * 100);
  std::vector<double> knots(4, 0.0);
  for (int i = 1; i < 97; ++i) knots.push_back(i / 97.0);
  knots.insert(knots.end(), 4, 1.0);
  const absl::StatusOr<Curve> curve =
      BSplineCurve::Create({3, {3, control}, knots, {}});
  ASSERT_TRUE(curve.ok());
  std::vector<double> queries = RandomValues(rng, 3 * 600, -1.2, 1.2);
  const std::vector<double> far = RandomValues(rng, 3 * 100, -6.0, 6.0);
  queries.insert(queries.end(), far.begin(), far.end());
  const std::vector<double> on =
      CurvePoints(*curve, RandomValues(rng, 100, 0, 1));
  queries.insert(queries.end(), on.begin(), on.end());
  const PointsView view{3, queries};
  const absl::StatusOr<ClosestPoints> answer = CurveClosestPoints(*curve, view);
  ASSERT_TRUE(answer.ok());
  CheckCurveAnswer(*curve, view, *answer);
  const std::vector<double> samples = Grid(0.0, 1.0, 4000);
  const std::vector<double> points = CurvePoints(*curve, samples);
  for (size_t r = 0; r < view.size(); ++r) {
    EXPECT_TRUE(answer->complete[r]) << r;
    const double reference =
        CurveReference(*curve, samples, points, view.point(r));
    EXPECT_LE(answer->distances[r], reference + 1e-9) << r;
    if (r >= 700) {
      EXPECT_LE(answer->distances[r], 1e-12) << r;
    }
  }
}

TEST(ClosestPointTest, PointsOnCurvesInvertToTheirParameter) {
  std::mt19937_64 rng(7);
  CurveData data;
  for (const CurveCase& c : CurveCases(rng, data)) {
    ASSERT_TRUE(c.curve.ok()) << c.name;
    const Curve& curve = *c.curve;
    const ParameterDomain domain = DomainOf(curve);
    const std::vector<double> parameters =
        RandomValues(rng, 200, domain.start, domain.end);
    const std::vector<double> points = CurvePoints(curve, parameters);
    const absl::StatusOr<ClosestPoints> answer =
        CurveClosestPoints(curve, {DimensionOf(curve), points});
    ASSERT_TRUE(answer.ok()) << answer.status();
    for (size_t r = 0; r < parameters.size(); ++r) {
      EXPECT_LE(answer->distances[r], 1e-12) << c.name;
      double nearest = INFINITY;
      for (int k = 0; k < answer->counts[r]; ++k) {
        nearest = std::min(
            nearest, std::abs(answer->parameters[r * 8 + k] - parameters[r]));
      }
      EXPECT_LE(nearest, 1e-9 * (domain.end - domain.start))
          << c.name << " t=" << parameters[r];
    }
  }
}

TEST(ClosestPointTest, EndPointsAreNearestBeyondTheEnds) {
  // An arch: beyond each end along the tangent, the end point is nearest.
  const std::vector<double> arch = {0, 0, 1, 1, 2, 1, 3, 0};
  const absl::StatusOr<Curve> curve = BezierCurve::Create({{2, arch}, {}});
  const double h = 0.5 / std::sqrt(2.0);
  const std::vector<double> queries = {-h, -h, 3 + h, -h};
  const absl::StatusOr<ClosestPoints> answer =
      CurveClosestPoints(*curve, {2, queries});
  ASSERT_TRUE(answer.ok());
  EXPECT_EQ(answer->parameters[0], 0.0);
  EXPECT_EQ(answer->parameters[8], 1.0);
  EXPECT_NEAR(answer->distances[0], 0.5, 1e-15);
  EXPECT_NEAR(answer->distances[1], 0.5, 1e-15);
  // The same arch as a clamped B-spline on [2, 5].
  const std::vector<double> knots = {2, 2, 2, 2, 5, 5, 5, 5};
  const absl::StatusOr<Curve> spline =
      BSplineCurve::Create({3, {2, arch}, knots, {}});
  const absl::StatusOr<ClosestPoints> spline_answer =
      CurveClosestPoints(*spline, {2, queries});
  ASSERT_TRUE(spline_answer.ok());
  EXPECT_EQ(spline_answer->parameters[0], 2.0);
  EXPECT_EQ(spline_answer->parameters[8], 5.0);
}

TEST(ClosestPointTest, NurbsCircle) {
  const double radius = 2.0;
  const BSplineCurveData data = testing_util::NurbsCircle(radius, 1.0, -1.0);
  const absl::StatusOr<Curve> curve = BSplineCurve::Create(data.view());
  ASSERT_TRUE(curve.ok());
  std::mt19937_64 rng(3);
  std::vector<double> queries = RandomValues(rng, 2000, -3.0, 5.0);
  queries.insert(queries.end(), {1.0, -1.0});  // the centre, last
  const size_t count = queries.size() / 2;
  const absl::StatusOr<ClosestPoints> answer =
      CurveClosestPoints(*curve, {2, queries});
  ASSERT_TRUE(answer.ok());
  CheckCurveAnswer(*curve, {2, queries}, *answer);
  for (size_t r = 0; r + 1 < count; ++r) {
    const double dx = queries[2 * r] - 1.0;
    const double dy = queries[2 * r + 1] + 1.0;
    const double rho = std::hypot(dx, dy);
    EXPECT_NEAR(answer->distances[r], std::abs(rho - radius), 1e-12);
    EXPECT_EQ(answer->counts[r], 1);
    EXPECT_TRUE(answer->complete[r]);
    EXPECT_NEAR(answer->points[16 * r], 1.0 + radius * dx / rho, 1e-12);
    EXPECT_NEAR(answer->points[16 * r + 1], -1.0 + radius * dy / rho, 1e-12);
  }
  // The centre: every parameter is a minimum. The answer is a bounded set
  // of max_minima distinct points at distance r, flagged incomplete.
  const size_t c = count - 1;
  EXPECT_NEAR(answer->distances[c], radius, 1e-12);
  EXPECT_FALSE(answer->complete[c]);
  EXPECT_EQ(answer->counts[c], 8);
  for (int k = 0; k < 8; ++k) {
    const double* p = answer->points.data() + (c * 8 + k) * 2;
    EXPECT_NEAR(std::hypot(p[0] - 1.0, p[1] + 1.0), radius, 1e-12);
    for (int m = 0; m < k; ++m) {
      EXPECT_NE(answer->parameters[c * 8 + k], answer->parameters[c * 8 + m]);
    }
  }
}

TEST(ClosestPointTest, SphereAndTorusPatches) {
  const double radius = 1.5;
  const SurfaceData sphere_data = testing_util::SpherePatch(radius);
  const absl::StatusOr<Surface> sphere =
      BezierSurface::Create(sphere_data.bezier_view());
  ASSERT_TRUE(sphere.ok());
  std::mt19937_64 rng(5);
  std::vector<double> queries;
  for (int r = 0; r < 1000; ++r) {
    const std::vector<double> d = RandomValues(rng, 3, 0.05, 1.0);
    const double scale = RandomValues(rng, 1, 0.5, 3.0)[0];
    for (double x : d) queries.push_back(scale * x);
  }
  const absl::StatusOr<ClosestPoints> answer =
      SurfaceClosestPoints(*sphere, {3, queries});
  ASSERT_TRUE(answer.ok());
  for (size_t r = 0; r < 1000; ++r) {
    const double* q = queries.data() + 3 * r;
    const double rho = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    ASSERT_NEAR(answer->distances[r], std::abs(rho - radius), 1e-12);
    for (int x = 0; x < 3; ++x) {
      EXPECT_NEAR(answer->points[24 * r + x], radius * q[x] / rho, 1e-9);
    }
  }
  const std::vector<double> centre = {0, 0, 0};
  const absl::StatusOr<ClosestPoints> at_centre =
      SurfaceClosestPoints(*sphere, {3, centre});
  ASSERT_TRUE(at_centre.ok());
  EXPECT_NEAR(at_centre->distances[0], radius, 1e-12);
  EXPECT_FALSE(at_centre->complete[0]);
  EXPECT_EQ(at_centre->counts[0], 8);

  // The torus: points pushed off the patch along its normal by delta < r
  // are delta from their foot point.
  const double major = 2.0, minor = 0.5;
  const SurfaceData torus_data = testing_util::TorusPatch(major, minor);
  const absl::StatusOr<Surface> torus =
      BezierSurface::Create(torus_data.bezier_view());
  ASSERT_TRUE(torus.ok());
  std::vector<double> offsets;
  std::vector<double> deltas;
  for (int r = 0; r < 1000; ++r) {
    const std::vector<double> a = RandomValues(rng, 2, 0.0, M_PI / 2);
    const double delta = RandomValues(rng, 1, -0.3, 1.0)[0];
    const double rho = major + (minor + delta) * std::cos(a[1]);
    offsets.insert(offsets.end(), {rho * std::cos(a[0]), rho * std::sin(a[0]),
                                   (minor + delta) * std::sin(a[1])});
    deltas.push_back(delta);
  }
  const absl::StatusOr<ClosestPoints> torus_answer =
      SurfaceClosestPoints(*torus, {3, offsets});
  ASSERT_TRUE(torus_answer.ok());
  for (size_t r = 0; r < 1000; ++r) {
    EXPECT_NEAR(torus_answer->distances[r], std::abs(deltas[r]), 1e-12);
  }
}

// Owned surfaces of every kind.
struct SurfaceCase {
  std::string name;
  absl::StatusOr<Surface> surface;
};

std::vector<SurfaceCase> SurfaceCases(std::mt19937_64& rng, CurveData& data) {
  data.arrays.reserve(64);
  std::vector<SurfaceCase> cases;
  auto net = [&](size_t count) -> const std::vector<double>& {
    return data.Keep(RandomValues(rng, count * 3));
  };
  cases.push_back(
      {"bezier bicubic", BezierSurface::Create({{3, 4, 4, net(16)}, {}})});
  cases.push_back(
      {"rational bezier 3x4",
       BezierSurface::Create(
           {{3, 3, 4, net(12)}, data.Keep(RandomValues(rng, 12, 0.3, 3.0))})});
  cases.push_back(
      {"bspline bicubic 6x5",
       BSplineSurface::Create({3,
                               3,
                               {3, 6, 5, net(30)},
                               data.Keep({0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1}),
                               data.Keep({0, 0, 0, 0, 0.5, 1, 1, 1, 1}),
                               {}})});
  cases.push_back({"nurbs unclamped 5x5",
                   BSplineSurface::Create(
                       {2,
                        2,
                        {3, 5, 5, net(25)},
                        data.Keep(testing_util::RandomKnots(rng, 2, 4, false)),
                        data.Keep(testing_util::RandomKnots(rng, 2, 4, false)),
                        data.Keep(RandomValues(rng, 25, 0.3, 3.0))})});
  cases.push_back({"interpolating patch",
                   BezierSurface::FromInterpolatingPatch({3, 4, 4, net(16)})});
  cases.push_back({"hermite patch", BezierSurface::FromHermitePatch(
                                        {3, 2, 2, net(4)}, {3, 2, 2, net(4)},
                                        {3, 2, 2, net(4)}, {3, 2, 2, net(4)})});
  cases.push_back(
      {"triangular cubic", TriangularPatch::Create({3, {3, net(10)}, {}, {}})});
  cases.push_back(
      {"rational triangular quadratic",
       TriangularPatch::Create(
           {2, {3, net(6)}, data.Keep(RandomValues(rng, 6, 0.3, 3.0)), {}})});
  return cases;
}

TEST(ClosestPointTest, SurfacesNeverFartherThanDenseReference) {
  std::mt19937_64 rng(21);
  CurveData data;
  for (const SurfaceCase& c : SurfaceCases(rng, data)) {
    ASSERT_TRUE(c.surface.ok()) << c.name << ": " << c.surface.status();
    const Surface& surface = *c.surface;
    const std::vector<double> queries = RandomValues(rng, 3000, -1.5, 1.5);
    const auto start = std::chrono::steady_clock::now();
    const absl::StatusOr<ClosestPoints> answer =
        SurfaceClosestPoints(surface, {3, queries});
    const double ms = std::chrono::duration<double, std::milli>(
                          std::chrono::steady_clock::now() - start)
                          .count();
    ASSERT_TRUE(answer.ok()) << c.name << ": " << answer.status();
    const SurfaceReference reference(surface);
    double worst = -INFINITY;
    for (size_t r = 0; r < 1000; ++r) {
      const double* q = queries.data() + 3 * r;
      const double expected = reference.Nearest(q);
      worst = std::max(worst, answer->distances[r] - expected);
      EXPECT_LE(answer->distances[r], expected + 1e-9) << c.name << " " << r;
      EXPECT_TRUE(answer->complete[r]) << c.name << " " << r;
      // The returned point is the surface's point at the returned (u, v).
      const std::vector<double> uv(answer->parameters.begin() + 16 * r,
                                   answer->parameters.begin() + 16 * r + 2);
      const std::vector<double> point =
          SurfacePoints(surface, SurfaceSamples::Pairs(uv));
      EXPECT_LE(Distance(point.data(), answer->points.data() + 24 * r, 3),
                1e-12);
      EXPECT_NEAR(Distance(point.data(), q, 3), answer->distances[r], 1e-12);
    }
    std::printf("%s: 1000 queries %.1f ms, worst excess over reference %.2e\n",
                c.name.c_str(), ms, worst);
  }
}

// A point at height h along the normal of an affine patch S(u, v) = A + u U
// + v V (a biquadratic net, so the patch is in its general Bezier form) is
// nearest at (u, v) itself. The search's corners are dyadic, and a corner
// 1e-8 from (u, v) computes a distance within rounding of the true one: the
// polished parameters must still be those of the minimum, not the corner's
// (the load test once got v = 0.871246337890625 for 0.87124635020443231).
TEST(ClosestPointTest, AffinePatchesGiveTheFootOfThePerpendicular) {
  // The load test's case: the patch's (u, v) by the normal equations.
  {
    const std::vector<double> net = {
        1.7686087357451359, 0.11562001138377509,  1.7900250632644954,
        1.9612998414213036, -0.44790479057845622, 2.77520519391732,
        2.1539909470974714, -1.0114295925406875,  3.7603853245701453,
        1.5604571278687134, -0.27218948132447907, 2.4683680347297043,
        1.7531482335448811, -0.83571428328671038, 3.4535481653825295,
        1.9458393392210489, -1.3992390852489418,  4.4387282960353538,
        1.3523055199922906, -0.65999897403273322, 3.1467110061949137,
        1.5449966256684584, -1.2235237759949644,  4.1318911368477389,
        1.7376877313446262, -1.7870485779571958,  5.1170712675005632};
    const std::vector<double> query = {1.8932993578398798, -2.0717408664820223,
                                       3.7279828050298676};
    double normal_matrix[2][2] = {}, right[2] = {};
    for (int c = 0; c < 3; ++c) {
      const double axes[2] = {net[18 + c] - net[c], net[6 + c] - net[c]};
      for (int k = 0; k < 2; ++k) {
        right[k] += axes[k] * (query[c] - net[c]);
        for (int l = 0; l < 2; ++l) normal_matrix[k][l] += axes[k] * axes[l];
      }
    }
    const double det = normal_matrix[0][0] * normal_matrix[1][1] -
                       normal_matrix[0][1] * normal_matrix[1][0];
    const double u =
        (right[0] * normal_matrix[1][1] - right[1] * normal_matrix[0][1]) / det;
    const double v =
        (right[1] * normal_matrix[0][0] - right[0] * normal_matrix[1][0]) / det;
    const Surface patch = *BezierSurface::Create(
        {.control_net = {
             .dimension = 3, .count_u = 3, .count_v = 3, .coordinates = net}});
    absl::StatusOr<ClosestPoints> found =
        SurfaceClosestPoints(patch, {.dimension = 3, .coordinates = query});
    ASSERT_TRUE(found.ok()) << found.status();
    EXPECT_NEAR(found->parameters[0], u, 1e-12);
    EXPECT_NEAR(found->parameters[1], v, 1e-12);
  }
  std::mt19937_64 rng(1112510476);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int checked = 0;
  while (checked < 300) {
    double a[3], u_axis[3], v_axis[3];
    for (int j = 0; j < 3; ++j) {
      a[j] = 2 * unit(rng);
      u_axis[j] = unit(rng);
      v_axis[j] = unit(rng);
    }
    const double normal[3] = {u_axis[1] * v_axis[2] - u_axis[2] * v_axis[1],
                              u_axis[2] * v_axis[0] - u_axis[0] * v_axis[2],
                              u_axis[0] * v_axis[1] - u_axis[1] * v_axis[0]};
    const double area = std::hypot(normal[0], normal[1], normal[2]);
    const double lengths = std::hypot(u_axis[0], u_axis[1], u_axis[2]) *
                           std::hypot(v_axis[0], v_axis[1], v_axis[2]);
    if (area < 0.3 * lengths) continue;  // axes at least 17 degrees apart
    std::vector<double> net;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        for (int c = 0; c < 3; ++c) {
          net.push_back(a[c] + i / 2.0 * u_axis[c] + j / 2.0 * v_axis[c]);
        }
      }
    }
    const Surface patch = *BezierSurface::Create(
        {.control_net = {
             .dimension = 3, .count_u = 3, .count_v = 3, .coordinates = net}});
    const double u = 0.05 + 0.9 * (unit(rng) + 1) / 2;
    const double v = 0.05 + 0.9 * (unit(rng) + 1) / 2;
    const double height = 3 * unit(rng);
    std::vector<double> query(3);
    for (int c = 0; c < 3; ++c) {
      query[c] =
          a[c] + u * u_axis[c] + v * v_axis[c] + height * normal[c] / area;
    }
    absl::StatusOr<ClosestPoints> found =
        SurfaceClosestPoints(patch, {.dimension = 3, .coordinates = query});
    ASSERT_TRUE(found.ok()) << found.status();
    EXPECT_NEAR(found->distances[0], std::abs(height), 1e-12) << checked;
    EXPECT_NEAR(found->parameters[0], u, 1e-12) << checked;
    EXPECT_NEAR(found->parameters[1], v, 1e-12) << checked;
    ++checked;
  }
}

TEST(ClosestPointTest, PatchBoundaryAndCorner) {
  // A planar bicubic patch over the unit square, unevenly parameterized.
  const double x[4] = {0, 0.2, 0.7, 1};
  std::vector<double> net;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) net.insert(net.end(), {x[i], x[j], 0.0});
  }
  const absl::StatusOr<Surface> patch =
      BezierSurface::Create({{3, 4, 4, net}, {}});
  const std::vector<double> queries = {0.4,  -0.3, 0.1,   // below edge v = 0
                                       1.2,  0.6,  -0.2,  // beyond edge u = 1
                                       -0.2, -0.3, 0.0,   // beyond corner 0, 0
                                       0.3,  0.8,  0.5};  // above the inside
  const absl::StatusOr<ClosestPoints> answer =
      SurfaceClosestPoints(*patch, {3, queries});
  ASSERT_TRUE(answer.ok());
  const double expected[4][3] = {
      {0.4, 0, 0}, {1, 0.6, 0}, {0, 0, 0}, {0.3, 0.8, 0}};
  const double distances[4] = {std::hypot(0.3, 0.1), std::hypot(0.2, 0.2),
                               std::hypot(0.2, 0.3), 0.5};
  for (int r = 0; r < 4; ++r) {
    EXPECT_NEAR(answer->distances[r], distances[r], 1e-14) << r;
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(answer->points[24 * r + k], expected[r][k], 1e-14) << r;
    }
  }
  EXPECT_EQ(answer->parameters[16 * 0 + 1], 0.0);  // on v = 0
  EXPECT_EQ(answer->parameters[16 * 1 + 0], 1.0);  // on u = 1
  EXPECT_EQ(answer->parameters[16 * 2 + 0], 0.0);
  EXPECT_EQ(answer->parameters[16 * 2 + 1], 0.0);
}

TEST(ClosestPointTest, UtahTeapot) {
  const testing_util::Patches teapot = testing_util::ReadTeapot();
  const std::vector<BezierSurfaceView> views = teapot.Views();
  std::mt19937_64 rng(8);
  std::vector<double> queries;
  for (int r = 0; r < 100; ++r) {
    const std::vector<double> q = RandomValues(rng, 3, -3.5, 3.5);
    queries.insert(queries.end(), {q[0], q[1], 0.5 * (q[2] + 3.5)});
  }
  std::vector<double> best(100, INFINITY);
  std::vector<double> reference(100, INFINITY);
  for (const BezierSurfaceView& view : views) {
    const absl::StatusOr<Surface> patch = BezierSurface::Create(view);
    ASSERT_TRUE(patch.ok());
    const absl::StatusOr<ClosestPoints> answer =
        SurfaceClosestPoints(*patch, {3, queries});
    ASSERT_TRUE(answer.ok());
    const SurfaceReference dense(*patch);
    for (size_t r = 0; r < 100; ++r) {
      best[r] = std::min(best[r], answer->distances[r]);
      reference[r] = std::min(reference[r], dense.Nearest(&queries[3 * r]));
    }
  }
  for (size_t r = 0; r < 100; ++r) {
    EXPECT_LE(best[r], reference[r] + 1e-9) << r;
    EXPECT_GE(best[r], reference[r] - 1e-6) << r;  // the reference is close
  }
}

TEST(ClosestPointTest, BatchOnThePoolMatchesSerial) {
  std::mt19937_64 rng(4);
  const std::vector<double> net = RandomValues(rng, 48);
  const absl::StatusOr<Surface> patch =
      BezierSurface::Create({{3, 4, 4, net}, {}});
  const std::vector<double> queries = RandomValues(rng, 3 * 500, -2, 2);
  ThreadPool pool(2);
  const absl::StatusOr<ClosestPoints> serial =
      SurfaceClosestPoints(*patch, {3, queries});
  const absl::StatusOr<ClosestPoints> parallel = SurfaceClosestPoints(
      *patch, {3, queries}, {}, {.pool = &pool, .grain = 4});
  ASSERT_TRUE(serial.ok() && parallel.ok());
  EXPECT_EQ(serial->distances, parallel->distances);
  EXPECT_EQ(serial->parameters, parallel->parameters);
}

// CornerPoint writes the point of RationalCorner(w) (shapes.h) at
// t = 1 - from_end when `from_end` is given (so that parameters within 1e-16
// of 1 exist), else at t, from its closed form in long double.
void CornerPoint(long double w, long double t, long double from_end,
                 long double* point) {
  const long double s = from_end > 0 ? from_end : 1 - t;
  if (from_end > 0) t = 1 - from_end;
  const long double d = s * s + 2 * w * t * s + t * t;
  point[0] = (s * s + 2 * w * t * s) / d;
  point[1] = (2 * w * t * s + t * t) / d;
}

// CornerSampleDistance returns the least distance from q to 40001 points of
// RationalCorner(w) spread evenly in log t near each end, down to 1e-40 / w
// of it: no point of the corner is nearer by much.
double CornerSampleDistance(long double w, const double* q) {
  long double best = INFINITY;
  const long double lowest = std::log10(1e-40L / w);
  for (int k = 0; k <= 20000; ++k) {
    const long double e =
        std::pow(10.0L, lowest + (-0.302L - lowest) * k / 20000);
    for (const bool from_end : {false, true}) {
      long double point[2];
      CornerPoint(w, e, from_end ? e : 0, point);
      best = std::min(best, std::hypot(point[0] - q[0], point[1] - q[1]));
    }
  }
  return static_cast<double>(best);
}

// The corner with weights 1, w, 1 runs its second leg, from near (1, 1) to
// (0, 1), for t within 1/w of 1, where adjacent doubles of t are 1.1e-16
// apart. Up to w = 1e10 every query is answered: the returned point is the
// curve's point at the returned parameter, the distance is its distance, no
// sample of the curve is nearer by more than the tolerance, and the lower
// bound is within it. From w = 1e15 on, the first leg (near t = 0, where
// doubles are dense) still is; a query whose nearest point lies on the
// second leg cannot be answered by any double parameter and is refused
// naming the weights (with 1e50 the search reported a distance of 1 for a
// point 1.118 away).
TEST(ClosestPointTest, ExtremeWeightsAreAnsweredOrRefused) {
  const std::vector<double> legs = {2.0, 0.5, 0.5, 2.0, 0.9, 0.9};
  for (const double w : {1e5, 1e10, 1e15, 1e50, 1e300}) {
    const BezierCurveData data = testing_util::RationalCorner(w);
    const Curve corner = *BezierCurve::Create(data.view());
    for (size_t r = 0; r < legs.size() / 2; ++r) {
      const std::vector<double> q(legs.begin() + 2 * r,
                                  legs.begin() + 2 * r + 2);
      const absl::StatusOr<ClosestPoints> answer =
          CurveClosestPoints(corner, {2, q});
      if (w >= 1e15 && r == 1) {
        EXPECT_EQ(answer.status().code(), absl::StatusCode::kInvalidArgument);
        EXPECT_EQ(FieldPathOf(answer.status()), "weights") << answer.status();
        continue;
      }
      ASSERT_TRUE(answer.ok()) << "w = " << w << ": " << answer.status();
      ASSERT_GE(answer->counts[0], 1);
      const std::vector<double> at = {answer->parameters[0]};
      const std::vector<double> point = CurvePoints(corner, at);
      EXPECT_EQ(point[0], answer->points[0]);
      EXPECT_EQ(point[1], answer->points[1]);
      EXPECT_NEAR(answer->distances[0], Distance(point.data(), q.data(), 2),
                  1e-15);
      EXPECT_LE(answer->distances[0], CornerSampleDistance(w, q.data()) + 1e-9)
          << "w = " << w << ", q = (" << q[0] << ", " << q[1] << ")";
      // Every returned minimum is at the distance (within the tolerance).
      for (int k = 0; k < answer->counts[0]; ++k) {
        EXPECT_LE(Distance(answer->points.data() + 2 * k, q.data(), 2),
                  answer->distances[0] + 1e-8)
            << "w = " << w << ", r = " << r << ", minimum " << k;
      }
      // (0.9, 0.9) has a second minimum, (0.9, 1) on the second leg, which
      // no double parameter reaches from w = 1e15 on: the answer holds the
      // first leg's and says it is incomplete (it returned (0, 1), 0.9
      // away, as a second minimum).
      EXPECT_EQ(answer->complete[0] != 0, !(w >= 1e15 && r == 2))
          << "w = " << w << ", r = " << r;
      EXPECT_LE(answer->lower_bounds[0], answer->distances[0]);
      EXPECT_GE(answer->lower_bounds[0], answer->distances[0] - 1e-9);
    }
  }
}

// The corner extruded along z as a rational surface (weights 1, w, 1 across
// the corner): the same answers, refusals and checks.
TEST(ClosestPointTest, ExtremeWeightsOnSurfacesAreAnsweredOrRefused) {
  for (const double w : {1e5, 1e50}) {
    const std::vector<double> net = {1, 0, 0, 1, 0, 1, 1, 1, 0,
                                     1, 1, 1, 0, 1, 0, 0, 1, 1};
    const std::vector<double> weights = {1, 1, w, w, 1, 1};
    const Surface sheet = *BezierSurface::Create(
        {.control_net = {3, 3, 2, net}, .weights = weights});
    const std::vector<double> first = {2.0, 0.5, 0.5};
    const absl::StatusOr<ClosestPoints> answer =
        SurfaceClosestPoints(sheet, {3, first});
    ASSERT_TRUE(answer.ok()) << answer.status();
    const std::vector<double> uv = {answer->parameters[0],
                                    answer->parameters[1]};
    const std::vector<double> point =
        SurfacePoints(sheet, SurfaceSamples::Pairs(uv));
    EXPECT_NEAR(answer->distances[0], Distance(point.data(), first.data(), 3),
                1e-15);
    EXPECT_NEAR(answer->distances[0], 1.0, 1e-4);
    EXPECT_NEAR(point[2], 0.5, 1e-9);
    const std::vector<double> second = {0.5, 2.0, 0.5};
    const absl::StatusOr<ClosestPoints> other =
        SurfaceClosestPoints(sheet, {3, second});
    if (w < 1e15) {
      ASSERT_TRUE(other.ok()) << other.status();
      const std::vector<double> st = {other->parameters[0],
                                      other->parameters[1]};
      const std::vector<double> there =
          SurfacePoints(sheet, SurfaceSamples::Pairs(st));
      EXPECT_NEAR(other->distances[0], Distance(there.data(), second.data(), 3),
                  1e-15);
      EXPECT_NEAR(other->distances[0], 1.0, 1e-4);
    } else {
      EXPECT_EQ(FieldPathOf(other.status()), "weights") << other.status();
    }
  }
}

// A control point of weight 0 is a direction: its homogeneous point is
// (P, 0). The queries search a copy with the weights divided by a power of
// two, and a direction divided only like the points there moved the
// geometry: the fuzzer's biquadratic with the middle weight 0 (weights up to
// 2) had a point 0.45 from the query while the search certified 0.66.
// The smallest weight ratio the geometry takes (2^-1021, rational.h) still
// weighs its point: a degree-0 rational B-spline is its control points
// whatever their weights, and a quadratic's end is its end point (the
// Bezier pieces divide by w; multiplied by 1 / w they took w P times an
// infinite reciprocal below 2^-1024). Below the ratio, the homogeneous
// point w P underflows (0.3 times 5e-324 is 0), so such weights are
// refused: a fuzz finding of issue 30 lost the first step of such a
// B-spline (distance 1 for 0), another answered an intersection point 1
// off its curve.
TEST(ClosestPointTest, TheSmallestWeightRatioKeepsItsPoint) {
  const std::vector<double> points = {0, 0, 0, 1, 0, 0, 3, 2, 0, 4, 0, 0};
  const std::vector<double> knots = {0, 0.25, 0.5, 0.75, 1};
  const std::vector<double> clamped = {0, 0, 0, 0.5, 1, 1, 1};
  const std::vector<double> origin = {0, 0, 0};
  for (double largest : {1.0, 0x1p1000}) {
    const std::vector<double> weights = {largest * kSmallestWeightRatio,
                                         largest, largest, largest};
    const Curve steps = *BSplineCurve::Create({.degree = 0,
                                               .control_points = {3, points},
                                               .knots = knots,
                                               .weights = weights});
    const absl::StatusOr<ClosestPoints> answer =
        CurveClosestPoints(steps, {3, origin});
    ASSERT_TRUE(answer.ok()) << answer.status();
    EXPECT_EQ(answer->distances[0], 0.0) << largest;
    EXPECT_EQ(answer->parameters[0], 0.0) << largest;

    const Curve quadratic =
        *BSplineCurve::Create({.degree = 2,
                               .control_points = {3, points},
                               .knots = clamped,
                               .weights = weights});
    const absl::StatusOr<ClosestPoints> end =
        CurveClosestPoints(quadratic, {3, origin});
    ASSERT_TRUE(end.ok()) << end.status();
    EXPECT_LE(end->distances[0], 1e-9) << largest;
  }
  for (double weight : {1e-310, 4.9406564584124654e-324}) {
    const std::vector<double> weights = {weight, 1, 1, 1};
    const absl::StatusOr<BSplineCurve> refused =
        BSplineCurve::Create({.degree = 0,
                              .control_points = {3, points},
                              .knots = knots,
                              .weights = weights});
    ASSERT_FALSE(refused.ok()) << weight;
    EXPECT_EQ(FieldPathOf(refused.status()), "weights[0]") << weight;
  }
  // Only the ratio counts: weights scaled alike are the same geometry.
  const std::vector<double> tiny = {1e-310, 2e-310, 1e-310, 3e-310};
  EXPECT_TRUE(BSplineCurve::Create({.degree = 0,
                                    .control_points = {3, points},
                                    .knots = knots,
                                    .weights = tiny})
                  .ok());
}

TEST(ClosestPointTest, ZeroWeightsAreDirectionsInTheScaledCopy) {
  const std::vector<double> net = {0, 0, 0, 2.0000114440917969,
                                   0, 0, 4, 0,
                                   0, 0, 2, 0,
                                   2, 2, 0, 4,
                                   2, 2, 0, 4,
                                   0, 2, 4, 4.0000000000022737,
                                   4, 4, 4};
  const std::vector<double> weights = {1, 2, 1, 0.5, 0, 0.5, 1, 2, 1};
  const Surface patch = *BezierSurface::Create(
      {.control_net = {3, 3, 3, net}, .weights = weights});
  const std::vector<double> queries = {0.5, 9.918212890625e-05, 0.5, 3,
                                       3,   3.0000019073477207};
  const absl::StatusOr<ClosestPoints> answer =
      SurfaceClosestPoints(patch, {3, queries});
  ASSERT_TRUE(answer.ok()) << answer.status();
  const SurfaceReference dense(patch);
  for (size_t r = 0; r < 2; ++r) {
    const double* q = queries.data() + 3 * r;
    const double expected = dense.Nearest(q);
    EXPECT_LE(answer->distances[r], expected + 1e-9) << r;
    EXPECT_LE(answer->lower_bounds[r], expected) << r;
    EXPECT_TRUE(answer->complete[r]) << r;
  }
  // A conic whose middle control point is the direction (1, 1): the search
  // runs on a copy whose weights are divided by 4, where that direction
  // must be divided by 4 too.
  const std::vector<double> conic_points = {0, 0, 1, 1, 2, 0};
  const std::vector<double> conic_weights = {1, 0, 3};
  const Curve conic = *BezierCurve::Create(
      {.control_points = {2, conic_points}, .weights = conic_weights});
  const std::vector<double> near = {1.2, 0.5, 0.3, 0.1, 1.9, -0.2};
  const absl::StatusOr<ClosestPoints> on_conic =
      CurveClosestPoints(conic, {2, near});
  ASSERT_TRUE(on_conic.ok()) << on_conic.status();
  const std::vector<double> samples = Grid(0.0, 1.0, 4000);
  const std::vector<double> points = CurvePoints(conic, samples);
  for (size_t r = 0; r < 3; ++r) {
    const double expected =
        CurveReference(conic, samples, points, near.data() + 2 * r);
    EXPECT_LE(on_conic->distances[r], expected + 1e-9) << r;
    EXPECT_LE(on_conic->lower_bounds[r], expected) << r;
  }
}

// A segment of length s and a unit square scaled by s, with queries at
// s above them, have distance s and the foot of the perpendicular at every
// scale (at 1e-200 the squared distances underflowed to 0; past 1e154 they
// overflowed to infinity). A query up to 1e300 away from the unit segment
// gets its finite distance, with a point of the segment.
TEST(ClosestPointTest, EveryScale) {
  for (int k = -300; k <= 300; k += 25) {
    const double s = std::pow(10.0, k);
    const std::vector<double> segment = {0, 0, s, 0};
    const Curve line = *BezierCurve::Create({.control_points = {2, segment}});
    const std::vector<double> q = {0.3 * s, s};
    const ClosestPointOptions options{.tolerance = 1e-12 * s,
                                      .separation = 1e-9 * s};
    const absl::StatusOr<ClosestPoints> answer =
        CurveClosestPoints(line, {2, q}, options);
    ASSERT_TRUE(answer.ok()) << answer.status();
    EXPECT_NEAR(answer->distances[0] / s, 1.0, 1e-12) << s;
    EXPECT_NEAR(answer->parameters[0], 0.3, 1e-9) << s;
    EXPECT_TRUE(answer->complete[0]) << s;
    const std::vector<double> square = {0, 0, 0, 0, s, 0, s, 0, 0, s, s, 0};
    const Surface plane =
        *BezierSurface::Create({.control_net = {3, 2, 2, square}});
    const std::vector<double> above = {0.3 * s, 0.6 * s, s};
    const absl::StatusOr<ClosestPoints> foot =
        SurfaceClosestPoints(plane, {3, above}, options);
    ASSERT_TRUE(foot.ok()) << foot.status();
    EXPECT_NEAR(foot->distances[0] / s, 1.0, 1e-12) << s;
    EXPECT_NEAR(foot->parameters[0], 0.3, 1e-9) << s;
    EXPECT_NEAR(foot->parameters[1], 0.6, 1e-9) << s;
    if (k < 0) continue;
    const std::vector<double> unit = {0, 0, 1, 0};
    const Curve unit_line = *BezierCurve::Create({.control_points = {2, unit}});
    const std::vector<double> far = {0.3, s};
    const absl::StatusOr<ClosestPoints> distant =
        CurveClosestPoints(unit_line, {2, far});
    ASSERT_TRUE(distant.ok()) << distant.status();
    EXPECT_NEAR(distant->distances[0] / s, 1.0, 1e-15) << s;
    EXPECT_LE(distant->lower_bounds[0], distant->distances[0]);
    EXPECT_EQ(distant->points[1], 0.0);
    EXPECT_GE(distant->points[0], 0.0);
    EXPECT_LE(distant->points[0], 1.0);
  }
}

// A constant curve (every control point equal) is a stretch of minima at
// every degree, as a degree-0 spline is: max_minima distinct parameters,
// all at the point, with complete = false. A constant surface gives its one
// point (its parameters count as one minimum) with complete = false.
TEST(ClosestPointTest, ConstantGeometryIsAStretchOfMinimaAtEveryDegree) {
  const std::vector<double> q = {4, 6};
  const ClosestPointOptions options{.max_minima = 4};
  const std::vector<double> three = {1, 2, 1, 2, 1, 2};
  const std::vector<double> four = {1, 2, 1, 2, 1, 2, 1, 2};
  const std::vector<double> step_knots = {0, 1, 2, 3};
  const std::vector<double> linear_knots = {0, 0, 1, 2, 2};
  std::vector<Curve> curves = {
      *BSplineCurve::Create(
          {.degree = 0, .control_points = {2, three}, .knots = step_knots}),
      *BSplineCurve::Create(
          {.degree = 1, .control_points = {2, three}, .knots = linear_knots}),
      *BezierCurve::Create({.control_points = {2, four}})};
  for (const Curve& curve : curves) {
    const absl::StatusOr<ClosestPoints> answer =
        CurveClosestPoints(curve, {2, q}, options);
    ASSERT_TRUE(answer.ok()) << answer.status();
    EXPECT_EQ(answer->counts[0], 4);
    EXPECT_FALSE(answer->complete[0]);
    EXPECT_NEAR(answer->distances[0], 5.0, 1e-14);
    std::vector<double> parameters(answer->parameters.begin(),
                                   answer->parameters.begin() + 4);
    std::sort(parameters.begin(), parameters.end());
    EXPECT_EQ(std::adjacent_find(parameters.begin(), parameters.end()),
              parameters.end());
    for (int k = 0; k < 4; ++k) {  // to the rounding of the evaluation
      EXPECT_NEAR(answer->points[2 * k], 1.0, 1e-15);
      EXPECT_NEAR(answer->points[2 * k + 1], 2.0, 1e-15);
    }
  }
  const std::vector<double> q3 = {4, 6, 0};
  const std::vector<double> point = {1, 2, 0};
  std::vector<double> constant_net;
  for (int k = 0; k < 4; ++k) {
    constant_net.insert(constant_net.end(), point.begin(), point.end());
  }
  const std::vector<Surface> surfaces = {
      *BezierSurface::Create({.control_net = {3, 1, 1, point}}),
      *BezierSurface::Create({.control_net = {3, 2, 2, constant_net}})};
  for (const Surface& surface : surfaces) {
    const absl::StatusOr<ClosestPoints> answer =
        SurfaceClosestPoints(surface, {3, q3}, options);
    ASSERT_TRUE(answer.ok()) << answer.status();
    EXPECT_EQ(answer->counts[0], 1);
    EXPECT_FALSE(answer->complete[0]);
    EXPECT_NEAR(answer->distances[0], 5.0, 1e-14);
  }
}

TEST(ClosestPointTest, ErrorsNameTheirField) {
  const std::vector<double> arch = {0, 0, 1, 1, 2, 1, 3, 0};
  const absl::StatusOr<Curve> curve = BezierCurve::Create({{2, arch}, {}});
  const std::vector<double> queries3 = {0, 0, 0};
  EXPECT_EQ(FieldPathOf(CurveClosestPoints(*curve, {3, queries3}).status()),
            "queries.dimension");
  const std::vector<double> bad = {0, 0, NAN, 1};
  EXPECT_EQ(FieldPathOf(CurveClosestPoints(*curve, {2, bad}).status()),
            "queries.coordinates[2]");
  const std::vector<double> good = {0, 0};
  EXPECT_EQ(
      FieldPathOf(
          CurveClosestPoints(*curve, {2, good}, {.tolerance = 0}).status()),
      "tolerance");
  EXPECT_EQ(
      FieldPathOf(
          CurveClosestPoints(*curve, {2, good}, {.max_minima = 0}).status()),
      "max_minima");
  CancellationToken token;
  token.Cancel();
  EXPECT_EQ(CurveClosestPoints(*curve, {2, good}, {}, {.cancellation = &token})
                .status()
                .code(),
            absl::StatusCode::kCancelled);
  EXPECT_EQ(ClosestPointsValues(10, 3, 2, 8), 10u * (2 + 8 * 5));
}

}  // namespace
}  // namespace freeform
