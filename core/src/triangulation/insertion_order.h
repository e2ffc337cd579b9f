// The order in which Delaunay insertion takes the points: a biased
// randomized insertion order (BRIO, Amenta, Choi & Rote 2003;
// docs/references.md) whose rounds (each about half of the points not yet
// taken, from the last round backwards) are sorted along a Hilbert curve,
// so that consecutive points are close (short walks) while the rounds keep
// the expected cost of randomized insertion. The shuffle has a fixed seed:
// the same points always give the same order. Internal to the core.
#ifndef FREEFORM_CORE_SRC_TRIANGULATION_INSERTION_ORDER_H_
#define FREEFORM_CORE_SRC_TRIANGULATION_INSERTION_ORDER_H_

#include <cstdint>
#include <vector>

#include "absl/types/span.h"
#include "freeform/core/constrained_delaunay.h"

namespace freeform::internal {

// HilbertIndex returns the position of the cell (x, y) of a 2^16 x 2^16 grid
// (the points' bounding box; finer cells would only order points that are
// already neighbours) along the Hilbert curve that fills it.
uint64_t HilbertIndex(uint32_t x, uint32_t y);

// BiasedRandomizedOrder returns a permutation of the indices of `points`
// (finite coordinates).
std::vector<int32_t> BiasedRandomizedOrder(absl::Span<const Point2> points);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_TRIANGULATION_INSERTION_ORDER_H_
