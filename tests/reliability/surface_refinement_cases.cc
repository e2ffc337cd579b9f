// SurfaceService.Split, InsertKnots, ElevateDegree and Interpolate: pieces,
// refined and elevated surfaces trace the original at sample points (with
// the reference sums), the worked split of docs/references.md, and
// interpolating surfaces pass through their grid at their parameters.
#include <algorithm>
#include <cmath>

#include "../core/test_util.h"
#include "absl/strings/str_cat.h"
#include "cases.h"

namespace freeform::reliability {
namespace {

constexpr int kSamples = 6;
constexpr double kSolved = 1e-8;

using SurfaceAt = std::function<Values(double u, double v)>;

// CheckSameSurface checks actual(u, v) == expected(map(u, v)) at the
// corners of [0, 1]^2 scaled into the actual domain and at random points.
void CheckSameSurface(
    Checker& check, Rng& rng, const SurfaceAt& actual, double u0, double u1,
    double v0, double v1, const SurfaceAt& expected,
    const std::function<std::pair<double, double>(double s, double t)>& map,
    absl::string_view what) {
  for (int k = 0; k < kSamples + 4; ++k) {
    const double s = k < 4 ? k % 2 : Uniform(rng, 0, 1);
    const double t = k < 4 ? k / 2 : Uniform(rng, 0, 1);
    const auto [eu, ev] = map(s, t);
    const double u = u0 + s * (u1 - u0), v = v0 + t * (v1 - v0);
    if (!check.NearPoint(actual(u, v), expected(eu, ev), kTight, what, u)) {
      return;
    }
  }
}

// The identity map of a domain onto itself.
std::function<std::pair<double, double>(double, double)> Same(
    const TensorShape& shape) {
  return [&shape](double s, double t) {
    return std::pair(shape.start_u() + s * (shape.end_u() - shape.start_u()),
                     shape.start_v() + t * (shape.end_v() - shape.start_v()));
  };
}

SurfaceAt AtOf(const TensorShape& shape) {
  return [&shape](double u, double v) { return shape.At(u, v); };
}

// docs/references.md, 'Worked example: the bi-quadratic patch at (1/2,
// 1/2)': split at u = 1/2, the first piece reaches (2, 2, 1) at (1, 1/2).
CallResult SplitWorkedPatch(Client& client) {
  TensorShape shape;
  shape.degree_u = shape.degree_v = 2;
  shape.count_u = shape.count_v = 3;
  shape.net = {0, 0, 0, 2, 0, 0, 4, 0, 0, 0, 2, 0, 2, 2,
               0, 4, 2, 2, 0, 4, 0, 2, 4, 4, 4, 4, 4};
  v1::SplitSurfaceRequest request;
  *request.mutable_surface() = shape.ToSurface();
  request.set_direction(v1::SURFACE_DIRECTION_U);
  request.set_parameter(0.5);
  auto answer = client.SplitSurface(request);
  Checker check(request, 4);
  if (answer.ok() && check.True(answer->pieces_size() == 2, "two pieces")) {
    const TensorShape first = TensorShape::From(answer->pieces(0).bezier());
    check.NearPoint(first.At(1, 0.5), Values{2, 2, 1}, kTight, "first piece",
                    1);
  }
  return check.Result(answer.status());
}

CallResult SplitTensor(Client& client, Rng& rng) {
  const TensorShape shape = RandomBezierPatch(
      rng, UniformInt(rng, 1, 4), UniformInt(rng, 1, 4), Coin(rng, 0.3));
  const bool in_u = Coin(rng);
  const double at = Uniform(rng, 0.05, 0.95);
  v1::SplitSurfaceRequest request;
  *request.mutable_surface() = shape.ToSurface();
  request.set_direction(in_u ? v1::SURFACE_DIRECTION_U
                             : v1::SURFACE_DIRECTION_V);
  request.set_parameter(at);
  auto answer = client.SplitSurface(request);
  Checker check(request, 2);
  if (answer.ok() && check.True(answer->pieces_size() == 2, "two pieces")) {
    for (int k = 0; k < 2; ++k) {
      const TensorShape piece = TensorShape::From(answer->pieces(k).bezier());
      const double a = k == 0 ? 0 : at, b = k == 0 ? at : 1;
      CheckSameSurface(
          check, rng, AtOf(piece), 0, 1, 0, 1, AtOf(shape),
          [&](double s, double t) {
            return in_u ? std::pair(a + s * (b - a), t)
                        : std::pair(s, a + t * (b - a));
          },
          absl::StrCat("piece ", k));
    }
  }
  return check.Result(answer.status());
}

// A triangular patch split at the barycentric point p into three pieces:
// piece k is the original over the domain triangle with vertex k replaced
// by p, its own barycentric coordinates mapped linearly.
CallResult SplitTriangle(Client& client, Rng& rng) {
  const TriangleShape shape =
      RandomTriangle(rng, UniformInt(rng, 1, 5), Coin(rng, 0.3));
  double a = Uniform(rng, 0.05, 0.9), b = Uniform(rng, 0.05, 0.9);
  if (a + b > 0.95) a = 0.95 - b * 0.9, b *= 0.9;
  v1::SplitSurfaceRequest request;
  *request.mutable_surface() = shape.ToSurface();
  request.set_u(a);
  request.set_v(b);
  auto answer = client.SplitSurface(request);
  Checker check(request, 2);
  if (answer.ok() && check.True(answer->pieces_size() == 3, "three pieces")) {
    const double p[3] = {a, b, 1 - a - b};
    for (int k = 0; k < 3; ++k) {
      const TriangleShape piece =
          TriangleShape::From(answer->pieces(k).triangular_bezier());
      for (int sample = 0; sample < kSamples; ++sample) {
        double x = Uniform(rng, 0, 1), y = Uniform(rng, 0, 1);
        if (x + y > 1) x = 1 - x, y = 1 - y;
        const double own[3] = {x, y, 1 - x - y};
        // Vertex i of the piece is the unit vector e_i, or p for i == k.
        double original[3] = {0, 0, 0};
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) {
            original[j] += own[i] * (i == k ? p[j] : (i == j ? 1.0 : 0.0));
          }
        }
        if (!check.NearPoint(piece.At(x, y), shape.At(original[0], original[1]),
                             kTight, absl::StrCat("piece ", k), x)) {
          break;
        }
      }
    }
  }
  return check.Result(answer.status());
}

