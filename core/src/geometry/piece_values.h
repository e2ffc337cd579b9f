// Internal: the size of a set of Bezier pieces, in doubles, for the
// a-priori bounds of curve.h and surface.h (DecomposedCurveValues,
// SurfacePieceValues).
#ifndef FREEFORM_CORE_SRC_GEOMETRY_PIECE_VALUES_H_
#define FREEFORM_CORE_SRC_GEOMETRY_PIECE_VALUES_H_

#include <cstdint>

namespace freeform::internal {

// PieceValues returns the doubles of `pieces` pieces of `points` control
// points of `dimension` coordinates (and a weight each when rational),
// plus `breakpoints`, saturating at UINT64_MAX.
inline uint64_t PieceValues(uint64_t pieces, uint64_t points, int dimension,
                            bool rational, uint64_t breakpoints) {
  uint64_t per_piece = 0, total = 0;
  if (__builtin_mul_overflow(
          points, static_cast<uint64_t>(dimension) + (rational ? 1 : 0),
          &per_piece) ||
      __builtin_mul_overflow(pieces, per_piece, &total) ||
      __builtin_add_overflow(total, breakpoints, &total)) {
    return UINT64_MAX;
  }
  return total;
}

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_GEOMETRY_PIECE_VALUES_H_
