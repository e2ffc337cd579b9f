// Halving of Bezier pieces stored flat, for the subdivision searches (the
// tight bounding boxes of bounding_box.cc, and through bezier_net.h's Halve
// the closest points, intersections and sections): de Casteljau at the
// middle of a tensor net's u or v, and the bisection of a triangular patch
// through a vertex.
// Each works on `width` values a point (coordinates, or homogeneous
// coordinates w x, w of a rational piece) and writes into caller-owned
// arrays of the parent's size, so a search allocates nothing per halving.
// Internal to the core.
#ifndef FREEFORM_CORE_SRC_REFINE_BEZIER_HALVING_H_
#define FREEFORM_CORE_SRC_REFINE_BEZIER_HALVING_H_

#include <cstddef>
#include <vector>

namespace freeform::internal {

// HalveNet splits the count_u x count_v net `values` (point (a, b) at
// (a count_v + b) width) at the middle of u (in_u) or v, as
// SplitBezierSurface at 0.5: `first` gets the half of parameters [0, 1/2],
// `second` the half [1/2, 1], each a count_u x count_v net.
void HalveNet(const double* values, int count_u, int count_v, int width,
              bool in_u, double* first, double* second);

// BisectTriangle splits the degree-n triangular patch `values` (storage of
// TriangularIndex) at the midpoint M of the edge opposite vertex `edge`
// (0, 1 or 2), as BisectTriangularPatch: with a < b the other two
// vertices, `first` is the piece with M in place of vertex a and `second`
// the piece with M in place of b. Each row of points parallel to the split
// edge is a Bezier curve, halved by de Casteljau (a split along a line
// through a vertex). `row` is scratch, resized as needed.
void BisectTriangle(const double* values, int n, int width, int edge,
                    double* first, double* second, std::vector<double>& row);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_REFINE_BEZIER_HALVING_H_
