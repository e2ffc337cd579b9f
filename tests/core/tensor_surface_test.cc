#include "freeform/core/tensor_surface.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "freeform/core/bezier.h"
#include "freeform/core/bspline.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/normals.h"
#include "freeform/core/status.h"
#include "freeform/core/thread_pool.h"
#include "shapes.h"
#include "test_util.h"

namespace freeform {
namespace {

using ::freeform::testing_util::EvenlySpaced;
using ::freeform::testing_util::RandomValues;

using ::testing::ElementsAre;
using ::testing::Optional;

// Partials in PartialIndex order, each count * dimension values.
using Partials = std::vector<std::vector<double>>;

Partials Buffers(size_t count, int dimension, int max_order) {
  return Partials(PartialCount(max_order),
                  std::vector<double>(count * static_cast<size_t>(dimension)));
}

std::vector<absl::Span<double>> Spans(Partials& buffers) {
  return std::vector<absl::Span<double>>(buffers.begin(), buffers.end());
}

template <typename Surface, typename Evaluator>
Partials Evaluate(Evaluator evaluate, const Surface& surface,
                  const SurfaceSamples& samples, int max_order,
                  const ExecutionContext& context = {}) {
  Partials buffers =
      Buffers(samples.size(), surface.control_net.dimension, max_order);
  const std::vector<absl::Span<double>> output = Spans(buffers);
  const absl::Status status = evaluate(surface, samples, output, context);
  EXPECT_TRUE(status.ok()) << status;
  return buffers;
}

Partials EvaluateBezier(const BezierSurfaceView& surface,
                        const SurfaceSamples& samples, int max_order,
                        const ExecutionContext& context = {}) {
  return Evaluate(EvaluateBezierSurface, surface, samples, max_order, context);
}

Partials EvaluateBSpline(const BSplineSurfaceView& surface,
                         const SurfaceSamples& samples, int max_order,
                         const ExecutionContext& context = {}) {
  return Evaluate(EvaluateBSplineSurface, surface, samples, max_order, context);
}

// Sorted random knots, unclamped: every value distinct, so any degree is
// valid.
std::vector<double> RandomKnots(std::mt19937_64& rng, int count, int degree) {
  std::vector<double> knots =
      RandomValues(rng, static_cast<size_t>(count + degree + 1), 0.0, 3.0);
  std::sort(knots.begin(), knots.end());
  return knots;
}

// The derivatives 0..orders-1 at t of the curve through `points` along one
// direction of the surface, from the curve units.
using CurveReference = std::function<std::vector<std::vector<double>>(
    int direction, const std::vector<double>& points, double t, int orders)>;

// Partials (k, l), k + l <= d, of the tensor surface computed as curves of
// curves (docs/references.md, 'Tensor-product surfaces'): curves along one
// direction for each row (column) of the net, then one curve through their
// derivatives.
std::vector<std::vector<double>> CurveOfCurves(
    bool rows_first, const std::vector<double>& net, int count_u, int count_v,
    int dim, double u, double v, int d, const CurveReference& curve) {
  const int inner = rows_first ? 1 : 0;  // direction of the first curves
  const int lines = rows_first ? count_u : count_v;
  const int along = rows_first ? count_v : count_u;
  std::vector<std::vector<double>> by_order(
      static_cast<size_t>(d + 1),
      std::vector<double>(static_cast<size_t>(lines * dim)));
  for (int line = 0; line < lines; ++line) {
    std::vector<double> points;
    for (int m = 0; m < along; ++m) {
      const int i = rows_first ? line : m;
      const int j = rows_first ? m : line;
      const double* p = net.data() + (i * count_v + j) * dim;
      points.insert(points.end(), p, p + dim);
    }
    const auto ders = curve(inner, points, rows_first ? v : u, d + 1);
    for (int order = 0; order <= d; ++order) {
      std::copy_n(ders[order].begin(), dim,
                  by_order[order].begin() + line * dim);
    }
  }
  std::vector<std::vector<double>> partials(PartialCount(d));
  for (int first = 0; first <= d; ++first) {
    const auto ders =
        curve(1 - inner, by_order[first], rows_first ? u : v, d + 1 - first);
    for (int second = 0; second <= d - first; ++second) {
      const int k = rows_first ? second : first;
      const int l = rows_first ? first : second;
      partials[PartialIndex(k, l)] = ders[second];
    }
  }
  return partials;
}

std::vector<std::vector<double>> CurveDerivatives(
    const std::function<absl::Status(absl::Span<const double>, CurveOutput)>&
        evaluate,
    int dim, double t, int orders) {
  std::vector<std::vector<double>> ders(static_cast<size_t>(orders),
                                        std::vector<double>(dim));
  std::vector<absl::Span<double>> output(ders.begin(), ders.end());
  const std::vector<double> parameters = {t};
  const absl::Status status = evaluate(parameters, output);
  EXPECT_TRUE(status.ok()) << status;
  return ders;
}

// Compares every partial at every sample against both curve-of-curves
// orders, relative to the partial's magnitude.
void ExpectMatchesCurvesOfCurves(const Partials& surface,
                                 const std::vector<double>& uv,
                                 const std::vector<double>& net, int count_u,
                                 int count_v, int dim, int d,
                                 const CurveReference& curve) {
  for (size_t r = 0; r < uv.size() / 2; ++r) {
    for (const bool rows_first : {true, false}) {
      const auto reference =
          CurveOfCurves(rows_first, net, count_u, count_v, dim, uv[2 * r],
                        uv[2 * r + 1], d, curve);
      for (size_t m = 0; m < reference.size(); ++m) {
        for (int x = 0; x < dim; ++x) {
          const double expected = reference[m][x];
          EXPECT_NEAR(surface[m][r * dim + x], expected,
                      1e-12 * (1.0 + std::abs(expected)))
              << "partial " << m << " point " << r << " rows_first "
              << rows_first;
        }
      }
    }
  }
}

TEST(TensorSurfaceTest, SeedBiquadraticExample) {
  // S(1/2, 1/2) = (2, 2, 1) (docs/references.md,
  // 'Worked example: the bi-quadratic patch at (1/2, 1/2)').
  const std::vector<double> net = {0, 0, 0, 2, 0, 0, 4, 0, 0,  //
                                   0, 2, 0, 2, 2, 0, 4, 2, 2,  //
                                   0, 4, 0, 2, 4, 4, 4, 4, 4};
  const BezierSurfaceView surface{.control_net = {.dimension = 3,
                                                  .count_u = 3,
                                                  .count_v = 3,
                                                  .coordinates = net},
                                  .weights = {}};
  const std::vector<double> uv = {0.5, 0.5};
  const Partials result = EvaluateBezier(surface, SurfaceSamples::Pairs(uv), 0);
  EXPECT_THAT(result[0], ElementsAre(2.0, 2.0, 1.0));
}

TEST(TensorSurfaceTest, BezierRowFirstAndColumnFirstAgree) {
  std::mt19937_64 rng(11);
  constexpr int kMaxOrder = 3;
  for (int pu = 1; pu <= 7; ++pu) {
    for (int pv = 1; pv <= 7; ++pv) {
      const int dim = 1 + (pu + pv) % 4;
      const int count_u = pu + 1;
      const int count_v = pv + 1;
      const std::vector<double> net =
          RandomValues(rng, static_cast<size_t>(count_u * count_v * dim));
      // Separable weights a_i b_j make the rational basis a product of the
      // curves' rational bases, so curves of curves are exact references.
      const bool rational = (pu + pv) % 2 == 1;
      const std::vector<double> a = rational
                                        ? RandomValues(rng, count_u, 0.5, 2.0)
                                        : std::vector<double>{};
      const std::vector<double> b = rational
                                        ? RandomValues(rng, count_v, 0.5, 2.0)
                                        : std::vector<double>{};
      std::vector<double> weights;
      for (const double wa : a) {
        for (const double wb : b) weights.push_back(wa * wb);
      }
      std::vector<double> uv = {0, 0, 1, 1, 0, 1};
      const std::vector<double> random = RandomValues(rng, 6, 0.0, 1.0);
      uv.insert(uv.end(), random.begin(), random.end());
      const BezierSurfaceView surface{.control_net = {.dimension = dim,
                                                      .count_u = count_u,
                                                      .count_v = count_v,
                                                      .coordinates = net},
                                      .weights = weights};
      const Partials result =
          EvaluateBezier(surface, SurfaceSamples::Pairs(uv), kMaxOrder);
      const CurveReference curve = [&](int direction,
                                       const std::vector<double>& points,
                                       double t, int orders) {
        const BezierCurveView view{
            .control_points = {.dimension = dim, .coordinates = points},
            .weights = direction == 0 ? a : b};
        return CurveDerivatives(
            [&](absl::Span<const double> params, CurveOutput output) {
              return EvaluateBezierCurve(view, params, output);
            },
            dim, t, orders);
      };
      SCOPED_TRACE(::testing::Message() << "degrees " << pu << ", " << pv);
      ExpectMatchesCurvesOfCurves(result, uv, net, count_u, count_v, dim,
                                  kMaxOrder, curve);
    }
  }
}

TEST(TensorSurfaceTest, BSplineRowFirstAndColumnFirstAgree) {
  std::mt19937_64 rng(12);
  constexpr int kMaxOrder = 3;
  for (int pu = 1; pu <= 7; ++pu) {
    for (int pv = 1; pv <= 7; ++pv) {
      const int dim = 1 + (pu * pv) % 4;
      const int count_u = pu + 1 + (pu + pv) % 3;
      const int count_v = pv + 1 + (pu * pv) % 3;
      const std::vector<double> net =
          RandomValues(rng, static_cast<size_t>(count_u * count_v * dim));
      const std::vector<double> knots_u = RandomKnots(rng, count_u, pu);
      const std::vector<double> knots_v = RandomKnots(rng, count_v, pv);
      const bool rational = (pu + pv) % 2 == 0;
      const std::vector<double> a = rational
                                        ? RandomValues(rng, count_u, 0.5, 2.0)
                                        : std::vector<double>{};
      const std::vector<double> b = rational
                                        ? RandomValues(rng, count_v, 0.5, 2.0)
                                        : std::vector<double>{};
      std::vector<double> weights;
      for (const double wa : a) {
        for (const double wb : b) weights.push_back(wa * wb);
      }
      const BSplineSurfaceView surface{.degree_u = pu,
                                       .degree_v = pv,
                                       .control_net = {.dimension = dim,
                                                       .count_u = count_u,
                                                       .count_v = count_v,
                                                       .coordinates = net},
                                       .knots_u = knots_u,
                                       .knots_v = knots_v,
                                       .weights = weights};
      const SurfaceDomain domain = BSplineSurfaceDomain(surface);
      std::vector<double> uv = {domain.u_start,  domain.v_end,
                                domain.u_end,    domain.v_start,
                                knots_u[pu + 1], knots_v[pv + 1]};
      for (int s = 0; s < 3; ++s) {
        uv.push_back(RandomValues(rng, 1, domain.u_start, domain.u_end)[0]);
        uv.push_back(RandomValues(rng, 1, domain.v_start, domain.v_end)[0]);
      }
      const Partials result =
          EvaluateBSpline(surface, SurfaceSamples::Pairs(uv), kMaxOrder);
      const CurveReference curve = [&](int direction,
                                       const std::vector<double>& points,
                                       double t, int orders) {
        const BSplineCurveView view{
            .degree = direction == 0 ? pu : pv,
            .control_points = {.dimension = dim, .coordinates = points},
            .knots = direction == 0 ? knots_u : knots_v,
            .weights = direction == 0 ? a : b};
        return CurveDerivatives(
            [&](absl::Span<const double> params, CurveOutput output) {
              return EvaluateBSplineCurve(view, params, output);
            },
            dim, t, orders);
      };
      SCOPED_TRACE(::testing::Message() << "degrees " << pu << ", " << pv);
      ExpectMatchesCurvesOfCurves(result, uv, net, count_u, count_v, dim,
                                  kMaxOrder, curve);
    }
  }
}

// A random NURBS surface with non-separable weights.
struct RandomNurbs {
  std::vector<double> net, knots_u, knots_v, weights;
  BSplineSurfaceView view;
};

RandomNurbs MakeRandomNurbs(std::mt19937_64& rng, int pu, int pv, int count_u,
                            int count_v, int dim, bool rational) {
  RandomNurbs s;
  s.net = RandomValues(rng, static_cast<size_t>(count_u * count_v * dim));
  s.knots_u = RandomKnots(rng, count_u, pu);
  s.knots_v = RandomKnots(rng, count_v, pv);
  if (rational) s.weights = RandomValues(rng, count_u * count_v, 0.5, 2.0);
  s.view = {.degree_u = pu,
            .degree_v = pv,
            .control_net = {.dimension = dim,
                            .count_u = count_u,
                            .count_v = count_v,
                            .coordinates = s.net},
            .knots_u = s.knots_u,
            .knots_v = s.knots_v,
            .weights = s.weights};
  return s;
}

TEST(TensorSurfaceTest, RationalPartialsMatchDifferencesOfLowerOrders) {
  std::mt19937_64 rng(13);
  const RandomNurbs nurbs = MakeRandomNurbs(rng, 3, 2, 6, 5, 3, true);
  const SurfaceDomain domain = BSplineSurfaceDomain(nurbs.view);
  const double h = 1e-6;
  for (int trial = 0; trial < 5; ++trial) {
    const double u =
        RandomValues(rng, 1, domain.u_start + h, domain.u_end - h)[0];
    const double v =
        RandomValues(rng, 1, domain.v_start + h, domain.v_end - h)[0];
    const std::vector<double> uv = {u, v, u + h, v, u - h,
                                    v, u, v + h, u, v - h};
    const Partials p =
        EvaluateBSpline(nurbs.view, SurfaceSamples::Pairs(uv), 3);
    for (int k = 0; k <= 2; ++k) {
      for (int l = 0; l <= 2 - k; ++l) {
        const auto& lower = p[PartialIndex(k, l)];
        const auto& du = p[PartialIndex(k + 1, l)];
        const auto& dv = p[PartialIndex(k, l + 1)];
        for (int x = 0; x < 3; ++x) {
          const double fd_u = (lower[3 + x] - lower[6 + x]) / (2 * h);
          const double fd_v = (lower[9 + x] - lower[12 + x]) / (2 * h);
          EXPECT_NEAR(du[x], fd_u, 1e-5 * (1 + std::abs(du[x])));
          EXPECT_NEAR(dv[x], fd_v, 1e-5 * (1 + std::abs(dv[x])));
        }
      }
    }
  }
}

// Compares partials relative to the largest magnitude among them: a zero
// partial of a rational surface is a cancellation of the lower ones.
void ExpectSame(const Partials& a, const Partials& b, double relative) {
  ASSERT_EQ(a.size(), b.size());
  double scale = 1.0;
  for (const std::vector<double>& partial : b) {
    for (const double value : partial) scale = std::max(scale, std::abs(value));
  }
  for (size_t m = 0; m < a.size(); ++m) {
    ASSERT_EQ(a[m].size(), b[m].size());
    for (size_t x = 0; x < a[m].size(); ++x) {
      EXPECT_NEAR(a[m][x], b[m][x], relative * scale)
          << "partial " << m << " value " << x;
    }
  }
}

// The pairs of a u-major grid.
std::vector<double> GridPairs(const std::vector<double>& u,
                              const std::vector<double>& v) {
  std::vector<double> uv;
  for (const double a : u) {
    for (const double b : v) uv.insert(uv.end(), {a, b});
  }
  return uv;
}

TEST(TensorSurfaceTest, GridEqualsPairsAndPoolEqualsSerial) {
  std::mt19937_64 rng(14);
  ThreadPool pool(2);
  for (const bool rational : {false, true}) {
    const RandomNurbs nurbs = MakeRandomNurbs(rng, 3, 2, 7, 6, 3, rational);
    const SurfaceDomain domain = BSplineSurfaceDomain(nurbs.view);
    const std::vector<double> u =
        EvenlySpaced(domain.u_start, domain.u_end, 23);
    const std::vector<double> v =
        EvenlySpaced(domain.v_start, domain.v_end, 17);
    const std::vector<double> uv = GridPairs(u, v);
    const SurfaceSamples grid = SurfaceSamples::Grid(u, v);
    const Partials by_grid = EvaluateBSpline(nurbs.view, grid, 2);
    ExpectSame(by_grid,
               EvaluateBSpline(nurbs.view, SurfaceSamples::Pairs(uv), 2),
               1e-14);
    const ExecutionContext parallel{.pool = &pool, .grain = 40};
    EXPECT_EQ(EvaluateBSpline(nurbs.view, grid, 2, parallel), by_grid);

    const BezierSurfaceView bezier{.control_net = nurbs.view.control_net,
                                   .weights = nurbs.weights};
    const std::vector<double> unit = EvenlySpaced(0, 1, 19);
    const SurfaceSamples bezier_grid = SurfaceSamples::Grid(unit, unit);
    const std::vector<double> bezier_uv = GridPairs(unit, unit);
    const Partials bezier_by_grid = EvaluateBezier(bezier, bezier_grid, 2);
    ExpectSame(bezier_by_grid,
               EvaluateBezier(bezier, SurfaceSamples::Pairs(bezier_uv), 2),
               1e-14);
    EXPECT_EQ(EvaluateBezier(bezier, bezier_grid, 2, parallel), bezier_by_grid);
  }
}

TEST(TensorSurfaceTest, ClampedSingleSpanBSplineEqualsBezier) {
  std::mt19937_64 rng(15);
  for (const bool rational : {false, true}) {
    const int pu = 4;
    const int pv = 2;
    const std::vector<double> net = RandomValues(rng, 5 * 3 * 2);
    const std::vector<double> weights =
        rational ? RandomValues(rng, 15, 0.5, 2.0) : std::vector<double>{};
    const std::vector<double> knots_u = {0, 0, 0, 0, 0, 1, 1, 1, 1, 1};
    const std::vector<double> knots_v = {0, 0, 0, 1, 1, 1};
    const ControlNetView control_net{
        .dimension = 2, .count_u = 5, .count_v = 3, .coordinates = net};
    const BSplineSurfaceView bspline{.degree_u = pu,
                                     .degree_v = pv,
                                     .control_net = control_net,
                                     .knots_u = knots_u,
                                     .knots_v = knots_v,
                                     .weights = weights};
    const BezierSurfaceView bezier{.control_net = control_net,
                                   .weights = weights};
    const std::vector<double> uv = RandomValues(rng, 40, 0.0, 1.0);
    ExpectSame(EvaluateBSpline(bspline, SurfaceSamples::Pairs(uv), 3),
               EvaluateBezier(bezier, SurfaceSamples::Pairs(uv), 3), 1e-13);
  }
}

TEST(TensorSurfaceTest, EqualWeightsGiveTheNonRationalSurface) {
  std::mt19937_64 rng(16);
  RandomNurbs nurbs = MakeRandomNurbs(rng, 2, 3, 5, 6, 4, false);
  const std::vector<double> weights(30, 2.5);
  BSplineSurfaceView rational = nurbs.view;
  rational.weights = weights;
  const SurfaceDomain domain = BSplineSurfaceDomain(nurbs.view);
  const std::vector<double> u = EvenlySpaced(domain.u_start, domain.u_end, 9);
  const std::vector<double> v = EvenlySpaced(domain.v_start, domain.v_end, 8);
  const SurfaceSamples grid = SurfaceSamples::Grid(u, v);
  ExpectSame(EvaluateBSpline(rational, grid, 3),
             EvaluateBSpline(nurbs.view, grid, 3), 1e-13);
}

// The rational quadratic quarter circle from (1, 0) to (0, 1).
constexpr double kHalfSqrt2 = 0.70710678118654752440;
const double kArcX[] = {1, 1, 0};
const double kArcY[] = {0, 1, 1};
const double kArcW[] = {1, kHalfSqrt2, 1};

TEST(TensorSurfaceTest, NurbsCylinderStaysOnTheCylinder) {
  // Quarter circle in u times the segment z = 0..2 in v.
  std::vector<double> net;
  std::vector<double> weights;
  for (int i = 0; i < 3; ++i) {
    for (const double z : {0.0, 2.0}) {
      net.insert(net.end(), {kArcX[i], kArcY[i], z});
      weights.push_back(kArcW[i]);
    }
  }
  const std::vector<double> knots_u = {0, 0, 0, 1, 1, 1};
  const std::vector<double> knots_v = {0, 0, 1, 1};
  const BSplineSurfaceView cylinder{.degree_u = 2,
                                    .degree_v = 1,
                                    .control_net = {.dimension = 3,
                                                    .count_u = 3,
                                                    .count_v = 2,
                                                    .coordinates = net},
                                    .knots_u = knots_u,
                                    .knots_v = knots_v,
                                    .weights = weights};
  const std::vector<double> grid = EvenlySpaced(0, 1, 100);
  const Partials p =
      EvaluateBSpline(cylinder, SurfaceSamples::Grid(grid, grid), 0);
  for (size_t r = 0; r < grid.size() * grid.size(); ++r) {
    const double* s = p[0].data() + 3 * r;
    EXPECT_NEAR(std::hypot(s[0], s[1]), 1.0, 1e-14);
    EXPECT_NEAR(s[2], 2.0 * grid[r % grid.size()], 1e-14);
  }
}

// The octant of the unit sphere (SpherePatch) as a NURBS surface on the
// knots 0,0,0,1,1,1 in u and v.
SurfaceData MakeSphereOctant() {
  SurfaceData sphere = testing_util::SpherePatch(1.0);
  sphere.knots_u = sphere.knots_v = {0, 0, 0, 1, 1, 1};
  return sphere;
}

TEST(TensorSurfaceTest, NurbsSphereStaysOnTheSphereWithRadialNormals) {
  const SurfaceData sphere = MakeSphereOctant();
  const std::vector<double> grid = EvenlySpaced(0, 1, 100);
  const SurfaceSamples samples = SurfaceSamples::Grid(grid, grid);
  Partials p = EvaluateBSpline(sphere.bspline_view(), samples, 2);
  std::vector<double> normals(3 * samples.size());
  ASSERT_TRUE(ComputeUnitNormals(Spans(p), samples,
                                 BSplineSurfaceDomain(sphere.bspline_view()),
                                 absl::MakeSpan(normals))
                  .ok());
  const double sign =
      normals[0] * p[0][0] + normals[1] * p[0][1] + normals[2] * p[0][2];
  EXPECT_NEAR(std::abs(sign), 1.0, 1e-13);
  for (size_t r = 0; r < samples.size(); ++r) {
    const double* s = p[0].data() + 3 * r;
    const double* n = normals.data() + 3 * r;
    EXPECT_NEAR(std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]), 1.0, 1e-14);
    for (int x = 0; x < 3; ++x) {
      EXPECT_NEAR(n[x], sign * s[x], 1e-13) << "point " << r;
    }
  }
}

