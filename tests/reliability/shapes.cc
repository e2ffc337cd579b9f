// Random geometry and its proto round trip (shapes.h).
#include "shapes.h"

#include <algorithm>
#include <cmath>

#include "../core/test_util.h"
#include "check.h"

namespace freeform::reliability {
namespace {

Values Copy(const google::protobuf::RepeatedField<double>& field) {
  return Values(field.begin(), field.end());
}

void SetNet(const TensorShape& shape, v1::ControlNet* net) {
  net->set_dimension(static_cast<uint32_t>(shape.dimension));
  net->set_count_u(shape.count_u);
  net->set_count_v(shape.count_v);
  net->mutable_coordinates()->Add(shape.net.begin(), shape.net.end());
}

TensorShape FromNet(const v1::ControlNet& net,
                    const google::protobuf::RepeatedField<double>& weights) {
  TensorShape shape;
  shape.dimension = static_cast<int>(net.dimension());
  shape.count_u = net.count_u();
  shape.count_v = net.count_v();
  shape.net = Copy(net.coordinates());
  shape.weights = Copy(weights);
  shape.degree_u = static_cast<int>(shape.count_u) - 1;
  shape.degree_v = static_cast<int>(shape.count_v) - 1;
  return shape;
}

}  // namespace

double Uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

int UniformInt(Rng& rng, int lo, int hi) {
  return std::uniform_int_distribution<int>(lo, hi)(rng);
}

bool Coin(Rng& rng, double probability) {
  return std::bernoulli_distribution(probability)(rng);
}

Values RandomValues(Rng& rng, size_t count, double lo, double hi, bool sorted) {
  Values values = testing_util::RandomValues(rng, count, lo, hi);
  if (sorted) std::sort(values.begin(), values.end());
  return values;
}

Values SpreadValues(Rng& rng, size_t count, double lo, double hi, double gap) {
  // count points in (lo, hi) with gaps of at least `gap`: draw in the
  // interval shortened by the gaps, sort, then add k gaps to the k-th.
  const double room = hi - lo - static_cast<double>(count + 1) * gap;
  Values values = RandomValues(rng, count, 0, room, /*sorted=*/true);
  for (size_t k = 0; k < count; ++k) {
    values[k] += lo + static_cast<double>(k + 1) * gap;
  }
  return values;
}

Values RandomWeights(Rng& rng, size_t count, bool rational) {
  return rational ? RandomValues(rng, count, 0.5, 2.0) : Values();
}

std::vector<Values> BezierShape::At(double t, int orders) const {
  return BezierCurveAt(dimension, points, weights, t, orders);
}

v1::Curve BezierShape::ToCurve() const {
  v1::Curve curve;
  SetPoints(dimension, points,
            curve.mutable_bezier()->mutable_control_points());
  curve.mutable_bezier()->mutable_weights()->Add(weights.begin(),
                                                 weights.end());
  return curve;
}

BezierShape BezierShape::From(const v1::BezierCurve& curve) {
  return {.dimension = static_cast<int>(curve.control_points().dimension()),
          .points = Flat(curve.control_points()),
          .weights = Copy(curve.weights())};
}

std::vector<Values> BSplineShape::At(double u, int orders) const {
  return BSplineCurveAt(degree, knots, dimension, points, weights, u, orders);
}

v1::Curve BSplineShape::ToCurve() const {
  v1::Curve curve;
  v1::BSplineCurve* bspline = curve.mutable_bspline();
  bspline->set_degree(static_cast<uint32_t>(degree));
  SetPoints(dimension, points, bspline->mutable_control_points());
  bspline->mutable_knots()->Add(knots.begin(), knots.end());
  bspline->mutable_weights()->Add(weights.begin(), weights.end());
  return curve;
}

BSplineShape BSplineShape::From(const v1::BSplineCurve& curve) {
  return {.degree = static_cast<int>(curve.degree()),
          .knots = Copy(curve.knots()),
          .dimension = static_cast<int>(curve.control_points().dimension()),
          .points = Flat(curve.control_points()),
          .weights = Copy(curve.weights())};
}

BezierShape RandomBezier(Rng& rng, int degree, int dimension, bool rational) {
  const auto count = static_cast<size_t>(degree + 1);
  return {.dimension = dimension,
          .points = RandomValues(rng, count * dimension, -2, 2),
          .weights = RandomWeights(rng, count, rational)};
}

BSplineShape RandomBSpline(Rng& rng, int degree, int count, int dimension,
                           bool clamped, bool rational) {
  const auto n = static_cast<size_t>(count);
  return {.degree = degree,
          .knots = testing_util::RandomKnots(rng, degree, count - 1, clamped),
          .dimension = dimension,
          .points = RandomValues(rng, n * dimension, -2, 2),
          .weights = RandomWeights(rng, n, rational)};
}

double TensorShape::start_u() const {
  return bezier() ? 0.0 : knots_u[static_cast<size_t>(degree_u)];
}
double TensorShape::end_u() const { return bezier() ? 1.0 : knots_u[count_u]; }
double TensorShape::start_v() const {
  return bezier() ? 0.0 : knots_v[static_cast<size_t>(degree_v)];
}
double TensorShape::end_v() const { return bezier() ? 1.0 : knots_v[count_v]; }

Values TensorShape::At(double u, double v, int order_u, int order_v) const {
  const BasisDerivatives f = bezier()
                                 ? BernsteinBasis(degree_u, u, order_u)
                                 : BSplineBasis(degree_u, knots_u, u, order_u);
  const BasisDerivatives g = bezier()
                                 ? BernsteinBasis(degree_v, v, order_v)
                                 : BSplineBasis(degree_v, knots_v, v, order_v);
  return TensorAt(f, g, dimension, net, weights, order_u, order_v);
}

v1::Surface TensorShape::ToSurface() const {
  v1::Surface surface;
  if (bezier()) {
    SetNet(*this, surface.mutable_bezier()->mutable_control_net());
    surface.mutable_bezier()->mutable_weights()->Add(weights.begin(),
                                                     weights.end());
    return surface;
  }
  v1::BSplineSurface* bspline = surface.mutable_bspline();
  bspline->set_degree_u(static_cast<uint32_t>(degree_u));
  bspline->set_degree_v(static_cast<uint32_t>(degree_v));
  SetNet(*this, bspline->mutable_control_net());
  bspline->mutable_knots_u()->Add(knots_u.begin(), knots_u.end());
  bspline->mutable_knots_v()->Add(knots_v.begin(), knots_v.end());
  bspline->mutable_weights()->Add(weights.begin(), weights.end());
  return surface;
}

TensorShape TensorShape::From(const v1::BezierSurface& surface) {
  return FromNet(surface.control_net(), surface.weights());
}

TensorShape TensorShape::From(const v1::BSplineSurface& surface) {
  TensorShape shape = FromNet(surface.control_net(), surface.weights());
  shape.degree_u = static_cast<int>(surface.degree_u());
  shape.degree_v = static_cast<int>(surface.degree_v());
  shape.knots_u = Copy(surface.knots_u());
  shape.knots_v = Copy(surface.knots_v());
  return shape;
}

Values BumpyNet(Rng& rng, uint32_t count_u, uint32_t count_v) {
  Values net;
  const double a = Uniform(rng, -0.5, 0.5);
  const double b = Uniform(rng, 1, 3);
  for (uint32_t i = 0; i < count_u; ++i) {
    for (uint32_t j = 0; j < count_v; ++j) {
      const double u = static_cast<double>(i) / (count_u - 1);
      const double v = static_cast<double>(j) / (count_v - 1);
      net.push_back(u + Uniform(rng, -0.05, 0.05) / count_u);
      net.push_back(v + Uniform(rng, -0.05, 0.05) / count_v);
      net.push_back(a * std::sin(b * u) * std::cos(b * v) +
                    Uniform(rng, -0.1, 0.1));
    }
  }
  return net;
}

TensorShape RandomBezierPatch(Rng& rng, int degree_u, int degree_v,
                              bool rational) {
  TensorShape shape;
  shape.degree_u = degree_u;
  shape.degree_v = degree_v;
  shape.count_u = static_cast<uint32_t>(degree_u + 1);
  shape.count_v = static_cast<uint32_t>(degree_v + 1);
  shape.net = BumpyNet(rng, shape.count_u, shape.count_v);
  shape.weights = RandomWeights(rng, shape.count_u * shape.count_v, rational);
  return shape;
}

TensorShape RandomBSplinePatch(Rng& rng, int degree_u, int degree_v,
                               uint32_t count_u, uint32_t count_v,
                               bool rational) {
  TensorShape shape;
  shape.degree_u = degree_u;
  shape.degree_v = degree_v;
  shape.knots_u = testing_util::RandomKnots(
      rng, degree_u, static_cast<int>(count_u) - 1, Coin(rng));
  shape.knots_v = testing_util::RandomKnots(
      rng, degree_v, static_cast<int>(count_v) - 1, Coin(rng));
  shape.count_u = count_u;
  shape.count_v = count_v;
  shape.net = BumpyNet(rng, count_u, count_v);
  shape.weights = RandomWeights(rng, count_u * count_v, rational);
  return shape;
}

Values CubicPatchShape::At(double u, double v, int order_u, int order_v) const {
  const auto basis = [this](double t, int orders) {
    if (!hermite) return LagrangeBasis({0, 1.0 / 3, 2.0 / 3, 1}, t, orders);
    BasisDerivatives b(static_cast<size_t>(orders) + 1, Values(4));
    for (int k = 0; k <= orders; ++k) {
      for (int i = 0; i < 4; ++i) b[k][i] = Hermite(i, t, k);
    }
    return b;
  };
  return TensorAt(basis(u, order_u), basis(v, order_v), 3, net, {}, order_u,
                  order_v);
}

v1::Surface CubicPatchShape::ToSurface() const {
  v1::Surface surface;
  const auto fill = [](v1::ControlNet* target, uint32_t count) {
    target->set_dimension(3);
    target->set_count_u(count);
    target->set_count_v(count);
    return target->mutable_coordinates();
  };
  if (!hermite) {
    auto* points =
        fill(surface.mutable_bicubic_interpolating()->mutable_points(), 4);
    points->Add(net.begin(), net.end());
    return surface;
  }
  v1::BicubicHermitePatch* patch = surface.mutable_bicubic_hermite();
  // Block (row offset, column offset) of G for each field.
  const std::pair<v1::ControlNet*, std::pair<int, int>> blocks[] = {
      {patch->mutable_positions(), {0, 0}},
      {patch->mutable_derivatives_u(), {2, 0}},
      {patch->mutable_derivatives_v(), {0, 2}},
      {patch->mutable_twists(), {2, 2}}};
  for (const auto& [target, offset] : blocks) {
    auto* coordinates = fill(target, 2);
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        const size_t r =
            static_cast<size_t>((offset.first + i) * 4 + offset.second + j);
        coordinates->Add(net.begin() + 3 * r, net.begin() + 3 * r + 3);
      }
    }
  }
  return surface;
}

