// The queries of CurveService and SurfaceService on random geometry whose
// answers are known in closed form: circles (closest points, arc lengths,
// curvature, boxes), lines (crossings), affine patches (closest points and
// crossings along the normal) and sphere patches (sections, curvatures,
// boxes).
#include <cmath>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "cases.h"

namespace freeform::reliability {
namespace {

constexpr double kPi = std::numbers::pi;

struct Circle {
  double cx = 0, cy = 0, radius = 1;

  // The 9-point quadratic NURBS circle: a quarter per knot span, starting
  // at angle 0 (The NURBS Book, ex. 7.1).
  v1::Curve ToCurve() const {
    const double w = std::sqrt(0.5);
    const double unit[9][2] = {{1, 0},   {1, 1},  {0, 1},  {-1, 1}, {-1, 0},
                               {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
    BSplineShape shape{
        .degree = 2,
        .knots = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1},
        .dimension = 2,
        .weights = {1, w, 1, w, 1, w, 1, w, 1}};
    for (const auto& p : unit) {
      shape.points.push_back(cx + radius * p[0]);
      shape.points.push_back(cy + radius * p[1]);
    }
    return shape.ToCurve();
  }
  Values At(double angle) const {
    return {cx + radius * std::cos(angle), cy + radius * std::sin(angle)};
  }
};

Circle RandomCircle(Rng& rng) {
  return {.cx = Uniform(rng, -5, 5),
          .cy = Uniform(rng, -5, 5),
          .radius = Uniform(rng, 0.5, 3)};
}

// The rational biquadratic patch of the sphere of `radius` about the
// origin over the first octant: the quarter meridian from the equator
// (u = 0) to the pole (u = 1) turned from the x axis (v = 0) to the y axis.
// S_u x S_v points inwards.
TensorShape SpherePatch(double radius) {
  const double w = std::sqrt(0.5);
  const double rho[3] = {radius, radius, 0}, z[3] = {0, radius, radius};
  const double x[3] = {1, 1, 0}, y[3] = {0, 1, 1}, weight[3] = {1, w, 1};
  TensorShape sphere{.degree_u = 2, .degree_v = 2, .count_u = 3, .count_v = 3};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      sphere.net.insert(sphere.net.end(), {rho[i] * x[j], rho[i] * y[j], z[i]});
      sphere.weights.push_back(weight[i] * weight[j]);
    }
  }
  return sphere;
}

// An affine patch S(u, v) = o + u U + v V of random degrees (linear
// precision: its net is the grid of the map), with its unit normal.
struct AffinePatch {
  TensorShape shape;
  Values origin, u_axis, v_axis, normal;

  Values At(double u, double v) const {
    Values p(3);
    for (int j = 0; j < 3; ++j) {
      p[j] = origin[j] + u * u_axis[j] + v * v_axis[j];
    }
    return p;
  }
};

AffinePatch RandomAffinePatch(Rng& rng) {
  AffinePatch patch{.origin = RandomValues(rng, 3, -2, 2),
                    .u_axis = RandomValues(rng, 3, -2, 2),
                    .v_axis = RandomValues(rng, 3, -2, 2)};
  const Values& a = patch.u_axis;
  const Values& b = patch.v_axis;
  Values n = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
              a[0] * b[1] - a[1] * b[0]};
  const double length = std::hypot(n[0], n[1], n[2]);
  if (length < 0.5) return RandomAffinePatch(rng);  // nearly degenerate
  for (double& c : n) c /= length;
  patch.normal = n;
  const int degree_u = UniformInt(rng, 1, 3), degree_v = UniformInt(rng, 1, 3);
  patch.shape = {.degree_u = degree_u,
                 .degree_v = degree_v,
                 .count_u = static_cast<uint32_t>(degree_u + 1),
                 .count_v = static_cast<uint32_t>(degree_v + 1)};
  for (int i = 0; i <= degree_u; ++i) {
    for (int j = 0; j <= degree_v; ++j) {
      const Values p = patch.At(static_cast<double>(i) / degree_u,
                                static_cast<double>(j) / degree_v);
      patch.shape.net.insert(patch.shape.net.end(), p.begin(), p.end());
    }
  }
  return patch;
}

double Distance(Coordinates a, Coordinates b) {
  double sum = 0;
  for (size_t j = 0; j < a.size(); ++j) sum += (a[j] - b[j]) * (a[j] - b[j]);
  return std::sqrt(sum);
}

