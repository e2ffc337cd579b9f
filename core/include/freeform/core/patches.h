// Bicubic patches given by data rather than by a Bezier net: the bicubic
// interpolating patch (docs/references.md, 'The bicubic interpolating
// patch') and the bicubic Hermite (Ferguson) patch, both turned into the 4 x 4
// Bezier net of the same surface so that every Bezier surface operation applies
// to them.
//
// Nets are row-major, u with the row i: point (i, j) at (4 i + j) * dimension.
// Thread-safe.
#ifndef FREEFORM_CORE_PATCHES_H_
#define FREEFORM_CORE_PATCHES_H_

#include <vector>

#include "absl/types/span.h"

namespace freeform {

// InterpolatingToBezierNet returns the bicubic Bezier net of the patch that
// passes through the 4 x 4 points at the parameters 0, 1/3, 2/3, 1 in u and
// in v: S(i/3, j/3) = Q[i][j]. Each direction applies the inverse of the
// cubic Bernstein collocation matrix on those nodes:
// b0 = q0, b1 = (-5 q0 + 18 q1 - 9 q2 + 2 q3) / 6,
// b2 = (2 q0 - 9 q1 + 18 q2 - 5 q3) / 6, b3 = q3.
std::vector<double> InterpolatingToBezierNet(int dimension,
                                             absl::Span<const double> points);

// HermiteToBezierNet returns the bicubic Bezier net of the Ferguson patch
// with, at the corners (u, v) = (0,0), (0,1), (1,0), (1,1) (2 x 2 row-major),
// positions P, u-derivatives S_u, v-derivatives S_v and twists S_uv (empty
// twists mean zero). Around corner (a, b), with s = +1 at 0 and -1 at 1:
// b[3a + s_u][3b] = P + s_u S_u / 3, b[3a][3b + s_v] = P + s_v S_v / 3,
// b[3a + s_u][3b + s_v] = P + s_u S_u / 3 + s_v S_v / 3 + s_u s_v S_uv / 9.
std::vector<double> HermiteToBezierNet(int dimension,
                                       absl::Span<const double> positions,
                                       absl::Span<const double> derivatives_u,
                                       absl::Span<const double> derivatives_v,
                                       absl::Span<const double> twists);

}  // namespace freeform

#endif  // FREEFORM_CORE_PATCHES_H_
