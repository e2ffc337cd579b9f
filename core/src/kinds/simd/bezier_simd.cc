// Bezier curve evaluation across parameters, with one vector lane per
// parameter: LadderBezierPoint (bezier.cc), Warren's ladder, which needs no
// division; and HornerBezierPoint, Horner's rule in t/(1-t) below t = 1/2
// and in (1-t)/t above, where each lane picks its form (and so the order of
// the coefficients) with a mask, so lanes on both sides of 1/2 share a
// vector.
#include <algorithm>
#include <cstddef>

#include "hwy/aligned_allocator.h"
#include "kinds/bspline_spans.h"
#include "kinds/simd/curve_simd.h"

// foreach_target.h compiles this file once per target: it must follow the
// definition of HWY_TARGET_INCLUDE, and highway.h and the -inl.h headers it.
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "kinds/simd/bezier_simd.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "kinds/simd/curve_lanes-inl.h"
// clang-format on

HWY_BEFORE_NAMESPACE();
namespace freeform::simd::HWY_NAMESPACE {
namespace {

using internal::DegreeOf;

// What Horner needs of the parameters of one group.
struct HornerLanes {
  hn::Mask<LaneTag> from_start;  // t < 1/2: Horner in t/(1-t)
  LaneVec ratio;                 // t/(1-t), else (1-t)/t
  LaneVec factor;                // 1-t, else t: the factored-out power's base
};

HWY_INLINE HornerLanes PrepareHorner(LaneTag d, LaneVec t) {
  const LaneVec s = hn::Sub(hn::Set(d, 1.0), t);
  const auto from_start = hn::Lt(t, hn::Set(d, 0.5));
  return {.from_start = from_start,
          .ratio = hn::Div(hn::IfThenElse(from_start, t, s),
                           hn::IfThenElse(from_start, s, t)),
          .factor = hn::IfThenElse(from_start, s, t)};
}

// HornerBezierPoint for the degree-n curve whose scaled control points are
// `scaled`: coordinate c of every lane's point to points[c].
template <int kDegree, int kDimension>
HWY_INLINE void HornerPointLanes(LaneTag d, const HornerLanes& horner,
                                 const double* scaled, int runtime_n,
                                 int runtime_dimension, double* points) {
  const int n = DegreeOf<kDegree>(runtime_n);
  const int dimension = SizeOf<kDimension>(runtime_dimension);
  const size_t lanes = hn::Lanes(d);
  // The i-th coefficient of the Horner sum: i-th from the end below 1/2.
  const auto coefficient = [&](int i, int c) {
    return hn::IfThenElse(horner.from_start,
                          hn::Set(d, scaled[(n - i) * dimension + c]),
                          hn::Set(d, scaled[i * dimension + c]));
  };
  LaneVec scale = hn::Set(d, 1.0);
#pragma GCC unroll 8
  for (int i = 0; i < n; ++i) scale = hn::Mul(scale, horner.factor);
#pragma GCC unroll 4
  for (int c = 0; c < dimension; ++c) {
    LaneVec sum = coefficient(0, c);
#pragma GCC unroll 8
    for (int i = 1; i <= n; ++i) {
      sum = hn::Add(hn::Mul(sum, horner.ratio), coefficient(i, c));
    }
    hn::Store(hn::Mul(sum, scale), d, points + c * lanes);
  }
}

// LadderBezierPoint for the degree-n curve whose scaled control points are
// `scaled`: point = (1-t) point + t^k scaled[k], k = 1..n; coordinate c of
// every lane's point to points[c].
template <int kDegree, int kDimension>
HWY_INLINE void LadderPointLanes(LaneTag d, LaneVec t, const double* scaled,
                                 int runtime_n, int runtime_dimension,
                                 double* points) {
  const int n = DegreeOf<kDegree>(runtime_n);
  const int dimension = SizeOf<kDimension>(runtime_dimension);
  const size_t lanes = hn::Lanes(d);
  const LaneVec s = hn::Sub(hn::Set(d, 1.0), t);
#pragma GCC unroll 4
  for (int c = 0; c < dimension; ++c) {
    hn::Store(hn::Set(d, scaled[c]), d, points + c * lanes);
  }
  LaneVec power = hn::Set(d, 1.0);
#pragma GCC unroll 8
  for (int k = 1; k <= n; ++k) {
    power = hn::Mul(power, t);
    const double* rung = scaled + k * dimension;
#pragma GCC unroll 4
    for (int c = 0; c < dimension; ++c) {
      double* point = points + c * lanes;
      hn::Store(hn::Add(hn::Mul(s, hn::Load(d, point)),
                        hn::Mul(power, hn::Set(d, rung[c]))),
                d, point);
    }
  }
}

// Runs point.template operator()<degree>(scaled, n, out) for derivatives
// k = 0..top: on the hodograph of degree n - k, into sums + k dimension
// lanes (its own compiled-in degree for k = 0).
template <int kDegree, typename Point>
HWY_INLINE void EachDerivative(const BezierLanesBatch& batch, int top,
                               size_t stride, double* sums, Point point) {
  point.template operator()<kDegree>(batch.hodographs[0], batch.n, sums);
  for (int k = 1; k <= top; ++k) {
    point.template operator()<internal::kAnyDegree>(
        batch.hodographs[k], batch.n - k,
        sums + static_cast<size_t>(k) * stride);
  }
}

// Evaluates the derivatives 0..top of one group into `sums` by the batch's
// scheme.
template <int kDegree, int kDimension>
HWY_INLINE void EvaluateGroup(LaneTag d, const BezierLanesBatch& batch, int top,
                              LaneVec t, double* sums) {
  const int dimension = SizeOf<kDimension>(batch.dimension);
  const size_t stride = static_cast<size_t>(dimension) * hn::Lanes(d);
  if (batch.ladder) {
    return EachDerivative<kDegree>(
        batch, top, stride, sums,
        [&]<int kPointDegree>(const double* scaled, int n, double* out) {
          LadderPointLanes<kPointDegree, kDimension>(d, t, scaled, n, dimension,
                                                     out);
        });
  }
  const HornerLanes horner = PrepareHorner(d, t);
  EachDerivative<kDegree>(
      batch, top, stride, sums,
      [&]<int kPointDegree>(const double* scaled, int n, double* out) {
        HornerPointLanes<kPointDegree, kDimension>(d, horner, scaled, n,
                                                   dimension, out);
      });
}

template <int kDegree, int kDimension>
void EvaluateChunk(const BezierLanesBatch& batch, size_t begin, size_t end) {
  const LaneTag d;
  const size_t lanes = hn::Lanes(d);
  const int top = std::min(batch.max_order, batch.n);
  const size_t vectors =
      (static_cast<size_t>(top) + 1) * static_cast<size_t>(batch.dimension);
  const hwy::AlignedFreeUniquePtr<double[]> sums =
      hwy::AllocateAligned<double>(vectors * lanes);
  const LaneResults results{
      .soa = sums.get(), .dimension = batch.dimension, .top = top};
  for (size_t r = begin; r < end; r += lanes) {
    const size_t count = std::min(lanes, end - r);
    const LaneVec t = LoadParameters(d, batch.parameters, r, count);
    EvaluateGroup<kDegree, kDimension>(d, batch, top, t, sums.get());
    WriteGroup<kDimension>(d, results, batch.max_order, batch.output, r, count);
  }
}

}  // namespace

void EvaluateBezierChunkLanes(const BezierLanesBatch& batch, size_t begin,
                              size_t end) {
  WithDegreeAndDimension(
      batch.n, batch.dimension, [&]<int kDegree, int kDimension>() {
        EvaluateChunk<kDegree, kDimension>(batch, begin, end);
      });
}

}  // namespace freeform::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace freeform::simd {

HWY_EXPORT(EvaluateBezierChunkLanes);

void EvaluateBezierChunk(const BezierLanesBatch& batch, size_t begin,
                         size_t end) {
  HWY_DYNAMIC_DISPATCH(EvaluateBezierChunkLanes)(batch, begin, end);
}

}  // namespace freeform::simd
#endif  // HWY_ONCE
