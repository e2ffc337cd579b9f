// Independent checks of a PlanarTriangulation, shared by the triangulation
// tests and the fuzzer: orientation, edge manifoldness, Euler's formula, the
// hull's area, the (constrained) Delaunay certificate on every edge and the
// segments' presence as chains of constrained edges. Each returns an empty
// string when the property holds, else what is wrong.
#ifndef FREEFORM_TESTS_CORE_TRIANGULATION_CHECKS_H_
#define FREEFORM_TESTS_CORE_TRIANGULATION_CHECKS_H_

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/types/span.h"
#include "freeform/core/constrained_delaunay.h"
#include "triangulation/predicates.h"

namespace freeform::testing {

using Edge = std::pair<int32_t, int32_t>;

// The apex of each directed edge of the triangles.
inline std::map<Edge, int32_t> DirectedEdges(const PlanarTriangulation& mesh,
                                             std::string& error) {
  std::map<Edge, int32_t> apex;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const Edge edge{t[k], t[(k + 1) % 3]};
      if (!apex.emplace(edge, t[(k + 2) % 3]).second && error.empty()) {
        error = absl::StrCat("directed edge (", edge.first, ", ", edge.second,
                             ") is in two triangles");
      }
    }
  }
  return apex;
}

inline std::set<Edge> ConstrainedEdgeSet(const PlanarTriangulation& mesh) {
  std::set<Edge> edges;
  for (const auto& e : mesh.constrained_edges) {
    edges.insert({std::min(e[0], e[1]), std::max(e[0], e[1])});
  }
  return edges;
}

// CheckTriangles: indices valid and representatives, counter-clockwise,
// each directed edge once, and every edge between two triangles that
// carries no segment locally Delaunay (the far apex not strictly inside the
// circle): the certificate of the constrained Delaunay property.
inline std::string CheckTriangles(const PlanarTriangulation& mesh) {
  const auto count = static_cast<int32_t>(mesh.points.size());
  for (const auto& t : mesh.triangles) {
    for (const int32_t v : t) {
      if (v < 0 || v >= count) return absl::StrCat("vertex ", v, " invalid");
      if (static_cast<size_t>(v) < mesh.representative.size() &&
          mesh.representative[v] != v) {
        return absl::StrCat("vertex ", v, " is merged into another");
      }
    }
    if (internal::Orient2d(mesh.points[t[0]], mesh.points[t[1]],
                           mesh.points[t[2]]) <= 0.0) {
      return absl::StrCat("triangle (", t[0], ", ", t[1], ", ", t[2],
                          ") is not counter-clockwise");
    }
  }
  std::string error;
  const std::map<Edge, int32_t> apex = DirectedEdges(mesh, error);
  if (!error.empty()) return error;
  const std::set<Edge> constrained = ConstrainedEdgeSet(mesh);
  for (const auto& [edge, c] : apex) {
    const auto across = apex.find({edge.second, edge.first});
    if (across == apex.end()) continue;
    if (constrained.count({std::min(edge.first, edge.second),
                           std::max(edge.first, edge.second)}) != 0) {
      continue;
    }
    if (internal::InCircle(mesh.points[edge.first], mesh.points[edge.second],
                           mesh.points[c], mesh.points[across->second]) > 0.0) {
      return absl::StrCat("edge (", edge.first, ", ", edge.second,
                          ") is not locally Delaunay");
    }
  }
  return "";
}