// Closest points on a circle: q at distance d from the centre is
// | d - r | from the circle, at c + r (q - c) / d.
CallResult CurveClosestPoint(Client& client, Rng& rng) {
  const Circle circle = RandomCircle(rng);
  v1::CurveClosestPointRequest request;
  *request.mutable_curve() = circle.ToCurve();
  const int count = UniformInt(rng, 1, 20);
  std::vector<double> angles;
  Values queries;
  for (int k = 0; k < count; ++k) {
    angles.push_back(Uniform(rng, 0.01, 2 * kPi - 0.01));
    const double d = Uniform(rng, 0.2, 3) * circle.radius;
    queries.push_back(circle.cx + d * std::cos(angles.back()));
    queries.push_back(circle.cy + d * std::sin(angles.back()));
  }
  SetPoints(2, queries, request.mutable_queries());
  auto answer = client.Unary(client.curves(),
                             &v1::CurveService::Stub::ClosestPoint, request);
  Checker check(request, 10);
  if (answer.ok() && check.True(answer->distances_size() == count &&
                                    answer->minima_counts_size() == count,
                                "one answer per query")) {
    int first = 0;
    for (int k = 0; k < count; ++k) {
      const Values q = {queries[2 * k], queries[2 * k + 1]};
      const double d = Distance(q, Values{circle.cx, circle.cy});
      check.Near(answer->distances(k), std::abs(d - circle.radius), kTight,
                 absl::StrCat("distance of query ", k));
      const Values point = {answer->points().coordinates(2 * first),
                            answer->points().coordinates(2 * first + 1)};
      // The distance is certified to the tolerance; the point lies on the
      // circle at that distance from q, and where the distance is flat
      // (q well inside) its position is known to about 1e-7 of r: the
      // polishing Newton stops there in about 1 of 6000 queries.
      check.Near(Distance(point, Values{circle.cx, circle.cy}), circle.radius,
                 kTight, "nearest point on the circle");
      check.Near(Distance(point, q), answer->distances(k), kTight,
                 "nearest point at the distance");
      check.NearPoint(point, circle.At(angles[k]), 1e-6, "nearest point", k);
      first += static_cast<int>(answer->minima_counts(k));
    }
  }
  return check.Result(answer.status());
}

// Two segments crossing at known parameters, or apart.
CallResult CurveIntersect(Client& client, Rng& rng) {
  const Values a0 = RandomValues(rng, 2, -5, 5),
               a1 = RandomValues(rng, 2, -5, 5);
  const double s = Uniform(rng, 0.05, 0.95), t = Uniform(rng, 0.05, 0.95);
  const Values direction = RandomValues(rng, 2, -5, 5);
  Values hit(2), b0(2), b1(2);
  for (int j = 0; j < 2; ++j) {
    hit[j] = a0[j] + s * (a1[j] - a0[j]);
    b0[j] = hit[j] - t * direction[j];
    b1[j] = hit[j] + (1 - t) * direction[j];
  }
  const double cross =
      (a1[0] - a0[0]) * direction[1] - (a1[1] - a0[1]) * direction[0];
  const double lengths =
      Distance(a0, a1) * std::hypot(direction[0], direction[1]);
  const bool apart = Coin(rng, 0.3);
  if (apart) {  // the second segment moved off the first's line
    for (int j = 0; j < 2; ++j) b1[j] = hit[j] - 0.01 * direction[j];
  }
  v1::IntersectCurvesRequest request;
  *request.mutable_first() = BezierShape{
      .dimension = 2,
      .points = {a0[0], a0[1], a1[0],
                 a1[1]}}.ToCurve();
  *request.mutable_second() = BezierShape{
      .dimension = 2,
      .points = {b0[0], b0[1], b1[0],
                 b1[1]}}.ToCurve();
  auto answer = client.Unary(client.curves(),
                             &v1::CurveService::Stub::Intersect, request);
  Checker check(request, 10);
  // Crossings at tiny angles are overlaps within the tolerance: only clear
  // ones are checked.
  if (answer.ok() && std::abs(cross) > 0.05 * lengths) {
    if (apart) {
      check.True(answer->first_parameters().empty(), "no crossing");
    } else if (check.True(answer->first_parameters_size() == 1,
                          "one crossing")) {
      check.Near(answer->first_parameters(0), s, kTight, "first parameter");
      check.Near(answer->second_parameters(0), t, kTight, "second parameter");
    }
  }
  return check.Result(answer.status());
}