CallResult Split(Client& client, Rng& rng) {
  switch (UniformInt(rng, 0, 4)) {
    case 0:
      return SplitWorkedPatch(client);
    case 1:
    case 2:
      return SplitTriangle(client, rng);
    default:
      return SplitTensor(client, rng);
  }
}

TensorShape RandomBSplineSurface(Rng& rng, bool rational) {
  const int p = UniformInt(rng, 1, 3), q = UniformInt(rng, 1, 3);
  return RandomBSplinePatch(
      rng, p, q, static_cast<uint32_t>(UniformInt(rng, p + 1, 7)),
      static_cast<uint32_t>(UniformInt(rng, q + 1, 7)), rational);
}

CallResult InsertKnots(Client& client, Rng& rng) {
  const TensorShape shape = RandomBSplineSurface(rng, Coin(rng, 0.3));
  const bool in_u = Coin(rng);
  const Values knots =
      RandomValues(rng, static_cast<size_t>(UniformInt(rng, 1, 3)),
                   in_u ? shape.start_u() : shape.start_v(),
                   in_u ? shape.end_u() : shape.end_v(), /*sorted=*/true);
  v1::InsertSurfaceKnotsRequest request;
  *request.mutable_surface() = shape.ToSurface();
  request.set_direction(in_u ? v1::SURFACE_DIRECTION_U
                             : v1::SURFACE_DIRECTION_V);
  request.mutable_knots()->Add(knots.begin(), knots.end());
  auto answer = client.InsertSurfaceKnots(request);
  Checker check(request, 2);
  if (answer.ok()) {
    const TensorShape refined = TensorShape::From(answer->surface().bspline());
    Values merged = in_u ? shape.knots_u : shape.knots_v;
    merged.insert(merged.end(), knots.begin(), knots.end());
    std::sort(merged.begin(), merged.end());
    check.NearPoint(in_u ? refined.knots_u : refined.knots_v, merged, kTight,
                    "refined knot vector", knots[0]);
    check.NearPoint(in_u ? refined.knots_v : refined.knots_u,
                    in_u ? shape.knots_v : shape.knots_u, 0,
                    "the other knot vector", 0);
    CheckSameSurface(check, rng, AtOf(refined), shape.start_u(), shape.end_u(),
                     shape.start_v(), shape.end_v(), AtOf(shape), Same(shape),
                     "refined surface");
  }
  return check.Result(answer.status());
}

