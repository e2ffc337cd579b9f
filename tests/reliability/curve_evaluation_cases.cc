// CurveService.Evaluate, EvaluateStream and EvaluateBasis: a line in every
// curve representation, the worked cubic and the rational circles of
// docs/references.md, random curves against the reference sums, and every
// blending function against its definition and partition of unity.
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <utility>

#include "absl/strings/str_cat.h"
#include "cases.h"

namespace freeform::reliability {
namespace {

// The derivatives 0..orders of the exact curve at one parameter.
using CurveReference = std::function<std::vector<Values>(double t)>;

// kTight relative to the expected values (derivatives can be large).
double Tolerance(Coordinates expected) {
  return kTight * std::max(1.0, Scale(expected));
}

// Checks evaluation messages (one for a unary answer, the chunks of a
// stream in order) against `reference` at every `stride`-th of
// `parameters` and at the last.
void CheckSamples(absl::Span<const v1::EvaluateCurveResponse> messages,
                  const Values& parameters, int dimension, int orders,
                  const CurveReference& reference, Checker& check,
                  size_t stride = 1) {
  uint64_t next = 0;
  for (const v1::EvaluateCurveResponse& message : messages) {
    if (!check.True(message.first_index() == next, "chunks in order") ||
        !check.True(message.dimension() == static_cast<uint32_t>(dimension),
                    "dimension") ||
        !check.True(message.derivatives_size() == orders + 1,
                    "one Points per derivative order")) {
      return;
    }
    for (int k = 0; k <= orders; ++k) {
      if (!check.True(message.derivatives(k).coordinates_size() ==
                          static_cast<int>(message.count()) * dimension,
                      "count * dimension coordinates")) {
        return;
      }
    }
    for (uint32_t r = 0; r < message.count(); ++r) {
      const uint64_t index = next + r;
      if (index >= parameters.size()) break;
      if (index % stride != 0 && index + 1 != parameters.size()) continue;
      const double t = parameters[index];
      const std::vector<Values> expected = reference(t);
      for (int k = 0; k <= orders; ++k) {
        const Coordinates actual =
            Coordinates(message.derivatives(k).coordinates())
                .subspan(r * static_cast<size_t>(dimension),
                         static_cast<size_t>(dimension));
        if (!check.NearPoint(actual, expected[k], Tolerance(expected[k]),
                             absl::StrCat("derivative ", k), t)) {
          return;
        }
      }
    }
    next += message.count();
  }
  check.True(next == parameters.size(), "one sample per parameter");
}

// EvaluateAndCheck sends `request` to CurveService.Evaluate and checks its
// unary answer against `reference` at every one of `parameters`, with the
// tolerances multiplied by `scale`.
CallResult EvaluateAndCheck(Client& client,
                            const v1::EvaluateCurveRequest& request,
                            const Values& parameters, int dimension, int orders,
                            const CurveReference& reference, double scale = 1) {
  auto answer =
      client.Unary(client.curves(), &v1::CurveService::Stub::Evaluate, request);
  Checker check(request, scale);
  if (answer.ok()) {
    CheckSamples(absl::MakeConstSpan(&*answer, 1), parameters, dimension,
                 orders, reference, check);
  }
  return check.Result(answer.status());
}

// Parameters inside [start, end] as a list (with both ends) or a range
// (with or without explicit ends); `values` receives them.
v1::Parameters RandomParameters(Rng& rng, double start, double end,
                                Values* values) {
  v1::Parameters parameters;
  const auto count = static_cast<uint32_t>(UniformInt(rng, 1, 64));
  if (Coin(rng)) {
    *values = RandomValues(rng, count, start, end);
    values->push_back(start);
    values->push_back(end);
    parameters.mutable_list()->mutable_values()->Add(values->begin(),
                                                     values->end());
    return parameters;
  }
  v1::UniformRange* range = parameters.mutable_range();
  range->set_count(count);
  if (Coin(rng)) {
    const double a = Uniform(rng, start, end);
    const double b = Uniform(rng, start, end);
    range->set_start(std::min(a, b));
    range->set_end(std::max(a, b));
    *values = Linspace(range->start(), range->end(), count);
  } else {
    *values = Linspace(start, end, count);
  }
  return parameters;
}

// The blending functions 0..orders of a curve at one parameter.
using BasisReference = std::function<BasisDerivatives(double t, int orders)>;

// The line L(t) = a + t d in one of the curve representations, on a
// domain that depends on the representation.
struct Line {
  v1::Curve curve;
  double start = 0;
  double end = 1;
  // The blending functions and max |P_i| when they can be large (Bezier,
  // B-spline, Lagrange); empty for Hermite and power form, whose
  // derivatives stay small on the domains drawn here.
  BasisReference basis;
  double magnitude = 0;
};

// The factor by which kTight must grow to cover rounding in a sum
// sum_i P_i B_i^(k)(t). Its computed value is off by up to about
// (n + 1) eps sum_i |P_i| |B_i^(k)(t)| (Higham, 'Accuracy and Stability of
// Numerical Algorithms', 3.1). With clustered Lagrange nodes or short knot
// spans the B_i^(k) reach 10^7 while the sum is 0 for k >= 2.
double RoundingScale(const Line& line, const Values& parameters, int orders) {
  if (!line.basis) return 1;
  double worst = 0;
  for (const double t : parameters) {
    for (const Values& order : line.basis(t, orders)) {
      double sum = 0;
      for (const double value : order) sum += std::abs(value);
      const double unit = static_cast<double>(order.size() + 1) *
                          std::numeric_limits<double>::epsilon();
      worst = std::max(worst, 8 * unit * line.magnitude * sum);
    }
  }
  return std::max(1.0, worst / kTight);
}

Line LineAs(Rng& rng, int kind, Coordinates a, Coordinates d) {
  const int dimension = static_cast<int>(a.size());
  const auto on_line = [&](const Values& at) {
    Values points;
    for (const double t : at) {
      for (int j = 0; j < dimension; ++j) points.push_back(a[j] + t * d[j]);
    }
    return points;
  };
  Line line;
  switch (kind) {
    case 0:  // Bezier: P_i = L(i / n); with equal weights as rational.
    case 1: {
      const auto n = static_cast<uint32_t>(UniformInt(rng, 1, 7));
      BezierShape bezier{.dimension = dimension,
                         .points = on_line(Linspace(0, 1, n + 1))};
      if (kind == 1) bezier.weights.assign(n + 1, Uniform(rng, 0.2, 5));
      line.curve = bezier.ToCurve();
      line.basis = [n](double t, int orders) {
        return BernsteinBasis(static_cast<int>(n), t, orders);
      };
      line.magnitude = Scale(bezier.points);
      return line;
    }
    case 2: {  // B-spline at the Greville abscissae (linear precision).
      const int p = UniformInt(rng, 1, 4);
      BSplineShape bspline = RandomBSpline(rng, p, UniformInt(rng, p + 1, 12),
                                           dimension, Coin(rng), false);
      Values greville;
      for (size_t i = 0; i + p + 1 < bspline.knots.size(); ++i) {
        double sum = 0;
        for (int k = 1; k <= p; ++k) sum += bspline.knots[i + k];
        greville.push_back(sum / p);
      }
      bspline.points = on_line(greville);
      line.curve = bspline.ToCurve();
      line.start = bspline.start();
      line.end = bspline.end();
      line.basis = [p, knots = bspline.knots](double u, int orders) {
        return BSplineBasis(p, knots, u, orders);
      };
      line.magnitude = Scale(bspline.points);
      return line;
    }
    case 3: {  // Lagrange through L(t_i) at random nodes.
      const Values nodes = SpreadValues(
          rng, static_cast<size_t>(UniformInt(rng, 2, 8)), -1, 1, 0.05);
      const Values points = on_line(nodes);
      v1::LagrangeCurve* lagrange = line.curve.mutable_lagrange();
      SetPoints(dimension, points, lagrange->mutable_points());
      lagrange->mutable_nodes()->Add(nodes.begin(), nodes.end());
      line.start = nodes.front();
      line.end = nodes.back();
      line.basis = [nodes](double t, int orders) {
        return LagrangeBasis(nodes, t, orders);
      };
      line.magnitude = Scale(points);
      return line;
    }
    case 4: {  // Hermite: points on the line, every tangent d.
      const Values nodes = SpreadValues(
          rng, static_cast<size_t>(UniformInt(rng, 2, 6)), 0, 3, 0.1);
      v1::HermiteCurve* hermite = line.curve.mutable_hermite();
      SetPoints(dimension, on_line(nodes), hermite->mutable_points());
      Values tangents;
      for (size_t k = 0; k < nodes.size(); ++k) {
        tangents.insert(tangents.end(), d.begin(), d.end());
      }
      SetPoints(dimension, tangents, hermite->mutable_tangents());
      hermite->mutable_nodes()->Add(nodes.begin(), nodes.end());
      line.start = nodes.front();
      line.end = nodes.back();
      return line;
    }
    default: {  // Power form a + d t + 0 t^2 + ...
      Values coefficients(a.begin(), a.end());
      coefficients.insert(coefficients.end(), d.begin(), d.end());
      coefficients.resize(coefficients.size() +
                          static_cast<size_t>(UniformInt(rng, 0, 2)) *
                              static_cast<size_t>(dimension));
      SetPoints(dimension, coefficients,
                line.curve.mutable_power()->mutable_coefficients());
      return line;
    }
  }
}

CallResult EvaluateLine(Client& client, Rng& rng) {
  const int dimension = UniformInt(rng, 1, 16);
  const Values a = RandomValues(rng, static_cast<size_t>(dimension), -3, 3);
  const Values d = RandomValues(rng, static_cast<size_t>(dimension), -3, 3);
  Line line = LineAs(rng, UniformInt(rng, 0, 5), a, d);
  v1::EvaluateCurveRequest request;
  *request.mutable_curve() = line.curve;
  Values parameters;
  *request.mutable_parameters() =
      RandomParameters(rng, line.start, line.end, &parameters);
  const int orders = UniformInt(rng, 0, 3);
  request.set_derivative_order(static_cast<uint32_t>(orders));
  request.set_bezier_algorithm(
      static_cast<v1::BezierAlgorithm>(UniformInt(rng, 0, 3)));
  const CurveReference reference = [&](double t) {
    std::vector<Values> expected(static_cast<size_t>(orders) + 1,
                                 Values(static_cast<size_t>(dimension), 0.0));
    for (int j = 0; j < dimension; ++j) {
      expected[0][j] = a[j] + t * d[j];
      if (orders >= 1) expected[1][j] = d[j];
    }
    return expected;
  };
  return EvaluateAndCheck(client, request, parameters, dimension, orders,
                          reference, RoundingScale(line, parameters, orders));
}

// docs/references.md, 'Worked example: the cubic Bezier curve (0,0), (1,2),
// (3,2), (4,0)'.
CallResult EvaluateWorkedCubic(Client& client, Rng& rng) {
  v1::EvaluateCurveRequest request;
  *request.mutable_curve() =
      BezierShape{.dimension = 2, .points = {0, 0, 1, 2, 3, 2, 4, 0}}.ToCurve();
  AddValues({0.0, 0.5, 1.0},
            request.mutable_parameters()->mutable_list()->mutable_values());
  request.set_derivative_order(2);
  request.set_bezier_algorithm(
      static_cast<v1::BezierAlgorithm>(UniformInt(rng, 0, 3)));
  const std::vector<std::vector<Values>> expected = {
      {{0, 0}, {3, 6}, {6, -12}},
      {{2, 1.5}, {4.5, 0}, {0, -12}},
      {{4, 0}, {3, -6}, {-6, -12}}};
  return EvaluateAndCheck(
      client, request, {0.0, 0.5, 1.0}, 2, 2,
      [&](double t) { return expected[static_cast<size_t>(t * 2)]; });
}

// The quarter circle (docs/references.md, 'Worked example: the rational
// quarter circle') and the 9-point NURBS circle ('Worked example: the
// 9-point NURBS circle'): every point at distance 1 from the origin, the
// tangent perpendicular to the radius, and the worked points.
CallResult EvaluateCircle(Client& client, Rng& rng) {
  const double h = std::numbers::sqrt2 / 2;
  v1::EvaluateCurveRequest request;
  Values parameters;
  std::vector<std::pair<double, Values>> worked;
  if (Coin(rng)) {
    const bool standard = Coin(rng);
    *request.mutable_curve() = BezierShape{
        .dimension = 2,
        .points = {1, 0, 1, 1, 0, 1},
        .weights =
            standard
                ? Values{1, h, 1}
                : Values{1, 1, 2}}.ToCurve();
    parameters = RandomValues(rng, 32, 0, 1);
    if (standard) worked = {{0.5, {h, h}}};
  } else {
    *request.mutable_curve() = BSplineShape{
        .degree = 2,
        .knots = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1},
        .dimension = 2,
        .points = {1, 0, 1, 1, 0, 1, -1, 1, -1, 0, -1, -1, 0, -1, 1, -1, 1, 0},
        .weights = {1, h, 1, h, 1, h, 1, h,
                    1}}.ToCurve();
    parameters = RandomValues(rng, 32, 0, 1);
    worked = {{0.25, {0, 1}}, {0.5, {-1, 0}}, {0.75, {0, -1}}};
  }
  for (const auto& [t, point] : worked) parameters.push_back(t);
  request.mutable_parameters()->mutable_list()->mutable_values()->Add(
      parameters.begin(), parameters.end());
  request.set_derivative_order(1);
  auto answer =
      client.Unary(client.curves(), &v1::CurveService::Stub::Evaluate, request);
  Checker check(request);
  if (answer.ok() && check.True(answer->derivatives_size() == 2 &&
                                    answer->count() == parameters.size(),
                                "one point and one tangent per parameter")) {
    const Values points = Flat(answer->derivatives(0));
    const Values tangents = Flat(answer->derivatives(1));
    for (size_t r = 0; r < parameters.size(); ++r) {
      const Coordinates point = Coordinates(points).subspan(2 * r, 2);
      const Coordinates tangent = Coordinates(tangents).subspan(2 * r, 2);
      check.Near(Norm(point), 1, kTight, "distance from the centre");
      check.Near(Dot(point, tangent), 0, kTight * Norm(tangent),
                 "tangent . radius");
    }
    for (size_t w = 0; w < worked.size(); ++w) {
      const size_t r = parameters.size() - worked.size() + w;
      check.NearPoint(Coordinates(points).subspan(2 * r, 2), worked[w].second,
                      kTight, "worked point", worked[w].first);
    }
  }
  return check.Result(answer.status());
}

// A random (rational) Bezier or B-spline curve against the reference sums.
CallResult EvaluateRandomCurve(Client& client, Rng& rng) {
  const int dimension = UniformInt(rng, 1, 8);
  const bool rational = Coin(rng, 0.3);
  v1::EvaluateCurveRequest request;
  CurveReference reference;
  double start = 0, end = 1;
  const int orders = UniformInt(rng, 0, 2);
  if (Coin(rng)) {
    BezierShape bezier =
        RandomBezier(rng, UniformInt(rng, 0, 8), dimension, rational);
    *request.mutable_curve() = bezier.ToCurve();
    reference = [bezier, orders](double t) { return bezier.At(t, orders); };
  } else {
    const int p = UniformInt(rng, 1, 4);
    BSplineShape bspline = RandomBSpline(rng, p, UniformInt(rng, p + 1, 16),
                                         dimension, Coin(rng), rational);
    *request.mutable_curve() = bspline.ToCurve();
    start = bspline.start();
    end = bspline.end();
    reference = [bspline, orders](double u) { return bspline.At(u, orders); };
  }
  Values parameters;
  *request.mutable_parameters() =
      RandomParameters(rng, start, end, &parameters);
  request.set_derivative_order(static_cast<uint32_t>(orders));
  return EvaluateAndCheck(client, request, parameters, dimension, orders,
                          reference);
}

CallResult Evaluate(Client& client, Rng& rng) {
  switch (UniformInt(rng, 0, 5)) {
    case 0:
      return EvaluateWorkedCubic(client, rng);
    case 1:
      return EvaluateCircle(client, rng);
    case 2:
    case 3:
      return EvaluateRandomCurve(client, rng);
    default:
      return EvaluateLine(client, rng);
  }
}

// A cubic (NURBS) B-spline in 3D over a range of `size` points, streamed.
CallResult EvaluateStream(Client& client, Rng& rng, StreamSize size) {
  const BSplineShape bspline =
      RandomBSpline(rng, 3, 20, 3, Coin(rng), Coin(rng, 0.3));
  v1::EvaluateCurveRequest request;
  *request.mutable_curve() = bspline.ToCurve();
  const auto count =
      static_cast<uint32_t>(UniformInt(rng, static_cast<int>(size.min_points),
                                       static_cast<int>(size.max_points)));
  request.mutable_parameters()->mutable_range()->set_count(count);
  request.set_chunk_size(static_cast<uint32_t>(UniformInt(rng, 64, 2048)));
  const int orders = UniformInt(rng, 0, 1);
  request.set_derivative_order(static_cast<uint32_t>(orders));
  std::unique_ptr<grpc::ClientContext> context = client.NewContext();
  auto reader = client.curves().EvaluateStream(context.get(), request);
  std::vector<v1::EvaluateCurveResponse> chunks;
  const absl::Status status = ReadStream(*reader, &chunks);
  Checker check(request);
  if (status.ok()) {
    // Check at most about 2000 points per call: the client shares the cores.
    const size_t stride = std::max<size_t>(1, count / 2000);
    CheckSamples(
        chunks, Linspace(bspline.start(), bspline.end(), count), 3, orders,
        [&](double u) { return bspline.At(u, orders); }, check, stride);
  }
  return check.Result(status, chunks.size());
}

CallResult EvaluateBasis(Client& client, Rng& rng) {
  BasisCase c = RandomBasis(rng);
  v1::EvaluateBasisRequest request;
  *request.mutable_basis() = c.basis;
  Values parameters;
  *request.mutable_parameters() =
      RandomParameters(rng, c.start, c.end, &parameters);
  const int orders = UniformInt(rng, 0, 2);
  request.set_derivative_order(static_cast<uint32_t>(orders));
  auto answer = client.EvaluateBasis(request);
  Checker check(request);
  if (answer.ok() &&
      check.True(
          answer->count == parameters.size() &&
              answer->derivatives.size() == static_cast<size_t>(orders) + 1,
          "one row per parameter and one table per order")) {
    const size_t functions = answer->function_count;
    for (size_t r = 0; r < parameters.size(); ++r) {
      const double t = parameters[r];
      const BasisDerivatives expected = c.reference(t, orders);
      if (!check.True(expected[0].size() == functions, "function count")) {
        break;
      }
      for (int k = 0; k <= orders; ++k) {
        const Coordinates row = Coordinates(answer->derivatives[k])
                                    .subspan(r * functions, functions);
        const double tolerance = kTight * std::max(1.0, Scale(expected[k]));
        check.NearPoint(row, expected[k], tolerance,
                        absl::StrCat("basis derivative ", k), t);
        double sum = 0;
        for (const double value : row) sum += value;
        if (c.partition_of_unity) {
          check.Near(sum, k == 0 ? 1 : 0, tolerance, "partition of unity");
        } else if (k == 0) {
          check.Near(row[0] + row[1], 1, kTight, "H0 + H1 = 1");
        }
      }
    }
  }
  return check.Result(answer.status());
}

}  // namespace

