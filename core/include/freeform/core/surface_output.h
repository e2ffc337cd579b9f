// SurfaceOutput: where batch surface evaluations write their results.
//
// A surface evaluation with derivative order d writes every partial
// derivative d^(k+l) S / du^k dv^l with k + l <= d, one buffer per partial,
// ordered by total order and then by l: (0,0), (1,0), (0,1), (2,0), (1,1),
// (0,2), ... PartialIndex(k, l) gives the position. Each buffer holds
// count * dimension doubles: point r, coordinate j at [r * dimension + j].
// Points are either (u, v) pairs or a grid ordered u-major (the point of u_i
// and v_j is i * count(v) + j). Thread-safe.
#ifndef FREEFORM_CORE_SURFACE_OUTPUT_H_
#define FREEFORM_CORE_SURFACE_OUTPUT_H_

#include <cstddef>

#include "absl/status/status.h"
#include "absl/types/span.h"

namespace freeform {

// Buffers of the partials in PartialIndex order.
using SurfaceOutput = absl::Span<const absl::Span<double>>;

// PartialCount returns the number of partials with k + l <= max_order.
constexpr size_t PartialCount(int max_order) {
  return static_cast<size_t>((max_order + 1) * (max_order + 2) / 2);
}

// PartialIndex returns where d^(k+l) S / du^k dv^l sits in a SurfaceOutput.
constexpr size_t PartialIndex(int order_u, int order_v) {
  const int total = order_u + order_v;
  return static_cast<size_t>(total * (total + 1) / 2 + order_v);
}

// MaxOrderOf returns d for an output of PartialCount(d) buffers, or -1 when
// the number of buffers is not such a count.
int MaxOrderOf(SurfaceOutput output);

// ValidateSurfaceOutput checks that the output has PartialCount(d) buffers
// for some d >= 0, each of count * dimension doubles.
absl::Status ValidateSurfaceOutput(SurfaceOutput output, size_t count,
                                   int dimension);

// Where a surface is evaluated: (u, v) pairs, or the grid of every u with
// every v.
struct SurfaceSamples {
  // Pairs u_0, v_0, u_1, v_1, ... (used when `grid` is false).
  absl::Span<const double> uv;
  // Grid coordinates (used when `grid` is true).
  bool grid = false;
  absl::Span<const double> u;
  absl::Span<const double> v;

  size_t size() const { return grid ? u.size() * v.size() : uv.size() / 2; }

  static SurfaceSamples Pairs(absl::Span<const double> pairs) {
    return {.uv = pairs, .grid = false, .u = {}, .v = {}};
  }
  static SurfaceSamples Grid(absl::Span<const double> grid_u,
                             absl::Span<const double> grid_v) {
    return {.uv = {}, .grid = true, .u = grid_u, .v = grid_v};
  }
};

// ValidateSurfaceSamples checks an even number of finite pair values inside
// [u_start, u_end] x [v_start, v_end] ("uv[i]"), or finite grid values inside
// their ranges ("u[i]", "v[i]").
absl::Status ValidateSurfaceSamples(const SurfaceSamples& samples,
                                    double u_start, double u_end,
                                    double v_start, double v_end);

}  // namespace freeform

#endif  // FREEFORM_CORE_SURFACE_OUTPUT_H_
