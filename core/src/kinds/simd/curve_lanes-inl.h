// Per-target helpers shared by the Highway curve kernels (bspline_simd.cc,
// bezier_simd.cc): loading a group of parameters into one vector and
// writing a group's results, kept one vector per coordinate (structure of
// arrays), into the point-after-point output of curve_output.h. Included
// once per target by foreach_target.h, hence the toggling include guard.
#if defined(FREEFORM_CORE_SRC_KINDS_SIMD_CURVE_LANES_INL_H_) == \
    defined(HWY_TARGET_TOGGLE)
#ifdef FREEFORM_CORE_SRC_KINDS_SIMD_CURVE_LANES_INL_H_
#undef FREEFORM_CORE_SRC_KINDS_SIMD_CURVE_LANES_INL_H_
#else
#define FREEFORM_CORE_SRC_KINDS_SIMD_CURVE_LANES_INL_H_
#endif

#include <algorithm>
#include <cstddef>

#include "hwy/highway.h"
#include "kinds/bspline_spans.h"

HWY_BEFORE_NAMESPACE();
namespace freeform::simd::HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

using LaneTag = hn::ScalableTag<double>;
using LaneVec = hn::Vec<LaneTag>;

// The most lanes a vector of doubles has on this target, for buffers on
// the stack.
constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);

// Template argument for a size known only at run time.
constexpr int kRuntime = 0;

// Calls f.template operator()<kDegree, kDimension>() with the degree
// compiled in for 0..internal::kMaxInlineDegree (else internal::kAnyDegree)
// and the dimension for 2, 3 and 4 (else kRuntime).
template <typename F>
HWY_INLINE void WithDegreeAndDimension(int degree, int dimension, F&& f) {
  internal::WithDegree(degree, [&]<int kDegree>() {
    switch (dimension) {
      case 2:
        return f.template operator()<kDegree, 2>();
      case 3:
        return f.template operator()<kDegree, 3>();
      case 4:
        return f.template operator()<kDegree, 4>();
      default:
        return f.template operator()<kDegree, kRuntime>();
    }
  });
}

template <int kSize>
constexpr int SizeOf(int runtime_size) {
  return kSize == kRuntime ? runtime_size : kSize;
}

// LoadParameters returns parameters[r..r+count) in lanes 0..count-1 and
// parameters[r] in the lanes beyond `count` (so that they stay in the
// domain and on the first lane's span).
HWY_INLINE LaneVec LoadParameters(LaneTag d, const double* parameters, size_t r,
                                  size_t count) {
  const size_t lanes = hn::Lanes(d);
  if (count == lanes) return hn::LoadU(d, parameters + r);
  HWY_ALIGN double padded[kMaxLanes];
  std::fill_n(padded, lanes, parameters[r]);
  std::copy_n(parameters + r, count, padded);
  return hn::Load(d, padded);
}

// One group's results: soa[(k * dimension + c) * lanes + i] is coordinate c
// of derivative k at lane i, for k = 0..top.
struct LaneResults {
  const double* soa = nullptr;
  int dimension = 0;
  int top = 0;
};

// Writes one full vector of points of kDimension (2..4) coordinates from
// their coordinate vectors.
template <int kDimension>
HWY_INLINE void StoreInterleavedPoints(LaneTag d, const double* coordinates,
                                       double* out) {
  const size_t lanes = hn::Lanes(d);
  const auto at = [&](int c) { return hn::Load(d, coordinates + c * lanes); };
  if constexpr (kDimension == 2) {
    hn::StoreInterleaved2(at(0), at(1), d, out);
  } else if constexpr (kDimension == 3) {
    hn::StoreInterleaved3(at(0), at(1), at(2), d, out);
  } else {
    static_assert(kDimension == 4);
    hn::StoreInterleaved4(at(0), at(1), at(2), at(3), d, out);
  }
}

// Writes the points of one derivative order for lanes i < count with
// keep(i) to out + i * dimension.
template <int kDimension, typename Keep>
HWY_INLINE void StoreLanes(LaneTag d, const double* coordinates,
                           int runtime_dimension, size_t count, Keep keep,
                           bool all, double* out) {
  const size_t lanes = hn::Lanes(d);
  const int dimension = SizeOf<kDimension>(runtime_dimension);
  if constexpr (kDimension != kRuntime) {
    if (all && count == lanes) {
      return StoreInterleavedPoints<kDimension>(d, coordinates, out);
    }
  }
  if (dimension == 1 && all && count == lanes) {
    return hn::StoreU(hn::Load(d, coordinates), d, out);
  }
  for (size_t i = 0; i < count; ++i) {
    if (!keep(i)) continue;
    for (int c = 0; c < dimension; ++c) {
      out[i * dimension + c] = coordinates[c * lanes + i];
    }
  }
}

// WriteLanes writes a group's results for the parameters r..r+count-1 into
// output[0..max_order] (orders above results.top are zero), only for the
// lanes i with keep(i) unless `all`.
template <int kDimension, typename Keep>
HWY_INLINE void WriteLanes(LaneTag d, const LaneResults& results, int max_order,
                           double* const* output, size_t r, size_t count,
                           Keep keep, bool all) {
  const size_t lanes = hn::Lanes(d);
  const int dimension = SizeOf<kDimension>(results.dimension);
  const size_t offset = r * static_cast<size_t>(dimension);
#pragma GCC unroll 2
  for (int k = 0; k <= max_order; ++k) {
    double* out = output[k] + offset;
    if (k <= results.top) {
      StoreLanes<kDimension>(
          d, results.soa + static_cast<size_t>(k * dimension) * lanes,
          dimension, count, keep, all, out);
      continue;
    }
    for (size_t i = 0; i < count; ++i) {
      if (all || keep(i)) std::fill_n(out + i * dimension, dimension, 0.0);
    }
  }
}

// WriteGroup is WriteLanes for every lane.
template <int kDimension>
HWY_INLINE void WriteGroup(LaneTag d, const LaneResults& results, int max_order,
                           double* const* output, size_t r, size_t count) {
  WriteLanes<kDimension>(
      d, results, max_order, output, r, count, [](size_t) { return true; },
      true);
}

}  // namespace freeform::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // include guard toggle