// Arcs of whole quarters of a circle: 2 pi r times the fraction.
CallResult ArcLength(Client& client, Rng& rng) {
  const Circle circle = RandomCircle(rng);
  v1::ArcLengthRequest request;
  *request.mutable_curve() = circle.ToCurve();
  const int count = UniformInt(rng, 1, 8);
  Values expected;
  for (int k = 0; k < count; ++k) {
    const int first = UniformInt(rng, 0, 3), last = UniformInt(rng, first, 4);
    v1::ParameterInterval* interval = request.add_intervals();
    interval->set_start(first / 4.0);
    interval->set_end(last / 4.0);
    expected.push_back(2 * kPi * circle.radius * (last - first) / 4.0);
  }
  auto answer = client.Unary(client.curves(),
                             &v1::CurveService::Stub::ArcLength, request);
  Checker check(request, 10);
  if (answer.ok()) {
    check.NearPoint(Values(answer->lengths().begin(), answer->lengths().end()),
                    expected, kTight, "lengths", 0);
  }
  return check.Result(answer.status());
}

// The point at arc length L from angle 0 is at angle L / r.
CallResult ParametersAtArcLength(Client& client, Rng& rng) {
  const Circle circle = RandomCircle(rng);
  v1::ParametersAtArcLengthRequest request;
  *request.mutable_curve() = circle.ToCurve();
  const Values lengths =
      RandomValues(rng, UniformInt(rng, 1, 20), 0, 2 * kPi * circle.radius);
  AddValues(lengths, request.mutable_lengths());
  auto answer = client.Unary(
      client.curves(), &v1::CurveService::Stub::ParametersAtArcLength, request);
  Checker check(request, 10);
  if (answer.ok() && check.True(answer->points().coordinates_size() ==
                                    static_cast<int>(2 * lengths.size()),
                                "a point per length")) {
    const Values points = Flat(answer->points());
    for (size_t k = 0; k < lengths.size(); ++k) {
      check.NearPoint(Coordinates(points).subspan(2 * k, 2),
                      circle.At(lengths[k] / circle.radius), kTight, "point",
                      lengths[k]);
    }
  }
  return check.Result(answer.status());
}

// count samples at equal arc length around the circle: angles 2 pi k /
// (count - 1).
CallResult SampleByArcLength(Client& client, Rng& rng) {
  const Circle circle = RandomCircle(rng);
  v1::SampleByArcLengthRequest request;
  *request.mutable_curve() = circle.ToCurve();
  const int count = UniformInt(rng, 2, 50);
  request.set_count(static_cast<uint32_t>(count));
  auto answer = client.Unary(
      client.curves(), &v1::CurveService::Stub::SampleByArcLength, request);
  Checker check(request, 10);
  if (answer.ok() &&
      check.True(answer->points().coordinates_size() == 2 * count,
                 "count points")) {
    for (int k = 0; k < count; ++k) {
      check.NearPoint(Values{answer->points().coordinates(2 * k),
                             answer->points().coordinates(2 * k + 1)},
                      circle.At(2 * kPi * k / (count - 1)), kTight, "sample",
                      k);
    }
  }
  return check.Result(answer.status());
}

// A circle of radius r has curvature 1 / r; its unit normal is across the
// unit tangent.
CallResult CurveCurvature(Client& client, Rng& rng) {
  const Circle circle = RandomCircle(rng);
  v1::CurveCurvatureRequest request;
  *request.mutable_curve() = circle.ToCurve();
  const int count = UniformInt(rng, 1, 50);
  request.mutable_parameters()->mutable_range()->set_count(
      static_cast<uint32_t>(count));
  auto answer = client.Unary(client.curves(),
                             &v1::CurveService::Stub::Curvature, request);
  Checker check(request);
  if (answer.ok() &&
      check.True(answer->curvatures_size() == count, "a curvature each")) {
    for (int k = 0; k < count; ++k) {
      check.Near(answer->curvatures(k), 1 / circle.radius, kTight, "curvature");
      const auto& t = answer->tangents().coordinates();
      const auto& n = answer->normals().coordinates();
      check.Near(t[2 * k] * n[2 * k] + t[2 * k + 1] * n[2 * k + 1], 0, kTight,
                 "T . N");
    }
  }
  return check.Result(answer.status());
}

