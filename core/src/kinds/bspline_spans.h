// What the scalar B-spline evaluator (bspline.cc), its Highway twin across
// parameters (simd/bspline_simd.cc) and the collocation rows of global
// interpolation (open_interpolation.cc) share: kernels compiled for low
// degrees, the reciprocal knot differences of a span that they multiply by
// instead of dividing, and the basis functions of a span (A2.2). Internal to
// the core.
#ifndef FREEFORM_CORE_SRC_KINDS_BSPLINE_SPANS_H_
#define FREEFORM_CORE_SRC_KINDS_BSPLINE_SPANS_H_

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

// The NURBS Book A2.2 (BasisFuns), multiplying by `inverse` (filled by
// InverseKnotDifferences for `span`) instead of dividing. Writes
// N_{span-p+r,p}(u) to n[r], r = 0..p, or with kAllDegrees every degree
// j <= p, N_{span-j+r,j}(u), to n[r * (p + 1) + j] (the upper triangle of
// A2.3's ndu). When `first` is not null it also gets the first derivatives,
// N'_{i,p} = p N_{i,p-1} / (u_{i+p} - u_i) - p N_{i+1,p-1} /
// (u_{i+p+1} - u_{i+1}) (The NURBS Book eq. 2.7), whose quotients are the
// `temp` values of the last step. `left` and `right` hold p + 1 doubles.
template <int kDegree, bool kAllDegrees>
inline void BasisFunctionsOn(const double* knots, int span, double u,
                             int runtime_p, const double* inverse, double* left,
                             double* right, double* n, double* first) {
  const int p = DegreeOf<kDegree>(runtime_p);
  const auto at = [n, p](int r, int j) -> double& {
    return kAllDegrees ? n[r * (p + 1) + j] : n[r];
  };
  at(0, 0) = 1.0;
  double previous_temp = 0.0;  // N_{i,p-1} / (u_{i+p} - u_i), i one lower
#pragma GCC unroll 8
  for (int j = 1; j <= p; ++j) {
    left[j] = u - knots[span + 1 - j];
    right[j] = knots[span + j] - u;
    const double* inverse_j = inverse + j * (j - 1) / 2;
    double saved = 0.0;
#pragma GCC unroll 8
    for (int r = 0; r < j; ++r) {
      const double temp = at(r, j - 1) * inverse_j[r];
      at(r, j) = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
      if (j == p && first != nullptr) {
        first[r] = p * (previous_temp - temp);
        previous_temp = temp;
      }
    }
    at(j, j) = saved;
  }
  if (first != nullptr) first[p] = p * previous_temp;
}

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_KINDS_BSPLINE_SPANS_H_