// Checks unit length and orthogonality to S_u and S_v at every point.
void ExpectUnitAndOrthogonal(const Partials& p,
                             const std::vector<double>& normals) {
  for (size_t r = 0; r < normals.size() / 3; ++r) {
    const double* n = normals.data() + 3 * r;
    EXPECT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-14);
    for (const size_t m : {PartialIndex(1, 0), PartialIndex(0, 1)}) {
      const double* d = p[m].data() + 3 * r;
      const double scale = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      EXPECT_NEAR(n[0] * d[0] + n[1] * d[1] + n[2] * d[2], 0.0,
                  1e-14 * (1 + scale));
    }
  }
}

TEST(NormalsTest, UnitAndOrthogonalOnRandomPatches) {
  std::mt19937_64 rng(17);
  for (const bool rational : {false, true}) {
    const RandomNurbs nurbs = MakeRandomNurbs(rng, 3, 3, 6, 7, 3, rational);
    const SurfaceDomain domain = BSplineSurfaceDomain(nurbs.view);
    const std::vector<double> u =
        EvenlySpaced(domain.u_start, domain.u_end, 31);
    const std::vector<double> v =
        EvenlySpaced(domain.v_start, domain.v_end, 29);
    const SurfaceSamples grid = SurfaceSamples::Grid(u, v);
    Partials p = EvaluateBSpline(nurbs.view, grid, 1);
    std::vector<double> normals(3 * grid.size());
    ASSERT_TRUE(
        ComputeUnitNormals(Spans(p), grid.size(), absl::MakeSpan(normals))
            .ok());
    ExpectUnitAndOrthogonal(p, normals);
  }
}