// The rotation-minimizing frame of a plane curve started from the plane's
// normal keeps it.
CallResult RotationMinimizingFrames(Client& client, Rng& rng) {
  BezierShape curve = RandomBezier(rng, UniformInt(rng, 1, 5), 3, false);
  for (size_t k = 2; k < curve.points.size(); k += 3) curve.points[k] = 1.5;
  v1::RotationMinimizingFramesRequest request;
  *request.mutable_curve() = curve.ToCurve();
  const int count = UniformInt(rng, 2, 40);
  request.mutable_parameters()->mutable_range()->set_count(
      static_cast<uint32_t>(count));
  AddValues(Values{0, 0, 1}, request.mutable_initial_reference());
  auto answer =
      client.Unary(client.curves(),
                   &v1::CurveService::Stub::RotationMinimizingFrames, request);
  Checker check(request);
  if (answer.ok()) {
    const Values references = Flat(answer->references());
    for (int k = 0; k < count; ++k) {
      check.NearPoint(
          Coordinates(references).subspan(3 * static_cast<size_t>(k), 3),
          Values{0, 0, 1}, kTight, "reference", k);
    }
  }
  return check.Result(answer.status());
}

// The box of a circle is its centre +- r.
CallResult CurveBoundingBox(Client& client, Rng& rng) {
  const Circle circle = RandomCircle(rng);
  v1::CurveBoundingBoxRequest request;
  *request.mutable_curve() = circle.ToCurve();
  auto answer = client.Unary(client.curves(),
                             &v1::CurveService::Stub::BoundingBox, request);
  Checker check(request, 10);
  if (answer.ok()) {
    check.NearPoint(
        Values(answer->lower().begin(), answer->lower().end()),
        Values{circle.cx - circle.radius, circle.cy - circle.radius}, kTight,
        "lower", 0);
    check.NearPoint(
        Values(answer->upper().begin(), answer->upper().end()),
        Values{circle.cx + circle.radius, circle.cy + circle.radius}, kTight,
        "upper", 0);
  }
  return check.Result(answer.status());
}

// A point at height d above S(u, v) of an affine patch is d from it, at
// (u, v).
CallResult SurfaceClosestPoint(Client& client, Rng& rng) {
  const AffinePatch patch = RandomAffinePatch(rng);
  const double u = Uniform(rng, 0.05, 0.95), v = Uniform(rng, 0.05, 0.95);
  const double height = Uniform(rng, -3, 3);
  Values query = patch.At(u, v);
  for (int j = 0; j < 3; ++j) query[j] += height * patch.normal[j];
  v1::SurfaceClosestPointRequest request;
  *request.mutable_surface() = patch.shape.ToSurface();
  SetPoints(3, query, request.mutable_queries());
  auto answer = client.Unary(client.surfaces(),
                             &v1::SurfaceService::Stub::ClosestPoint, request);
  Checker check(request, 10);
  if (answer.ok()) {
    check.Near(answer->distances(0), std::abs(height), kTight, "distance");
    check.NearPoint(Values{answer->parameters(0), answer->parameters(1)},
                    Values{u, v}, kTight, "parameters", 0);
  }
  return check.Result(answer.status());
}

// The normal line through S(u, v) of an affine patch crosses it there.
CallResult SurfaceIntersectCurve(Client& client, Rng& rng) {
  const AffinePatch patch = RandomAffinePatch(rng);
  const double u = Uniform(rng, 0.05, 0.95), v = Uniform(rng, 0.05, 0.95);
  const double t = Uniform(rng, 0.1, 0.9);
  const Values hit = patch.At(u, v);
  Values line(6);
  for (int j = 0; j < 3; ++j) {
    line[j] = hit[j] - 4 * t * patch.normal[j];
    line[3 + j] = hit[j] + 4 * (1 - t) * patch.normal[j];
  }
  v1::IntersectCurveSurfaceRequest request;
  *request.mutable_curve() =
      BezierShape{.dimension = 3, .points = line}.ToCurve();
  *request.mutable_surface() = patch.shape.ToSurface();
  auto answer = client.Unary(
      client.surfaces(), &v1::SurfaceService::Stub::IntersectCurve, request);
  Checker check(request, 10);
  if (answer.ok() &&
      check.True(answer->curve_parameters_size() == 1, "one crossing")) {
    check.Near(answer->curve_parameters(0), t, kTight, "curve parameter");
    check.NearPoint(
        Values{answer->surface_parameters(0), answer->surface_parameters(1)},
        Values{u, v}, kTight, "surface parameters", t);
  }
  return check.Result(answer.status());
}

