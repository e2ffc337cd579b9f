// What the scalar B-spline evaluator (bspline.cc) and its Highway twin
// across parameters (simd/bspline_simd.cc) share: kernels compiled for low
// degrees, and the reciprocal knot differences of a span that both multiply
// by instead of dividing. Internal to the core.
#ifndef FREEFORM_CORE_SRC_BSPLINE_SPANS_H_
#define FREEFORM_CORE_SRC_BSPLINE_SPANS_H_

namespace freeform::internal {

// Template argument of the kernels for a degree known only at run time.
inline constexpr int kAnyDegree = -1;

// Degrees 0..kMaxInlineDegree get kernels compiled for their degree: the
// basis lives in fixed-size arrays and the loops over it unroll.
inline constexpr int kMaxInlineDegree = 5;

template <int kDegree>
constexpr int DegreeOf(int runtime_degree) {
  if constexpr (kDegree == kAnyDegree) {
    return runtime_degree;
  } else {
    return kDegree;
  }
}

// Calls f.template operator()<p>() when p <= kMaxInlineDegree, else
// f.template operator()<kAnyDegree>().
template <int kDegree = 0, typename F>
void WithDegree(int p, F&& f) {
  if constexpr (kDegree > kMaxInlineDegree) {
    f.template operator()<kAnyDegree>();
  } else if (p == kDegree) {
    f.template operator()<kDegree>();
  } else {
    WithDegree<kDegree + 1>(p, f);
  }
}

// Reciprocals of the knot differences that A2.2 and A2.3 divide by on span
// `span`: inverse[j (j - 1) / 2 + r] = 1 / (u_{span+r+1} - u_{span+1-j+r}),
// the textbooks' 1 / (right[r+1] + left[j-r]), for j = 1..p and r < j. They
// depend on the span only, so a batch computes them once per span and the
// work per point has no division. On a non-empty span every difference is
// at least u_{span+1} - u_span > 0.
template <int kDegree>
void InverseKnotDifferences(const double* knots, int span, int runtime_p,
                            double* inverse) {
  const int p = DegreeOf<kDegree>(runtime_p);
  for (int j = 1; j <= p; ++j) {
    for (int r = 0; r < j; ++r) {
      inverse[j * (j - 1) / 2 + r] =
          1.0 / (knots[span + r + 1] - knots[span + 1 - j + r]);
    }
  }
}

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_BSPLINE_SPANS_H_
