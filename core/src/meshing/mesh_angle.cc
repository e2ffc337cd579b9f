// RefineNormalAngles of mesh_plan.h: the normal-angle limit of PlanMesh
// (docs/references.md, 'Meshing surfaces within a tolerance').
//
// The plan fixes every edge of the mesh before any vertex is made: the
// edges of each piece's interior grid, the segments of its sides, and the
// zipper between them (mesh_ring.h). So the limit is checked on exactly
// those edges, with the unit normals the builder gives their ends (the
// piece's normals at their (u, v), limits from inside at degenerate
// points). Where an edge's normals differ by more than the limit, a count
// is raised by the ratio of the angle to the limit (at least kLeastGrowth,
// at most kMostGrowth): the side's segments for an edge along a side, else
// the piece's grid along u and v in proportion to how much of the turn of
// the normal each direction makes (an edge along u or v: that direction; a
// cell's diagonal: the turns along the cell's u and v sides it spans; a
// ring edge: its extent in cells times the piece's largest turn per cell
// in each direction), so a normal that turns fast along u only does not
// refine v. A raised grid raises its sides to as many segments (as the
// tolerance plan does), and every piece whose grid or sides changed is
// checked again, until no edge exceeds the limit or the vertex cap is
// reached. Counts grow geometrically, so the normals evaluated cost a small
// multiple of the final mesh's vertices.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/mesh.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "meshing/mesh_plan.h"
#include "meshing/mesh_ring.h"