// The plane z = h cuts the sphere patch of radius r in a quarter circle of
// radius sqrt(r^2 - h^2).
CallResult SurfaceSection(Client& client, Rng& rng) {
  const double radius = Uniform(rng, 0.5, 3);
  const double h = Uniform(rng, 0.05, 0.95) * radius;
  v1::SectionSurfaceRequest request;
  *request.mutable_surface() = SpherePatch(radius).ToSurface();
  AddValues(Values{0, 0, h}, request.mutable_plane_point());
  AddValues(Values{0, 0, 1}, request.mutable_plane_normal());
  // Its answer, a few hundred vertices, is planned for this many.
  request.set_max_points(4096);
  auto answer = client.Unary(client.surfaces(),
                             &v1::SurfaceService::Stub::Section, request);
  Checker check(request, 10);
  if (answer.ok() &&
      check.True(answer->polylines_size() == 1, "one polyline")) {
    const Values points = Flat(answer->polylines(0).points());
    for (size_t k = 0; k + 2 < points.size(); k += 3) {
      check.Near(std::hypot(points[k], points[k + 1]),
                 std::sqrt(radius * radius - h * h), 1e-6, "radius");
      check.Near(points[k + 2], h, kTight, "height");
    }
  }
  return check.Result(answer.status());
}

// A sphere of radius r: K = 1 / r^2, H = 1 / r with the inward normal.
CallResult SurfaceCurvature(Client& client, Rng& rng) {
  const double radius = Uniform(rng, 0.5, 3);
  v1::SurfaceCurvatureRequest request;
  *request.mutable_surface() = SpherePatch(radius).ToSurface();
  const int count = UniformInt(rng, 1, 10);
  const Values uv = RandomValues(rng, 2 * static_cast<size_t>(count), 0, 0.9);
  AddValues(uv, request.mutable_parameters()->mutable_points()->mutable_uv());
  auto answer = client.Unary(client.surfaces(),
                             &v1::SurfaceService::Stub::Curvature, request);
  Checker check(request);
  if (answer.ok() &&
      check.True(answer->gaussian_size() == count, "a curvature each")) {
    for (int k = 0; k < count; ++k) {
      check.Near(answer->gaussian(k), 1 / (radius * radius), kTight,
                 "Gaussian curvature");
      check.Near(answer->mean(k), 1 / radius, kTight, "mean curvature");
    }
  }
  return check.Result(answer.status());
}

// The sphere patch of radius r lies in [0, r]^3 and touches every side.
CallResult SurfaceBoundingBox(Client& client, Rng& rng) {
  const double radius = Uniform(rng, 0.5, 3);
  v1::SurfaceBoundingBoxRequest request;
  *request.mutable_surface() = SpherePatch(radius).ToSurface();
  auto answer = client.Unary(client.surfaces(),
                             &v1::SurfaceService::Stub::BoundingBox, request);
  Checker check(request, 10);
  if (answer.ok()) {
    check.NearPoint(Values(answer->lower().begin(), answer->lower().end()),
                    Values{0, 0, 0}, kTight, "lower", 0);
    check.NearPoint(Values(answer->upper().begin(), answer->upper().end()),
                    Values{radius, radius, radius}, kTight, "upper", 0);
  }
  return check.Result(answer.status());
}

}  // namespace

std::vector<RpcCase> QueryCases() {
  return {{"CurveService.ClosestPoint", false, CurveClosestPoint},
          {"CurveService.Intersect", false, CurveIntersect},
          {"CurveService.ArcLength", false, ArcLength},
          {"CurveService.ParametersAtArcLength", false, ParametersAtArcLength},
          {"CurveService.SampleByArcLength", false, SampleByArcLength},
          {"CurveService.Curvature", false, CurveCurvature},
          {"CurveService.RotationMinimizingFrames", false,
           RotationMinimizingFrames},
          {"CurveService.BoundingBox", false, CurveBoundingBox},
          {"SurfaceService.ClosestPoint", false, SurfaceClosestPoint},
          {"SurfaceService.IntersectCurve", false, SurfaceIntersectCurve},
          {"SurfaceService.Section", false, SurfaceSection},
          {"SurfaceService.Curvature", false, SurfaceCurvature},
          {"SurfaceService.BoundingBox", false, SurfaceBoundingBox}};
}

}  // namespace freeform::reliability