CallResult ElevateDegree(Client& client, Rng& rng) {
  v1::ElevateSurfaceDegreeRequest request;
  Checker check(request, 2);
  if (Coin(rng, 0.3)) {
    const TriangleShape shape =
        RandomTriangle(rng, UniformInt(rng, 1, 4), Coin(rng, 0.3));
    const int by = UniformInt(rng, 1, 2);
    *request.mutable_surface() = shape.ToSurface();
    request.set_by(static_cast<uint32_t>(by));
    auto answer = client.ElevateSurfaceDegree(request);
    if (answer.ok()) {
      const TriangleShape elevated =
          TriangleShape::From(answer->surface().triangular_bezier());
      check.True(elevated.degree == shape.degree + by, "degree + by");
      for (int sample = 0; sample < kSamples; ++sample) {
        double u = Uniform(rng, 0, 1), v = Uniform(rng, 0, 1);
        if (u + v > 1) u = 1 - u, v = 1 - v;
        check.NearPoint(elevated.At(u, v), shape.At(u, v), kTight,
                        "elevated patch", u);
      }
    }
    return check.Result(answer.status());
  }
  const bool rational = Coin(rng, 0.3);
  TensorShape shape = Coin(rng)
                          ? RandomBezierPatch(rng, UniformInt(rng, 1, 4),
                                              UniformInt(rng, 1, 4), rational)
                          : RandomBSplineSurface(rng, rational);
  if (!shape.bezier()) {  // elevation of B-splines: clamped knots
    shape.knots_u = testing_util::RandomKnots(
        rng, shape.degree_u, static_cast<int>(shape.count_u) - 1, true);
    shape.knots_v = testing_util::RandomKnots(
        rng, shape.degree_v, static_cast<int>(shape.count_v) - 1, true);
  }
  const int by_u = UniformInt(rng, 0, 2);
  const int by_v = by_u == 0 ? UniformInt(rng, 1, 2) : UniformInt(rng, 0, 2);
  *request.mutable_surface() = shape.ToSurface();
  request.set_by_u(static_cast<uint32_t>(by_u));
  request.set_by_v(static_cast<uint32_t>(by_v));
  auto answer = client.ElevateSurfaceDegree(request);
  if (answer.ok()) {
    const TensorShape elevated =
        shape.bezier() ? TensorShape::From(answer->surface().bezier())
                       : TensorShape::From(answer->surface().bspline());
    check.True(elevated.degree_u == shape.degree_u + by_u &&
                   elevated.degree_v == shape.degree_v + by_v,
               "degrees + by");
    CheckSameSurface(check, rng, AtOf(elevated), shape.start_u(), shape.end_u(),
                     shape.start_v(), shape.end_v(), AtOf(shape), Same(shape),
                     "elevated surface");
  }
  return check.Result(answer.status());
}

CallResult Interpolate(Client& client, Rng& rng) {
  const auto count_u = static_cast<uint32_t>(UniformInt(rng, 4, 12));
  const auto count_v = static_cast<uint32_t>(UniformInt(rng, 4, 12));
  const Values grid = BumpyNet(rng, count_u, count_v);
  v1::InterpolateSurfaceRequest request;
  v1::ControlNet* points = request.mutable_points();
  points->set_dimension(3);
  points->set_count_u(count_u);
  points->set_count_v(count_v);
  points->mutable_coordinates()->Add(grid.begin(), grid.end());
  request.set_degree_u(static_cast<uint32_t>(UniformInt(rng, 1, 3)));
  request.set_degree_v(static_cast<uint32_t>(UniformInt(rng, 1, 3)));
  const auto parameterization =
      static_cast<v1::Parameterization>(UniformInt(rng, 0, 4));
  request.set_parameterization(parameterization);
  if (parameterization == v1::PARAMETERIZATION_UNIFORM && Coin(rng)) {
    request.set_knot_rule(v1::KNOT_RULE_UNIFORM);
  }
  auto answer = client.InterpolateSurface(request);
  Checker check(request, 2);
  if (answer.ok()) {
    const TensorShape surface = TensorShape::From(answer->surface().bspline());
    const Values pu(answer->parameters_u().begin(),
                    answer->parameters_u().end());
    const Values pv(answer->parameters_v().begin(),
                    answer->parameters_v().end());
    if (check.True(pu.size() == count_u && pv.size() == count_v,
                   "one parameter per row and per column")) {
      if (parameterization == v1::PARAMETERIZATION_UNIFORM) {
        check.NearPoint(pu, Linspace(0, 1, count_u), kTight, "parameters_u", 0);
        check.NearPoint(pv, Linspace(0, 1, count_v), kTight, "parameters_v", 0);
      }
      for (uint32_t k = 0; k < count_u; ++k) {
        for (uint32_t l = 0; l < count_v; ++l) {
          if (!check.NearPoint(
                  surface.At(pu[k], pv[l]),
                  Coordinates(grid).subspan(3 * (k * count_v + l), 3), kSolved,
                  "through the grid point", pu[k])) {
            return check.Result(answer.status());
          }
        }
      }
    }
  }
  return check.Result(answer.status());
}

}  // namespace

std::vector<RpcCase> SurfaceRefinementCases() {
  return {{"SurfaceService.Split", false, Split},
          {"SurfaceService.InsertKnots", false, InsertKnots},
          {"SurfaceService.ElevateDegree", false, ElevateDegree},
          {"SurfaceService.Interpolate", false, Interpolate}};
}

}  // namespace freeform::reliability