// A random bicubic Bezier net whose row `row` collapses to one point, like
// the apex of the Utah teapot lid.
std::vector<double> CollapsedBicubic(std::mt19937_64& rng, int row) {
  std::vector<double> net = RandomValues(rng, 4 * 4 * 3);
  for (int j = 1; j < 4; ++j) {
    std::copy_n(net.begin() + row * 12, 3, net.begin() + row * 12 + j * 3);
  }
  return net;
}

// Normals at (u, v) for each v, using the samples-aware overload.
std::vector<double> NormalsAt(const BezierSurfaceView& surface, double u,
                              const std::vector<double>& v, int max_order) {
  const std::vector<double> us = {u};
  const SurfaceSamples samples = SurfaceSamples::Grid(us, v);
  Partials p = EvaluateBezier(surface, samples, max_order);
  std::vector<double> normals(3 * v.size());
  EXPECT_TRUE(ComputeUnitNormals(Spans(p), samples, BezierSurfaceDomain(),
                                 absl::MakeSpan(normals))
                  .ok());
  return normals;
}

TEST(NormalsTest, CollapsedRowGivesTheLimitNormal) {
  std::mt19937_64 rng(18);
  const std::vector<double> v = EvenlySpaced(0, 1, 11);
  for (const int row : {0, 3}) {
    const std::vector<double> net = CollapsedBicubic(rng, row);
    const BezierSurfaceView lid{.control_net = {.dimension = 3,
                                                .count_u = 4,
                                                .count_v = 4,
                                                .coordinates = net},
                                .weights = {}};
    const double edge = row == 0 ? 0.0 : 1.0;
    const double inside = row == 0 ? 1e-6 : 1 - 1e-6;
    const std::vector<double> at_edge = NormalsAt(lid, edge, v, 2);
    const std::vector<double> nearby = NormalsAt(lid, inside, v, 2);
    for (size_t x = 0; x < at_edge.size(); ++x) {
      EXPECT_NEAR(at_edge[x], nearby[x], 1e-4) << "row " << row << " " << x;
    }
    // The count-only overload approaches from above: right at u = 0.
    if (row == 0) {
      const std::vector<double> us = {0.0};
      const SurfaceSamples samples = SurfaceSamples::Grid(us, v);
      Partials p = EvaluateBezier(lid, samples, 2);
      std::vector<double> normals(3 * v.size());
      ASSERT_TRUE(
          ComputeUnitNormals(Spans(p), v.size(), absl::MakeSpan(normals)).ok());
      EXPECT_EQ(normals, at_edge);
    }
    // Without second partials the limit is unknown: the zero vector.
    EXPECT_THAT(NormalsAt(lid, edge, {0.5}, 1), ElementsAre(0.0, 0.0, 0.0));
  }
}

