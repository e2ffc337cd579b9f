// Random planar straight-line graphs for the triangulation tests: points on
// a small integer grid (scaled by 1/8, so duplicates, collinear and
// cocircular points are frequent) and random segments between them, each
// kept only if it neither properly crosses nor overlaps one kept before
// (decided with exact integer arithmetic). Segments may pass through
// points and end on other segments, as the triangulation allows.
#ifndef FREEFORM_TESTS_CORE_TRIANGULATION_SEGMENTS_H_
#define FREEFORM_TESTS_CORE_TRIANGULATION_SEGMENTS_H_

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "freeform/core/constrained_delaunay.h"
#include "triangulation_checks.h"

namespace freeform::testing {

struct SegmentSet {
  std::vector<Point2> points;
  std::vector<std::array<int32_t, 2>> segments;
};

struct GridPoint {
  int64_t x;
  int64_t y;
};

inline int64_t GridOrient(GridPoint a, GridPoint b, GridPoint c) {
  const int64_t value = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  return (value > 0) - (value < 0);
}

// Whether the segments pq and rs cross at a point inside both or share a
// piece of positive length.
inline bool GridSegmentsConflict(GridPoint p, GridPoint q, GridPoint r,
                                 GridPoint s) {
  const int64_t o1 = GridOrient(p, q, r), o2 = GridOrient(p, q, s);
  const int64_t o3 = GridOrient(r, s, p), o4 = GridOrient(r, s, q);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  if (o1 != 0 || o2 != 0) return false;
  const bool by_x = p.x != q.x;
  const auto key = [by_x](GridPoint g) { return by_x ? g.x : g.y; };
  const int64_t low =
      std::max(std::min(key(p), key(q)), std::min(key(r), key(s)));
  const int64_t high =
      std::min(std::max(key(p), key(q)), std::max(key(r), key(s)));
  return low < high;
}

inline SegmentSet RandomSegmentSet(uint64_t seed) {
  TestRandom random(seed);
  const int grid = 3 + random.Below(30);
  const int count = 4 + random.Below(80);
  std::vector<GridPoint> grid_points;
  SegmentSet set;
  for (int i = 0; i < count; ++i) {
    grid_points.push_back({random.Below(grid), random.Below(grid)});
    set.points.push_back(
        {std::ldexp(static_cast<double>(grid_points[i].x), -3),
         std::ldexp(static_cast<double>(grid_points[i].y), -3)});
  }
  // Three corners far apart make the points never all collinear.
  for (const GridPoint corner :
       {GridPoint{-1, -1}, GridPoint{grid, -1}, GridPoint{-1, grid}}) {
    grid_points.push_back(corner);
    set.points.push_back({std::ldexp(static_cast<double>(corner.x), -3),
                          std::ldexp(static_cast<double>(corner.y), -3)});
  }
  const int tries = random.Below(2 * count + 1);
  const auto total = static_cast<int>(grid_points.size());
  for (int t = 0; t < tries; ++t) {
    const int32_t a = random.Below(total), b = random.Below(total);
    const GridPoint p = grid_points[a], q = grid_points[b];
    if (p.x == q.x && p.y == q.y) continue;
    bool conflict = false;
    for (const auto& s : set.segments) {
      conflict = conflict || GridSegmentsConflict(p, q, grid_points[s[0]],
                                                  grid_points[s[1]]);
    }
    if (!conflict) set.segments.push_back({a, b});
  }
  return set;
}

}  // namespace freeform::testing

#endif  // FREEFORM_TESTS_CORE_TRIANGULATION_SEGMENTS_H_