namespace freeform::internal {
namespace {

// A count is multiplied by kMargin times the ratio of angle to limit
// (the angles of a smooth normal shrink in proportion to the cells), at
// least kLeastGrowth and at most kMostGrowth times in one round.
constexpr double kMargin = 1.1;
constexpr double kLeastGrowth = 1.25;
constexpr double kMostGrowth = 8.0;
// The least turn per cell a ring edge is attributed by, relative to the
// limit.
constexpr double kLeastTurn = 1e-3;
// Grid nodes evaluated at once (whole rows, at least one).
constexpr size_t kBatchNodes = 1024;
// Arithmetic per evaluated normal, for the cancellation polls.
constexpr size_t kNormalWork = 200;

// What changed in a piece since it was last checked.
enum Change : uint8_t { kGridChanged = 1, kRingChanged = 2 };

bool IsZero(const double* n) { return n[0] == 0 && n[1] == 0 && n[2] == 0; }

// CosAngle returns the cosine of the angle between unit normals a and b,
// or 1 when either is zero (the surface has no normal there; such ends are
// exempt).
double CosAngle(const double* a, const double* b) {
  if (IsZero(a) || IsZero(b)) return 1.0;
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// NormalAngle returns the angle between unit normals a and b, accurate for
// small angles too (unlike acos), or 0 when either is zero.
double NormalAngle(const double* a, const double* b) {
  if (IsZero(a) || IsZero(b)) return 0.0;
  const double cross[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                           a[0] * b[1] - a[1] * b[0]};
  return std::atan2(std::hypot(cross[0], cross[1], cross[2]),
                    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

class AngleRefiner {
 public:
  AngleRefiner(MeshPlan& plan, const MeshOptions& options,
               double& vertex_count);

  absl::Status Run(const CancellationToken* cancel);

 private:
  BezierSurfaceView PieceView(uint32_t piece) const {
    const PiecePlan& plan = plan_.pieces[piece];
    return plan_.decompositions[plan.surface]
        .pieces.patches[plan.piece]
        .bezier_view();
  }
  // RatioOf returns the ratio of the angle between the normals a and b at
  // the ends of an edge, whose cosine is `cos`, to the limit; 0 when the
  // cosine, which is cheap, shows it within the limit.
  double RatioOf(double cos, const double* a, const double* b) const {
    return cos >= cos_within_ ? 0.0 : NormalAngle(a, b) / limit_;
  }
  double Ratio(const double* a, const double* b) const {
    return RatioOf(CosAngle(a, b), a, b);
  }
  // The checks note the ratio of angle to limit of the edges over it.
  absl::Status CheckGrid(uint32_t piece, CancellationPoll& poll);
  absl::Status CheckRing(uint32_t piece, CancellationPoll& poll);
  // NoteEdge notes the ratio of an edge of a piece over the grid, for each
  // direction in proportion to its share `turn_u`, `turn_v` of the turn
  // (both zero: the whole ratio for both).
  void NoteEdge(uint32_t piece, double turn_u, double turn_v, double ratio);
  // Grow raises the counts the checks asked for; false when none.
  absl::StatusOr<bool> Grow();
  absl::Status RaiseGrid(uint32_t piece, int axis, double cells);
  absl::Status RaiseEdge(int edge, double segments);
  absl::Status AddVertices(double count);

  MeshPlan& plan_;
  const double limit_;
  // Normals whose angle has a cosine of at least this are within the limit
  // despite rounding.
  const double cos_within_;
  const size_t max_vertices_;
  double& vertex_count_;
  // The pieces that use each edge.
  std::vector<std::vector<uint32_t>> users_;
  std::vector<uint8_t> changed_;
  // The largest ratio of angle to limit noted per piece axis (u, v) and
  // per edge.
  std::vector<std::array<double, 2>> piece_ratio_;
  std::vector<double> edge_ratio_;
  // The largest angle along one cell's u and v side per piece, from its
  // last grid check.
  std::vector<std::array<double, 2>> cell_turn_;
  PieceEvaluator evaluator_;
  std::vector<double> uv_;
};

AngleRefiner::AngleRefiner(MeshPlan& plan, const MeshOptions& options,
                           double& vertex_count)
    : plan_(plan),
      limit_(options.max_normal_angle),
      cos_within_(std::cos(options.max_normal_angle) + 1e-12),
      max_vertices_(options.max_vertices),
      vertex_count_(vertex_count),
      users_(plan.edges.size()),
      changed_(plan.pieces.size(), kGridChanged | kRingChanged),
      piece_ratio_(plan.pieces.size(), {0.0, 0.0}),
      edge_ratio_(plan.edges.size(), 0.0),
      cell_turn_(plan.pieces.size(), {0.0, 0.0}) {
  for (uint32_t piece = 0; piece < plan.pieces.size(); ++piece) {
    for (const int edge : plan.pieces[piece].edge) {
      users_[static_cast<size_t>(edge)].push_back(piece);
    }
  }
}

void AngleRefiner::NoteEdge(uint32_t piece, double turn_u, double turn_v,
                            double ratio) {
  if (!(ratio > 1.0)) return;
  const double most = std::max(turn_u, turn_v);
  const double share_u = most > 0.0 ? turn_u / most : 1.0;
  const double share_v = most > 0.0 ? turn_v / most : 1.0;
  std::array<double, 2>& noted = piece_ratio_[piece];
  noted[0] = std::max(noted[0], share_u * ratio);
  noted[1] = std::max(noted[1], share_v * ratio);
}

// CheckGrid checks the edges between the interior grid nodes, row (fixed
// i) after row, evaluated kBatchNodes at a time: from node (i, j) to (i,
// j + 1), from (i - 1, j) to (i, j), and the diagonal from (i - 1, j) to
// (i, j + 1), whose turn is shared by the two before.
absl::Status AngleRefiner::CheckGrid(uint32_t piece, CancellationPoll& poll) {
  const int nu = plan_.pieces[piece].grid_u;
  const int nv = plan_.pieces[piece].grid_v;
  const size_t row = static_cast<size_t>(nv - 1);
  const int rows_per_batch =
      static_cast<int>(std::max<size_t>(1, kBatchNodes / row));
  // The least cosine along u and v, for cell_turn_.
  double least_u = 1.0, least_v = 1.0;
  // The normals of the row before the batch, then of the batch's rows.
  std::vector<double> normals;
  for (int first = 1; first < nu; first += rows_per_batch) {
    const int last = std::min(nu - 1, first + rows_per_batch - 1);
    uv_.clear();
    for (int i = first; i <= last; ++i) {
      for (int j = 1; j < nv; ++j) {
        uv_.insert(uv_.end(),
                   {static_cast<double>(i) / nu, static_cast<double>(j) / nv});
      }
    }
    RETURN_IF_ERROR(evaluator_.Evaluate(PieceView(piece), uv_));
    const bool has_previous = first > 1;
    if (has_previous) {
      normals.erase(normals.begin(), normals.end() - 3 * row);
    } else {
      normals.clear();
    }
    normals.insert(normals.end(), evaluator_.normals().begin(),
                   evaluator_.normals().end());
    for (int i = first; i <= last; ++i) {
      const size_t at = static_cast<size_t>(i - first + has_previous) * row;
      for (size_t j = 0; j < row; ++j) {
        const double* n = &normals[3 * (at + j)];
        if (j + 1 < row) {
          const double cos_v = CosAngle(n, n + 3);
          least_v = std::min(least_v, cos_v);
          NoteEdge(piece, 0.0, 1.0, RatioOf(cos_v, n, n + 3));
        }
        if (i == 1) continue;
        const double* below = n - 3 * row;
        const double cos_u = CosAngle(below, n);
        least_u = std::min(least_u, cos_u);
        NoteEdge(piece, 1.0, 0.0, RatioOf(cos_u, below, n));
        if (j + 1 < row) {
          if (const double ratio = Ratio(below, n + 3); ratio > 1.0) {
            NoteEdge(piece, NormalAngle(below, n), NormalAngle(n, n + 3),
                     ratio);
          }
        }
      }
    }
    RETURN_IF_ERROR(poll.Done(uv_.size() / 2 * kNormalWork));
  }
  cell_turn_[piece] = {std::acos(std::clamp(least_u, -1.0, 1.0)),
                       std::acos(std::clamp(least_v, -1.0, 1.0))};
  return absl::OkStatus();
}

// CheckRing checks the triangles of the ring (ZipLoops): side segments,
// which raise their edge, and zipper and inner loop edges, which raise the
// grid by their extent in cells times the piece's turn per cell.
absl::Status AngleRefiner::CheckRing(uint32_t piece, CancellationPoll& poll) {
  const PiecePlan& plan = plan_.pieces[piece];
  const std::vector<OuterPlace> outer = OuterLoop(plan, plan_.edges);
  const std::vector<InnerPlace> inner = InnerLoop(plan.grid_u, plan.grid_v);
  uv_.clear();
  for (const OuterPlace& place : outer) {
    uv_.insert(uv_.end(), {place.u, place.v});
  }
  for (const InnerPlace& place : inner) {
    uv_.insert(uv_.end(), {place.u, place.v});
  }
  RETURN_IF_ERROR(evaluator_.Evaluate(PieceView(piece), uv_));
  const absl::Span<const double> normals = evaluator_.normals();
  const std::array<double, 2>& turn = cell_turn_[piece];
  // A turn of zero (a grid too coarse to tell) counts as a small one, so
  // an edge along one direction still raises that direction only.
  const double turn_u = std::max(turn[0], kLeastTurn * limit_);
  const double turn_v = std::max(turn[1], kLeastTurn * limit_);
  auto note = [&](const auto& a, const auto& b, const double* normal_a,
                  const double* normal_b) {
    NoteEdge(piece, std::abs(a.u - b.u) * plan.grid_u * turn_u,
             std::abs(a.v - b.v) * plan.grid_v * turn_v,
             Ratio(normal_a, normal_b));
  };
  auto outer_normal = [&](size_t k) { return &normals[3 * k]; };
  auto inner_normal = [&](size_t k) {
    return &normals[3 * (outer.size() + k)];
  };
  ZipLoops(outer, inner, [&](size_t i, size_t j, bool outer_step) {
    note(outer[i], inner[j], outer_normal(i), inner_normal(j));
    if (outer_step) {
      note(outer[i + 1], inner[j], outer_normal(i + 1), inner_normal(j));
      // A side segment; a corner repeated by the next side and a collapsed
      // side (one vertex) make none.
      const int side = outer[i].side;
      const size_t edge = static_cast<size_t>(plan.edge[side]);
      if (outer[i + 1].side == side && !plan_.edges[edge].collapsed) {
        edge_ratio_[edge] = std::max(
            edge_ratio_[edge], Ratio(outer_normal(i), outer_normal(i + 1)));
      }
    } else {
      note(outer[i], inner[j + 1], outer_normal(i), inner_normal(j + 1));
      note(inner[j], inner[j + 1], inner_normal(j), inner_normal(j + 1));
    }
  });
  return poll.Done(uv_.size() / 2 * kNormalWork);
}

absl::Status AngleRefiner::AddVertices(double count) {
  vertex_count_ += count;
  if (vertex_count_ > static_cast<double>(max_vertices_) ||
      vertex_count_ >= UINT32_MAX) {
    return ExhaustedFieldError(
        "max_normal_angle",
        absl::StrCat("the mesh needs more than ", max_vertices_,
                     " vertices to hold the normal angle to ", limit_));
  }
  return absl::OkStatus();
}

absl::Status AngleRefiner::RaiseEdge(int edge, double segments) {
  EdgePlan& plan = plan_.edges[static_cast<size_t>(edge)];
  if (plan.collapsed || segments <= plan.segments) return absl::OkStatus();
  if (segments > kMaxMeshCells) return AddVertices(INFINITY);
  const double added = segments - plan.segments;
  plan.segments = static_cast<int>(segments);
  for (const uint32_t piece : users_[static_cast<size_t>(edge)]) {
    changed_[piece] |= kRingChanged;
  }
  return AddVertices(added);
}

// RaiseGrid gives a piece `cells` grid cells along u (axis 0) or v, and as
// many segments to its sides along that axis.
absl::Status AngleRefiner::RaiseGrid(uint32_t piece, int axis, double cells) {
  PiecePlan& plan = plan_.pieces[piece];
  if (cells > kMaxMeshCells) return AddVertices(INFINITY);
  const double before = (plan.grid_u - 1.0) * (plan.grid_v - 1.0);
  (axis == 0 ? plan.grid_u : plan.grid_v) = static_cast<int>(cells);
  changed_[piece] |= kGridChanged | kRingChanged;
  RETURN_IF_ERROR(
      AddVertices((plan.grid_u - 1.0) * (plan.grid_v - 1.0) - before));
  for (const int side : axis == 0 ? std::array<int, 2>{kBottom, kTop}
                                  : std::array<int, 2>{kRight, kLeft}) {
    RETURN_IF_ERROR(RaiseEdge(plan.edge[side], cells));
  }
  return absl::OkStatus();
}

absl::StatusOr<bool> AngleRefiner::Grow() {
  const auto grown = [](int count, double& ratio) {
    const double factor =
        std::clamp(kMargin * ratio, kLeastGrowth, kMostGrowth);
    ratio = 0.0;
    return std::ceil(count * factor);
  };
  bool grew = false;
  for (size_t edge = 0; edge < plan_.edges.size(); ++edge) {
    if (!(edge_ratio_[edge] > 1.0)) continue;
    grew = true;
    RETURN_IF_ERROR(
        RaiseEdge(static_cast<int>(edge),
                  grown(plan_.edges[edge].segments, edge_ratio_[edge])));
  }
  for (uint32_t piece = 0; piece < plan_.pieces.size(); ++piece) {
    for (int axis = 0; axis < 2; ++axis) {
      double& ratio = piece_ratio_[piece][axis];
      if (!(ratio > 1.0)) continue;
      grew = true;
      const PiecePlan& plan = plan_.pieces[piece];
      RETURN_IF_ERROR(RaiseGrid(
          piece, axis, grown(axis == 0 ? plan.grid_u : plan.grid_v, ratio)));
    }
  }
  return grew;
}

absl::Status AngleRefiner::Run(const CancellationToken* cancel) {
  CancellationPoll poll(cancel);
  while (true) {
    for (uint32_t piece = 0; piece < plan_.pieces.size(); ++piece) {
      if ((changed_[piece] & kGridChanged) != 0) {
        RETURN_IF_ERROR(CheckGrid(piece, poll));
      }
      if ((changed_[piece] & kRingChanged) != 0) {
        RETURN_IF_ERROR(CheckRing(piece, poll));
      }
      changed_[piece] = 0;
    }
    absl::StatusOr<bool> grew = Grow();
    if (!grew.ok()) return grew.status();
    if (!*grew) return absl::OkStatus();
  }
}

}  // namespace

absl::Status RefineNormalAngles(MeshPlan& plan, const MeshOptions& options,
                                double& vertex_count,
                                const CancellationToken* cancel) {
  return AngleRefiner(plan, options, vertex_count).Run(cancel);
}

}  // namespace freeform::internal
