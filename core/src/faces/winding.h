// Winding numbers of (u, v) points about a face's loops, certified against
// the true trim curves (the scheme of ClassifyPoints, trimmed_surface.h):
// chords farther than their Hausdorff bound plus the tolerance count as
// they are, nearer ones are replaced by a finer tessellation of their arc,
// recursively. Internal to the core; thread-safe.
#ifndef FREEFORM_CORE_SRC_FACES_WINDING_H_
#define FREEFORM_CORE_SRC_FACES_WINDING_H_

#include "faces/face_boundary.h"

namespace freeform::internal {

// The winding number of the loops about a point, or that the point lies
// within the tolerance of a loop (winding then meaningless).
struct WindingAt {
  bool on_boundary = false;
  int winding = 0;
};

// FaceWinding returns the sum of the winding numbers of every loop but
// `exclude_loop` (-1: none) about `p`, found through the grid.
WindingAt FaceWinding(const FaceBoundary& boundary, const Point2& p,
                      double tolerance, int exclude_loop = -1);

// TrimMayBeWithin reports whether a chord of a loop comes within its
// bound plus `reach` of p: false certifies that no trim comes within
// `reach` of p.
bool TrimMayBeWithin(const FaceBoundary& boundary, const Point2& p,
                     double reach);

// LoopWinding returns the winding number of one loop about `p`, from all
// its segments.
WindingAt LoopWinding(const FaceBoundary& boundary, int loop, const Point2& p,
                      double tolerance);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_FACES_WINDING_H_
