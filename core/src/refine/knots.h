// Queries on sorted knot vectors that the core's refinement, elevation and
// decomposition algorithms share, each logarithmic or linear in the knots
// so that no algorithm grows quadratically with them. Internal to the core.
#ifndef FREEFORM_CORE_SRC_REFINE_KNOTS_H_
#define FREEFORM_CORE_SRC_REFINE_KNOTS_H_

#include <algorithm>

#include "absl/types/span.h"

namespace freeform::internal {

// Multiplicity returns how many of the non-decreasing `knots` equal `u`, by
// binary search.
inline int Multiplicity(absl::Span<const double> knots, double u) {
  const auto [first, last] = std::equal_range(knots.begin(), knots.end(), u);
  return static_cast<int>(last - first);
}

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_REFINE_KNOTS_H_
