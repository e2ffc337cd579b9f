// SurfaceService.Evaluate, EvaluateStream and EvaluateBasis: a plane in
// every surface representation (points, partials and normals known in
// closed form), the worked patches of docs/references.md, random patches
// against the reference sums, and the tensor and triangular blending
// functions against their definitions and partition of unity.
#include <cmath>
#include <functional>

#include "absl/strings/str_cat.h"
#include "cases.h"

namespace freeform::reliability {
namespace {

// Partial (order_u, order_v) of the exact surface at (u, v).
using SurfaceReference =
    std::function<Values(double u, double v, int order_u, int order_v)>;

// The (order_u, order_v) pairs of every partial up to `orders`, in the
// server's order: by total order, then by order_v.
std::vector<std::pair<int, int>> PartialOrders(int orders) {
  std::vector<std::pair<int, int>> pairs;
  for (int total = 0; total <= orders; ++total) {
    for (int v = 0; v <= total; ++v) pairs.push_back({total - v, v});
  }
  return pairs;
}

// Checks evaluation messages (one, or a stream's chunks in order) at every
// `stride`-th of the points `uv` (pairs) and at the last.
void CheckSurfaceSamples(absl::Span<const v1::EvaluateSurfaceResponse> messages,
                         const Values& uv, int orders, bool normals,
                         const SurfaceReference& reference, Checker& check,
                         size_t stride = 1) {
  const std::vector<std::pair<int, int>> pairs = PartialOrders(orders);
  const size_t count = uv.size() / 2;
  uint64_t next = 0;
  for (const v1::EvaluateSurfaceResponse& message : messages) {
    if (!check.True(message.first_index() == next, "chunks in order") ||
        !check.True(message.partials_size() == static_cast<int>(pairs.size()),
                    "every partial up to the order")) {
      return;
    }
    const auto d = static_cast<size_t>(message.dimension());
    for (size_t k = 0; k < pairs.size(); ++k) {
      const v1::PartialDerivative& partial =
          message.partials(static_cast<int>(k));
      if (!check.True(
              static_cast<int>(partial.order_u()) == pairs[k].first &&
                  static_cast<int>(partial.order_v()) == pairs[k].second &&
                  partial.values().coordinates_size() ==
                      static_cast<int>(message.count() * d),
              "partials in order, count * dimension values")) {
        return;
      }
    }
    for (uint32_t r = 0; r < message.count(); ++r) {
      const uint64_t index = next + r;
      if (index >= count) break;
      if (index % stride != 0 && index + 1 != count) continue;
      const double u = uv[2 * index], v = uv[2 * index + 1];
      for (size_t k = 0; k < pairs.size(); ++k) {
        const Values expected =
            reference(u, v, pairs[k].first, pairs[k].second);
        const Coordinates actual =
            Coordinates(
                message.partials(static_cast<int>(k)).values().coordinates())
                .subspan(r * d, d);
        if (!check.NearPoint(actual, expected,
                             kTight * std::max(1.0, Scale(expected)),
                             absl::StrCat("partial (", pairs[k].first, ",",
                                          pairs[k].second, ") at u ", u, " v"),
                             v)) {
          return;
        }
      }
      if (normals) {
        Values n = Cross(reference(u, v, 1, 0), reference(u, v, 0, 1));
        const double length = Norm(n);
        for (double& x : n) x /= length;
        check.NearPoint(
            Coordinates(message.normals().coordinates()).subspan(3 * r, 3), n,
            1e-7, "unit normal", u);
      }
    }
    next += message.count();
  }
  check.True(next == count, "one answer per point");
}

// Surface parameters inside [u0, u1] x [v0, v1]: pairs or a grid (list or
// range in each direction); `uv` receives the pairs in answer order.
v1::SurfaceParameters RandomSurfaceParameters(Rng& rng, double u0, double u1,
                                              double v0, double v1,
                                              Values* uv) {
  v1::SurfaceParameters parameters;
  if (Coin(rng)) {
    const int count = UniformInt(rng, 1, 40);
    for (int k = 0; k < count; ++k) {
      uv->push_back(Uniform(rng, u0, u1));
      uv->push_back(Uniform(rng, v0, v1));
    }
    uv->insert(uv->end(), {u0, v0, u1, v1});
    parameters.mutable_points()->mutable_uv()->Add(uv->begin(), uv->end());
    return parameters;
  }
  const auto axis = [&](double start, double end, v1::Parameters* target) {
    const auto count = static_cast<uint32_t>(UniformInt(rng, 1, 12));
    if (Coin(rng)) {
      target->mutable_range()->set_count(count);
      return Linspace(start, end, count);
    }
    Values values = RandomValues(rng, count, start, end);
    target->mutable_list()->mutable_values()->Add(values.begin(), values.end());
    return values;
  };
  const Values us = axis(u0, u1, parameters.mutable_grid()->mutable_u());
  const Values vs = axis(v0, v1, parameters.mutable_grid()->mutable_v());
  for (const double u : us) {
    for (const double v : vs) uv->insert(uv->end(), {u, v});
  }
  return parameters;
}

// `count` barycentric pairs (u, v) inside the triangle, corners included.
Values TrianglePoints(Rng& rng, int count) {
  Values uv = {1, 0, 0, 1, 0, 0};
  for (int k = 0; k < count; ++k) {
    double u = Uniform(rng, 0, 1), v = Uniform(rng, 0, 1);
    if (u + v > 1) u = 1 - u, v = 1 - v;
    uv.insert(uv.end(), {u, v});
  }
  return uv;
}

// The plane S(u, v) = o + u e + v f in one representation, its domain, and
// whether its parameters are barycentric pairs.
struct Plane {
  v1::Surface surface;
  double u0 = 0, u1 = 1, v0 = 0, v1 = 1;
  bool triangle = false;
};

Plane PlaneAs(Rng& rng, int kind, Coordinates o, Coordinates e, Coordinates f) {
  const auto at = [&](double u, double v) {
    return Values{o[0] + u * e[0] + v * f[0], o[1] + u * e[1] + v * f[1],
                  o[2] + u * e[2] + v * f[2]};
  };
  const auto net = [&](const Values& us, const Values& vs) {
    Values points;
    for (const double u : us) {
      for (const double v : vs) {
        const Values p = at(u, v);
        points.insert(points.end(), p.begin(), p.end());
      }
    }
    return points;
  };
  const auto greville = [](const Values& knots, int p) {
    Values abscissae;
    for (size_t i = 0; i + p + 1 < knots.size(); ++i) {
      double sum = 0;
      for (int k = 1; k <= p; ++k) sum += knots[i + k];
      abscissae.push_back(sum / p);
    }
    return abscissae;
  };
  Plane plane;
  switch (kind) {
    case 0:  // Bezier: P_ij = S(i/m, j/n); with equal weights as rational.
    case 1: {
      TensorShape shape = RandomBezierPatch(rng, UniformInt(rng, 1, 4),
                                            UniformInt(rng, 1, 4), false);
      shape.net =
          net(Linspace(0, 1, shape.count_u), Linspace(0, 1, shape.count_v));
      if (kind == 1) {
        shape.weights.assign(shape.count_u * shape.count_v,
                             Uniform(rng, 0.2, 5));
      }
      plane.surface = shape.ToSurface();
      return plane;
    }
    case 2: {  // B-spline at the Greville abscissae in u and v.
      const int p = UniformInt(rng, 1, 3), q = UniformInt(rng, 1, 3);
      TensorShape shape = RandomBSplinePatch(
          rng, p, q, static_cast<uint32_t>(UniformInt(rng, p + 1, 7)),
          static_cast<uint32_t>(UniformInt(rng, q + 1, 7)), false);
      shape.net = net(greville(shape.knots_u, p), greville(shape.knots_v, q));
      plane.surface = shape.ToSurface();
      plane.u0 = shape.start_u();
      plane.u1 = shape.end_u();
      plane.v0 = shape.start_v();
      plane.v1 = shape.end_v();
      return plane;
    }
    case 3:    // Bicubic interpolating: the grid S(i/3, j/3).
    case 4: {  // Hermite: corner positions, tangents e and f, no twist.
      CubicPatchShape shape{.hermite = kind == 4};
      if (kind == 3) {
        shape.net = net(Linspace(0, 1, 4), Linspace(0, 1, 4));
      } else {
        shape.net.assign(48, 0.0);
        for (int a = 0; a < 4; ++a) {
          for (int b = 0; b < 4; ++b) {
            const Values p = a < 2 && b < 2    ? at(a, b)
                             : a >= 2 && b < 2 ? Values(e.begin(), e.end())
                             : a < 2           ? Values(f.begin(), f.end())
                                               : Values(3, 0.0);
            std::copy(p.begin(), p.end(), shape.net.begin() + 3 * (a * 4 + b));
          }
        }
      }
      plane.surface = shape.ToSurface();
      return plane;
    }
    default: {  // Triangular: P_ijk = (i A + j B + k C) / n, A = S(1, 0),
                // B = S(0, 1), C = S(0, 0).
      TriangleShape shape = RandomTriangle(rng, UniformInt(rng, 1, 4), false);
      shape.points.clear();
      const double n = shape.degree;
      for (int i = shape.degree; i >= 0; --i) {
        for (int j = shape.degree - i; j >= 0; --j) {
          const Values p = at(i / n, j / n);
          shape.points.insert(shape.points.end(), p.begin(), p.end());
        }
      }
      plane.surface = shape.ToSurface();
      plane.triangle = true;
      return plane;
    }
  }
}

CallResult EvaluatePlane(Client& client, Rng& rng) {
  const Values o = RandomValues(rng, 3, -3, 3);
  Values e, f;
  do {
    e = RandomValues(rng, 3, -2, 2);
    f = RandomValues(rng, 3, -2, 2);
  } while (Norm(Cross(e, f)) < 0.2);
  const Plane plane = PlaneAs(rng, UniformInt(rng, 0, 5), o, e, f);
  v1::EvaluateSurfaceRequest request;
  *request.mutable_surface() = plane.surface;
  Values uv;
  if (plane.triangle) {
    uv = TrianglePoints(rng, UniformInt(rng, 1, 30));
    request.mutable_parameters()->mutable_points()->mutable_uv()->Add(
        uv.begin(), uv.end());
  } else {
    *request.mutable_parameters() = RandomSurfaceParameters(
        rng, plane.u0, plane.u1, plane.v0, plane.v1, &uv);
  }
  const int orders = UniformInt(rng, 0, 2);
  request.set_derivative_order(static_cast<uint32_t>(orders));
  request.set_normals(Coin(rng));
  auto answer = client.Unary(client.surfaces(),
                             &v1::SurfaceService::Stub::Evaluate, request);
  Checker check(request);
  if (answer.ok()) {
    CheckSurfaceSamples(
        absl::MakeConstSpan(&*answer, 1), uv, orders, request.normals(),
        [&](double u, double v, int order_u, int order_v) {
          if (order_u + order_v == 0) {
            return Values{o[0] + u * e[0] + v * f[0],
                          o[1] + u * e[1] + v * f[1],
                          o[2] + u * e[2] + v * f[2]};
          }
          if (order_u + order_v > 1) return Values(3, 0.0);
          return order_u == 1 ? e : f;
        },
        check);
  }
  return check.Result(answer.status());
}

// docs/references.md, 'Worked example: the bi-quadratic patch at (1/2,
// 1/2)' and 'Worked example: the quadratic triangular patch at the
// centroid'.
CallResult EvaluateWorkedPatch(Client& client, Rng& rng) {
  v1::EvaluateSurfaceRequest request;
  const bool triangle = Coin(rng);
  Values expected;
  if (triangle) {
    *request.mutable_surface() = TriangleShape{
        .degree = 2,
        .points = {6, 0, 9, 3, 3, 6, 3, 0, 0, 0, 6, 0, 0, 3, 3, 0, 0,
                   0}}.ToSurface();
    AddValues({1.0 / 3, 1.0 / 3},
              request.mutable_parameters()->mutable_points()->mutable_uv());
    request.set_derivative_order(1);
    expected = {2, 2, 3, 6, 0, 8, 0, 6, 4};
  } else {
    TensorShape shape = RandomBezierPatch(rng, 2, 2, false);
    shape.net = {0, 0, 0, 2, 0, 0, 4, 0, 0, 0, 2, 0, 2, 2,
                 0, 4, 2, 2, 0, 4, 0, 2, 4, 4, 4, 4, 4};
    *request.mutable_surface() = shape.ToSurface();
    AddValues({0.5, 0.5},
              request.mutable_parameters()->mutable_points()->mutable_uv());
    expected = {2, 2, 1};
  }
  auto answer = client.Unary(client.surfaces(),
                             &v1::SurfaceService::Stub::Evaluate, request);
  Checker check(request, 10);
  if (answer.ok()) {
    Values actual;
    for (const v1::PartialDerivative& partial : answer->partials()) {
      const Values values = Flat(partial.values());
      actual.insert(actual.end(), values.begin(), values.end());
    }
    check.NearPoint(actual, expected, kTight, "worked point and partials", 0);
  }
  return check.Result(answer.status());
}

// A random tensor-product patch against the reference sums.
CallResult EvaluateRandomPatch(Client& client, Rng& rng) {
  const bool rational = Coin(rng, 0.3);
  const TensorShape shape =
      Coin(rng) ? RandomBezierPatch(rng, UniformInt(rng, 1, 5),
                                    UniformInt(rng, 1, 5), rational)
                : RandomBSplinePatch(
                      rng, 3, 2, static_cast<uint32_t>(UniformInt(rng, 4, 9)),
                      static_cast<uint32_t>(UniformInt(rng, 3, 9)), rational);
  v1::EvaluateSurfaceRequest request;
  *request.mutable_surface() = shape.ToSurface();
  Values uv;
  *request.mutable_parameters() = RandomSurfaceParameters(
      rng, shape.start_u(), shape.end_u(), shape.start_v(), shape.end_v(), &uv);
  // The reference differentiates polynomial patches only.
  const int orders = rational ? 0 : UniformInt(rng, 0, 2);
  request.set_derivative_order(static_cast<uint32_t>(orders));
  request.set_normals(orders > 0 && Coin(rng));
  auto answer = client.Unary(client.surfaces(),
                             &v1::SurfaceService::Stub::Evaluate, request);
  Checker check(request);
  if (answer.ok()) {
    CheckSurfaceSamples(
        absl::MakeConstSpan(&*answer, 1), uv, orders, request.normals(),
        [&](double u, double v, int order_u, int order_v) {
          return shape.At(u, v, order_u, order_v);
        },
        check);
  }
  return check.Result(answer.status());
}

CallResult Evaluate(Client& client, Rng& rng) {
  switch (UniformInt(rng, 0, 4)) {
    case 0:
      return EvaluateWorkedPatch(client, rng);
    case 1:
    case 2:
      return EvaluateRandomPatch(client, rng);
    default:
      return EvaluatePlane(client, rng);
  }
}

// A bicubic B-spline patch on a grid of about `size` points, streamed.
CallResult EvaluateStream(Client& client, Rng& rng, StreamSize size) {
  const TensorShape shape = RandomBSplinePatch(rng, 3, 3, 8, 8, false);
  v1::EvaluateSurfaceRequest request;
  *request.mutable_surface() = shape.ToSurface();
  const int total = UniformInt(rng, static_cast<int>(size.min_points),
                               static_cast<int>(size.max_points));
  const int count_u = UniformInt(rng, 16, 64);
  const auto count_v = static_cast<uint32_t>(std::max(1, total / count_u));
  v1::SurfaceGrid* grid = request.mutable_parameters()->mutable_grid();
  grid->mutable_u()->mutable_range()->set_count(static_cast<uint32_t>(count_u));
  grid->mutable_v()->mutable_range()->set_count(count_v);
  const int orders = UniformInt(rng, 0, 1);
  request.set_derivative_order(static_cast<uint32_t>(orders));
  request.set_chunk_size(static_cast<uint32_t>(UniformInt(rng, 64, 2048)));
  std::unique_ptr<grpc::ClientContext> context = client.NewContext();
  auto reader = client.surfaces().EvaluateStream(context.get(), request);
  std::vector<v1::EvaluateSurfaceResponse> chunks;
  const absl::Status status = ReadStream(*reader, &chunks);
  Checker check(request);
  if (status.ok()) {
    Values uv;
    for (const double u : Linspace(shape.start_u(), shape.end_u(),
                                   static_cast<uint32_t>(count_u))) {
      for (const double v : Linspace(shape.start_v(), shape.end_v(), count_v)) {
        uv.insert(uv.end(), {u, v});
      }
    }
    const size_t stride = std::max<size_t>(1, uv.size() / 2 / 2000);
    CheckSurfaceSamples(
        chunks, uv, orders, false,
        [&](double u, double v, int order_u, int order_v) {
          return shape.At(u, v, order_u, order_v);
        },
        check, stride);
  }
  return check.Result(status, chunks.size());
}

CallResult EvaluateBasis(Client& client, Rng& rng) {
  v1::EvaluateSurfaceBasisRequest request;
  Values uv;
  std::function<Values(double, double)> reference;
  bool partition_of_unity = true;
  if (Coin(rng, 0.3)) {
    const int n = UniformInt(rng, 0, 6);
    request.set_triangular_degree(static_cast<uint32_t>(n));
    uv = TrianglePoints(rng, UniformInt(rng, 1, 30));
    request.mutable_parameters()->mutable_points()->mutable_uv()->Add(
        uv.begin(), uv.end());
    reference = [n](double u, double v) { return TriangularBasis(n, u, v); };
  } else {
    const BasisCase bu = RandomBasis(rng);
    const BasisCase bv = RandomBasis(rng);
    *request.mutable_tensor()->mutable_u() = bu.basis;
    *request.mutable_tensor()->mutable_v() = bv.basis;
    *request.mutable_parameters() =
        RandomSurfaceParameters(rng, bu.start, bu.end, bv.start, bv.end, &uv);
    partition_of_unity = bu.partition_of_unity && bv.partition_of_unity;
    reference = [bu, bv](double u, double v) {
      const Values f = bu.reference(u, 0)[0];
      const Values g = bv.reference(v, 0)[0];
      Values values;
      for (const double a : f) {
        for (const double b : g) values.push_back(a * b);
      }
      return values;
    };
  }
  auto answer = client.EvaluateSurfaceBasis(request);
  Checker check(request);
  if (answer.ok() &&
      check.True(answer->count == uv.size() / 2, "one row per point")) {
    const size_t functions = answer->function_count;
    for (size_t r = 0; r < answer->count; ++r) {
      const Values expected = reference(uv[2 * r], uv[2 * r + 1]);
      if (!check.True(expected.size() == functions, "function count")) break;
      const Coordinates row =
          Coordinates(answer->derivatives[0]).subspan(r * functions, functions);
      const double tolerance = kTight * std::max(1.0, Scale(expected));
      check.NearPoint(row, expected, tolerance, "basis values", uv[2 * r]);
      if (partition_of_unity) {
        double sum = 0;
        for (const double value : row) sum += value;
        check.Near(sum, 1, tolerance, "partition of unity");
      }
    }
  }
  return check.Result(answer.status());
}

}  // namespace

std::vector<RpcCase> SurfaceEvaluationCases(StreamSize stream) {
  return {{"SurfaceService.Evaluate", false, Evaluate},
          {"SurfaceService.EvaluateStream", true,
           [stream](Client& client, Rng& rng) {
             return EvaluateStream(client, rng, stream);
           }},
          {"SurfaceService.EvaluateBasis", false, EvaluateBasis}};
}

}  // namespace freeform::reliability
