// TessellatePlanned of mesh.h: the pieces of a MeshPlan cut from their
// surfaces, meshed over their grids and rings, evaluated, and welded.
// Every array the builder keeps is sized from the plan before it is filled
// and the mesh is made in place of the builder's arrays, so its peak memory
// is known before it starts (PlannedMeshBytes).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "absl/hash/hash.h"
#include "absl/status/status.h"
#include "freeform/core/mesh.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/surface_output.h"
#include "meshing/mesh_plan.h"
#include "meshing/mesh_ring.h"

namespace freeform {
namespace {

using internal::EdgePlan;
using internal::kBottom;
using internal::kLeft;
using internal::kRight;
using internal::kTop;
using internal::PiecePlan;
using Point3 = std::array<double, 3>;

// A place in one piece's parameter square and the vertex there.
struct Sample {
  uint32_t vertex = 0;
  double u = 0.0;
  double v = 0.0;
};

// Where a vertex was evaluated: a piece and (s, t) in its square.
struct VertexSource {
  uint32_t piece = 0;
  double u = 0.0;
  double v = 0.0;
};

double Norm3(double x, double y, double z) {
  return std::sqrt(x * x + y * y + z * z);
}

// Vertices are evaluated this many at a time, so the evaluator's buffers
// stay small however large a piece's grid is.
constexpr size_t kEvaluationBatch = 4096;

// Bytes of the evaluator's buffers for one batch: the (u, v) pairs, the
// first partials (3 values each) and normals, and for degenerate points
// the second partials (6) and their normals, their (u, v) and indices.
constexpr uint64_t kEvaluationBatchBytes =
    kEvaluationBatch * 8 * (2 + 3 * 3 + 3 + 6 * 3 + 3 + 2 + 1);

// What one heap block costs beyond its bytes: glibc's header and rounding.
constexpr uint64_t kBlockOverhead = 32;

// Bytes of a node of the builder's std::map of corner points.
constexpr uint64_t kCornerNodeBytes = 96;

// WeldSlots returns the slots of the welding table of `count` vertices: a
// power of two at least twice the count, so at most half are used.
size_t WeldSlots(size_t count) {
  size_t slots = 16;
  while (slots < 2 * count) slots *= 2;
  return slots;
}

// The mesh under construction, before evaluation and welding.
class MeshBuilder {
 public:
  MeshBuilder(const MeshPlan& plan, CornerAttributes corner_attributes)
      : plan_(plan),
        keep_corners_(corner_attributes == CornerAttributes::kMake),
        corners_(plan.pieces.size()),
        edge_vertices_(plan.edges.size()) {}

  // Decompose cuts every surface into its Bezier pieces.
  absl::Status Decompose(const CancellationToken* cancel);
  // Build creates the vertices and triangles of every piece.
  absl::Status Build(const CancellationToken* cancel);
  // Evaluate computes positions and normals on each vertex's piece.
  absl::Status Evaluate(const CancellationToken* cancel);
  // Finish welds coincident vertices and returns the mesh.
  Mesh Finish();

 private:
  BezierSurfaceView PieceView(uint32_t piece) const {
    const PiecePlan& plan = plan_.pieces[piece];
    return (*decompositions_)[plan.surface]
        .pieces.patches[plan.piece]
        .bezier_view();
  }
  std::array<double, 2> SurfaceParameters(uint32_t piece, double s,
                                          double t) const {
    const PiecePlan& plan = plan_.pieces[piece];
    return SurfacePieceParameters((*decompositions_)[plan.surface], plan.piece,
                                  s, t);
  }
  uint32_t CornerVertex(uint32_t piece, int corner);
  uint32_t NewVertex(uint32_t piece, double u, double v);
  std::vector<Sample> SideSamples(uint32_t piece, int side);
  void AddTriangle(uint32_t piece, const Sample& a, const Sample& b,
                   const Sample& c);
  void ZipRing(uint32_t piece, const std::vector<uint32_t>& grid);
  void BuildPiece(uint32_t piece);

