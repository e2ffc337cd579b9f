// TriangulateConstrained and ConstrainedTriangulation
// (freeform/core/constrained_delaunay.h) against the mathematics: the
// checks of triangulation_checks.h (orientation, manifold edges, Euler's
// formula, the hull's area, the locally Delaunay certificate of every
// unconstrained edge, the segments as chains of constrained edges), areas
// of regions against the shoelace formula, and the refusals.
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "freeform/core/constrained_delaunay.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "triangulation_checks.h"
#include "triangulation_segments.h"

namespace freeform {
namespace {

using testing::CheckHullCover;
using testing::CheckSegmentsPresent;
using testing::CheckTriangles;
using ::testing::HasSubstr;
using testing::TestRandom;
using Region = ConstrainedTriangulationOptions::Region;
using Segments = std::vector<std::array<int32_t, 2>>;

PlanarTriangulation Triangulate(const std::vector<Point2>& points,
                                const Segments& segments = {},
                                Region region = Region::kConvexHull) {
  absl::StatusOr<PlanarTriangulation> mesh =
      TriangulateConstrained(points, segments, {region}, nullptr);
  EXPECT_TRUE(mesh.ok()) << mesh.status();
  return mesh.ok() ? *std::move(mesh) : PlanarTriangulation{};
}

void ExpectDelaunayOfHull(const std::vector<Point2>& points) {
  const PlanarTriangulation mesh = Triangulate(points);
  EXPECT_EQ(CheckTriangles(mesh), "");
  EXPECT_EQ(CheckHullCover(mesh), "");
  EXPECT_TRUE(mesh.constrained_edges.empty());
}

std::vector<Point2> Uniform(int count, uint64_t seed) {
  TestRandom random(seed);
  std::vector<Point2> points;
  for (int i = 0; i < count; ++i) {
    points.push_back({random.Uniform(), random.Uniform()});
  }
  return points;
}

// The regular polygon of `count` vertices of radius `radius` around
// (cx, cy), counter-clockwise, appended to `points` and joined into a loop
// of segments.
void AddLoop(std::vector<Point2>& points, Segments& segments, int count,
             double cx, double cy, double radius) {
  const auto first = static_cast<int32_t>(points.size());
  for (int i = 0; i < count; ++i) {
    const double angle = 2 * std::numbers::pi * i / count;
    points.push_back(
        {cx + radius * std::cos(angle), cy + radius * std::sin(angle)});
    segments.push_back({first + i, first + (i + 1) % count});
  }
}

// The area of the polygon of points[first, first + count) (shoelace).
long double PolygonArea(const std::vector<Point2>& points, size_t first,
                        size_t count) {
  long double area = 0;
  for (size_t i = 0; i < count; ++i) {
    const Point2 a = points[first + i];
    const Point2 b = points[first + (i + 1) % count];
    area += static_cast<long double>(a.x) * b.y -
            static_cast<long double>(b.x) * a.y;
  }
  return area / 2;
}

// Relative agreement to 1e-12.
void ExpectRelativelyNear(long double actual, long double expected) {
  EXPECT_LE(std::abs(actual - expected), 1e-12L * std::abs(expected))
      << static_cast<double>(actual) << " against "
      << static_cast<double>(expected);
}

void AddSquare(std::vector<Point2>& points, Segments& segments, double low,
               double high) {
  const auto first = static_cast<int32_t>(points.size());
  points.insert(points.end(),
                {{low, low}, {high, low}, {high, high}, {low, high}});
  for (int32_t i = 0; i < 4; ++i) {
    segments.push_back({first + i, first + (i + 1) % 4});
  }
}

TEST(DelaunayTest, UniformRandomPoints) {
  for (const int count : {3, 4, 10, 100, 2000}) {
    ExpectDelaunayOfHull(Uniform(count, count));
  }
}

// A grid: four cocircular points in every cell and collinear points along
// the hull.
TEST(DelaunayTest, GridOfCocircularPoints) {
  std::vector<Point2> points;
  for (int i = 0; i < 40; ++i) {
    for (int j = 0; j < 30; ++j) points.push_back({i * 0.125, j * 0.125});
  }
  ExpectDelaunayOfHull(points);
  const PlanarTriangulation mesh = Triangulate(points);
  // 2n - 2 - h triangles for n points, h of them on the hull's boundary.
  EXPECT_EQ(mesh.triangles.size(), 2u * 1200 - 2 - (2 * 39 + 2 * 29));
}

TEST(DelaunayTest, PointsOnACircleAndItsCenter) {
  std::vector<Point2> points;
  for (int i = 0; i < 500; ++i) {
    const double angle = 2 * std::numbers::pi * i / 500;
    points.push_back({std::cos(angle), std::sin(angle)});
  }
  ExpectDelaunayOfHull(points);
  points.push_back({0, 0});
  ExpectDelaunayOfHull(points);
}

TEST(DelaunayTest, ClusteredPoints) {
  TestRandom random(7);
  std::vector<Point2> points;
  for (int cluster = 0; cluster < 20; ++cluster) {
    const double cx = random.Uniform() * 100, cy = random.Uniform() * 100;
    const double spread = std::ldexp(1.0, -random.Below(40));
    for (int i = 0; i < 100; ++i) {
      points.push_back(
          {cx + spread * random.Uniform(), cy + spread * random.Uniform()});
    }
  }
  ExpectDelaunayOfHull(points);
}

TEST(DelaunayTest, DuplicatesMergeIntoTheSmallestIndex) {
  std::vector<Point2> points = Uniform(300, 3);
  points.push_back(points[10]);
  points.push_back(points[20]);
  points.push_back(points[10]);
  const PlanarTriangulation mesh = Triangulate(points);
  EXPECT_EQ(CheckTriangles(mesh), "");
  EXPECT_EQ(CheckHullCover(mesh), "");
  EXPECT_EQ(mesh.representative[300], 10);
  EXPECT_EQ(mesh.representative[301], 20);
  EXPECT_EQ(mesh.representative[302], 10);
  EXPECT_EQ(mesh.representative[10], 10);
  EXPECT_EQ(mesh.triangles.size(),
            Triangulate(Uniform(300, 3)).triangles.size());
}

TEST(DelaunayTest, SameInputSameOutput) {
  const std::vector<Point2> points = Uniform(3000, 11);
  EXPECT_EQ(Triangulate(points).triangles, Triangulate(points).triangles);
}

TEST(ConstrainedTest, SquareWithCircularHole) {
  std::vector<Point2> points;
  Segments segments;
  AddSquare(points, segments, 0, 1);
  AddLoop(points, segments, 64, 0.5, 0.5, 0.25);
  for (const Point2& p : Uniform(500, 5)) points.push_back(p);
  const PlanarTriangulation hull = Triangulate(points, segments);
  EXPECT_EQ(CheckTriangles(hull), "");
  EXPECT_EQ(CheckHullCover(hull), "");
  EXPECT_EQ(CheckSegmentsPresent(hull, segments), "");
  const PlanarTriangulation inside =
      Triangulate(points, segments, Region::kInsideSegments);
  const long double expected = 1 - PolygonArea(points, 4, 64);
  ExpectRelativelyNear(testing::TotalArea(inside), expected);
}

TEST(ConstrainedTest, NestedLoops) {
  std::vector<Point2> points;
  Segments segments;
  AddSquare(points, segments, 0, 10);
  AddSquare(points, segments, 2, 8);
  AddLoop(points, segments, 40, 5, 5, 2);
  AddLoop(points, segments, 20, 5, 5, 1);
  const PlanarTriangulation inside =
      Triangulate(points, segments, Region::kInsideSegments);
  EXPECT_EQ(CheckTriangles(inside), "");
  EXPECT_EQ(CheckSegmentsPresent(inside, segments), "");
  const long double expected =
      100 - 36 + PolygonArea(points, 8, 40) - PolygonArea(points, 48, 20);
  ExpectRelativelyNear(testing::TotalArea(inside), expected);
}

TEST(ConstrainedTest, LoopOfAHundredThousandSegments) {
  std::vector<Point2> points;
  Segments segments;
  AddLoop(points, segments, 100000, 0, 0, 1);
  const PlanarTriangulation inside =
      Triangulate(points, segments, Region::kInsideSegments);
  EXPECT_EQ(CheckSegmentsPresent(inside, segments), "");
  EXPECT_EQ(inside.constrained_edges.size(), 100000u);
  const long double expected = PolygonArea(points, 0, 100000);
  ExpectRelativelyNear(testing::TotalArea(inside), expected);
}

TEST(ConstrainedTest, TenThousandTinyHoles) {
  std::vector<Point2> points;
  Segments segments;
  AddSquare(points, segments, 0, 1);
  long double holes = 0;
  for (int i = 0; i < 100; ++i) {
    for (int j = 0; j < 100; ++j) {
      const size_t first = points.size();
      AddLoop(points, segments, 4, (i + 0.5) / 100, (j + 0.5) / 100, 0.001);
      holes += PolygonArea(points, first, 4);
    }
  }
  const PlanarTriangulation inside =
      Triangulate(points, segments, Region::kInsideSegments);
  EXPECT_EQ(CheckTriangles(inside), "");
  EXPECT_EQ(CheckSegmentsPresent(inside, segments), "");
  ExpectRelativelyNear(testing::TotalArea(inside), 1 - holes);
}

// Segments along the hull and between hull vertices: the hull edges carry
// segments, the region inside them is the whole hull.
TEST(ConstrainedTest, SegmentsTouchingTheHull) {
  std::vector<Point2> points = {{0, 0}, {4, 0}, {4, 3}, {0, 3}};
  for (const Point2& p : Uniform(200, 9)) points.push_back({4 * p.x, 3 * p.y});
  const Segments segments = {{0, 1}, {0, 2}, {1, 3}};
  const PlanarTriangulation mesh = Triangulate(points, {{0, 1}, {0, 2}});
  EXPECT_EQ(CheckTriangles(mesh), "");
  EXPECT_EQ(CheckHullCover(mesh), "");
  EXPECT_EQ(CheckSegmentsPresent(mesh, {{0, 1}, {0, 2}}), "");
  // The diagonals cross: refused.
  const auto crossing = TriangulateConstrained(points, segments, {}, nullptr);
  EXPECT_EQ(crossing.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(crossing.status().message(),
              HasSubstr("segments[2]: crosses or overlaps segments[1]"));
}

// Points on a segment split it; collinear segments that meet at a point
// are accepted, those that overlap are refused with both names.
TEST(ConstrainedTest, CollinearPointsAndSegments) {
  std::vector<Point2> points;
  for (int i = 0; i <= 10; ++i) points.push_back({i * 0.5, i * 0.25});
  points.push_back({1, 3});
  points.push_back({2, -3});
  const PlanarTriangulation mesh = Triangulate(points, {{0, 10}});
  EXPECT_EQ(CheckTriangles(mesh), "");
  EXPECT_EQ(CheckSegmentsPresent(mesh, {{0, 10}}), "");
  EXPECT_EQ(mesh.constrained_edges.size(), 10u);
  EXPECT_EQ(CheckSegmentsPresent(Triangulate(points, {{0, 5}, {5, 10}}),
                                 {{0, 5}, {5, 10}}),
            "");
  for (const Segments& overlapping :
       {Segments{{0, 6}, {4, 10}}, Segments{{0, 6}, {6, 2}},
        Segments{{3, 4}, {4, 3}}}) {
    const auto result =
        TriangulateConstrained(points, overlapping, {}, nullptr);
    EXPECT_THAT(result.status().message(),
                HasSubstr("segments[1]: crosses or overlaps segments[0]"));
  }
}

TEST(ConstrainedTest, RefusesBadInput) {
  std::vector<Point2> points = Uniform(10, 1);
  const auto status = [&](const Segments& segments) {
    return TriangulateConstrained(points, segments, {}, nullptr).status();
  };
  EXPECT_THAT(status({{0, 10}}).message(), HasSubstr("segments[0]"));
  EXPECT_THAT(status({{1, 2}, {-1, 2}}).message(), HasSubstr("segments[1]"));
  points.push_back(points[3]);
  EXPECT_THAT(status({{1, 2}, {3, 10}}).message(),
              HasSubstr("segments[1]: (3, 10) joins a point to itself"));
  points[4].y = std::nan("");
  EXPECT_THAT(status({}).message(), HasSubstr("points[4]"));
  points[4].y = 1e300;
  EXPECT_THAT(status({}).message(), HasSubstr("points[4]"));
  points[4].y = 1e-300;
  EXPECT_THAT(status({}).message(), HasSubstr("points[4]"));
  const std::vector<Point2> line = {{0, 0}, {1, 1}, {2, 2}, {2, 2}};
  EXPECT_THAT(TriangulateConstrained(line, {}, {}, nullptr).status().message(),
              HasSubstr("collinear"));
  EXPECT_FALSE(TriangulateConstrained({}, {}, {}, nullptr).ok());
}

// The case the random sets found: a segment that crosses every triangle
// around a vertex (without passing through it), next to a segment edge.
TEST(ConstrainedTest, SegmentAroundAVertexWhoseStarItCrosses) {
  const testing::SegmentSet set = testing::RandomSegmentSet(1496);
  const PlanarTriangulation mesh = Triangulate(set.points, set.segments);
  EXPECT_EQ(CheckTriangles(mesh), "");
  EXPECT_EQ(CheckHullCover(mesh), "");
  EXPECT_EQ(CheckSegmentsPresent(mesh, set.segments), "");
}

TEST(ConstrainedTest, StopsWhenCancelled) {
  CancellationToken token;
  token.Cancel();
  const auto result = TriangulateConstrained(Uniform(10000, 2), {}, {}, &token);
  EXPECT_EQ(result.status().code(), absl::StatusCode::kCancelled);
}

// Random planar straight-line graphs on a small integer grid (many points on
// segments, many cocircular points), a few hundred of them here;
// triangulation_long_test.cc runs 10^5.
TEST(ConstrainedTest, RandomSegmentSets) {
  for (uint64_t seed = 0; seed < 300; ++seed) {
    const testing::SegmentSet set = testing::RandomSegmentSet(seed);
    const PlanarTriangulation mesh = Triangulate(set.points, set.segments);
    ASSERT_EQ(CheckTriangles(mesh), "") << seed;
    ASSERT_EQ(CheckHullCover(mesh), "") << seed;
    ASSERT_EQ(CheckSegmentsPresent(mesh, set.segments), "") << seed;
  }
}

// A segment that crosses another deep inside the mesh is refused with both
// indices, whichever comes first.
TEST(ConstrainedTest, CrossingsAreNamed) {
  std::vector<Point2> points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const Point2& p : Uniform(300, 4)) points.push_back(p);
  EXPECT_THAT(
      TriangulateConstrained(points, {{0, 1}, {0, 2}, {1, 3}}, {}, nullptr)
          .status()
          .message(),
      HasSubstr("segments[2]: crosses or overlaps segments[1]"));
  EXPECT_THAT(TriangulateConstrained(points, {{1, 3}, {0, 2}}, {}, nullptr)
                  .status()
                  .message(),
              HasSubstr("segments[1]: crosses or overlaps segments[0]"));
}

TEST(IncrementalTest, InsertPointKeepsTheConstrainedDelaunayProperty) {
  std::vector<Point2> points;
  Segments segments;
  AddSquare(points, segments, 0, 1);
  AddLoop(points, segments, 32, 0.5, 0.5, 0.3);
  absl::StatusOr<ConstrainedTriangulation> triangulation =
      ConstrainedTriangulation::Build(points, segments, nullptr);
  ASSERT_TRUE(triangulation.ok()) << triangulation.status();
  TestRandom random(21);
  for (int i = 0; i < 2000; ++i) {
    const Point2 p{random.Uniform(), random.Uniform()};
    const absl::StatusOr<int32_t> vertex = triangulation->InsertPoint(p);
    ASSERT_TRUE(vertex.ok());
    EXPECT_EQ(*vertex, static_cast<int32_t>(points.size()) + i);
    if (i % 500 == 0) {
      const PlanarTriangulation mesh =
          triangulation->Result(Region::kConvexHull);
      ASSERT_EQ(CheckTriangles(mesh), "") << i;
    }
  }
  const PlanarTriangulation mesh = triangulation->Result(Region::kConvexHull);
  EXPECT_EQ(CheckTriangles(mesh), "");
  EXPECT_EQ(CheckHullCover(mesh), "");
  EXPECT_EQ(CheckSegmentsPresent(mesh, segments), "");
  const PlanarTriangulation inside =
      triangulation->Result(Region::kInsideSegments);
  const long double expected = 1 - PolygonArea(points, 4, 32);
  ExpectRelativelyNear(testing::TotalArea(inside), expected);
  // A point already there is that vertex.
  EXPECT_EQ(*triangulation->InsertPoint(points[5]), 5);
}

TEST(IncrementalTest, PointOnAConstrainedEdgeSplitsIt) {
  std::vector<Point2> points;
  Segments segments;
  AddSquare(points, segments, 0, 1);
  points.push_back({0.5, 0.5});
  absl::StatusOr<ConstrainedTriangulation> triangulation =
      ConstrainedTriangulation::Build(points, segments, nullptr);
  ASSERT_TRUE(triangulation.ok());
  const absl::StatusOr<int32_t> middle = triangulation->InsertPoint({0.5, 0.0});
  ASSERT_TRUE(middle.ok());
  const PlanarTriangulation mesh = triangulation->Result(Region::kConvexHull);
  EXPECT_EQ(CheckTriangles(mesh), "");
  EXPECT_EQ(CheckHullCover(mesh), "");
  const std::set<testing::Edge> edges = testing::ConstrainedEdgeSet(mesh);
  EXPECT_EQ(edges.count({0, *middle}), 1u);
  EXPECT_EQ(edges.count({1, *middle}), 1u);
  EXPECT_EQ(edges.count({0, 1}), 0u);
  EXPECT_EQ(edges.size(), 5u);
  // Outside the hull: the hull grows.
  ASSERT_TRUE(triangulation->InsertPoint({2, 2}).ok());
  EXPECT_EQ(CheckHullCover(triangulation->Result(Region::kConvexHull)), "");
  EXPECT_FALSE(triangulation->InsertPoint({std::nan(""), 0}).ok());
}

TEST(IncrementalTest, LocateTriangle) {
  const std::vector<Point2> points = Uniform(200, 8);
  absl::StatusOr<ConstrainedTriangulation> triangulation =
      ConstrainedTriangulation::Build(points, {}, nullptr);
  ASSERT_TRUE(triangulation.ok());
  for (const Point2& p : Uniform(100, 9)) {
    const auto triangle = triangulation->LocateTriangle(p);
    if (!triangle.has_value()) continue;
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(internal::Orient2d(points[(*triangle)[k]],
                                   points[(*triangle)[(k + 1) % 3]], p),
                0.0);
    }
  }
  EXPECT_FALSE(triangulation->LocateTriangle({5, 5}).has_value());
  EXPECT_TRUE(triangulation->LocateTriangle(points[0]).has_value());
}

}  // namespace
}  // namespace freeform
