// The geometry the reliability requests are built from: random Bezier and
// B-spline curves and tensor-product and triangular surfaces, converted to
// and from their proto messages, and evaluated by the reference
// mathematics (reference.h).
#ifndef FREEFORM_TESTS_RELIABILITY_SHAPES_H_
#define FREEFORM_TESTS_RELIABILITY_SHAPES_H_

#include <cstdint>
#include <random>
#include <vector>

#include "freeform/v1/geometry.pb.h"
#include "reference.h"

namespace freeform::reliability {

using Rng = std::mt19937_64;

double Uniform(Rng& rng, double lo, double hi);
int UniformInt(Rng& rng, int lo, int hi);  // lo..hi inclusive
bool Coin(Rng& rng, double probability = 0.5);
// `count` values drawn uniformly from [lo, hi), sorted when `sorted`.
Values RandomValues(Rng& rng, size_t count, double lo, double hi,
                    bool sorted = false);
// `count` strictly increasing values in (lo, hi), at least `gap` apart.
Values SpreadValues(Rng& rng, size_t count, double lo, double hi, double gap);
// Positive weights in [0.5, 2), or none.
Values RandomWeights(Rng& rng, size_t count, bool rational);

// A (rational) Bezier curve on [0, 1].
struct BezierShape {
  int dimension = 3;
  Values points;
  Values weights;

  int degree() const { return static_cast<int>(points.size()) / dimension - 1; }
  std::vector<Values> At(double t, int orders = 0) const;
  v1::Curve ToCurve() const;
  static BezierShape From(const v1::BezierCurve& curve);
};

// A B-spline (NURBS) curve on its domain [u_p, u_{n+1}].
struct BSplineShape {
  int degree = 3;
  Values knots;
  int dimension = 3;
  Values points;
  Values weights;

  double start() const { return knots[static_cast<size_t>(degree)]; }
  double end() const { return knots[knots.size() - degree - 1]; }
  std::vector<Values> At(double u, int orders = 0) const;
  v1::Curve ToCurve() const;
  static BSplineShape From(const v1::BSplineCurve& curve);
};

BezierShape RandomBezier(Rng& rng, int degree, int dimension, bool rational);
// `count` control points; clamped or not (docs: the domain is
// [u_p, u_{n+1}] either way); interior knots repeated up to p times.
BSplineShape RandomBSpline(Rng& rng, int degree, int count, int dimension,
                           bool clamped, bool rational);

// A tensor-product Bezier (no knots) or B-spline surface.
struct TensorShape {
  int degree_u = 3;
  int degree_v = 3;
  Values knots_u;  // empty: Bezier
  Values knots_v;
  int dimension = 3;
  uint32_t count_u = 4;
  uint32_t count_v = 4;
  Values net;
  Values weights;

  bool bezier() const { return knots_u.empty(); }
  // The domain: [0, 1]^2 for Bezier, [u_p, u_{n+1}] x [v_q, v_{m+1}].
  double start_u() const;
  double end_u() const;
  double start_v() const;
  double end_v() const;
  // Partial (order_u, order_v) at (u, v) (rational: positions only).
  Values At(double u, double v, int order_u = 0, int order_v = 0) const;
  v1::Surface ToSurface() const;
  static TensorShape From(const v1::BezierSurface& surface);
  static TensorShape From(const v1::BSplineSurface& surface);
};

// A bumpy random net over [0, 1]^2 in 3D: (u, v) of the grid plus small
// random offsets and a random height, so patches have no folds.
Values BumpyNet(Rng& rng, uint32_t count_u, uint32_t count_v);
TensorShape RandomBezierPatch(Rng& rng, int degree_u, int degree_v,
                              bool rational);
TensorShape RandomBSplinePatch(Rng& rng, int degree_u, int degree_v,
                               uint32_t count_u, uint32_t count_v,
                               bool rational);

// A bicubic interpolating patch (through a 4 x 4 grid at 0, 1/3, 2/3, 1:
// the tensor product of the cubic Lagrange basis on those nodes) or a
// bicubic Hermite (Ferguson) patch (the tensor product of H0..H3 over the
// geometry matrix G: G[a][b] is the position at corner (u, v) = (a, b) for
// a, b < 2, the u-derivative there for a >= 2 (corner (a - 2, b)), the
// v-derivative for b >= 2 and the twist for both), on [0, 1]^2.
struct CubicPatchShape {
  bool hermite = false;
  // 16 points in 3D, point a * 4 + b.
  Values net;

  Values At(double u, double v, int order_u = 0, int order_v = 0) const;
  v1::Surface ToSurface() const;
};

// A random bumpy patch of either kind over about [0, 1]^2.
CubicPatchShape RandomCubicPatch(Rng& rng, bool hermite);

// A (rational) triangular Bezier patch, barycentric parameters.
struct TriangleShape {
  int degree = 2;
  int dimension = 3;
  Values points;
  Values weights;

  Values At(double u, double v) const;
  v1::Surface ToSurface() const;
  static TriangleShape From(const v1::TriangularBezierPatch& patch);
};

TriangleShape RandomTriangle(Rng& rng, int degree, bool rational);

}  // namespace freeform::reliability

#endif  // FREEFORM_TESTS_RELIABILITY_SHAPES_H_