BasisCase RandomBasis(Rng& rng) {
  BasisCase c;
  switch (UniformInt(rng, 0, 3)) {
    case 0: {
      const int n = UniformInt(rng, 0, 10);
      const Values weights =
          RandomWeights(rng, static_cast<size_t>(n) + 1, Coin(rng, 0.3));
      c.basis.mutable_bernstein()->set_degree(static_cast<uint32_t>(n));
      c.basis.mutable_bernstein()->mutable_weights()->Add(weights.begin(),
                                                          weights.end());
      c.reference = [n, weights](double t, int orders) {
        BasisDerivatives b = BernsteinBasis(n, t, orders);
        if (weights.empty()) return b;
        // R_i = w_i B_i / sum_j w_j B_j: the rational curve whose control
        // points are the unit vectors.
        Values identity(weights.size() * weights.size(), 0.0);
        for (size_t i = 0; i < weights.size(); ++i) {
          identity[i * weights.size() + i] = 1;
        }
        return Combine(static_cast<int>(weights.size()), identity, weights, b);
      };
      return c;
    }
    case 1: {
      // Degree 0 allows no interior knot (geometry.proto): from 1 on.
      const int p = UniformInt(rng, 1, 4);
      const BSplineShape shape = RandomBSpline(
          rng, p, UniformInt(rng, p + 1, 12), 1, Coin(rng), Coin(rng, 0.3));
      v1::BSplineBasis* bspline = c.basis.mutable_bspline();
      bspline->set_degree(static_cast<uint32_t>(p));
      bspline->mutable_knots()->Add(shape.knots.begin(), shape.knots.end());
      bspline->mutable_weights()->Add(shape.weights.begin(),
                                      shape.weights.end());
      c.start = shape.start();
      c.end = shape.end();
      c.reference = [shape](double u, int orders) {
        BasisDerivatives b = BSplineBasis(shape.degree, shape.knots, u, orders);
        if (shape.weights.empty()) return b;
        const size_t count = shape.weights.size();
        Values identity(count * count, 0.0);
        for (size_t i = 0; i < count; ++i) identity[i * count + i] = 1;
        return Combine(static_cast<int>(count), identity, shape.weights, b);
      };
      return c;
    }
    case 2: {
      const Values nodes = SpreadValues(
          rng, static_cast<size_t>(UniformInt(rng, 2, 8)), -2, 2, 0.1);
      c.basis.mutable_lagrange()->mutable_nodes()->Add(nodes.begin(),
                                                       nodes.end());
      c.start = nodes.front();
      c.end = nodes.back();
      c.reference = [nodes](double t, int orders) {
        return LagrangeBasis(nodes, t, orders);
      };
      return c;
    }
    default:
      c.basis.mutable_hermite();
      c.partition_of_unity = false;
      c.reference = [](double t, int orders) {
        BasisDerivatives b(static_cast<size_t>(orders) + 1, Values(4));
        for (int k = 0; k <= orders; ++k) {
          for (int i = 0; i < 4; ++i) b[k][i] = Hermite(i, t, k);
        }
        return b;
      };
      return c;
  }
}

