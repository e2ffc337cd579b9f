// CurveService.ElevateDegree, ReduceDegree and Interpolate: elevation keeps
// the shape (and gives the worked values of docs/references.md), reduction
// undoes an elevation exactly and bounds its error honestly, interpolants
// pass through their data with the parameters and end conditions asked for,
// and least squares reproduces data taken from a curve of its space.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "cases.h"

namespace freeform::reliability {
namespace {

constexpr int kSamples = 5;
// Interpolation solves a linear system: a little more room than kTight.
constexpr double kSolved = 1e-8;

// ElevateBezier raises the degree of polynomial control points by r with
// the product formula (docs/references.md, 'Degree elevation by the
// product formula').
Values ElevateBezier(const Values& points, int dimension, int r) {
  const int n = static_cast<int>(points.size()) / dimension - 1;
  Values q(static_cast<size_t>((n + r + 1) * dimension), 0.0);
  for (int i = 0; i <= n + r; ++i) {
    for (int j = std::max(0, i - r); j <= std::min(n, i); ++j) {
      const double c = Binomial(n, j) * Binomial(r, i - j) / Binomial(n + r, i);
      for (int x = 0; x < dimension; ++x) {
        q[i * dimension + x] += c * points[j * dimension + x];
      }
    }
  }
  return q;
}

// Worked examples: the quadratic (0,0), (3,6), (6,0) elevated to (0,0),
// (2,4), (4,4), (6,0), and the half circle with a point at infinity
// elevated to the weights 1, 1/3, 1/3, 1 (docs/references.md, 'Worked
// example: a quadratic Bezier curve elevated to a cubic').
CallResult ElevateWorked(Client& client, Rng& rng) {
  const bool circle = Coin(rng);
  const BezierShape curve =
      circle ? BezierShape{.dimension = 2,
                           .points = {1, 0, 0, 1, -1, 0},
                           .weights = {1, 0, 1}}
             : BezierShape{.dimension = 2, .points = {0, 0, 3, 6, 6, 0}};
  v1::ElevateCurveDegreeRequest request;
  *request.mutable_curve() = curve.ToCurve();
  request.set_by(1);
  auto answer = client.ElevateCurveDegree(request);
  Checker check(request, 6);
  if (answer.ok()) {
    const BezierShape elevated = BezierShape::From(answer->curve().bezier());
    if (circle) {
      check.NearPoint(elevated.weights, Values{1, 1.0 / 3, 1.0 / 3, 1}, kTight,
                      "weights", 1);
    } else {
      check.NearPoint(elevated.points, Values{0, 0, 2, 4, 4, 4, 6, 0}, kTight,
                      "control points", 1);
    }
    CheckSameCurve(
        check, rng, kSamples, [&](double t) { return elevated.At(t)[0]; }, 0, 1,
        [&](double t) { return curve.At(t)[0]; }, 0, 1, "elevated curve");
  }
  return check.Result(answer.status());
}

// Distinct values and their multiplicities.
std::vector<std::pair<double, int>> Runs(const Values& knots) {
  std::vector<std::pair<double, int>> runs;
  for (const double knot : knots) {
    if (!runs.empty() && runs.back().first == knot) {
      ++runs.back().second;
    } else {
      runs.push_back({knot, 1});
    }
  }
  return runs;
}

CallResult ElevateDegree(Client& client, Rng& rng) {
  if (Coin(rng, 0.2)) return ElevateWorked(client, rng);
  const int by = UniformInt(rng, 1, 3);
  const int dimension = UniformInt(rng, 1, 4);
  const bool rational = Coin(rng, 0.3);
  v1::ElevateCurveDegreeRequest request;
  request.set_by(static_cast<uint32_t>(by));
  Checker check(request, 2);
  if (Coin(rng)) {
    const BezierShape curve =
        RandomBezier(rng, UniformInt(rng, 1, 6), dimension, rational);
    *request.mutable_curve() = curve.ToCurve();
    auto answer = client.ElevateCurveDegree(request);
    if (answer.ok()) {
      const BezierShape elevated = BezierShape::From(answer->curve().bezier());
      check.True(elevated.degree() == curve.degree() + by, "degree + by");
      CheckSameCurve(
          check, rng, kSamples, [&](double t) { return elevated.At(t)[0]; }, 0,
          1, [&](double t) { return curve.At(t)[0]; }, 0, 1, "elevated curve");
    }
    return check.Result(answer.status());
  }
  const int p = UniformInt(rng, 1, 3);
  const BSplineShape curve = RandomBSpline(rng, p, UniformInt(rng, p + 1, 10),
                                           dimension, true, rational);
  *request.mutable_curve() = curve.ToCurve();
  auto answer = client.ElevateCurveDegree(request);
  if (answer.ok()) {
    const BSplineShape elevated = BSplineShape::From(answer->curve().bspline());
    check.True(elevated.degree == p + by, "degree + by");
    // The same knot values, every multiplicity raised by `by`.
    std::vector<std::pair<double, int>> expected = Runs(curve.knots);
    for (auto& [value, multiplicity] : expected) multiplicity += by;
    check.True(Runs(elevated.knots) == expected,
               "knots: the same values, multiplicities + by");
    CheckSameCurve(
        check, rng, kSamples, [&](double u) { return elevated.At(u)[0]; },
        curve.start(), curve.end(), [&](double u) { return curve.At(u)[0]; },
        curve.start(), curve.end(), "elevated curve");
  }
  return check.Result(answer.status());
}

CallResult ReduceDegree(Client& client, Rng& rng) {
  const int dimension = UniformInt(rng, 1, 4);
  v1::ReduceCurveDegreeRequest request;
  Checker check(request, 2);
  if (Coin(rng)) {
    // An elevated curve reduces back to the curve it came from, exactly.
    const BezierShape low =
        RandomBezier(rng, UniformInt(rng, 1, 5), dimension, false);
    const int by = UniformInt(rng, 1, 3);
    *request.mutable_curve() =
        BezierShape{.dimension = dimension,
                    .points = ElevateBezier(low.points, dimension, by)}
            .ToCurve();
    request.set_by(static_cast<uint32_t>(by));
    auto answer = client.ReduceCurveDegree(request);
    if (answer.ok()) {
      check.NearPoint(Flat(answer->curve().bezier().control_points()),
                      low.points, kSolved, "reduced control points", by);
      check.Near(answer->error_bound(), 0, kSolved, "error bound");
    }
    return check.Result(answer.status());
  }
  // Any curve: the bound holds at every sample.
  const BezierShape curve =
      RandomBezier(rng, UniformInt(rng, 2, 8), dimension, false);
  const int by = UniformInt(rng, 1, curve.degree() - 1);
  *request.mutable_curve() = curve.ToCurve();
  request.set_by(static_cast<uint32_t>(by));
  auto answer = client.ReduceCurveDegree(request);
  if (answer.ok()) {
    const BezierShape reduced = BezierShape::From(answer->curve().bezier());
    check.True(reduced.degree() == curve.degree() - by, "degree - by");
    double distance = 0;
    for (const double t : Linspace(0, 1, 101)) {
      distance = std::max(distance, Distance(reduced.At(t)[0], curve.At(t)[0]));
    }
    check.True(answer->error_bound() >= distance * (1 - 1e-9),
               absl::StrCat("error bound ", answer->error_bound(),
                            " below the distance ", distance));
  }
  return check.Result(answer.status());
}

// Parameters of chord length (power 1) or centripetal (power 1/2).
Values ChordParameters(const Values& points, int dimension, double power) {
  const auto d = static_cast<size_t>(dimension);
  const size_t count = points.size() / d;
  Values t(count, 0.0);
  for (size_t k = 1; k < count; ++k) {
    t[k] = t[k - 1] +
           std::pow(Distance(Coordinates(points).subspan(k * d, d),
                             Coordinates(points).subspan((k - 1) * d, d)),
                    power);
  }
  for (double& value : t) value /= t.back();
  return t;
}

// Checks that `curve` passes through the data at the answer's parameters.
void CheckThrough(const BSplineShape& curve, const Values& points,
                  const google::protobuf::RepeatedField<double>& parameters,
                  Checker& check) {
  const auto d = static_cast<size_t>(curve.dimension);
  if (!check.True(static_cast<size_t>(parameters.size()) * d == points.size(),
                  "one parameter per point")) {
    return;
  }
  for (int k = 0; k < parameters.size(); ++k) {
    if (!check.NearPoint(curve.At(parameters[k])[0],
                         Coordinates(points).subspan(k * d, d), kSolved,
                         "through the data point", parameters[k])) {
      return;
    }
  }
}

// docs/references.md, 'Worked example: a cubic B-spline through five
// planar points'.
CallResult InterpolateWorked(Client& client, Rng& rng) {
  const bool universal = Coin(rng);
  const Values points = {0, 0, 3, 4, -1, 4, -4, 0, -4, -3};
  v1::InterpolateCurveRequest request;
  SetPoints(2, points, request.mutable_points());
  request.mutable_bspline()->set_degree(3);
  request.mutable_bspline()->set_parameterization(
      universal ? v1::PARAMETERIZATION_UNIVERSAL
                : v1::PARAMETERIZATION_CHORD_LENGTH);
  auto answer = client.InterpolateCurve(request);
  Checker check(request, 4);
  if (answer.ok()) {
    const double s = std::numbers::sqrt2;
    const Values t = universal ? Values{0, (3 - s) / 7, 0.5, (4 + s) / 7, 1}
                               : Values{0, 5.0 / 17, 9.0 / 17, 14.0 / 17, 1};
    const double knot = universal ? 0.5 : 28.0 / 51;
    const BSplineShape curve = BSplineShape::From(answer->curve().bspline());
    check.NearPoint(
        Values(answer->parameters().begin(), answer->parameters().end()), t,
        kSolved, "parameters", 0);
    check.NearPoint(curve.knots, Values{0, 0, 0, 0, knot, 1, 1, 1, 1}, kSolved,
                    "knots", knot);
    CheckThrough(curve, points, answer->parameters(), check);
  }
  return check.Result(answer.status());
}

CallResult InterpolateBSpline(Client& client, Rng& rng) {
  const int dimension = UniformInt(rng, 2, 3);
  const int p = UniformInt(rng, 1, 4);
  const bool closed = Coin(rng, 0.25);
  const auto count = static_cast<size_t>(UniformInt(rng, p + 2, 30));
  const Values points = RandomValues(rng, count * dimension, -2, 2);
  v1::InterpolateCurveRequest request;
  SetPoints(dimension, points, request.mutable_points());
  v1::BSplineInterpolation* method = request.mutable_bspline();
  method->set_degree(static_cast<uint32_t>(p));
  method->set_closed(closed);
  const auto parameterization =
      static_cast<v1::Parameterization>(UniformInt(rng, 0, 4));
  method->set_parameterization(parameterization);
  const bool uniform_parameters =
      parameterization == v1::PARAMETERIZATION_UNIFORM;
  if (uniform_parameters && Coin(rng)) {
    method->set_knot_rule(v1::KNOT_RULE_UNIFORM);
  }
  const bool derivatives = !closed && p >= 2 && Coin(rng, 0.3);
  Values start_derivative, end_derivative;
  if (derivatives) {
    start_derivative = RandomValues(rng, static_cast<size_t>(dimension), -5, 5);
    end_derivative = RandomValues(rng, static_cast<size_t>(dimension), -5, 5);
    SetPoints(dimension, start_derivative, method->mutable_start_derivative());
    SetPoints(dimension, end_derivative, method->mutable_end_derivative());
  }
  auto answer = client.InterpolateCurve(request);
  Checker check(request, 2);
  if (!answer.ok()) return check.Result(answer.status());
  const BSplineShape curve = BSplineShape::From(answer->curve().bspline());
  CheckThrough(curve, points, answer->parameters(), check);
  check.Near(answer->max_residual(), 0, kSolved, "max_residual");
  const Values t(answer->parameters().begin(), answer->parameters().end());
  if (!closed && parameterization != v1::PARAMETERIZATION_UNIVERSAL) {
    const Values expected =
        uniform_parameters ? Linspace(0, 1, static_cast<uint32_t>(count))
        : parameterization == v1::PARAMETERIZATION_CENTRIPETAL
            ? ChordParameters(points, dimension, 0.5)
            : ChordParameters(points, dimension, 1);
    check.NearPoint(t, expected, kTight, "parameters", 0);
  }
  if (derivatives) {
    check.NearPoint(curve.At(t.front(), 1)[1], start_derivative, kSolved,
                    "start derivative", t.front());
    check.NearPoint(curve.At(t.back(), 1)[1], end_derivative, kSolved,
                    "end derivative", t.back());
  }
  if (closed) {
    // One period: the curve and its first p - 1 derivatives close up.
    const std::vector<Values> start = curve.At(curve.start(), p - 1);
    const std::vector<Values> end = curve.At(curve.end(), p - 1);
    for (int k = 0; k < p; ++k) {
      check.NearPoint(end[k], start[k], kSolved * std::pow(10.0, k),
                      absl::StrCat("closed: derivative ", k), curve.end());
    }
  }
  return check.Result(answer.status());
}

CallResult InterpolateCubicSpline(Client& client, Rng& rng) {
  const int dimension = UniformInt(rng, 1, 3);
  const auto count = static_cast<size_t>(UniformInt(rng, 4, 20));
  const Values x = SpreadValues(rng, count, -3, 3, 0.05);
  Values y = RandomValues(rng, count * dimension, -2, 2);
  const auto end = static_cast<v1::SplineEndCondition>(UniformInt(rng, 0, 4));
  const auto d = static_cast<size_t>(dimension);
  if (end == v1::SPLINE_END_CONDITION_PERIODIC) {
    std::copy(y.begin(), y.begin() + d, y.end() - d);
  }
  v1::InterpolateCurveRequest request;
  SetPoints(dimension, y, request.mutable_points());
  v1::CubicSplineInterpolation* method = request.mutable_cubic_spline();
  method->mutable_parameters()->Add(x.begin(), x.end());
  method->set_end_condition(end);
  const Values slopes = RandomValues(rng, 2 * d, -3, 3);
  if (end == v1::SPLINE_END_CONDITION_CLAMPED) {
    SetPoints(dimension, Coordinates(slopes).subspan(0, d),
              method->mutable_start_derivative());
    SetPoints(dimension, Coordinates(slopes).subspan(d, d),
              method->mutable_end_derivative());
  }
  auto answer = client.InterpolateCurve(request);
  Checker check(request, 4);
  if (!answer.ok()) return check.Result(answer.status());
  const BSplineShape s = BSplineShape::From(answer->curve().bspline());
  CheckThrough(s, y, answer->parameters(), check);
  check.NearPoint(
      Values(answer->parameters().begin(), answer->parameters().end()), x,
      kTight, "parameters", 0);
  const std::vector<Values> first = s.At(x.front(), 3);
  const std::vector<Values> last = s.At(x.back(), 3);
  const Values zero(d, 0.0);
  switch (end) {
    case v1::SPLINE_END_CONDITION_NATURAL:
      check.NearPoint(first[2], zero, kSolved * 100, "s''(x_0)", x.front());
      check.NearPoint(last[2], zero, kSolved * 100, "s''(x_n)", x.back());
      break;
    case v1::SPLINE_END_CONDITION_CLAMPED:
      check.NearPoint(first[1], Coordinates(slopes).subspan(0, d), kSolved,
                      "s'(x_0)", x.front());
      check.NearPoint(last[1], Coordinates(slopes).subspan(d, d), kSolved,
                      "s'(x_n)", x.back());
      break;
    case v1::SPLINE_END_CONDITION_PERIODIC:
      check.NearPoint(first[1], last[1], kSolved * 10, "s' periodic", x.back());
      check.NearPoint(first[2], last[2], kSolved * 100, "s'' periodic",
                      x.back());
      break;
    default: {  // Not-a-knot: one cubic on [x_0, x_2] and on [x_{n-2}, x_n].
      const auto third = [&](double at) { return s.At(at, 3)[3]; };
      const Values a = third((x[0] + x[1]) / 2);
      const Values b = third((x[1] + x[2]) / 2);
      const double scale = std::max(1.0, Scale(a));
      check.NearPoint(a, b, kSolved * 1000 * scale, "s''' at x_1", x[1]);
      const Values c = third((x[count - 3] + x[count - 2]) / 2);
      const Values e = third((x[count - 2] + x[count - 1]) / 2);
      check.NearPoint(c, e, kSolved * 1000 * std::max(1.0, Scale(c)),
                      "s''' at x_{n-1}", x[count - 2]);
    }
  }
  return check.Result(answer.status());
}

CallResult ApproximateLeastSquares(Client& client, Rng& rng) {
  const int dimension = UniformInt(rng, 2, 3);
  const int p = UniformInt(rng, 2, 3);
  const auto count = static_cast<size_t>(UniformInt(rng, p + 3, 40));
  const auto d = static_cast<size_t>(dimension);
  // Data on a polynomial of degree p: the fit reproduces it exactly.
  const bool exact = Coin(rng);
  const BezierShape source = RandomBezier(rng, p, dimension, false);
  // Spread parameters and at most half as many control points as data, so
  // every knot span of the fit holds data and its least-squares solution is
  // unique (Schoenberg-Whitney).
  Values t =
      SpreadValues(rng, count - 2, 0, 1, 0.3 / static_cast<double>(count));
  t.insert(t.begin(), 0.0);
  t.push_back(1.0);
  Values points;
  for (const double value : t) {
    const Values point = source.At(value)[0];
    points.insert(points.end(), point.begin(), point.end());
  }
  if (!exact) {
    for (double& value : points) value += Uniform(rng, -0.05, 0.05);
  }
  v1::InterpolateCurveRequest request;
  SetPoints(dimension, points, request.mutable_points());
  v1::LeastSquaresApproximation* method = request.mutable_least_squares();
  method->set_degree(static_cast<uint32_t>(p));
  method->set_control_point_count(static_cast<uint32_t>(
      UniformInt(rng, p + 1, std::max(p + 1, static_cast<int>(count) / 2))));
  method->mutable_parameters()->Add(t.begin(), t.end());
  auto answer = client.InterpolateCurve(request);
  Checker check(request, 2);
  if (!answer.ok()) return check.Result(answer.status());
  const BSplineShape fit = BSplineShape::From(answer->curve().bspline());
  double max = 0, squares = 0;
  for (size_t k = 0; k < count; ++k) {
    const double distance =
        Distance(fit.At(answer->parameters(static_cast<int>(k)))[0],
                 Coordinates(points).subspan(k * d, d));
    max = std::max(max, distance);
    squares += distance * distance;
  }
  check.Near(answer->max_residual(), max, kSolved, "max_residual");
  check.Near(answer->rms_residual(),
             std::sqrt(squares / static_cast<double>(count)), kSolved,
             "rms_residual");
  check.NearPoint(fit.At(0)[0], Coordinates(points).subspan(0, d), kSolved,
                  "first point interpolated", 0);
  check.NearPoint(fit.At(1)[0], Coordinates(points).subspan((count - 1) * d, d),
                  kSolved, "last point interpolated", 1);
  if (exact) {
    CheckSameCurve(
        check, rng, kSamples, [&](double u) { return fit.At(u)[0]; }, 0, 1,
        [&](double u) { return source.At(u)[0]; }, 0, 1,
        "fit of a curve in the spline space");
  }
  return check.Result(answer.status());
}

CallResult Interpolate(Client& client, Rng& rng) {
  switch (UniformInt(rng, 0, 4)) {
    case 0:
      return InterpolateWorked(client, rng);
    case 1:
      return InterpolateCubicSpline(client, rng);
    case 2:
      return ApproximateLeastSquares(client, rng);
    default:
      return InterpolateBSpline(client, rng);
  }
}

}  // namespace

std::vector<RpcCase> CurveConstructionCases() {
  return {{"CurveService.ElevateDegree", false, ElevateDegree},
          {"CurveService.ReduceDegree", false, ReduceDegree},
          {"CurveService.Interpolate", false, Interpolate}};
}

}  // namespace freeform::reliability