TEST(NormalsTest, RejectsBadBuffers) {
  Partials p = Buffers(2, 3, 1);
  std::vector<double> normals(6);
  EXPECT_TRUE(ComputeUnitNormals(Spans(p), 2, absl::MakeSpan(normals)).ok());
  std::vector<double> short_normals(5);
  EXPECT_EQ(
      ComputeUnitNormals(Spans(p), 2, absl::MakeSpan(short_normals)).code(),
      absl::StatusCode::kInvalidArgument);
  Partials planar = Buffers(2, 2, 1);
  EXPECT_EQ(
      ComputeUnitNormals(Spans(planar), 2, absl::MakeSpan(normals)).code(),
      absl::StatusCode::kInvalidArgument);
  Partials positions = Buffers(2, 3, 0);
  EXPECT_EQ(
      ComputeUnitNormals(Spans(positions), 2, absl::MakeSpan(normals)).code(),
      absl::StatusCode::kInvalidArgument);
}

// A valid rational bicubic B-spline surface (5 x 4 points in 3D) whose
// fields the validation tests break one at a time.
struct ValidSurface {
  std::vector<double> net = std::vector<double>(5 * 4 * 3, 0.5);
  std::vector<double> knots_u = {0, 0, 0, 0, 0.5, 1, 1, 1, 1};
  std::vector<double> knots_v = {0, 0, 0, 0, 1, 1, 1, 1};
  std::vector<double> weights = std::vector<double>(20, 1.0);
  int degree_u = 3;
  int count_u = 5;
  int count_v = 4;
  BSplineSurfaceView bspline() const {
    return {.degree_u = degree_u,
            .degree_v = 3,
            .control_net = {.dimension = 3,
                            .count_u = count_u,
                            .count_v = count_v,
                            .coordinates = net},
            .knots_u = knots_u,
            .knots_v = knots_v,
            .weights = weights};
  }
  BezierSurfaceView bezier() const {
    return {.control_net = bspline().control_net, .weights = weights};
  }
};

