// The ring layout and the piece normals of mesh_ring.h.
#include "meshing/mesh_ring.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/normals.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/tensor_surface.h"
#include "kinds/validated_tensor_surface.h"

namespace freeform::internal {
namespace {

bool AlongU(int side) { return side == kBottom || side == kTop; }

// RingCoordinate returns the perimeter coordinate of the point (u, v) of a
// side: side k covers [k, k + 1], counter-clockwise from (0, 0).
double RingCoordinate(int side, double u, double v) {
  return side + (side == kBottom  ? u
                 : side == kRight ? v
                 : side == kTop   ? 1.0 - u
                                  : 1.0 - v);
}

// PartialNormals evaluates the partials to `order` of a piece at `uv` into
// `buffers` and its unit normals into `normals`.
absl::Status PartialNormals(const BezierSurfaceView& piece, int order,
                            absl::Span<const double> uv,
                            std::vector<std::vector<double>>& buffers,
                            std::vector<double>& normals) {
  const size_t count = uv.size() / 2;
  buffers.resize(PartialCount(order));
  std::vector<absl::Span<double>> output;
  for (std::vector<double>& buffer : buffers) {
    buffer.resize(3 * count);
    output.push_back(absl::MakeSpan(buffer));
  }
  const SurfaceSamples samples = SurfaceSamples::Pairs(uv);
  // The pieces of surfaces PlanMesh checked are valid.
  if (absl::Status status =
          EvaluateValidBezierSurface(piece, samples, output, {});
      !status.ok()) {
    return status;
  }
  normals.resize(3 * count);
  return ComputeUnitNormals(output, samples, BezierSurfaceDomain(),
                            absl::MakeSpan(normals));
}

}  // namespace

int SideSegments(const PiecePlan& piece, const EdgePlan& edge, int side) {
  if (!edge.collapsed) return edge.segments;
  return AlongU(side) ? piece.grid_u : piece.grid_v;
}

std::array<double, 2> SidePoint(int side, int m, int n) {
  const double t = static_cast<double>(m) / n;
  const double fixed = side == kRight || side == kTop ? 1.0 : 0.0;
  return AlongU(side) ? std::array<double, 2>{t, fixed}
                      : std::array<double, 2>{fixed, t};
}

std::vector<OuterPlace> OuterLoop(const PiecePlan& piece,
                                  absl::Span<const EdgePlan> edges) {
  std::vector<OuterPlace> loop;
  for (int side = 0; side < 4; ++side) {
    const int n =
        SideSegments(piece, edges[static_cast<size_t>(piece.edge[side])], side);
    const bool backward = side == kTop || side == kLeft;
    for (int k = 0; k <= n; ++k) {
      const int m = backward ? n - k : k;
      const auto [u, v] = SidePoint(side, m, n);
      loop.push_back({side, m, u, v, RingCoordinate(side, u, v)});
    }
  }
  return loop;
}

std::vector<InnerPlace> InnerLoop(int grid_u, int grid_v) {
  std::vector<InnerPlace> loop;
  auto add_side = [&](int side, int count, auto at) {
    for (int k = 0; k < count; ++k) {
      const auto [i, j] = at(k);
      const double u = static_cast<double>(i) / grid_u;
      const double v = static_cast<double>(j) / grid_v;
      loop.push_back({i, j, u, v, RingCoordinate(side, u, v)});
    }
  };
  const int last_u = grid_u - 1, last_v = grid_v - 1;
  // Each side from its start corner to its end corner; a single node is
  // both (count 2 then repeats it).
  add_side(kBottom, std::max(2, last_u), [&](int k) {
    return std::array<int, 2>{std::min(1 + k, last_u), 1};
  });
  add_side(kRight, std::max(2, last_v), [&](int k) {
    return std::array<int, 2>{last_u, std::min(1 + k, last_v)};
  });
  add_side(kTop, std::max(2, last_u), [&](int k) {
    return std::array<int, 2>{std::max(last_u - k, 1), last_v};
  });
  add_side(kLeft, std::max(2, last_v), [&](int k) {
    return std::array<int, 2>{1, std::max(last_v - k, 1)};
  });
  return loop;
}

absl::Status PieceEvaluator::Evaluate(const BezierSurfaceView& piece,
                                      absl::Span<const double> uv) {
  // First partials give the normal of every regular point; the zero
  // normals of degenerate points (a collapsed side) are then replaced by
  // the limit from the second partials, evaluated for them only.
  RETURN_IF_ERROR(PartialNormals(piece, 1, uv, buffers_, normals_));
  degenerate_.clear();
  degenerate_uv_.clear();
  for (size_t k = 0; 3 * k < normals_.size(); ++k) {
    if (normals_[3 * k] == 0 && normals_[3 * k + 1] == 0 &&
        normals_[3 * k + 2] == 0) {
      degenerate_.push_back(k);
      degenerate_uv_.insert(degenerate_uv_.end(), {uv[2 * k], uv[2 * k + 1]});
    }
  }
  if (degenerate_.empty()) return absl::OkStatus();
  RETURN_IF_ERROR(PartialNormals(piece, 2, degenerate_uv_, second_buffers_,
                                 second_normals_));
  for (size_t d = 0; d < degenerate_.size(); ++d) {
    std::copy_n(&second_normals_[3 * d], 3, &normals_[3 * degenerate_[d]]);
  }
  return absl::OkStatus();
}

}  // namespace freeform::internal
