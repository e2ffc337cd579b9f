// CurveService.Split, InsertKnots, Decompose, Subdivide and Tessellate:
// every piece, refined curve and segment traces the original (checked at
// sample parameters with the reference sums), the worked examples of
// docs/references.md, subdivision masks, and polylines within their
// tolerance.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "cases.h"

namespace freeform::reliability {
namespace {

constexpr int kSamples = 5;

// docs/references.md, 'Worked example: the cubic Bezier curve (0,0), (1,2),
// (3,2), (4,0)': the split at 1/2.
CallResult SplitWorkedCubic(Client& client) {
  v1::SplitCurveRequest request;
  *request.mutable_curve() =
      BezierShape{.dimension = 2, .points = {0, 0, 1, 2, 3, 2, 4, 0}}.ToCurve();
  request.add_parameters(0.5);
  auto answer = client.SplitCurve(request);
  Checker check(request);
  if (answer.ok() && check.True(answer->pieces_size() == 2, "two pieces")) {
    const Values left = {0, 0, 0.5, 1, 1.25, 1.5, 2, 1.5};
    const Values right = {2, 1.5, 2.75, 1.5, 3.5, 1, 4, 0};
    check.NearPoint(Flat(answer->pieces(0).bezier().control_points()), left,
                    kTight, "left piece", 0.5);
    check.NearPoint(Flat(answer->pieces(1).bezier().control_points()), right,
                    kTight, "right piece", 0.5);
  }
  return check.Result(answer.status());
}

CallResult Split(Client& client, Rng& rng) {
  if (Coin(rng, 0.2)) return SplitWorkedCubic(client);
  const BezierShape curve = RandomBezier(rng, UniformInt(rng, 1, 8),
                                         UniformInt(rng, 1, 4), Coin(rng, 0.3));
  v1::SplitCurveRequest request;
  *request.mutable_curve() = curve.ToCurve();
  const Values at =
      SpreadValues(rng, static_cast<size_t>(UniformInt(rng, 1, 5)), 0, 1, 0.02);
  request.mutable_parameters()->Add(at.begin(), at.end());
  auto answer = client.SplitCurve(request);
  Checker check(request, Scale(curve.points));
  if (answer.ok() &&
      check.True(answer->pieces_size() == static_cast<int>(at.size()) + 1,
                 "one piece more than parameters")) {
    for (int k = 0; k < answer->pieces_size(); ++k) {
      const BezierShape piece = BezierShape::From(answer->pieces(k).bezier());
      check.True(piece.degree() == curve.degree(), "same degree");
      check.True(piece.weights.size() == curve.weights.size(), "weights");
      const double start = k == 0 ? 0.0 : at[k - 1];
      const double end = k == static_cast<int>(at.size()) ? 1.0 : at[k];
      CheckSameCurve(
          check, rng, kSamples, [&](double s) { return piece.At(s)[0]; }, 0, 1,
          [&](double t) { return curve.At(t)[0]; }, start, end,
          absl::StrCat("piece ", k));
    }
  }
  return check.Result(answer.status());
}

// docs/references.md, 'Worked example: the half circle with a point at
// infinity': the knot 1/2 inserted.
CallResult InsertKnotHalfCircle(Client& client) {
  v1::InsertKnotsRequest request;
  *request.mutable_curve() = BSplineShape{
      .degree = 2,
      .knots = {0, 0, 0, 1, 1, 1},
      .dimension = 2,
      .points = {1, 0, 0, 1, -1, 0},
      .weights = {1, 0, 1}}.ToCurve();
  request.add_knots(0.5);
  auto answer = client.InsertCurveKnots(request);
  Checker check(request);
  if (answer.ok()) {
    const BSplineShape refined = BSplineShape::From(answer->curve().bspline());
    check.NearPoint(refined.knots, Values{0, 0, 0, 0.5, 1, 1, 1}, kTight,
                    "knots", 0.5);
    check.NearPoint(refined.points, Values{1, 0, 1, 1, -1, 1, -1, 0}, kTight,
                    "control points", 0.5);
    check.NearPoint(refined.weights, Values{1, 0.5, 0.5, 1}, kTight, "weights",
                    0.5);
  }
  return check.Result(answer.status());
}

CallResult InsertKnots(Client& client, Rng& rng) {
  if (Coin(rng, 0.2)) return InsertKnotHalfCircle(client);
  const int p = UniformInt(rng, 1, 4);
  const BSplineShape curve =
      RandomBSpline(rng, p, UniformInt(rng, p + 1, 12), UniformInt(rng, 1, 4),
                    Coin(rng), Coin(rng, 0.3));
  // New values (never equal to a knot) and, at times, one of them twice.
  Values knots = RandomValues(rng, static_cast<size_t>(UniformInt(rng, 1, 4)),
                              curve.start(), curve.end(), /*sorted=*/true);
  if (p >= 2 && Coin(rng)) knots.push_back(knots.back());
  std::sort(knots.begin(), knots.end());
  v1::InsertKnotsRequest request;
  *request.mutable_curve() = curve.ToCurve();
  request.mutable_knots()->Add(knots.begin(), knots.end());
  auto answer = client.InsertCurveKnots(request);
  Checker check(request, Scale(curve.points));
  if (answer.ok()) {
    const BSplineShape refined = BSplineShape::From(answer->curve().bspline());
    Values merged = curve.knots;
    merged.insert(merged.end(), knots.begin(), knots.end());
    std::sort(merged.begin(), merged.end());
    check.True(refined.degree == p, "same degree");
    check.NearPoint(refined.knots, merged, kTight, "knot vector", knots[0]);
    check.True(refined.points.size() ==
                   curve.points.size() + knots.size() * curve.dimension,
               "one control point more per knot");
    CheckSameCurve(
        check, rng, kSamples, [&](double u) { return refined.At(u)[0]; },
        curve.start(), curve.end(), [&](double u) { return curve.At(u)[0]; },
        curve.start(), curve.end(), "refined curve");
  }
  return check.Result(answer.status());
}

// Checks Bezier segments and breakpoints against `original` on
// [breakpoints.front(), breakpoints.back()], expected to be `breakpoints`.
void CheckSegments(const v1::DecomposeCurveResponse& answer,
                   const Values& breakpoints, int degree,
                   const PointAt& original, Checker& check, Rng& rng) {
  const Values actual(answer.breakpoints().begin(), answer.breakpoints().end());
  if (!check.NearPoint(actual, breakpoints, kTight, "breakpoints", 0) ||
      !check.True(
          answer.segments_size() + 1 == static_cast<int>(breakpoints.size()),
          "one segment per breakpoint interval")) {
    return;
  }
  for (int k = 0; k < answer.segments_size(); ++k) {
    const BezierShape segment = BezierShape::From(answer.segments(k).bezier());
    check.True(segment.degree() == degree, "segment degree");
    CheckSameCurve(
        check, rng, kSamples, [&](double s) { return segment.At(s)[0]; }, 0, 1,
        original, breakpoints[k], breakpoints[k + 1],
        absl::StrCat("segment ", k));
  }
}

CallResult Decompose(Client& client, Rng& rng) {
  v1::DecomposeCurveRequest request;
  const int dimension = UniformInt(rng, 1, 4);
  const int kind = UniformInt(rng, 0, 4);
  Values breakpoints = {0, 1};
  int degree = 0;
  PointAt original;
  BSplineShape bspline;
  BezierShape bezier;
  Values nodes, points, tangents, coefficients;
  if (kind == 0 || kind == 1) {  // B-spline / NURBS: split at every knot.
    const int p = UniformInt(rng, 1, 4);
    bspline = RandomBSpline(rng, p, UniformInt(rng, p + 1, 12), dimension,
                            Coin(rng), kind == 1);
    *request.mutable_curve() = bspline.ToCurve();
    breakpoints.clear();
    for (const double knot : bspline.knots) {
      if (knot >= bspline.start() && knot <= bspline.end() &&
          (breakpoints.empty() || knot > breakpoints.back())) {
        breakpoints.push_back(knot);
      }
    }
    degree = p;
    original = [&](double u) { return bspline.At(u)[0]; };
  } else if (kind == 2) {  // Hermite: one cubic per node interval.
    const size_t count = static_cast<size_t>(UniformInt(rng, 2, 6));
    nodes = SpreadValues(rng, count, -1, 2, 0.1);
    points = RandomValues(rng, count * dimension, -2, 2);
    tangents = RandomValues(rng, count * dimension, -2, 2);
    v1::HermiteCurve* hermite = request.mutable_curve()->mutable_hermite();
    SetPoints(dimension, points, hermite->mutable_points());
    SetPoints(dimension, tangents, hermite->mutable_tangents());
    hermite->mutable_nodes()->Add(nodes.begin(), nodes.end());
    breakpoints = nodes;
    degree = 3;
    original = [&](double t) {
      return HermiteCurveAt(nodes, dimension, points, tangents, t)[0];
    };
  } else if (kind == 3) {  // Lagrange: one Bezier segment on [t_0, t_n].
    const size_t count = static_cast<size_t>(UniformInt(rng, 2, 7));
    nodes = SpreadValues(rng, count, -1, 2, 0.1);
    points = RandomValues(rng, count * dimension, -2, 2);
    v1::LagrangeCurve* lagrange = request.mutable_curve()->mutable_lagrange();
    SetPoints(dimension, points, lagrange->mutable_points());
    lagrange->mutable_nodes()->Add(nodes.begin(), nodes.end());
    breakpoints = {nodes.front(), nodes.back()};
    degree = static_cast<int>(count) - 1;
    original = [&](double t) {
      return LagrangeCurveAt(nodes, dimension, points, t)[0];
    };
  } else {  // Power form: one Bezier segment of the same degree.
    degree = UniformInt(rng, 1, 3);
    coefficients =
        RandomValues(rng, static_cast<size_t>(degree + 1) * dimension, -2, 2);
    SetPoints(dimension, coefficients,
              request.mutable_curve()->mutable_power()->mutable_coefficients());
    original = [&](double t) {
      Values point(static_cast<size_t>(dimension), 0.0);
      for (int k = degree; k >= 0; --k) {
        for (int j = 0; j < dimension; ++j) {
          point[j] = point[j] * t + coefficients[k * dimension + j];
        }
      }
      return point;
    };
  }
  auto answer = client.DecomposeCurve(request);
  Checker check(request, 2);
  if (answer.ok()) {
    CheckSegments(*answer, breakpoints, degree, original, check, rng);
  }
  return check.Result(answer.status());
}

// One level of uniform B-spline subdivision of degree d by its mask
// (docs/references.md, 'Uniform B-spline subdivision (Chaikin,
// Lane-Riesenfeld)'): Q_j = sum_i s_{j-2i} P_i, s_k = binom(d+1, k) / 2^d.
// Closed polygons are periodic and start at Q_d; open ones keep
// Q_d..Q_{2m-1}, the points whose stencil lies inside the polygon.
Values SubdivideOnce(const Values& polygon, int dimension, int d, bool closed) {
  const auto dim = static_cast<size_t>(dimension);
  const size_t m = polygon.size() / dim;
  Values q(2 * m * dim, 0.0);
  for (size_t i = 0; i < m; ++i) {
    for (int k = 0; k <= d + 1; ++k) {
      size_t j = 2 * i + static_cast<size_t>(k);
      if (closed) {
        j %= 2 * m;
      } else if (j >= 2 * m) {
        continue;
      }
      const double s = Binomial(d + 1, k) / std::pow(2.0, d);
      for (size_t x = 0; x < dim; ++x)
        q[j * dim + x] += s * polygon[i * dim + x];
    }
  }
  Values result;
  const size_t count = closed ? 2 * m : 2 * m - static_cast<size_t>(d);
  for (size_t r = 0; r < count; ++r) {
    const size_t j = (static_cast<size_t>(d) + r) % (2 * m);
    result.insert(result.end(), q.begin() + j * dim, q.begin() + (j + 1) * dim);
  }
  return result;
}

CallResult Subdivide(Client& client, Rng& rng) {
  v1::SubdivideRequest request;
  const bool chaikin = Coin(rng);
  const int d = chaikin ? 2 : UniformInt(rng, 1, 4);
  const bool closed = Coin(rng);
  const int dimension = UniformInt(rng, 2, 3);
  const int levels = UniformInt(rng, 1, 3);
  const int count = UniformInt(rng, closed ? 3 : d + 1, 10);
  Values polygon =
      RandomValues(rng, static_cast<size_t>(count * dimension), -2, 2);
  SetPoints(dimension, polygon, request.mutable_polygon());
  request.set_closed(closed);
  request.set_scheme(chaikin ? v1::SUBDIVISION_SCHEME_CHAIKIN
                             : v1::SUBDIVISION_SCHEME_UNIFORM_BSPLINE);
  if (!chaikin) request.set_degree(static_cast<uint32_t>(d));
  request.set_levels(static_cast<uint32_t>(levels));
  request.set_keep_levels(Coin(rng));
  auto answer = client.SubdividePolygon(request);
  Checker check(request, 2);
  if (answer.ok() &&
      check.True(answer->levels_size() == (request.keep_levels() ? levels : 0),
                 "one polygon per level with keep_levels")) {
    for (int level = 1; level <= levels; ++level) {
      polygon = SubdivideOnce(polygon, dimension, d, closed);
      if (level < levels && !request.keep_levels()) continue;
      const v1::Points& actual =
          level == levels ? answer->polygon() : answer->levels(level - 1);
      check.NearPoint(Flat(actual), polygon, kTight, "level", level);
    }
  }
  return check.Result(answer.status());
}

// A curve the tessellator takes, and its reference.
struct TessellatedCurve {
  v1::Curve curve;
  double start = 0, end = 1;
  bool rational = false;
  PointAt at;
};

TessellatedCurve RandomTessellatedCurve(Rng& rng, int dimension) {
  TessellatedCurve c;
  if (Coin(rng)) {
    const BezierShape bezier =
        RandomBezier(rng, UniformInt(rng, 1, 6), dimension, Coin(rng, 0.3));
    c.curve = bezier.ToCurve();
    c.rational = !bezier.weights.empty();
    c.at = [bezier](double t) { return bezier.At(t)[0]; };
    return c;
  }
  const int p = UniformInt(rng, 1, 4);
  const BSplineShape bspline = RandomBSpline(
      rng, p, UniformInt(rng, p + 1, 10), dimension, Coin(rng), Coin(rng, 0.3));
  c.curve = bspline.ToCurve();
  c.rational = !bspline.weights.empty();
  c.start = bspline.start();
  c.end = bspline.end();
  c.at = [bspline](double u) { return bspline.At(u)[0]; };
  return c;
}

CallResult Tessellate(Client& client, Rng& rng) {
  const int dimension = UniformInt(rng, 2, 3);
  const TessellatedCurve c = RandomTessellatedCurve(rng, dimension);
  const double tolerance = std::pow(10.0, Uniform(rng, -4, -2));
  v1::TessellateCurveRequest request;
  *request.mutable_curve() = c.curve;
  request.set_tolerance(tolerance);
  // Rational curves have no a priori point bound (tessellation.h): without
  // max_points the server plans the largest answer it allows (201 MB of the
  // default budget, even for a 17-point circle), so a few at once are
  // refused. A client bounds them with max_points.
  if (c.rational) request.set_max_points(100'000);
  auto answer = client.TessellateCurve(request);
  Checker check(request, 2);
  if (!answer.ok()) return check.Result(answer.status());
  const Values vertices = Flat(answer->points());
  const Values t(answer->parameters().begin(), answer->parameters().end());
  const auto dim = static_cast<size_t>(dimension);
  if (!check.True(t.size() >= 2 && vertices.size() == t.size() * dim,
                  "one parameter per vertex, at least two") ||
      !check.Near(t.front(), c.start, kTight, "first parameter") ||
      !check.Near(t.back(), c.end, kTight, "last parameter")) {
    return check.Result(answer.status());
  }
  for (size_t i = 0; i < t.size(); ++i) {
    const Coordinates vertex = Coordinates(vertices).subspan(i * dim, dim);
    check.NearPoint(vertex, c.at(t[i]), kTight, "vertex on the curve", t[i]);
    if (i == 0) continue;
    check.True(t[i] > t[i - 1], "increasing parameters");
    // The piece between two vertices lies within the tolerance of their
    // chord (docs/references.md, 'Flatness test for curve tessellation').
    const Coordinates previous =
        Coordinates(vertices).subspan((i - 1) * dim, dim);
    for (const double s : {0.25, 0.5, 0.75}) {
      const double u = t[i - 1] + s * (t[i] - t[i - 1]);
      const double distance = DistanceToSegment(c.at(u), previous, vertex);
      if (!check.True(distance <= tolerance * (1 + 1e-9) + 1e-13,
                      absl::StrCat("curve at ", u, " is ", distance,
                                   " from its chord"))) {
        return check.Result(answer.status());
      }
    }
  }
  return check.Result(answer.status());
}

}  // namespace

std::vector<RpcCase> CurveRefinementCases() {
  return {{"CurveService.Split", false, Split},
          {"CurveService.InsertKnots", false, InsertKnots},
          {"CurveService.Decompose", false, Decompose},
          {"CurveService.Subdivide", false, Subdivide},
          {"CurveService.Tessellate", false, Tessellate}};
}

}  // namespace freeform::reliability