std::optional<std::string> BSplineError(const ValidSurface& s) {
  const absl::Status status = ValidateBSplineSurface(s.bspline());
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << status;
  return FieldPathOf(status);
}

std::optional<std::string> BezierError(const ValidSurface& s) {
  const absl::Status status = ValidateBezierSurface(s.bezier());
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << status;
  return FieldPathOf(status);
}

TEST(TensorSurfaceTest, ValidationNamesTheField) {
  const ValidSurface valid;
  ASSERT_TRUE(ValidateBSplineSurface(valid.bspline()).ok());
  ASSERT_TRUE(ValidateBezierSurface(valid.bezier()).ok());

  ValidSurface s = valid;
  s.net.pop_back();
  EXPECT_THAT(BSplineError(s),
              Optional(std::string("control_net.coordinates")));
  EXPECT_THAT(BezierError(s), Optional(std::string("control_net.coordinates")));
  s = valid;
  s.net[7] = std::nan("");
  EXPECT_THAT(BezierError(s),
              Optional(std::string("control_net.coordinates[7]")));
  s = valid;
  s.weights.pop_back();
  EXPECT_THAT(BSplineError(s), Optional(std::string("weights")));
  EXPECT_THAT(BezierError(s), Optional(std::string("weights")));
  s = valid;
  s.weights[6] = -1;
  EXPECT_THAT(BSplineError(s), Optional(std::string("weights[6]")));
  EXPECT_THAT(BezierError(s), Optional(std::string("weights[6]")));
  s = valid;
  s.weights[19] = 0;  // the corner (u, v) = (1, 1)
  EXPECT_THAT(BSplineError(s), Optional(std::string("weights[19]")));
  EXPECT_THAT(BezierError(s), Optional(std::string("weights[19]")));
  s = valid;
  s.weights[1] = 0;  // an edge weight leaves the surface finite
  EXPECT_TRUE(ValidateBSplineSurface(s.bspline()).ok());
  EXPECT_TRUE(ValidateBezierSurface(s.bezier()).ok());
  s = valid;
  s.knots_u[5] = 0.25;
  EXPECT_THAT(BSplineError(s), Optional(std::string("knots_u[5]")));
  s = valid;
  s.knots_v.pop_back();
  EXPECT_THAT(BSplineError(s), Optional(std::string("knots_v")));
  s = valid;
  s.degree_u = 5;
  s.knots_u = {0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1};
  EXPECT_THAT(BSplineError(s), Optional(std::string("control_net.count_u")));
  s = valid;
  s.degree_u = -1;
  EXPECT_THAT(BSplineError(s), Optional(std::string("degree_u")));
}

