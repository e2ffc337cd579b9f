// AllInRange (range_simd.h) with one comparison per vector of values.
#include "base/simd/range_simd.h"

#include <cstddef>

// foreach_target.h compiles this file once per target: it must follow the
// definition of HWY_TARGET_INCLUDE, and highway.h and the -inl.h headers it.
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "base/simd/range_simd.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// clang-format on

HWY_BEFORE_NAMESPACE();
namespace freeform::simd::HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

bool AllInRangeLanes(const double* values, size_t count, double lo, double hi) {
  const hn::ScalableTag<double> d;
  const size_t lanes = hn::Lanes(d);
  const auto low = hn::Set(d, lo);
  const auto high = hn::Set(d, hi);
  auto inside = hn::FirstN(d, lanes);  // all true
  size_t i = 0;
  for (; i + lanes <= count; i += lanes) {
    const auto v = hn::LoadU(d, values + i);
    inside = hn::And(inside, hn::And(hn::Ge(v, low), hn::Le(v, high)));
  }
  bool tail = true;
  for (; i < count; ++i) tail &= (values[i] >= lo) & (values[i] <= hi);
  return tail && hn::AllTrue(d, inside);
}

}  // namespace freeform::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace freeform::simd {

HWY_EXPORT(AllInRangeLanes);

bool AllInRange(const double* values, size_t count, double lo, double hi) {
  return HWY_DYNAMIC_DISPATCH(AllInRangeLanes)(values, count, lo, hi);
}

}  // namespace freeform::simd
#endif  // HWY_ONCE
