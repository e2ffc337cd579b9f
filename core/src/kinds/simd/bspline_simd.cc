// B-spline curve evaluation across parameters: the scalar evaluator's
// A2.2 / A2.3 (basis functions and their derivatives) and A3.2 (combination
// with the control points) of bspline.cc, with one vector lane per
// parameter. A group of parameters on one span shares the span's knots and
// control points, broadcast to every lane.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "absl/types/span.h"
#include "freeform/core/bspline.h"
#include "hwy/aligned_allocator.h"
#include "kinds/bspline_spans.h"
#include "kinds/simd/curve_simd.h"

// foreach_target.h compiles this file once per target: it must follow the
// definition of HWY_TARGET_INCLUDE, and highway.h and the -inl.h headers it.
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "kinds/simd/bspline_simd.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "kinds/simd/curve_lanes-inl.h"
// clang-format on

HWY_BEFORE_NAMESPACE();
namespace freeform::simd::HWY_NAMESPACE {
namespace {

using internal::DegreeOf;
using internal::InverseKnotDifferences;

// The workspace of one chunk, in vectors of Lanes(d) doubles (one lane per
// parameter) unless noted; the names are those of bspline.cc.
struct LaneWorkspace {
  double* left = nullptr;     // p + 1
  double* right = nullptr;    // p + 1
  double* basis = nullptr;    // (p + 1)^2: derivative k of N_j at k (p+1) + j
  double* ndu = nullptr;      // (p + 1)^2, A2.3 only
  double* rows = nullptr;     // 2 (p + 1), A2.3 only
  double* sums = nullptr;     // (top + 1) dimension: the group's results
  double* inverse = nullptr;  // p (p + 1) / 2 doubles for span `span`
  int span = -1;
};

// Doubles of a LaneWorkspace for `lanes` lanes.
constexpr size_t WorkspaceSize(size_t lanes, int p, int top, int dimension) {
  const size_t w = static_cast<size_t>(p) + 1;
  const size_t vectors =
      4 * w + 2 * w * w + (static_cast<size_t>(top) + 1) * dimension;
  return vectors * lanes + w * w;
}

// Owns the memory of a LaneWorkspace: arrays on the stack for a compiled-in
// degree and dimension (which the unrolled kernels can keep in registers),
// else one allocation per chunk.
template <int kDegree, int kDimension>
class LaneStorage {
 public:
  LaneStorage(size_t lanes, int p, int top, int dimension) {
    double* next;
    if constexpr (kOnStack) {
      next = memory_.data();
    } else {
      memory_ =
          hwy::AllocateAligned<double>(WorkspaceSize(lanes, p, top, dimension));
      next = memory_.get();
    }
    const size_t w = static_cast<size_t>(p) + 1;
    const auto take = [&next, lanes](size_t count) {
      double* start = next;
      next += count * lanes;
      return start;
    };
    work_.left = take(w);
    work_.right = take(w);
    work_.basis = take(w * w);
    work_.ndu = take(w * w);
    work_.rows = take(2 * w);
    work_.sums = take((static_cast<size_t>(top) + 1) * dimension);
    work_.inverse = next;
  }
  LaneStorage(const LaneStorage&) = delete;
  LaneStorage& operator=(const LaneStorage&) = delete;

  LaneWorkspace& work() { return work_; }

