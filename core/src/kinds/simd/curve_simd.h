// The Highway kernels that evaluate curves with one vector lane per
// parameter (bspline_simd.cc, bezier_simd.cc), as bspline.cc and bezier.cc
// call them. Each call dispatches at run time to the best instruction set
// the CPU offers (AVX-512, AVX2, SSE4 or portable code). The kernels do
// the scalar evaluators' arithmetic in the same order, without fused
// multiply-adds, so every target gives the same bits as the scalar code.
// Internal to the core; thread-safe, no allocation per point.
#ifndef FREEFORM_CORE_SRC_KINDS_SIMD_CURVE_SIMD_H_
#define FREEFORM_CORE_SRC_KINDS_SIMD_CURVE_SIMD_H_

#include <cstddef>
#include <cstdint>

namespace freeform::simd {

// A valid non-rational B-spline curve of degree p with n + 1 control points
// and a batch of parameters in its domain, with one output buffer per
// derivative order 0..max_order (layout of curve_output.h).
struct BSplineLanesBatch {
  int p = 0;
  int n = 0;
  int dimension = 0;
  int max_order = 0;
  const double* control = nullptr;  // n + 1 points of `dimension` values
  const double* knots = nullptr;    // n + p + 2 knots
  const double* parameters = nullptr;
  double* const* output = nullptr;  // max_order + 1 buffers
};

// EvaluateBSplineChunk evaluates parameters [begin, end) of `batch` like
// the scalar A2.2 / A2.3 + A3.2 evaluator of bspline.cc. Sorted parameters
// go span by span, a vector of parameters at a time.
void EvaluateBSplineChunk(const BSplineLanesBatch& batch, size_t begin,
                          size_t end);

// A polynomial Bezier curve of degree n and a batch of parameters in
// [0, 1], evaluated by Warren's ladder (LadderBezierPoint) or by Horner's
// rule in t/(1-t) (HornerBezierPoint).
struct BezierLanesBatch {
  bool ladder = false;  // else Horner
  int n = 0;
  int dimension = 0;
  int max_order = 0;
  // hodographs[k], k = 0..min(max_order, n): the n - k + 1 control points of
  // the k-th derivative, each multiplied by binom(n - k, i).
  const double* const* hodographs = nullptr;
  const double* parameters = nullptr;
  double* const* output = nullptr;  // max_order + 1 buffers
};

// EvaluateBezierChunk evaluates parameters [begin, end) of `batch`.
void EvaluateBezierChunk(const BezierLanesBatch& batch, size_t begin,
                         size_t end);

// DispatchedTarget returns the Highway target (HWY_AVX2, HWY_SSE4, ...) the
// kernels run on now; tests force one with hwy::SetSupportedTargetsForTest.
int64_t DispatchedTarget();

}  // namespace freeform::simd

#endif  // FREEFORM_CORE_SRC_KINDS_SIMD_CURVE_SIMD_H_