// HullArea returns the area of the convex hull of `points` (Andrew's
// monotone chain).
inline long double HullArea(std::vector<Point2> points) {
  std::sort(points.begin(), points.end(), [](Point2 a, Point2 b) {
    return std::pair(a.x, a.y) < std::pair(b.x, b.y);
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  std::vector<Point2> hull;
  for (int pass = 0; pass < 2; ++pass) {
    const size_t base = hull.size();
    for (const Point2 p : points) {
      while (hull.size() >= base + 2 &&
             internal::Orient2d(hull[hull.size() - 2], hull.back(), p) <= 0) {
        hull.pop_back();
      }
      hull.push_back(p);
    }
    hull.pop_back();
    std::reverse(points.begin(), points.end());
  }
  long double area = 0;
  for (size_t i = 0; i < hull.size(); ++i) {
    const Point2 a = hull[i], b = hull[(i + 1) % hull.size()];
    area += static_cast<long double>(a.x) * b.y -
            static_cast<long double>(b.x) * a.y;
  }
  return area / 2;
}

inline long double TriangleArea(const PlanarTriangulation& mesh,
                                const std::array<int32_t, 3>& t) {
  const Point2 a = mesh.points[t[0]], b = mesh.points[t[1]],
               c = mesh.points[t[2]];
  return ((static_cast<long double>(b.x) - a.x) * (c.y - a.y) -
          (static_cast<long double>(b.y) - a.y) * (c.x - a.x)) /
         2;
}

inline long double TotalArea(const PlanarTriangulation& mesh) {
  long double area = 0;
  for (const auto& t : mesh.triangles) area += TriangleArea(mesh, t);
  return area;
}

// CheckHullCover: the triangles of a kConvexHull result form a disk
// (V - E + F = 1) holding every representative, of the hull's area.
inline std::string CheckHullCover(const PlanarTriangulation& mesh) {
  std::set<int32_t> used;
  std::set<Edge> edges;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      used.insert(t[k]);
      edges.insert(
          {std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
    }
  }
  for (size_t i = 0; i < mesh.points.size(); ++i) {
    const bool representative =
        i >= mesh.representative.size() ||
        mesh.representative[i] == static_cast<int32_t>(i);
    if (representative && used.count(static_cast<int32_t>(i)) == 0) {
      return absl::StrCat("point ", i, " is in no triangle");
    }
  }
  const auto euler = static_cast<int64_t>(used.size()) -
                     static_cast<int64_t>(edges.size()) +
                     static_cast<int64_t>(mesh.triangles.size());
  if (euler != 1) return absl::StrCat("V - E + F = ", euler);
  const long double hull = HullArea(mesh.points);
  const long double area = TotalArea(mesh);
  if (std::abs(area - hull) > 1e-12L * std::abs(hull)) {
    return absl::StrCat("area ", static_cast<double>(area), " != hull ",
                        static_cast<double>(hull));
  }
  return "";
}

// CheckSegmentsPresent: each segment is a chain of constrained edges
// through the vertices on it.
inline std::string CheckSegmentsPresent(
    const PlanarTriangulation& mesh,
    absl::Span<const std::array<int32_t, 2>> segments) {
  std::map<int32_t, std::vector<int32_t>> adjacent;
  for (const auto& e : mesh.constrained_edges) {
    adjacent[e[0]].push_back(e[1]);
    adjacent[e[1]].push_back(e[0]);
  }
  for (size_t i = 0; i < segments.size(); ++i) {
    const int32_t a = mesh.representative[segments[i][0]];
    const int32_t b = mesh.representative[segments[i][1]];
    const Point2 pa = mesh.points[a], pb = mesh.points[b];
    int32_t at = a;
    while (at != b) {
      int32_t next = -1;
      for (const int32_t w : adjacent[at]) {
        const Point2 pw = mesh.points[w];
        if (w == b || (internal::Orient2d(pa, pb, pw) == 0.0 &&
                       (pw.x - mesh.points[at].x) * (pb.x - pa.x) +
                               (pw.y - mesh.points[at].y) * (pb.y - pa.y) >
                           0.0)) {
          next = w;
          break;
        }
      }
      if (next < 0) return absl::StrCat("segments[", i, "] is missing");
      at = next;
    }
  }
  return "";
}

// A 64-bit linear congruential generator for the tests' reproducible
// random inputs.
class TestRandom {
 public:
  explicit TestRandom(uint64_t seed) : state_(seed * 2 + 1) {}
  uint64_t Next() {
    state_ = state_ * 6364136223846793005u + 1442695040888963407u;
    return state_ >> 11;
  }
  // Uniform returns a double in [0, 1).
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1p-42; }
  int Below(int bound) { return static_cast<int>(Next() % bound); }

 private:
  uint64_t state_;
};

}  // namespace freeform::testing

#endif  // FREEFORM_TESTS_CORE_TRIANGULATION_CHECKS_H_