TEST(TensorSurfaceTest, EvaluationRejectsBadSamplesAndOutput) {
  const ValidSurface valid;
  Partials buffers = Buffers(1, 3, 1);
  const std::vector<absl::Span<double>> output = Spans(buffers);
  const std::vector<double> odd = {0.5, 0.5, 0.5};
  EXPECT_THAT(FieldPathOf(EvaluateBSplineSurface(
                  valid.bspline(), SurfaceSamples::Pairs(odd), output)),
              Optional(std::string("uv")));
  const std::vector<double> outside = {0.5, 1.5};
  EXPECT_THAT(FieldPathOf(EvaluateBezierSurface(
                  valid.bezier(), SurfaceSamples::Pairs(outside), output)),
              Optional(std::string("uv[1]")));
  const std::vector<double> bad_u = {0.0, -0.1};
  const std::vector<double> v = {0.5};
  EXPECT_THAT(FieldPathOf(EvaluateBSplineSurface(
                  valid.bspline(), SurfaceSamples::Grid(bad_u, v), output)),
              Optional(std::string("u[1]")));
  const std::vector<double> two = {0.1, 0.2, 0.3, 0.4};
  EXPECT_EQ(EvaluateBSplineSurface(valid.bspline(), SurfaceSamples::Pairs(two),
                                   output)
                .code(),
            absl::StatusCode::kInvalidArgument);
  const std::vector<absl::Span<double>> two_buffers(2,
                                                    absl::MakeSpan(buffers[0]));
  const std::vector<double> one = {0.1, 0.2};
  EXPECT_EQ(EvaluateBSplineSurface(valid.bspline(), SurfaceSamples::Pairs(one),
                                   two_buffers)
                .code(),
            absl::StatusCode::kInvalidArgument);
}

