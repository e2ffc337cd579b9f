// FaceService's reliability calls: a plane square of side s, S(u, v) =
// (s u, s v, 0), with a circular hole of random centre and radius r (the
// NURBS circle, clockwise). Its area is s^2 (1 - pi r^2); a (u, v) point is
// outside exactly when it lies in the disk, and evaluation gives (s u, s v,
// 0) with the normal +z, or -z on a reversed face.
#include <cmath>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "cases.h"
#include "freeform/v1/face_service.grpc.pb.h"

namespace freeform::reliability {
namespace {

// Points this close to the hole's circle (in (u, v)) are not drawn: their
// location is the boundary tolerance's to decide.
constexpr double kClearance = 1e-3;

struct HoledSquare {
  double side = 1;
  double cu = 0.5, cv = 0.5, radius = 0.25;

  v1::TrimmedSurface ToFace() const {
    TensorShape plane{.degree_u = 1,
                      .degree_v = 1,
                      .dimension = 3,
                      .count_u = 2,
                      .count_v = 2,
                      .net = {0, 0, 0, 0, side, 0, side, 0, 0, side, side, 0}};
    v1::TrimmedSurface face;
    *face.mutable_surface() = plane.ToSurface();
    const double w = std::sqrt(0.5);
    // Clockwise: the counter-clockwise circle's points in reverse.
    const double unit[9][2] = {{1, 0},  {1, -1}, {0, -1}, {-1, -1}, {-1, 0},
                               {-1, 1}, {0, 1},  {1, 1},  {1, 0}};
    BSplineShape circle{
        .degree = 2,
        .knots = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1},
        .dimension = 2,
        .weights = {1, w, 1, w, 1, w, 1, w, 1}};
    for (const auto& p : unit) {
      circle.points.push_back(cu + radius * p[0]);
      circle.points.push_back(cv + radius * p[1]);
    }
    *face.add_holes()->add_curves() = circle.ToCurve();
    return face;
  }
  bool InHole(double u, double v) const {
    return std::hypot(u - cu, v - cv) < radius;
  }
  double FromCircle(double u, double v) const {
    return std::abs(std::hypot(u - cu, v - cv) - radius);
  }
};

HoledSquare RandomHoledSquare(Rng& rng) {
  const double radius = Uniform(rng, 0.05, 0.25);
  return {.side = Uniform(rng, 0.5, 4),
          .cu = Uniform(rng, 0.3, 0.7),
          .cv = Uniform(rng, 0.3, 0.7),
          .radius = radius};
}

// RandomFacePoints draws `count` (u, v) points inside the square, away from
// its edges and from the circle.
Values RandomFacePoints(Rng& rng, const HoledSquare& square, int count) {
  Values uv;
  while (uv.size() < 2 * static_cast<size_t>(count)) {
    const double u = Uniform(rng, 0.01, 0.99), v = Uniform(rng, 0.01, 0.99);
    if (square.FromCircle(u, v) > kClearance) uv.insert(uv.end(), {u, v});
  }
  return uv;
}

v1::FacePointLocation Expected(const HoledSquare& square, double u, double v) {
  return square.InHole(u, v) ? v1::FACE_POINT_OUTSIDE : v1::FACE_POINT_INSIDE;
}

CallResult FaceClassify(Client& client, Rng& rng) {
  const HoledSquare square = RandomHoledSquare(rng);
  const Values uv = RandomFacePoints(rng, square, 64);
  v1::ClassifyFacePointsRequest request;
  *request.mutable_face() = square.ToFace();
  request.mutable_parameters()->mutable_points()->mutable_uv()->Add(uv.begin(),
                                                                    uv.end());
  auto answer =
      client.Unary(client.faces(), &v1::FaceService::Stub::Classify, request);
  Checker check(request);
  if (answer.ok() &&
      check.True(answer->locations_size() == 64, "one location per point")) {
    for (int i = 0; i < 64; ++i) {
      check.True(
          answer->locations(i) == Expected(square, uv[2 * i], uv[2 * i + 1]),
          absl::StrCat("location of point ", i));
    }
  }
  return check.Result(answer.status());
}

CallResult FaceEvaluate(Client& client, Rng& rng) {
  const HoledSquare square = RandomHoledSquare(rng);
  const bool reversed = rng() % 2 == 0;
  const Values uv = RandomFacePoints(rng, square, 16);
  v1::EvaluateFaceRequest request;
  *request.mutable_face() = square.ToFace();
  request.mutable_face()->set_reversed(reversed);
  request.mutable_parameters()->mutable_points()->mutable_uv()->Add(uv.begin(),
                                                                    uv.end());
  request.set_normals(true);
  auto answer =
      client.Unary(client.faces(), &v1::FaceService::Stub::Evaluate, request);
  Checker check(request, square.side);
  if (answer.ok() &&
      check.True(
          answer->values().partials_size() == 1 &&
              answer->values().partials(0).values().coordinates_size() == 48 &&
              answer->values().normals().coordinates_size() == 48 &&
              answer->locations_size() == 16,
          "the answer's sizes")) {
    const auto& points = answer->values().partials(0).values().coordinates();
    const auto& normals = answer->values().normals().coordinates();
    for (int i = 0; i < 16; ++i) {
      const double u = uv[2 * i], v = uv[2 * i + 1];
      check.NearPoint(
          Values(points.begin() + 3 * i, points.begin() + 3 * i + 3),
          Values{square.side * u, square.side * v, 0}, kTight, "position", i);
      check.NearPoint(
          Values(normals.begin() + 3 * i, normals.begin() + 3 * i + 3),
          Values{0, 0, reversed ? -1.0 : 1.0}, kTight, "normal", i);
      check.True(answer->locations(i) == Expected(square, u, v),
                 absl::StrCat("location of point ", i));
    }
  }
  return check.Result(answer.status());
}

CallResult FaceArea(Client& client, Rng& rng) {
  const HoledSquare square = RandomHoledSquare(rng);
  v1::FaceAreaRequest request;
  *request.mutable_face() = square.ToFace();
  const double area = square.side * square.side;
  request.set_tolerance(1e-10 * area);
  auto answer =
      client.Unary(client.faces(), &v1::FaceService::Stub::Area, request);
  Checker check(request, area);
  if (answer.ok()) {
    check.Near(answer->area(),
               area * (1 - std::numbers::pi * square.radius * square.radius),
               1e-9, "area");
    check.True(answer->converged(), "converged");
  }
  return check.Result(answer.status());
}

// The mesh of the holed square: every vertex S(u, v) = (s u, s v, 0) and
// outside the hole's disk, within the tolerance bound.
CallResult FaceTessellate(Client& client, Rng& rng) {
  const HoledSquare square = RandomHoledSquare(rng);
  v1::TessellateFaceRequest request;
  *request.mutable_face() = square.ToFace();
  request.set_tolerance(1e-3 * square.side);
  // The call reserves memory for its cap (about 860 bytes a vertex): a few
  // hundred vertices suffice, where a cap of 20,000 held 17 MB of the 604 MB
  // the load test's calls may use.
  request.set_max_vertices(4'000);
  auto answer =
      client.Unary(client.faces(), &v1::FaceService::Stub::Tessellate, request);
  Checker check(request, square.side);
  if (answer.ok()) {
    const auto& xyz = answer->vertices().coordinates();
    const auto& uv = answer->uv().coordinates();
    if (check.True(xyz.size() > 0 && uv.size() / 2 == xyz.size() / 3,
                   "one (u, v) per vertex")) {
      for (int k = 0; k < uv.size() / 2; ++k) {
        const double u = uv[2 * k], v = uv[2 * k + 1];
        check.NearPoint(Values(xyz.begin() + 3 * k, xyz.begin() + 3 * k + 3),
                        Values{square.side * u, square.side * v, 0}, kTight,
                        "vertex", k);
        check.True(
            std::hypot(u - square.cu, v - square.cv) >= square.radius - 1e-12,
            absl::StrCat("vertex ", k, " outside the hole"));
      }
    }
    check.True(answer->deviation_bound() <= request.tolerance(),
               "deviation bound within the tolerance");
  }
  return check.Result(answer.status());
}

}  // namespace

std::vector<RpcCase> FaceCases() {
  return {{"FaceService.Classify", false, FaceClassify},
          {"FaceService.Evaluate", false, FaceEvaluate},
          {"FaceService.Area", false, FaceArea},
          {"FaceService.Tessellate", false, FaceTessellate}};
}

}  // namespace freeform::reliability