 private:
  static constexpr bool kOnStack =
      kDegree != internal::kAnyDegree && kDimension != kRuntime;
  HWY_ALIGN std::conditional_t<
      kOnStack,
      std::array<double, WorkspaceSize(kMaxLanes, std::max(kDegree, 0),
                                       std::max(kDegree, 0), kDimension)>,
      hwy::AlignedFreeUniquePtr<double[]>>
      memory_;
  LaneWorkspace work_;
};

// A2.2 of BasisFunctionsOn (bspline.cc) for the parameters `u` on `span`:
// N_{span-p+r,p} to n[r] (vector r) or, with kAllDegrees, every degree
// j <= p to n[r (p + 1) + j]; with `first`, the first derivatives by
// eq. 2.7.
template <int kDegree, bool kAllDegrees>
HWY_INLINE void BasisLanes(LaneTag d, const double* knots, int span, LaneVec u,
                           int runtime_p, const double* inverse, double* left,
                           double* right, double* n, double* first) {
  const int p = DegreeOf<kDegree>(runtime_p);
  const size_t lanes = hn::Lanes(d);
  const auto at = [n, p, lanes](int r, int j) {
    return n + static_cast<size_t>(kAllDegrees ? r * (p + 1) + j : r) * lanes;
  };
  const LaneVec degree = hn::Set(d, static_cast<double>(p));
  hn::Store(hn::Set(d, 1.0), d, at(0, 0));
  LaneVec previous_temp = hn::Zero(d);
#pragma GCC unroll 8
  for (int j = 1; j <= p; ++j) {
    hn::Store(hn::Sub(u, hn::Set(d, knots[span + 1 - j])), d, left + j * lanes);
    hn::Store(hn::Sub(hn::Set(d, knots[span + j]), u), d, right + j * lanes);
    const double* inverse_j = inverse + j * (j - 1) / 2;
    LaneVec saved = hn::Zero(d);
#pragma GCC unroll 8
    for (int r = 0; r < j; ++r) {
      const LaneVec temp =
          hn::Mul(hn::Load(d, at(r, j - 1)), hn::Set(d, inverse_j[r]));
      hn::Store(
          hn::Add(saved, hn::Mul(hn::Load(d, right + (r + 1) * lanes), temp)),
          d, at(r, j));
      saved = hn::Mul(hn::Load(d, left + (j - r) * lanes), temp);
      if (j == p && first != nullptr) {
        hn::Store(hn::Mul(degree, hn::Sub(previous_temp, temp)), d,
                  first + r * lanes);
        previous_temp = temp;
      }
    }
    hn::Store(saved, d, at(j, j));
  }
  if (first != nullptr) {
    hn::Store(hn::Mul(degree, previous_temp), d, first + p * lanes);
  }
}

// A2.3 of BasisDerivativesOf (bspline.cc): work.basis[k (p + 1) + j] =
// N^(k)_{span-p+j,p}(u) for k = 0..top, with work.inverse filled for `span`.
template <int kDegree>
void DerivativesLanes(LaneTag d, const double* knots, int span, LaneVec u,
                      int runtime_p, int top, const LaneWorkspace& work) {
  const int p = DegreeOf<kDegree>(runtime_p);
  const int w = p + 1;
  const size_t lanes = hn::Lanes(d);
  BasisLanes<kDegree, true>(d, knots, span, u, p, work.inverse, work.left,
                            work.right, work.ndu, nullptr);
  const auto ndu = [&](int r, int j) {
    return hn::Load(d, work.ndu + static_cast<size_t>(r * w + j) * lanes);
  };
  const auto inverse = [&](int j, int r) {
    return hn::Set(d, work.inverse[j * (j - 1) / 2 + r]);
  };
  const auto ders = [&](int k, int j) {
    return work.basis + static_cast<size_t>(k * w + j) * lanes;
  };
  for (int j = 0; j <= p; ++j) hn::Store(ndu(j, p), d, ders(0, j));
  for (int r = 0; r <= p; ++r) {
    double* previous = work.rows;
    double* current = work.rows + w * lanes;
    hn::Store(hn::Set(d, 1.0), d, previous);
    for (int k = 1; k <= top; ++k) {
      const int rk = r - k;
      const int pk = p - k;
      LaneVec sum = hn::Zero(d);
      if (r >= k) {
        const LaneVec a = hn::Mul(hn::Load(d, previous), inverse(pk + 1, rk));
        hn::Store(a, d, current);
        sum = hn::Mul(a, ndu(rk, pk));
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = r - 1 <= pk ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        const LaneVec a =
            hn::Mul(hn::Sub(hn::Load(d, previous + j * lanes),
                            hn::Load(d, previous + (j - 1) * lanes)),
                    inverse(pk + 1, rk + j));
        hn::Store(a, d, current + j * lanes);
        sum = hn::Add(sum, hn::Mul(a, ndu(rk + j, pk)));
      }
      if (r <= pk) {
        const LaneVec a =
            hn::Mul(hn::Neg(hn::Load(d, previous + (k - 1) * lanes)),
                    inverse(pk + 1, r));
        hn::Store(a, d, current + k * lanes);
        sum = hn::Add(sum, hn::Mul(a, ndu(r, pk)));
      }
      hn::Store(sum, d, ders(k, r));
      std::swap(previous, current);
    }
  }
  double factor = p;  // p! / (p - k)!
  for (int k = 1; k <= top; ++k) {
    for (int j = 0; j <= p; ++j) {
      hn::Store(hn::Mul(hn::Load(d, ders(k, j)), hn::Set(d, factor)), d,
                ders(k, j));
    }
    factor *= p - k;
  }
}

// A3.2 of CombinePointsOf (bspline.cc): sums[c] = sum_j basis[j] *
// points[j * dimension + c], added in the same order.
template <int kDegree, int kDimension>
HWY_INLINE void CombineLanes(LaneTag d, const double* basis,
                             const double* points, int runtime_p,
                             int runtime_dimension, double* sums) {
  const int p = DegreeOf<kDegree>(runtime_p);
  const int dimension = SizeOf<kDimension>(runtime_dimension);
  const size_t lanes = hn::Lanes(d);
#pragma GCC unroll 4
  for (int c = 0; c < dimension; ++c) {
    LaneVec sum = hn::Zero(d);
#pragma GCC unroll 8
    for (int j = 0; j <= p; ++j) {
      sum = hn::Add(sum, hn::Mul(hn::Load(d, basis + j * lanes),
                                 hn::Set(d, points[j * dimension + c])));
    }
    hn::Store(sum, d, sums + c * lanes);
  }
}

// Evaluates derivatives 0..top at the parameters `u`, all taken on `span`,
// into work.sums.
template <int kDegree, int kDimension>
HWY_INLINE void EvaluateOnSpan(LaneTag d, const BSplineLanesBatch& batch,
                               int top, int span, LaneVec u,
                               LaneWorkspace& work) {
  const int p = DegreeOf<kDegree>(batch.p);
  const int dimension = SizeOf<kDimension>(batch.dimension);
  const size_t lanes = hn::Lanes(d);
  if (span != work.span) {
    InverseKnotDifferences<kDegree>(batch.knots, span, p, work.inverse);
    work.span = span;
  }
  if (top <= 1) {
    BasisLanes<kDegree, false>(
        d, batch.knots, span, u, p, work.inverse, work.left, work.right,
        work.basis, top == 1 ? work.basis + (p + 1) * lanes : nullptr);
  } else {
    DerivativesLanes<kDegree>(d, batch.knots, span, u, p, top, work);
  }
  const double* points =
      batch.control + static_cast<ptrdiff_t>(span - p) * dimension;
#pragma GCC unroll 2
  for (int k = 0; k <= top; ++k) {
    CombineLanes<kDegree, kDimension>(
        d, work.basis + static_cast<size_t>(k * (p + 1)) * lanes, points, p,
        dimension, work.sums + static_cast<size_t>(k * dimension) * lanes);
  }
}

// Whether every lane of `u` lies on `span` (FindSpan's answer): u_span <=
// u < u_{span+1}, or u_span <= u on the last non-empty span `last`, which
// also holds the end of the domain.
HWY_INLINE bool AllOnSpan(LaneTag d, const double* knots, int span, int last,
                          LaneVec u) {
  const double end =
      span == last ? std::numeric_limits<double>::infinity() : knots[span + 1];
  return hn::AllTrue(d, hn::And(hn::Ge(u, hn::Set(d, knots[span])),
                                hn::Lt(u, hn::Set(d, end))));
}

// Evaluates the `count` parameters from r whose spans differ from `span`
// (a span boundary or unsorted input): once per distinct span among them,
// keeping the lanes on it. Returns the last parameter's span.
template <int kDegree, int kDimension>
HWY_NOINLINE int EvaluateMixedGroup(LaneTag d, const BSplineLanesBatch& batch,
                                    int top, int span, size_t r, size_t count,
                                    LaneVec u, LaneWorkspace& work) {
  const absl::Span<const double> knots(
      batch.knots, static_cast<size_t>(batch.n + batch.p) + 2);
  int spans[kMaxLanes];
  for (size_t i = 0; i < count; ++i) {
    span = FindSpanFrom(span, batch.n, batch.p, batch.parameters[r + i], knots);
    spans[i] = span;
  }
  const bool uniform =
      std::all_of(spans, spans + count, [&](int s) { return s == spans[0]; });
  for (size_t i = 0; i < count; ++i) {
    if (std::find(spans, spans + i, spans[i]) != spans + i) continue;
    EvaluateOnSpan<kDegree, kDimension>(d, batch, top, spans[i], u, work);
    WriteLanes<kDimension>(
        d, {.soa = work.sums, .dimension = batch.dimension, .top = top},
        batch.max_order, batch.output, r, count,
        [&](size_t lane) { return spans[lane] == spans[i]; }, uniform);
  }
  return span;
}

// Template argument of EvaluateChunk for a highest derivative order known
// only at run time.
constexpr int kAnyOrder = -1;

// Evaluates parameters [begin, end) of `batch`, whose highest order is
// kMaxOrder unless that is kAnyOrder.
template <int kDegree, int kDimension, int kMaxOrder>
void EvaluateChunk(const BSplineLanesBatch& batch, size_t begin, size_t end) {
  const LaneTag d;
  const size_t lanes = hn::Lanes(d);
  const int p = DegreeOf<kDegree>(batch.p);
  const int max_order = kMaxOrder == kAnyOrder ? batch.max_order : kMaxOrder;
  const int top = std::min(max_order, p);
  const absl::Span<const double> knots(batch.knots,
                                       static_cast<size_t>(batch.n + p) + 2);
  const int last = FindSpan(batch.n, p, knots[batch.n + 1], knots);
  // The mixed groups' workspace is another, so that this loop's arrays stay
  // local to it.
  LaneStorage<kDegree, kDimension> storage(lanes, p, top, batch.dimension);
  LaneStorage<kDegree, kDimension> mixed(lanes, p, top, batch.dimension);
  LaneWorkspace& work = storage.work();
  const LaneResults results{
      .soa = work.sums, .dimension = batch.dimension, .top = top};
  int span = p;
  for (size_t r = begin; r < end; r += lanes) {
    const size_t count = std::min(lanes, end - r);
    const LaneVec u = LoadParameters(d, batch.parameters, r, count);
    if (AllOnSpan(d, batch.knots, span, last, u)) {
      EvaluateOnSpan<kDegree, kDimension>(d, batch, top, span, u, work);
      WriteGroup<kDimension>(d, results, max_order, batch.output, r, count);
    } else {
      span = EvaluateMixedGroup<kDegree, kDimension>(d, batch, top, span, r,
                                                     count, u, mixed.work());
    }
  }
}

}  // namespace

void EvaluateBSplineChunkLanes(const BSplineLanesBatch& batch, size_t begin,
                               size_t end) {
  // Compiled-in degrees also get kernels for positions alone and for
  // positions with first derivatives.
  WithDegreeAndDimension(
      batch.p, batch.dimension, [&]<int kDegree, int kDimension>() {
        if constexpr (kDegree != internal::kAnyDegree) {
          if (batch.max_order == 0) {
            return EvaluateChunk<kDegree, kDimension, 0>(batch, begin, end);
          }
          if (batch.max_order == 1) {
            return EvaluateChunk<kDegree, kDimension, 1>(batch, begin, end);
          }
        }
        EvaluateChunk<kDegree, kDimension, kAnyOrder>(batch, begin, end);
      });
}

int64_t TargetOfLanes() { return HWY_TARGET; }

}  // namespace freeform::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace freeform::simd {

HWY_EXPORT(EvaluateBSplineChunkLanes);
HWY_EXPORT(TargetOfLanes);

void EvaluateBSplineChunk(const BSplineLanesBatch& batch, size_t begin,
                          size_t end) {
  HWY_DYNAMIC_DISPATCH(EvaluateBSplineChunkLanes)(batch, begin, end);
}

int64_t DispatchedTarget() { return HWY_DYNAMIC_DISPATCH(TargetOfLanes)(); }

}  // namespace freeform::simd
#endif  // HWY_ONCE
