// The Highway kernel that finishes one row of a tensor-product surface grid
// with one vector lane per grid column, as tensor_surface.cc calls it. The
// row's v-direction nets are ready (one per u-derivative order); the kernel
// combines them with the columns' v bases, computed once per grid. Like
// simd/curve_simd.h it dispatches at run time and rounds exactly as the
// scalar code does, so every target gives the same bits. Internal to the
// core; thread-safe, no allocation per point.
#ifndef FREEFORM_CORE_SRC_KINDS_SIMD_SURFACE_SIMD_H_
#define FREEFORM_CORE_SRC_KINDS_SIMD_SURFACE_SIMD_H_

#include <cstddef>

namespace freeform::simd {

// Spare doubles at the end of every basis plane of a GridRowLanesBatch, so
// that a vector load at the last column stays inside the plane.
inline constexpr size_t kPlanePadding = 8;

// One grid row of a polynomial surface of v degree q.
struct GridRowLanesBatch {
  int q = 0;
  int dimension = 0;
  int max_order = 0;
  size_t columns = 0;
  // Per column j: the v span, and the end of the run of columns from j on
  // that share it.
  const int* spans = nullptr;
  const size_t* run_ends = nullptr;
  // N^(l)_{spans[j]-q+b}(v_j) at planes[(l * (q + 1) + b) * plane_stride + j]
  // for l = 0..max_order; plane_stride >= columns + kPlanePadding, and the
  // padding is zero.
  const double* planes = nullptr;
  size_t plane_stride = 0;
  // The v-direction net of u-derivative k (every net column, `dimension`
  // values each) at nets + k * net_stride, k = 0..max_order.
  const double* nets = nullptr;
  size_t net_stride = 0;
  // PartialCount(max_order) buffers (surface_output.h), each pointing at the
  // row's first point.
  double* const* output = nullptr;
};

// EvaluateGridRow writes partial (k, l) of every column j: the sum over b of
// N^(l)_{spans[j]-q+b}(v_j) times point spans[j]-q+b of net k, b = 0..q in
// that order, from a sum that starts at zero.
void EvaluateGridRow(const GridRowLanesBatch& batch);

}  // namespace freeform::simd

#endif  // FREEFORM_CORE_SRC_KINDS_SIMD_SURFACE_SIMD_H_
