// Surface grid rows across columns (simd/surface_simd.h): one vector lane
// per grid column. A run of columns on one v span shares the span's net
// points, broadcast to every lane, and loads its basis values from the
// planes, a vector at a time.
#include "kinds/simd/surface_simd.h"

#include <algorithm>
#include <cstddef>

#include "freeform/core/surface_output.h"
#include "hwy/aligned_allocator.h"
#include "kinds/bspline_spans.h"

// foreach_target.h compiles this file once per target: it must follow the
// definition of HWY_TARGET_INCLUDE, and highway.h and the -inl.h headers it.
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "kinds/simd/surface_simd.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "kinds/simd/curve_lanes-inl.h"
// clang-format on

HWY_BEFORE_NAMESPACE();
namespace freeform::simd::HWY_NAMESPACE {
namespace {

using internal::DegreeOf;

// One partial of the columns [begin, end), which share a span: the net
// points at `net` and the basis planes from `basis`.
template <int kDegree, int kDimension>
HWY_INLINE void CombineRun(LaneTag d, const GridRowLanesBatch& batch,
                           const double* net, const double* basis, size_t begin,
                           size_t end, double* coordinates, double* out) {
  const int q = DegreeOf<kDegree>(batch.q);
  const int dimension = SizeOf<kDimension>(batch.dimension);
  const size_t lanes = hn::Lanes(d);
  for (size_t j = begin; j < end; j += lanes) {
#pragma GCC unroll 4
    for (int c = 0; c < dimension; ++c) {
      LaneVec sum = hn::Zero(d);
#pragma GCC unroll 8
      for (int b = 0; b <= q; ++b) {
        const LaneVec value = hn::LoadU(
            d, basis + static_cast<size_t>(b) * batch.plane_stride + j);
        sum = hn::Add(sum, hn::Mul(value, hn::Set(d, net[b * dimension + c])));
      }
      hn::Store(sum, d, coordinates + static_cast<size_t>(c) * lanes);
    }
    StoreLanes<kDimension>(
        d, coordinates, dimension, std::min(lanes, end - j),
        [](size_t) { return true; }, true,
        out + j * static_cast<size_t>(dimension));
  }
}

template <int kDegree, int kDimension>
void EvaluateRow(const GridRowLanesBatch& batch) {
  const LaneTag d;
  const int q = DegreeOf<kDegree>(batch.q);
  const size_t dimension = static_cast<size_t>(batch.dimension);
  // A group's coordinate vectors: on the stack for a compiled-in dimension.
  HWY_ALIGN double on_stack[kMaxLanes * 4];
  hwy::AlignedFreeUniquePtr<double[]> allocated;
  if constexpr (kDimension == kRuntime) {
    allocated = hwy::AllocateAligned<double>(dimension * hn::Lanes(d));
  }
  double* coordinates = kDimension == kRuntime ? allocated.get() : on_stack;
  for (size_t begin = 0; begin < batch.columns;) {
    const size_t end = batch.run_ends[begin];
    const size_t first_point = static_cast<size_t>(batch.spans[begin] - q);
    for (int k = 0; k <= batch.max_order; ++k) {
      const double* net =
          batch.nets + k * batch.net_stride + first_point * dimension;
      for (int l = 0; l <= batch.max_order - k; ++l) {
        const double* basis = batch.planes + static_cast<size_t>(l * (q + 1)) *
                                                 batch.plane_stride;
        CombineRun<kDegree, kDimension>(d, batch, net, basis, begin, end,
                                        coordinates,
                                        batch.output[PartialIndex(k, l)]);
      }
    }
    begin = end;
  }
}

}  // namespace

void EvaluateGridRowLanes(const GridRowLanesBatch& batch) {
  WithDegreeAndDimension(batch.q, batch.dimension,
                         [&]<int kDegree, int kDimension>() {
                           EvaluateRow<kDegree, kDimension>(batch);
                         });
}

}  // namespace freeform::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace freeform::simd {

HWY_EXPORT(EvaluateGridRowLanes);

void EvaluateGridRow(const GridRowLanesBatch& batch) {
  HWY_DYNAMIC_DISPATCH(EvaluateGridRowLanes)(batch);
}

}  // namespace freeform::simd
#endif  // HWY_ONCE
