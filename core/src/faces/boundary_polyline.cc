// The certified polylines of a face's loops and their grid
// (face_boundary.h, BuildBoundaryPolylines).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "faces/face_boundary.h"
#include "freeform/core/saturating.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/tessellation.h"

namespace freeform::internal {
namespace {

// A loop's polyline is within this fraction of the loop's extent (or the
// face's tolerance, if larger) of the loop.
constexpr double kPolylineFraction = 0x1p-10;

// The grid has at most this many columns and rows, and at most
// GridEntryLimit(segments) segment entries in its cells (coarser beyond).
constexpr int kMaxGridSide = 2048;

// A grid of one cell holds every segment once, so the halving in BuildGrid
// always ends within the limit.
uint64_t GridEntryLimit(uint64_t segments) { return 8 * segments + 64; }

// LoopExtent returns the diagonal of the box of a loop's control points.
double LoopExtent(const FaceBoundary& boundary, const BoundaryLoop& loop) {
  Box2 box;
  for (int k = 0; k < loop.piece_count; ++k) {
    box.AddBox(
        ControlBox(boundary.pieces[loop.first_piece + k].bezier.coordinates));
  }
  return box.Diagonal();
}

double LoopEpsilon(const FaceBoundary& boundary, const BoundaryLoop& loop) {
  return std::max(boundary.tolerance,
                  kPolylineFraction * LoopExtent(boundary, loop));
}

// SegmentBound returns the tessellation's a-priori bound of the segments of
// every loop's polyline (saturating).
uint64_t SegmentBound(const FaceBoundary& boundary) {
  uint64_t segments = 0;
  for (const BoundaryLoop& loop : boundary.loops) {
    const double epsilon = LoopEpsilon(boundary, loop);
    for (int k = 0; k < loop.piece_count; ++k) {
      const BezierCurveView view =
          boundary.pieces[loop.first_piece + k].bezier.view();
      // One more for the gap to the next piece.
      segments = SaturatingSum(segments, BezierCurvePointBound(view, epsilon));
    }
  }
  return segments;
}

// CheckSegmentCount refuses polylines of more than kMaxFaceBoundarySegments
// segments, from the tessellation's a-priori bound, before any is made.
absl::Status CheckSegmentCount(const FaceBoundary& boundary) {
  const uint64_t segments = SegmentBound(boundary);
  if (segments <= kMaxFaceBoundarySegments) return absl::OkStatus();
  return ExhaustedFieldError(
      boundary.loops.size() > 1 ? "holes" : "outer",
      absl::StrCat("the loops' polylines would need up to ", segments,
                   " segments, more than ", kMaxFaceBoundarySegments));
}

// AddLoopSegments tessellates one loop into boundary->segments, closing
// the gaps between pieces with exact segments.
absl::Status AddLoopSegments(int loop_index, FaceBoundary* boundary,
                             const CancellationToken* cancel) {
  BoundaryLoop& loop = boundary->loops[loop_index];
  loop.epsilon = LoopEpsilon(*boundary, loop);
  loop.first_segment = static_cast<uint32_t>(boundary->segments.size());
  for (int k = 0; k < loop.piece_count; ++k) {
    const int index = loop.first_piece + k;
    const TrimPiece& piece = boundary->pieces[index];
    const TrimPiece& next =
        boundary->pieces[loop.first_piece + (k + 1) % loop.piece_count];
    const bool linear = piece.bezier.coordinates.size() <= 4;
    ASSIGN_OR_RETURN(Polyline polyline,
                     TessellateBezierCurve(piece.bezier.view(), loop.epsilon,
                                           kMaxFaceBoundarySegments, cancel));
    const size_t n = polyline.parameters.size();
    for (size_t r = 0; r + 1 < n; ++r) {
      const Point2 a =
          r == 0 ? piece.first
                 : Point2{polyline.points[2 * r], polyline.points[2 * r + 1]};
      const Point2 b = r + 2 == n ? piece.last
                                  : Point2{polyline.points[2 * r + 2],
                                           polyline.points[2 * r + 3]};
      boundary->segments.push_back({.a = a,
                                    .b = b,
                                    .s0 = polyline.parameters[r],
                                    .s1 = polyline.parameters[r + 1],
                                    .epsilon = linear ? 0.0 : loop.epsilon,
                                    .piece = index,
                                    .loop = loop_index});
    }
    if (piece.last != next.first) {
      boundary->segments.push_back({.a = piece.last,
                                    .b = next.first,
                                    .epsilon = 0.0,
                                    .piece = -1,
                                    .loop = loop_index});
    }
  }
  loop.segment_count =
      static_cast<uint32_t>(boundary->segments.size()) - loop.first_segment;
  loop.box = Box2{};
  for (uint32_t k = 0; k < loop.segment_count; ++k) {
    const BoundarySegment& s = boundary->segments[loop.first_segment + k];
    loop.box.Add(s.a);
    loop.box.Add(s.b);
  }
  const double e = loop.epsilon;
  loop.box = {.lo = {loop.box.lo[0] - e, loop.box.lo[1] - e},
              .hi = {loop.box.hi[0] + e, loop.box.hi[1] + e}};
  return absl::OkStatus();
}

// The cells a segment's box, widened by its bound, meets.
struct CellRange {
  int c0, c1, r0, r1;
};

CellRange CellsOf(const SegmentGrid& grid, const BoundarySegment& s) {
  const double e = s.epsilon;
  return {grid.Column(std::min(s.a[0], s.b[0]) - e),
          grid.Column(std::max(s.a[0], s.b[0]) + e),
          grid.Row(std::min(s.a[1], s.b[1]) - e),
          grid.Row(std::max(s.a[1], s.b[1]) + e)};
}

uint64_t GridEntries(const SegmentGrid& grid,
                     const std::vector<BoundarySegment>& segments) {
  uint64_t entries = 0;
  for (const BoundarySegment& s : segments) {
    const CellRange r = CellsOf(grid, s);
    entries += static_cast<uint64_t>(r.c1 - r.c0 + 1) * (r.r1 - r.r0 + 1);
  }
  return entries;
}

// SortRows orders every row both ways, grouped by loop, and lists its
// loops' runs (SegmentGrid).
void SortRows(const std::vector<BoundarySegment>& segments, SegmentGrid& grid) {
  const auto largest_u = [&segments](uint32_t i) {
    return std::max(segments[i].a[0], segments[i].b[0]);
  };
  const auto smallest_u = [&segments](uint32_t i) {
    return std::min(segments[i].a[0], segments[i].b[0]);
  };
  grid.leftward = grid.rightward;
  grid.run_start.assign(1, 0);
  grid.runs.clear();
  for (int r = 0; r < grid.rows; ++r) {
    const auto from = static_cast<ptrdiff_t>(grid.row_start[r]);
    const auto to = static_cast<ptrdiff_t>(grid.row_start[r + 1]);
    std::sort(grid.rightward.begin() + from, grid.rightward.begin() + to,
              [&](uint32_t x, uint32_t y) {
                if (segments[x].loop != segments[y].loop) {
                  return segments[x].loop < segments[y].loop;
                }
                return largest_u(x) > largest_u(y);
              });
    std::sort(grid.leftward.begin() + from, grid.leftward.begin() + to,
              [&](uint32_t x, uint32_t y) {
                if (segments[x].loop != segments[y].loop) {
                  return segments[x].loop < segments[y].loop;
                }
                return smallest_u(x) < smallest_u(y);
              });
    for (auto k = from; k < to; ++k) {
      const int32_t loop = segments[grid.rightward[k]].loop;
      if (k == from || grid.runs.back().loop != loop) {
        grid.runs.push_back({.loop = loop,
                             .begin = static_cast<uint32_t>(k),
                             .end = static_cast<uint32_t>(k)});
      }
      grid.runs.back().end = static_cast<uint32_t>(k + 1);
    }
    grid.run_start.push_back(static_cast<uint32_t>(grid.runs.size()));
  }
}

// FillCells lists every segment in the cells its widened box meets, and in
// the rows its v-range meets (horizontal segments never cross a ray along
// u and stay out of the rows).
void FillGrid(const std::vector<BoundarySegment>& segments, SegmentGrid& grid) {
  const size_t cells = static_cast<size_t>(grid.columns) * grid.rows;
  grid.cell_start.assign(cells + 1, 0);
  grid.row_start.assign(static_cast<size_t>(grid.rows) + 1, 0);
  const auto each = [&](auto&& add_cell, auto&& add_row) {
    for (uint32_t i = 0; i < segments.size(); ++i) {
      const BoundarySegment& s = segments[i];
      const CellRange r = CellsOf(grid, s);
      for (int row = r.r0; row <= r.r1; ++row) {
        for (int c = r.c0; c <= r.c1; ++c) {
          add_cell(static_cast<size_t>(row) * grid.columns + c, i);
        }
      }
      if (s.a[1] == s.b[1]) continue;
      const int v0 = grid.Row(std::min(s.a[1], s.b[1]));
      const int v1 = grid.Row(std::max(s.a[1], s.b[1]));
      for (int row = v0; row <= v1; ++row) add_row(row, i);
    }
  };
  each([&](size_t cell, uint32_t) { ++grid.cell_start[cell + 1]; },
       [&](int row, uint32_t) { ++grid.row_start[row + 1]; });
  for (size_t c = 0; c < cells; ++c) {
    grid.cell_start[c + 1] += grid.cell_start[c];
  }
  for (int r = 0; r < grid.rows; ++r)
    grid.row_start[r + 1] += grid.row_start[r];
  grid.cell_segments.resize(grid.cell_start[cells]);
  grid.rightward.resize(grid.row_start[grid.rows]);
  std::vector<uint32_t> cell_fill(grid.cell_start.begin(),
                                  grid.cell_start.end() - 1);
  std::vector<uint32_t> row_fill(grid.row_start.begin(),
                                 grid.row_start.end() - 1);
  each([&](size_t cell,
           uint32_t i) { grid.cell_segments[cell_fill[cell]++] = i; },
       [&](int row, uint32_t i) { grid.rightward[row_fill[row]++] = i; });
  SortRows(segments, grid);
}

// The columns and rows of the finest grid for `segments` segments: about
// two segments per cell, with cells of the domain's aspect.
std::pair<int, int> GridSides(const SurfaceDomain& d, uint64_t segments) {
  const double width = d.u_end - d.u_start;
  const double height = d.v_end - d.v_start;
  const double cells = std::max(1.0, 2.0 * static_cast<double>(segments));
  const double aspect = width / height;
  // Clamped as a double: an extreme aspect would not fit an int.
  const auto side = [](double wanted) {
    if (!(wanted >= 1.0)) return 1;
    return static_cast<int>(
        std::min(std::ceil(wanted), static_cast<double>(kMaxGridSide)));
  };
  return {side(std::sqrt(cells * aspect)), side(std::sqrt(cells / aspect))};
}

// BuildGrid sizes the grid by GridSides, coarser while its entries would
// exceed GridEntryLimit.
void BuildGrid(FaceBoundary* boundary) {
  const SurfaceDomain& d = boundary->domain;
  auto [columns, rows] = GridSides(d, boundary->segments.size());
  const uint64_t limit = GridEntryLimit(boundary->segments.size());
  SegmentGrid& grid = boundary->grid;
  while (true) {
    grid.u_start = d.u_start;
    grid.v_start = d.v_start;
    grid.columns = columns;
    grid.rows = rows;
    grid.cell_u = (d.u_end - d.u_start) / columns;
    grid.cell_v = (d.v_end - d.v_start) / rows;
    if ((columns == 1 && rows == 1) ||
        GridEntries(grid, boundary->segments) <= limit) {
      break;
    }
    columns = std::max(1, columns / 2);
    rows = std::max(1, rows / 2);
  }
  FillGrid(boundary->segments, grid);
}

}  // namespace

int SegmentGrid::Column(double u) const {
  const double x = std::floor((u - u_start) / cell_u);
  if (!(x >= 0.0)) return 0;
  return x >= columns ? columns - 1 : static_cast<int>(x);
}

int SegmentGrid::Row(double v) const {
  const double y = std::floor((v - v_start) / cell_v);
  if (!(y >= 0.0)) return 0;
  return y >= rows ? rows - 1 : static_cast<int>(y);
}

absl::StatusOr<uint64_t> BoundaryPolylineBytes(const FaceBoundary& boundary) {
  RETURN_IF_ERROR(CheckSegmentCount(boundary));
  const uint64_t segments = SegmentBound(boundary);
  // The largest polyline of one piece, made and dropped in turn: its
  // parameters and points (TessellateBezierCurve, 2D).
  uint64_t largest_piece = 0;
  for (const BoundaryLoop& loop : boundary.loops) {
    const double epsilon = LoopEpsilon(boundary, loop);
    for (int k = 0; k < loop.piece_count; ++k) {
      largest_piece = std::max<uint64_t>(
          largest_piece,
          BezierCurvePointBound(
              boundary.pieces[loop.first_piece + k].bezier.view(), epsilon));
    }
  }
  const auto [columns, rows] = GridSides(boundary.domain, segments);
  const uint64_t cells =
      static_cast<uint64_t>(columns) * static_cast<uint64_t>(rows);
  // Segments grow by push_back: up to twice their count. Each grid entry is
  // in cell_segments, and at most once in each row order; the fill
  // counters copy the starts.
  return 2 * segments * sizeof(BoundarySegment) +
         3 * GridEntryLimit(segments) * sizeof(uint32_t) +
         2 * (cells + static_cast<uint64_t>(rows) + 2) * sizeof(uint32_t) +
         largest_piece * 3 * sizeof(double);
}

absl::Status BuildBoundaryPolylines(FaceBoundary* boundary,
                                    const CancellationToken* cancel) {
  RETURN_IF_ERROR(CheckSegmentCount(*boundary));
  for (size_t l = 0; l < boundary->loops.size(); ++l) {
    RETURN_IF_ERROR(AddLoopSegments(static_cast<int>(l), boundary, cancel));
    RETURN_IF_ERROR(CheckCancelled(cancel));
  }
  if (boundary->segments.size() > kMaxFaceBoundarySegments) {
    return ExhaustedFieldError(
        "holes",
        absl::StrCat("the loops' polylines have ", boundary->segments.size(),
                     " segments, more than ", kMaxFaceBoundarySegments));
  }
  BuildGrid(boundary);
  return CheckCancelled(cancel);
}

}  // namespace freeform::internal
