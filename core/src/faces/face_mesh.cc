// TessellateFace (face_mesh.h): the boundary and the grid triangulated,
// refined until every triangle meets the a-priori bound, then evaluated.
#include "freeform/core/face_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <optional>
#include <vector>

#include "absl/status/status.h"
#include "faces/face_mesh_parts.h"
#include "faces/face_metric.h"
#include "freeform/core/constrained_delaunay.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/surface.h"

namespace freeform {
namespace {

using internal::FaceMetric;
using Region = ConstrainedTriangulationOptions::Region;

// A circumcentre closer than this (in barycentric terms) to an edge is not
// used: it would make a sliver.
constexpr double kMinCircumcentreWeight = 0.1;

std::array<Point2, 3> Corners(const PlanarTriangulation& mesh,
                              const std::array<int32_t, 3>& triangle) {
  return {mesh.points[static_cast<size_t>(triangle[0])],
          mesh.points[static_cast<size_t>(triangle[1])],
          mesh.points[static_cast<size_t>(triangle[2])]};
}

Point2 Combination(const std::array<Point2, 3>& p,
                   const std::array<double, 3>& weights) {
  return {weights[0] * p[0].x + weights[1] * p[1].x + weights[2] * p[2].x,
          weights[0] * p[0].y + weights[1] * p[1].y + weights[2] * p[2].y};
}

// Circumcentre returns the barycentric coordinates of the circumcentre of
// the triangle in the metric (u scaled by sqrt(a), v by sqrt(b)).
std::array<double, 3> Circumcentre(const std::array<Point2, 3>& p,
                                   internal::MetricWeights w) {
  std::array<double, 3> edge2;
  for (int k = 0; k < 3; ++k) {
    const Point2& a = p[(k + 1) % 3];
    const Point2& b = p[(k + 2) % 3];
    edge2[k] =
        w.a * (a.x - b.x) * (a.x - b.x) + w.b * (a.y - b.y) * (a.y - b.y);
  }
  std::array<double, 3> weights = {edge2[0] * (edge2[1] + edge2[2] - edge2[0]),
                                   edge2[1] * (edge2[2] + edge2[0] - edge2[1]),
                                   edge2[2] * (edge2[0] + edge2[1] - edge2[2])};
  const double sum = weights[0] + weights[1] + weights[2];
  for (double& x : weights) x /= sum;
  return weights;
}

// The candidates of a Steiner point per triangle.
constexpr size_t kCandidates = 5;

// SteinerCandidates appends the points to try for a triangle, best first:
// its metric circumcentre when well inside, its centroid, and the points
// halfway from the centroid to each corner.
void SteinerCandidates(const FaceMetric& metric, const std::array<Point2, 3>& p,
                       std::vector<double>& uv) {
  const auto add = [&](Point2 q) {
    uv.push_back(q.x);
    uv.push_back(q.y);
  };
  const double u0 = std::min({p[0].x, p[1].x, p[2].x});
  const double u1 = std::max({p[0].x, p[1].x, p[2].x});
  const double v0 = std::min({p[0].y, p[1].y, p[2].y});
  const double v1 = std::max({p[0].y, p[1].y, p[2].y});
  if (const std::optional<internal::KnotLine> line =
          metric.StraddledLine(u0, u1, v0, v1)) {
    // Across a C0 line: the points where the edges cross it.
    std::vector<Point2> crossings;
    for (int k = 0; k < 3; ++k) {
      const Point2 a = p[k], b = p[(k + 1) % 3];
      const double da = (line->in_u ? a.x : a.y) - line->value;
      const double db = (line->in_u ? b.x : b.y) - line->value;
      if ((da < 0.0) == (db < 0.0) || da == 0.0 || db == 0.0) continue;
      const double s = da / (da - db);
      Point2 q = {a.x + s * (b.x - a.x), a.y + s * (b.y - a.y)};
      (line->in_u ? q.x : q.y) = line->value;
      crossings.push_back(q);
    }
    for (size_t c = 0; c < kCandidates; ++c) {
      add(crossings.empty() ? Combination(p, {1.0 / 3, 1.0 / 3, 1.0 / 3})
                            : crossings[c % crossings.size()]);
    }
    return;
  }
  const internal::MetricWeights w = metric.WeightsOver(u0, u1, v0, v1);
  const std::array<double, 3> centre = Circumcentre(p, w);
  const bool inside =
      std::isfinite(centre[0]) &&
      std::min({centre[0], centre[1], centre[2]}) >= kMinCircumcentreWeight;
  const Point2 centroid = Combination(p, {1.0 / 3, 1.0 / 3, 1.0 / 3});
  add(inside ? Combination(p, centre) : centroid);
  add(centroid);
  for (int k = 0; k < 3; ++k) {
    add({0.5 * (centroid.x + p[k].x), 0.5 * (centroid.y + p[k].y)});
  }
}

// Refine inserts Steiner points until every triangle of the face meets the
// tolerance, and returns the final triangulation.
absl::StatusOr<PlanarTriangulation> Refine(const TrimmedSurface& face,
                                           const FaceMetric& metric,
                                           const FaceMeshOptions& options,
                                           ConstrainedTriangulation& cdt,
                                           const CancellationToken* cancel) {
  std::vector<double> candidates;
  while (true) {
    RETURN_IF_ERROR(CheckCancelled(cancel));
    PlanarTriangulation mesh = cdt.Result(Region::kInsideSegments);
    candidates.clear();
    for (const std::array<int32_t, 3>& triangle : mesh.triangles) {
      const std::array<Point2, 3> p = Corners(mesh, triangle);
      if (metric.TriangleBound(p) > options.tolerance) {
        SteinerCandidates(metric, p, candidates);
      }
    }
    if (candidates.empty()) return mesh;
    const size_t bad = candidates.size() / (2 * kCandidates);
    if (cdt.point_count() + bad > options.max_vertices) {
      return internal::TooManyVertices(options.max_vertices);
    }
    ASSIGN_OR_RETURN(const std::vector<PointLocation> where,
                     ClassifyPoints(face, candidates, 0.0,
                                    ExecutionContext{.cancellation = cancel}));
    const size_t before = cdt.point_count();
    for (size_t t = 0; t < bad; ++t) {
      for (size_t k = t * kCandidates; k < (t + 1) * kCandidates; ++k) {
        if (where[k] != PointLocation::kInside) continue;
        RETURN_IF_ERROR(
            cdt.InsertPoint({candidates[2 * k], candidates[2 * k + 1]})
                .status());
        break;
      }
    }
    if (cdt.point_count() == before) {
      return InvalidFieldError(
          "tolerance",
          "cannot be met: a triangle over the bound has no Steiner point "
          "inside the face");
    }
  }
}

// Angle returns the angle at a between b and c, in degrees.
double Angle(const double* a, const double* b, const double* c) {
  double ab[3], ac[3];
  for (int x = 0; x < 3; ++x) {
    ab[x] = b[x] - a[x];
    ac[x] = c[x] - a[x];
  }
  const double dot = ab[0] * ac[0] + ab[1] * ac[1] + ab[2] * ac[2];
  const double cross =
      std::hypot(ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2],
                 ab[0] * ac[1] - ab[1] * ac[0]);
  return std::atan2(cross, dot) * 180.0 / std::numbers::pi;
}

// MakeFaceMesh evaluates the used vertices and orients the triangles.
absl::StatusOr<FaceMesh> MakeFaceMesh(const TrimmedSurface& face,
                                      const FaceMetric& metric,
                                      const PlanarTriangulation& planar,
                                      const CancellationToken* cancel) {
  FaceMesh mesh;
  std::vector<int64_t> index(planar.points.size(), -1);
  mesh.deviation_bound = 0.0;
  for (const std::array<int32_t, 3>& triangle : planar.triangles) {
    mesh.deviation_bound = std::max(
        mesh.deviation_bound, metric.TriangleBound(Corners(planar, triangle)));
    for (const int32_t v : triangle) {
      int64_t& slot = index[static_cast<size_t>(v)];
      if (slot < 0) {
        slot = static_cast<int64_t>(mesh.uv.size() / 2);
        mesh.uv.push_back(planar.points[static_cast<size_t>(v)].x);
        mesh.uv.push_back(planar.points[static_cast<size_t>(v)].y);
      }
    }
    const std::array<int32_t, 3> order =
        face.reversed()
            ? std::array<int32_t, 3>{triangle[0], triangle[2], triangle[1]}
            : triangle;
    for (const int32_t v : order) {
      mesh.triangles.push_back(
          static_cast<uint32_t>(index[static_cast<size_t>(v)]));
    }
  }
  const size_t count = mesh.uv.size() / 2;
  mesh.vertices.resize(3 * count);
  mesh.normals.resize(3 * count);
  const absl::Span<double> positions(mesh.vertices);
  RETURN_IF_ERROR(
      EvaluateSurface(face.surface(), SurfaceSamples::Pairs(mesh.uv),
                      absl::Span<const absl::Span<double>>(&positions, 1),
                      absl::Span<double>(mesh.normals),
                      ExecutionContext{.cancellation = cancel}));
  OrientFaceNormals(face, absl::Span<double>(mesh.normals));
  mesh.min_angle_degrees = mesh.triangles.empty() ? 0.0 : 180.0;
  for (size_t t = 0; t < mesh.triangles.size(); t += 3) {
    const double* p[3];
    for (int k = 0; k < 3; ++k)
      p[k] = &mesh.vertices[3 * mesh.triangles[t + k]];
    for (int k = 0; k < 3; ++k) {
      mesh.min_angle_degrees = std::min(
          mesh.min_angle_degrees, Angle(p[k], p[(k + 1) % 3], p[(k + 2) % 3]));
    }
  }
  return mesh;
}

}  // namespace

absl::StatusOr<FaceMesh> TessellateFace(const TrimmedSurface& face,
                                        const FaceMeshOptions& options,
                                        const CancellationToken* cancel) {
  RETURN_IF_ERROR(ValidatePositive(options.tolerance, "tolerance"));
  ASSIGN_OR_RETURN(const FaceMetric metric, FaceMetric::Create(face.surface()));
  ASSIGN_OR_RETURN(internal::SampledBoundary boundary,
                   internal::SampleFaceBoundary(face, metric, options.tolerance,
                                                options.max_vertices, cancel));
  ASSIGN_OR_RETURN(const std::vector<Point2> interior,
                   internal::InteriorGrid(face, metric, options.tolerance,
                                          boundary.points.size(),
                                          options.max_vertices, cancel));
  boundary.points.insert(boundary.points.end(), interior.begin(),
                         interior.end());
  ASSIGN_OR_RETURN(ConstrainedTriangulation cdt,
                   ConstrainedTriangulation::Build(boundary.points,
                                                   boundary.segments, cancel));
  ASSIGN_OR_RETURN(const PlanarTriangulation planar,
                   Refine(face, metric, options, cdt, cancel));
  return MakeFaceMesh(face, metric, planar, cancel);
}

}  // namespace freeform