CubicPatchShape RandomCubicPatch(Rng& rng, bool hermite) {
  CubicPatchShape shape{.hermite = hermite};
  if (!hermite) {
    shape.net = BumpyNet(rng, 4, 4);
    return shape;
  }
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      Values point = RandomValues(rng, 3, -0.1, 0.1);
      if (a < 2 && b < 2) {  // positions on the unit square
        point[0] += a;
        point[1] += b;
      } else if (a >= 2 && b < 2) {  // u-derivatives about (1, 0, 0)
        point[0] += 1;
      } else if (a < 2) {  // v-derivatives about (0, 1, 0)
        point[1] += 1;
      }
      shape.net.insert(shape.net.end(), point.begin(), point.end());
    }
  }
  return shape;
}

Values TriangleShape::At(double u, double v) const {
  return TriangularAt(degree, dimension, points, weights, u, v);
}

v1::Surface TriangleShape::ToSurface() const {
  v1::Surface surface;
  v1::TriangularBezierPatch* patch = surface.mutable_triangular_bezier();
  patch->set_degree(static_cast<uint32_t>(degree));
  SetPoints(dimension, points, patch->mutable_control_points());
  patch->mutable_weights()->Add(weights.begin(), weights.end());
  return surface;
}

TriangleShape TriangleShape::From(const v1::TriangularBezierPatch& patch) {
  return {.degree = static_cast<int>(patch.degree()),
          .dimension = static_cast<int>(patch.control_points().dimension()),
          .points = Flat(patch.control_points()),
          .weights = Copy(patch.weights())};
}

TriangleShape RandomTriangle(Rng& rng, int degree, bool rational) {
  const auto count = static_cast<size_t>((degree + 1) * (degree + 2) / 2);
  return {.degree = degree,
          .dimension = 3,
          .points = RandomValues(rng, count * 3, -2, 2),
          .weights = RandomWeights(rng, count, rational)};
}

}  // namespace freeform::reliability