TEST(TensorSurfaceTest, CancelledTokenStopsABigGrid) {
  const ValidSurface valid;
  const std::vector<double> grid = EvenlySpaced(0, 1, 1000);
  const SurfaceSamples samples = SurfaceSamples::Grid(grid, grid);
  Partials buffers = Buffers(samples.size(), 3, 0);
  CancellationToken token;
  token.Cancel();
  ThreadPool pool(2);
  const ExecutionContext context{.pool = &pool, .cancellation = &token};
  EXPECT_EQ(
      EvaluateBSplineSurface(valid.bspline(), samples, Spans(buffers), context)
          .code(),
      absl::StatusCode::kCancelled);
}

TEST(TensorSurfaceTest, ProjectHomogeneousSurfaceDerivativesOfAConstant) {
  // (w P, w) with w = 1 + u + v^2 projects to the constant P.
  const int d = 2;
  std::vector<double> homogeneous(PartialCount(d) * 2, 0.0);
  const double point = 3.0;
  const double w00 = 2.0;
  const double wu = 1.0;
  const double wvv = 2.0;
  homogeneous[PartialIndex(0, 0) * 2] = point * w00;
  homogeneous[PartialIndex(0, 0) * 2 + 1] = w00;
  homogeneous[PartialIndex(1, 0) * 2] = point * wu;
  homogeneous[PartialIndex(1, 0) * 2 + 1] = wu;
  homogeneous[PartialIndex(0, 2) * 2] = point * wvv;
  homogeneous[PartialIndex(0, 2) * 2 + 1] = wvv;
  std::vector<double> partials(PartialCount(d));
  ProjectHomogeneousSurfaceDerivatives(homogeneous.data(), 1, d,
                                       partials.data());
  EXPECT_THAT(partials, ElementsAre(3.0, 0.0, 0.0, 0.0, 0.0, 0.0));
}

}  // namespace
}  // namespace freeform