std::vector<RpcCase> CurveEvaluationCases(StreamSize stream) {
  return {{"CurveService.Evaluate", false, Evaluate},
          {"CurveService.EvaluateStream", true,
           [stream](Client& client, Rng& rng) {
             return EvaluateStream(client, rng, stream);
           }},
          {"CurveService.EvaluateBasis", false, EvaluateBasis}};
}

RpcCase LargeCurveEvaluation(uint32_t points, uint32_t stride) {
  return {"CurveService.Evaluate", false,
          [points, stride](Client& client, Rng& rng) {
            const BSplineShape bspline =
                RandomBSpline(rng, 3, 100, 3, true, false);
            v1::EvaluateCurveRequest request;
            *request.mutable_curve() = bspline.ToCurve();
            request.mutable_parameters()->mutable_range()->set_count(points);
            auto answer = client.Unary(
                client.curves(), &v1::CurveService::Stub::Evaluate, request);
            Checker check(request);
            if (answer.ok()) {
              CheckSamples(
                  absl::MakeConstSpan(&*answer, 1),
                  Linspace(bspline.start(), bspline.end(), points), 3, 0,
                  [&](double u) { return bspline.At(u); }, check, stride);
            }
            return check.Result(answer.status());
          }};
}

}  // namespace freeform::reliability
