// A face's surface as Bezier pieces with their span rectangles in (u, v),
// for the face's sampling and bounding box. Internal to the core.
#ifndef FREEFORM_CORE_SRC_FACES_SURFACE_PIECES_H_
#define FREEFORM_CORE_SRC_FACES_SURFACE_PIECES_H_

#include <array>
#include <cstddef>

#include "freeform/core/surface.h"

namespace freeform::internal {

// The Bezier pieces of a tensor-product surface (DecomposeSurface) with
// their span rectangles.
struct SurfacePieces {
  SurfaceDecomposition decomposition;

  size_t rows() const { return decomposition.pieces.breakpoints_v.size() - 1; }
  // Rectangle returns {u0, u1, v0, v1} of piece `index`.
  std::array<double, 4> Rectangle(size_t index) const {
    const auto& p = decomposition.pieces;
    const size_t i = index / rows(), j = index % rows();
    return {p.breakpoints_u[i], p.breakpoints_u[i + 1], p.breakpoints_v[j],
            p.breakpoints_v[j + 1]};
  }
};

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_FACES_SURFACE_PIECES_H_