  const MeshPlan& plan_;
  // Whether the mesh gets Mesh::triangle_patch and Mesh::corner_uv.
  const bool keep_corners_;
  // The plan's pieces when it holds them, else owned_decompositions_.
  const std::vector<SurfaceDecomposition>* decompositions_ = nullptr;
  std::vector<SurfaceDecomposition> owned_decompositions_;
  // Build's own: per piece its corner vertices (0,0), (1,0), (1,1), (0,1);
  // per edge segments + 1 vertices in its canonical direction (created by
  // the first piece that uses it); the vertex of every corner point.
  std::vector<std::array<uint32_t, 4>> corners_;
  std::vector<std::vector<uint32_t>> edge_vertices_;
  std::map<Point3, uint32_t> corner_index_;
  // Per vertex (at most the plan's), and per triangle.
  std::vector<VertexSource> sources_;
  std::vector<double> positions_;
  std::vector<double> normals_;
  std::vector<uint32_t> triangles_;
  std::vector<uint32_t> triangle_piece_;
  std::vector<double> corner_uv_;
};

absl::Status MeshBuilder::Decompose(const CancellationToken* cancel) {
  decompositions_ = &owned_decompositions_;
  if (!plan_.decompositions.empty()) {
    decompositions_ = &plan_.decompositions;
    return absl::OkStatus();
  }
  owned_decompositions_.reserve(plan_.surfaces.size());
  for (const Surface& surface : plan_.surfaces) {
    absl::StatusOr<SurfaceDecomposition> decomposition =
        DecomposeSurface(surface, cancel);
    if (!decomposition.ok()) return decomposition.status();
    owned_decompositions_.push_back(*std::move(decomposition));
  }
  return absl::OkStatus();
}

uint32_t MeshBuilder::NewVertex(uint32_t piece, double u, double v) {
  sources_.push_back({piece, u, v});
  return static_cast<uint32_t>(sources_.size() - 1);
}

// CornerVertex returns the vertex at a corner of a piece: the corner
// control point, which the piece interpolates, shared by every piece with a
// corner there.
uint32_t MeshBuilder::CornerVertex(uint32_t piece, int corner) {
  const ControlNetView& net = PieceView(piece).control_net;
  const int i = corner == 1 || corner == 2 ? net.count_u - 1 : 0;
  const int j = corner >= 2 ? net.count_v - 1 : 0;
  const double* p = net.point(i, j);
  auto [it, inserted] = corner_index_.emplace(
      Point3{p[0], p[1], p[2]}, static_cast<uint32_t>(sources_.size()));
  if (inserted) NewVertex(piece, i == 0 ? 0.0 : 1.0, j == 0 ? 0.0 : 1.0);
  return it->second;
}

// SideSamples returns the samples of a side (SidePoint m = 0..n, n =
// SideSegments). The vertices belong to the side's edge, numbered in its
// canonical direction, so pieces that share the edge share them; a
// collapsed side is one vertex.
std::vector<Sample> MeshBuilder::SideSamples(uint32_t piece, int side) {
  const PiecePlan& plan = plan_.pieces[piece];
  const std::array<uint32_t, 4>& corner = corners_[piece];
  const EdgePlan& edge = plan_.edges[static_cast<size_t>(plan.edge[side])];
  std::vector<uint32_t>& vertices =
      edge_vertices_[static_cast<size_t>(plan.edge[side])];
  const bool reversed = plan.reversed[side];
  const int start_corner = side == kBottom  ? 0
                           : side == kRight ? 1
                           : side == kTop   ? 3
                                            : 0;
  const int end_corner = side == kBottom  ? 1
                         : side == kRight ? 2
                         : side == kTop   ? 2
                                          : 3;
  const int n = internal::SideSegments(plan, edge, side);
  if (vertices.empty() && !edge.collapsed) {
    vertices.resize(static_cast<size_t>(n) + 1);
    vertices.front() = reversed ? corner[end_corner] : corner[start_corner];
    vertices.back() = reversed ? corner[start_corner] : corner[end_corner];
    for (int k = 1; k < n; ++k) {
      const auto [u, v] = internal::SidePoint(side, reversed ? n - k : k, n);
      vertices[k] = NewVertex(piece, u, v);
    }
  }
  std::vector<Sample> samples(static_cast<size_t>(n) + 1);
  for (int m = 0; m <= n; ++m) {
    const auto [u, v] = internal::SidePoint(side, m, n);
    const uint32_t vertex =
        edge.collapsed ? corner[start_corner] : vertices[reversed ? n - m : m];
    samples[m] = Sample{vertex, u, v};
  }
  return samples;
}

void MeshBuilder::AddTriangle(uint32_t piece, const Sample& a, const Sample& b,
                              const Sample& c) {
  if (a.vertex == b.vertex || b.vertex == c.vertex || a.vertex == c.vertex) {
    return;
  }
  for (const Sample* s : {&a, &b, &c}) triangles_.push_back(s->vertex);
  if (!keep_corners_) return;
  for (const Sample* s : {&a, &b, &c}) {
    corner_uv_.push_back(s->u);
    corner_uv_.push_back(s->v);
  }
  triangle_piece_.push_back(piece);
}

// ZipRing triangulates the ring between the side samples and the interior
// grid `grid` of a piece (ZipLoops).
void MeshBuilder::ZipRing(uint32_t piece, const std::vector<uint32_t>& grid) {
  const PiecePlan& plan = plan_.pieces[piece];
  std::array<std::vector<Sample>, 4> sides;
  for (int side = 0; side < 4; ++side) sides[side] = SideSamples(piece, side);
  const std::vector<internal::OuterPlace> outer =
      internal::OuterLoop(plan, plan_.edges);
  const std::vector<internal::InnerPlace> inner =
      internal::InnerLoop(plan.grid_u, plan.grid_v);
  auto outer_sample = [&](size_t k) {
    return sides[outer[k].side][static_cast<size_t>(outer[k].m)];
  };
  auto inner_sample = [&](size_t k) {
    const internal::InnerPlace& place = inner[k];
    return Sample{grid[static_cast<size_t>(place.i - 1) * (plan.grid_v - 1) +
                       static_cast<size_t>(place.j - 1)],
                  place.u, place.v};
  };
  internal::ZipLoops(outer, inner, [&](size_t i, size_t j, bool outer_step) {
    if (outer_step) {
      AddTriangle(piece, outer_sample(i), outer_sample(i + 1), inner_sample(j));
    } else {
      AddTriangle(piece, outer_sample(i), inner_sample(j + 1), inner_sample(j));
    }
  });
}

void MeshBuilder::BuildPiece(uint32_t piece) {
  for (int corner = 0; corner < 4; ++corner) {
    corners_[piece][corner] = CornerVertex(piece, corner);
  }
  const int nu = plan_.pieces[piece].grid_u;
  const int nv = plan_.pieces[piece].grid_v;
  std::vector<uint32_t> grid;
  grid.reserve(static_cast<size_t>(nu - 1) * (nv - 1));
  for (int i = 1; i < nu; ++i) {
    for (int j = 1; j < nv; ++j) {
      grid.push_back(NewVertex(piece, static_cast<double>(i) / nu,
                               static_cast<double>(j) / nv));
    }
  }
  ZipRing(piece, grid);
  auto node = [&](int i, int j) {
    return Sample{grid[static_cast<size_t>(i - 1) * (nv - 1) + (j - 1)],
                  static_cast<double>(i) / nu, static_cast<double>(j) / nv};
  };
  for (int i = 1; i + 1 < nu; ++i) {
    for (int j = 1; j + 1 < nv; ++j) {
      AddTriangle(piece, node(i, j), node(i + 1, j), node(i + 1, j + 1));
      AddTriangle(piece, node(i, j), node(i + 1, j + 1), node(i, j + 1));
    }
  }
}

absl::Status MeshBuilder::Build(const CancellationToken* cancel) {
  // The plan's sizes bound what the pieces make (before welding).
  sources_.reserve(plan_.size.vertices);
  triangles_.reserve(3 * plan_.size.triangles);
  if (keep_corners_) {
    triangle_piece_.reserve(plan_.size.triangles);
    corner_uv_.reserve(6 * plan_.size.triangles);
  }
  for (uint32_t piece = 0; piece < plan_.pieces.size(); ++piece) {
    RETURN_IF_ERROR(CheckCancelled(cancel));
    BuildPiece(piece);
  }
  // Only the pieces' construction needs these.
  std::vector<std::array<uint32_t, 4>>().swap(corners_);
  std::vector<std::vector<uint32_t>>().swap(edge_vertices_);
  std::map<Point3, uint32_t>().swap(corner_index_);
  return absl::OkStatus();
}

absl::Status MeshBuilder::Evaluate(const CancellationToken* cancel) {
  // The vertices piece by piece (a counting sort): vertex order[k] for k in
  // [first[p], first[p + 1]) belongs to piece p.
  const size_t pieces = plan_.pieces.size();
  std::vector<uint32_t> first(pieces + 1, 0);
  for (const VertexSource& source : sources_) ++first[source.piece + 1];
  for (size_t piece = 0; piece < pieces; ++piece) {
    first[piece + 1] += first[piece];
  }
  std::vector<uint32_t> order(sources_.size());
  {
    std::vector<uint32_t> next(first.begin(), first.end() - 1);
    for (uint32_t r = 0; r < sources_.size(); ++r) {
      order[next[sources_[r].piece]++] = r;
    }
  }
  positions_.resize(3 * sources_.size());
  normals_.resize(3 * sources_.size());
  std::vector<double> uv;
  uv.reserve(2 * kEvaluationBatch);
  internal::PieceEvaluator evaluator;
  for (uint32_t piece = 0; piece < pieces; ++piece) {
    for (size_t start = first[piece]; start < first[piece + 1];
         start += kEvaluationBatch) {
      RETURN_IF_ERROR(CheckCancelled(cancel));
      const size_t end =
          std::min<size_t>(first[piece + 1], start + kEvaluationBatch);
      uv.clear();
      for (size_t k = start; k < end; ++k) {
        uv.push_back(sources_[order[k]].u);
        uv.push_back(sources_[order[k]].v);
      }
      RETURN_IF_ERROR(evaluator.Evaluate(PieceView(piece), uv));
      for (size_t k = start; k < end; ++k) {
        std::copy_n(&evaluator.positions()[3 * (k - start)], 3,
                    &positions_[3 * order[k]]);
        std::copy_n(&evaluator.normals()[3 * (k - start)], 3,
                    &normals_[3 * order[k]]);
      }
    }
  }
  return absl::OkStatus();
}

// CellIndex converts a cell coordinate to an integer, saturated at +-2^62
// (a NaN to 0): a vertex far out of the geometry's scale (an epsilon of
// 1e-300 against coordinates near 1) would overflow int64. Vertices it
// merges into one cell are still welded only within epsilon of each other.
int64_t CellIndex(double scaled) {
  constexpr double kLargest = 4611686018427387904.0;  // 2^62
  if (scaled >= kLargest) return int64_t{1} << 62;
  if (scaled <= -kLargest) return -(int64_t{1} << 62);
  if (!(scaled == scaled)) return 0;
  return static_cast<int64_t>(scaled);
}

// WeldMap returns, for every vertex, an earlier unwelded vertex within
// `epsilon` of it (itself when none), found by hashing into cells of 4
// epsilon: a vertex within epsilon of another lies in the same cell or in a
// neighbouring one across a cell side it is within epsilon of, so most
// vertices look into one cell only. The cells are an open-addressing table
// (linear probing) of WeldSlots(count) vertex numbers, each slot the first
// vertex of a cell, whose position gives the cell back; next[r] is the
// vertex after r in its cell.
std::vector<uint32_t> WeldMap(const std::vector<double>& positions,
                              double epsilon) {
  const size_t count = positions.size() / 3;
  const double cell_size = 4 * epsilon;
  using Cell = std::array<int64_t, 3>;
  auto cell_of = [&](size_t r) {
    Cell cell;
    for (int x = 0; x < 3; ++x) {
      cell[x] = CellIndex(std::floor(positions[3 * r + x] / cell_size));
    }
    return cell;
  };
  constexpr uint32_t kNone = UINT32_MAX;
  std::vector<uint32_t> slots(WeldSlots(count), kNone);
  const size_t mask = slots.size() - 1;
  // The slot of `cell`: the one holding its first vertex, or the empty one
  // where it goes.
  auto slot_of = [&](const Cell& cell) -> uint32_t& {
    const size_t hash = absl::Hash<Cell>{}(cell);
    size_t at = hash & mask;
    while (slots[at] != kNone && cell_of(slots[at]) != cell) {
      at = (at + 1) & mask;
    }
    return slots[at];
  };
  std::vector<uint32_t> target(count);
  std::vector<uint32_t> next(count, kNone);
  for (size_t r = 0; r < count; ++r) {
    target[r] = static_cast<uint32_t>(r);
    const double* p = &positions[3 * r];
    const Cell cell = cell_of(r);
    // Per axis the cells to search: its own, and the neighbour across a
    // side within epsilon.
    std::array<std::array<int, 2>, 3> steps;
    std::array<int, 3> step_count;
    for (int x = 0; x < 3; ++x) {
      const double offset = p[x] - std::floor(p[x] / cell_size) * cell_size;
      steps[x] = {0, 0};
      step_count[x] = 1;
      if (offset <= epsilon) steps[x][step_count[x]++] = -1;
      if (offset >= cell_size - epsilon) steps[x][step_count[x]++] = 1;
    }
    bool found = false;
    for (int i = 0; i < step_count[0] && !found; ++i) {
      for (int j = 0; j < step_count[1] && !found; ++j) {
        for (int k = 0; k < step_count[2] && !found; ++k) {
          for (uint32_t other =
                   slot_of({cell[0] + steps[0][i], cell[1] + steps[1][j],
                            cell[2] + steps[2][k]});
               other != kNone; other = next[other]) {
            const double* q = &positions[3 * other];
            if (Norm3(p[0] - q[0], p[1] - q[1], p[2] - q[2]) <= epsilon) {
              target[r] = other;
              found = true;
              break;
            }
          }
        }
      }
    }
    if (found) continue;
    uint32_t& head = slot_of(cell);
    next[r] = head;
    head = static_cast<uint32_t>(r);
  }
  return target;
}

// Finish makes the mesh in place of the builder's arrays: a kept vertex's
// new number is never above its old one, nor a kept triangle's, so each
// array is compacted from the front and moved into the mesh.
Mesh MeshBuilder::Finish() {
  const double epsilon = std::max(1e-12 * plan_.scale, 1e-300);
  // target[r] becomes vertex r's number in the mesh: its own for a kept
  // vertex, else that of the earlier kept vertex it was welded to.
  std::vector<uint32_t> target = WeldMap(positions_, epsilon);
  Mesh mesh;
  mesh.patch.reserve(target.size());
  mesh.uv.reserve(2 * target.size());
  size_t kept = 0;
  for (size_t r = 0; r < target.size(); ++r) {
    if (target[r] != r) {
      target[r] = target[target[r]];
      continue;
    }
    target[r] = static_cast<uint32_t>(kept);
    if (kept != r) {
      std::copy_n(&positions_[3 * r], 3, &positions_[3 * kept]);
      std::copy_n(&normals_[3 * r], 3, &normals_[3 * kept]);
    }
    const VertexSource& source = sources_[r];
    mesh.patch.push_back(plan_.pieces[source.piece].surface);
    const std::array<double, 2> uv =
        SurfaceParameters(source.piece, source.u, source.v);
    mesh.uv.insert(mesh.uv.end(), uv.begin(), uv.end());
    ++kept;
  }
  std::vector<VertexSource>().swap(sources_);
  positions_.resize(3 * kept);
  normals_.resize(3 * kept);
  mesh.vertices = std::move(positions_);
  mesh.normals = std::move(normals_);
  size_t made = 0;
  for (size_t t = 0; 3 * t < triangles_.size(); ++t) {
    std::array<uint32_t, 3> corners;
    for (int k = 0; k < 3; ++k) corners[k] = target[triangles_[3 * t + k]];
    if (corners[0] == corners[1] || corners[1] == corners[2] ||
        corners[0] == corners[2]) {
      continue;  // collapsed by welding
    }
    std::copy(corners.begin(), corners.end(), &triangles_[3 * made]);
    if (keep_corners_) {
      const uint32_t piece = triangle_piece_[t];
      triangle_piece_[made] = plan_.pieces[piece].surface;
      for (int k = 0; k < 3; ++k) {
        const std::array<double, 2> uv = SurfaceParameters(
            piece, corner_uv_[6 * t + 2 * k], corner_uv_[6 * t + 2 * k + 1]);
        std::copy(uv.begin(), uv.end(), &corner_uv_[6 * made + 2 * k]);
      }
    }
    ++made;
  }
  triangles_.resize(3 * made);
  mesh.triangles = std::move(triangles_);
  if (keep_corners_) {
    triangle_piece_.resize(made);
    corner_uv_.resize(6 * made);
    mesh.triangle_patch = std::move(triangle_piece_);
    mesh.corner_uv = std::move(corner_uv_);
  }
  return mesh;
}

}  // namespace

absl::StatusOr<Mesh> TessellatePlanned(const MeshPlan& plan,
                                       const CancellationToken* cancel,
                                       CornerAttributes corner_attributes) {
  MeshBuilder builder(plan, corner_attributes);
  absl::Status status = builder.Decompose(cancel);
  if (status.ok()) status = builder.Build(cancel);
  if (status.ok()) status = builder.Evaluate(cancel);
  if (!status.ok()) return status;
  return builder.Finish();
}

MeshMemory PlannedMeshMemory(const MeshPlan& plan,
                             CornerAttributes corner_attributes) {
  using internal::InnerPlace;
  using internal::OuterPlace;
  const uint64_t vertices = plan.size.vertices;
  const uint64_t triangles = plan.size.triangles;
  const uint64_t pieces = plan.pieces.size();
  const uint64_t edges = plan.edges.size();
  const bool corners = corner_attributes == CornerAttributes::kMake;
  // The Bezier pieces: their values, and per piece its SurfaceData (in a
  // vector grown by doubling) and its arrays' blocks. (The plan's sum
  // saturates; the sizes below stay far from overflowing once it is
  // within any memory.)
  if (plan.piece_values > (uint64_t{1} << 56) ||
      vertices > (uint64_t{1} << 40) || triangles > (uint64_t{1} << 40)) {
    return {UINT64_MAX, UINT64_MAX, UINT64_MAX};
  }
  const uint64_t piece_bytes =
      8 * plan.piece_values +
      pieces * (2 * sizeof(SurfaceData) + 2 * kBlockOverhead);
  const bool plan_holds_pieces = !plan.decompositions.empty();
  MeshMemory memory;
  memory.plan = pieces * sizeof(PiecePlan) + edges * sizeof(EdgePlan) +
                (plan_holds_pieces ? piece_bytes : 0);
  // The mesh: per vertex its position, normal, (u, v) and surface, per
  // triangle its corners (and its surface and corners' (u, v)).
  memory.mesh =
      vertices * (6 * sizeof(double) + 2 * sizeof(double) + sizeof(uint32_t)) +
      triangles * (3 * sizeof(uint32_t) +
                   (corners ? sizeof(uint32_t) + 6 * sizeof(double) : 0));
  // From Build to the end: the vertices' sources and the triangles (with
  // their pieces and corner parameters), sized from the plan.
  const uint64_t held =
      vertices * sizeof(VertexSource) + triangles * 3 * sizeof(uint32_t) +
      (corners ? triangles * (sizeof(uint32_t) + 6 * sizeof(double)) : 0);
  // Build alone: the corners and side vertices of every piece and edge,
  // the map of corner points, and the largest piece's grid and ring.
  uint64_t build =
      pieces * (sizeof(std::array<uint32_t, 4>) + 4 * kCornerNodeBytes) +
      edges * (sizeof(std::vector<uint32_t>) + kBlockOverhead);
  for (const EdgePlan& edge : plan.edges) {
    build += (static_cast<uint64_t>(edge.segments) + 1) * sizeof(uint32_t);
  }
  uint64_t largest_piece = 0;
  for (const PiecePlan& piece : plan.pieces) {
    uint64_t ring = 0;
    for (int side = 0; side < 4; ++side) {
      ring +=
          static_cast<uint64_t>(internal::SideSegments(
              piece, plan.edges[static_cast<size_t>(piece.edge[side])], side)) +
          1;
    }
    const uint64_t grid_u = static_cast<uint64_t>(piece.grid_u);
    const uint64_t grid_v = static_cast<uint64_t>(piece.grid_v);
    largest_piece = std::max(largest_piece,
                             (grid_u - 1) * (grid_v - 1) * sizeof(uint32_t) +
                                 ring * (sizeof(Sample) + sizeof(OuterPlace)) +
                                 2 * (grid_u + grid_v) * sizeof(InnerPlace));
  }
  build += largest_piece;
  // Evaluate: positions and normals, the vertices sorted by piece, and
  // one batch's evaluation.
  const uint64_t positions = vertices * 6 * sizeof(double);
  const uint64_t evaluate = positions + vertices * sizeof(uint32_t) +
                            (pieces + 1) * 2 * sizeof(uint32_t) +
                            kEvaluationBatchBytes;
  // Finish: the positions and normals (the mesh's now), every vertex's
  // target, then the welding table and the cells' chains, or afterwards
  // the mesh's surfaces and (u, v).
  const uint64_t finish =
      positions + vertices * sizeof(uint32_t) +
      std::max<uint64_t>(
          vertices * sizeof(uint32_t) + WeldSlots(vertices) * sizeof(uint32_t),
          vertices * (sizeof(uint32_t) + 2 * sizeof(double)));
  const uint64_t building = held + std::max({build, evaluate, finish});
  // Every large array ends in a partly used page.
  constexpr uint64_t kLargeArrays = 24;
  // Without the plan's pieces, Decompose cuts them first, and cutting a
  // surface holds its knot-refined nets beside them (InsertSurfaceKnots in
  // u, then in v): at most three times the pieces.
  memory.tessellation =
      kLargeArrays * 4096 +
      (plan_holds_pieces ? building
                         : std::max(3 * piece_bytes, piece_bytes + building));
  return memory;
}

absl::StatusOr<Mesh> TessellateSurfaces(absl::Span<const Surface> surfaces,
                                        const MeshOptions& options,
                                        const CancellationToken* cancel) {
  absl::StatusOr<std::shared_ptr<const MeshPlan>> plan =
      PlanMesh(surfaces, options, cancel);
  if (!plan.ok()) return plan.status();
  return TessellatePlanned(**plan, cancel);
}

}  // namespace freeform
