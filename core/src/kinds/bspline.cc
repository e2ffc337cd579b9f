#include "freeform/core/bspline.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "base/checked_chunks.h"
#include "freeform/core/bezier.h"
#include "freeform/core/rational.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "kinds/bspline_spans.h"
#include "kinds/scalar_reference.h"
#include "kinds/simd/curve_simd.h"
#include "kinds/validated_bspline.h"

namespace freeform {
namespace {

using internal::BasisFunctionsOn;
using internal::DegreeOf;
using internal::InverseKnotDifferences;
using internal::kAnyDegree;
using internal::WithDegree;

// How many spans FindSpanFrom walks from its hint before it searches.
constexpr int kSpanWalk = 4;

// The intermediate values of A2.2 and A2.3, carved out of one scratch array
// in this order: left, right and inverse (BasisScratchSize(p) doubles in
// all), then ndu and rows for A2.3 (BasisDerivativesScratchSize(p) in all).
struct BasisWorkspace {
  double* left = nullptr;     // p + 1
  double* right = nullptr;    // p + 1
  double* inverse = nullptr;  // p (p + 1) / 2, see InverseKnotDifferences
  double* ndu = nullptr;      // (p + 1)^2
  double* rows = nullptr;     // 2 (p + 1)
};

BasisWorkspace MakeWorkspace(double* scratch, int p) {
  const int w = p + 1;
  BasisWorkspace work;
  work.left = scratch;
  work.right = work.left + w;
  work.inverse = work.right + w;
  work.ndu = work.inverse + p * w / 2;
  work.rows = work.ndu + w * w;
  return work;
}

// BasisFunctionsOn with the workspace's arrays, or for a compiled-in degree
// with arrays on the stack that the unrolled loops keep in registers.
template <int kDegree, bool kAllDegrees = false>
inline void BasisFunctionsOf(const double* knots, int span, double u,
                             int runtime_p, const BasisWorkspace& work,
                             double* n, double* first) {
  if constexpr (kDegree == kAnyDegree || kAllDegrees) {
    BasisFunctionsOn<kDegree, kAllDegrees>(knots, span, u, runtime_p,
                                           work.inverse, work.left, work.right,
                                           n, first);
  } else {
    std::array<double, kDegree + 1> left;
    std::array<double, kDegree + 1> right;
    std::array<double, kDegree + 1> values;
    BasisFunctionsOn<kDegree, false>(knots, span, u, kDegree, work.inverse,
                                     left.data(), right.data(), values.data(),
                                     first);
    std::copy(values.begin(), values.end(), n);
  }
}

// The NURBS Book A2.3 (DersBasisFuns): ders[k * (p + 1) + j] =
// N^(k)_{span-p+j,p}(u) for k = 0..top (top <= p), with work.inverse filled
// for `span`; the textbook's divisions by the lower triangle of ndu are
// products with work.inverse.
template <int kDegree>
void BasisDerivativesOf(const double* knots, int span, double u, int runtime_p,
                        int top, const BasisWorkspace& work, double* ders) {
  const int p = DegreeOf<kDegree>(runtime_p);
  const int w = p + 1;
  const double* ndu = work.ndu;
  BasisFunctionsOf<kDegree, true>(knots, span, u, p, work, work.ndu, nullptr);
  const auto inverse = [&work](int j, int r) {
    return work.inverse[j * (j - 1) / 2 + r];  // 1 / ndu[j][r]
  };
  for (int j = 0; j <= p; ++j) ders[j] = ndu[j * w + p];
  // The k-th derivative of N_{span-p+r,p} combines the degree p - k
  // functions with the coefficients a[k][j] (The NURBS Book eq. 2.10).
  for (int r = 0; r <= p; ++r) {
    double* previous = work.rows;
    double* current = work.rows + w;
    previous[0] = 1.0;
    for (int k = 1; k <= top; ++k) {
      const int rk = r - k;
      const int pk = p - k;
      double d = 0.0;
      if (r >= k) {
        current[0] = previous[0] * inverse(pk + 1, rk);
        d = current[0] * ndu[rk * w + pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = r - 1 <= pk ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        current[j] = (previous[j] - previous[j - 1]) * inverse(pk + 1, rk + j);
        d += current[j] * ndu[(rk + j) * w + pk];
      }
      if (r <= pk) {
        current[k] = -previous[k - 1] * inverse(pk + 1, r);
        d += current[k] * ndu[r * w + pk];
      }
      ders[k * w + r] = d;
      std::swap(previous, current);
    }
  }
  double factor = p;  // p! / (p - k)!
  for (int k = 1; k <= top; ++k) {
    for (int j = 0; j <= p; ++j) ders[k * w + j] *= factor;
    factor *= p - k;
  }
}

// Scratch of one chunk: (p + 1)^2 basis derivatives and the workspace.
constexpr size_t ChunkScratchSize(int p) {
  return (static_cast<size_t>(p) + 1) * (static_cast<size_t>(p) + 1) +
         BasisDerivativesScratchSize(p);
}

// On the stack for a compiled-in degree, on the heap otherwise.
template <int kDegree>
using ChunkStorage = std::conditional_t<
    kDegree == kAnyDegree, std::vector<double>,
    std::array<double, ChunkScratchSize(std::max(kDegree, 0))>>;

// The local basis of the points of one chunk: derivatives 0..top of the
// p + 1 functions of a span, by A2.2 (with the first derivative by eq. 2.7)
// for top <= 1 and A2.3 above, with the reciprocal knot differences kept
// while the span stays the same.
template <int kDegree>
class ChunkBasis {
 public:
  ChunkBasis(const double* knots, int p, int top)
      : knots_(knots), p_(DegreeOf<kDegree>(p)), top_(top) {
    if constexpr (kDegree == kAnyDegree) storage_.resize(ChunkScratchSize(p));
    work_ = MakeWorkspace(storage_.data() + (p_ + 1) * (p_ + 1), p_);
  }
  ChunkBasis(const ChunkBasis&) = delete;
  ChunkBasis& operator=(const ChunkBasis&) = delete;

  // Evaluate returns basis[k * (p + 1) + j] = N^(k)_{span-p+j,p}(u) for
  // k = 0..top, valid until the next call.
  const double* Evaluate(int span, double u) {
    double* basis = storage_.data();
    if (span != span_) {
      InverseKnotDifferences<kDegree>(knots_, span, p_, work_.inverse);
      span_ = span;
    }
    if (top_ <= 1) {
      BasisFunctionsOf<kDegree>(knots_, span, u, p_, work_, basis,
                                top_ == 1 ? basis + p_ + 1 : nullptr);
    } else {
      BasisDerivativesOf<kDegree>(knots_, span, u, p_, top_, work_, basis);
    }
    return basis;
  }

 private:
  const double* knots_;
  int p_;
  int top_;
  int span_ = -1;
  ChunkStorage<kDegree> storage_;
  BasisWorkspace work_;
};

// out[c] = sum_j basis[j] * points[j * dimension + c]: one derivative of the
// curve from the p + 1 control points of a span (The NURBS Book A3.2). A
// compiled-in dimension (kDimension > 0) keeps the sums in registers; the
// order of the additions is the same either way.
template <int kDegree, int kDimension>
inline void CombinePointsOf(const double* basis, const double* points,
                            int runtime_p, int runtime_dimension, double* out) {
  const int p = DegreeOf<kDegree>(runtime_p);
  if constexpr (kDimension > 0) {
    std::array<double, kDimension> sums{};
#pragma GCC unroll 8
    for (int j = 0; j <= p; ++j) {
#pragma GCC unroll 4
      for (int c = 0; c < kDimension; ++c) {
        sums[c] += basis[j] * points[j * kDimension + c];
      }
    }
    std::copy(sums.begin(), sums.end(), out);
  } else {
    for (int c = 0; c < runtime_dimension; ++c) {
      double sum = 0.0;
      for (int j = 0; j <= p; ++j) {
        sum += basis[j] * points[j * runtime_dimension + c];
      }
      out[c] = sum;
    }
  }
}

template <int kDegree>
inline void CombinePoints(const double* basis, const double* points, int p,
                          int dimension, double* out) {
  switch (dimension) {
    case 2:
      return CombinePointsOf<kDegree, 2>(basis, points, p, dimension, out);
    case 3:
      return CombinePointsOf<kDegree, 3>(basis, points, p, dimension, out);
    case 4:
      return CombinePointsOf<kDegree, 4>(basis, points, p, dimension, out);
    default:
      return CombinePointsOf<kDegree, 0>(basis, points, p, dimension, out);
  }
}

// FindSpan on a raw knot array.
int SpanOf(int n, int p, double u, const double* knots) {
  // The span starts one before the first of u_{p+1..n} beyond u; at the end
  // of the domain, one before the first equal to u_{n+1}.
  const double* first = knots + p + 1;
  const double* last = knots + n + 1;
  const double* next = u < knots[n + 1]
                           ? std::upper_bound(first, last, u)
                           : std::lower_bound(first, last, knots[n + 1]);
  return static_cast<int>(next - knots) - 1;
}

// FindSpanFrom on a raw knot array.
inline int SpanFrom(int hint, int n, int p, double u, const double* knots) {
  int s = std::clamp(hint, p, n);
  for (int step = 0; step <= kSpanWalk; ++step) {
    if (u < knots[s]) {
      if (s == p) break;
      --s;
    } else if (u >= knots[s + 1]) {
      if (s == n) break;
      ++s;
    } else {
      return s;
    }
  }
  return SpanOf(n, p, u, knots);
}

// The buffer of every derivative order.
std::vector<double*> OutputBuffers(CurveOutput output) {
  std::vector<double*> buffers;
  for (const absl::Span<double> buffer : output)
    buffers.push_back(buffer.data());
  return buffers;
}

// What every chunk of one curve evaluation reads.
struct CurveBatch {
  int p = 0;
  int n = 0;
  int dimension = 0;
  // dimension + 1 for a rational curve (homogeneous points), else dimension.
  int work_dimension = 0;
  int max_order = 0;
  const double* control = nullptr;  // n + 1 points of work_dimension values
  const double* knots = nullptr;
  const double* parameters = nullptr;
  std::vector<double*> output;  // one buffer per order
};

// Evaluates parameters [begin, end) of `batch`: span, local basis
// derivatives, their combination with the span's control points (A3.2) and,
// for a rational curve, the projection of the homogeneous derivatives.
template <int kDegree>
void EvaluateCurveChunk(const CurveBatch& batch, size_t begin, size_t end) {
  const int p = DegreeOf<kDegree>(batch.p);
  const int w = batch.work_dimension;
  const int dimension = batch.dimension;
  const int max_order = batch.max_order;
  const int top = std::min(max_order, p);
  const bool rational = w != dimension;
  ChunkBasis<kDegree> chunk_basis(batch.knots, p, top);
  const size_t orders = static_cast<size_t>(max_order) + 1;
  std::vector<double> homogeneous(rational ? orders * w : 0);
  std::vector<double> projected(rational ? orders * dimension : 0);
  int span = p;
  for (size_t r = begin; r < end; ++r) {
    const double u = batch.parameters[r];
    span = SpanFrom(span, batch.n, p, u, batch.knots);
    const double* basis = chunk_basis.Evaluate(span, u);
    const double* points = batch.control + static_cast<ptrdiff_t>(span - p) * w;
    for (int k = 0; k <= max_order; ++k) {
      double* out = rational ? homogeneous.data() + k * w
                             : batch.output[k] + r * dimension;
      if (k <= top) {
        CombinePoints<kDegree>(basis + k * (p + 1), points, p, w, out);
      } else {
        std::fill_n(out, w, 0.0);
      }
    }
    if (!rational) continue;
    ProjectHomogeneousDerivatives(homogeneous.data(), dimension, max_order,
                                  projected.data());
    for (int k = 0; k <= max_order; ++k) {
      std::copy_n(projected.data() + k * dimension, dimension,
                  batch.output[k] + r * dimension);
    }
  }
}

// What every chunk of one dense basis evaluation reads.
struct BasisBatch {
  int p = 0;
  int function_count = 0;
  int max_order = 0;
  const double* knots = nullptr;
  const double* weights = nullptr;  // null: non-rational
  const double* parameters = nullptr;
  std::vector<double*> output;  // one buffer per order
};

// Turns basis[k * (p + 1) + j] (k = 0..top) into the derivatives of the
// rational basis R_{span-p+j} = w N / W for k = 0..max_order: the p + 1
// products w_{span-p+j} N_{span-p+j} are a homogeneous point of dimension
// p + 1 with weight W = sum_j w_j N_j, projected like a NURBS curve.
void RationalBasis(const BasisBatch& batch, int span, int top,
                   const double* basis, double* homogeneous,
                   double* projected) {
  const int p = batch.p;
  const int w = p + 2;
  for (int k = 0; k <= batch.max_order; ++k) {
    double* row = homogeneous + k * w;
    double weight = 0.0;
    for (int j = 0; j <= p; ++j) {
      row[j] =
          k <= top ? batch.weights[span - p + j] * basis[k * (p + 1) + j] : 0.0;
      weight += row[j];
    }
    row[p + 1] = weight;
  }
  ProjectHomogeneousDerivatives(homogeneous, p + 1, batch.max_order, projected);
}

// Evaluates parameters [begin, end) of `batch` into dense rows.
template <int kDegree>
void EvaluateBasisChunk(const BasisBatch& batch, size_t begin, size_t end) {
  const int p = DegreeOf<kDegree>(batch.p);
  const int max_order = batch.max_order;
  const int top = std::min(max_order, p);
  const size_t count = static_cast<size_t>(batch.function_count);
  const bool rational = batch.weights != nullptr;
  ChunkBasis<kDegree> chunk_basis(batch.knots, p, top);
  const size_t orders = static_cast<size_t>(max_order) + 1;
  std::vector<double> homogeneous(rational ? orders * (p + 2) : 0);
  std::vector<double> projected(rational ? orders * (p + 1) : 0);
  int span = p;
  for (size_t r = begin; r < end; ++r) {
    const double u = batch.parameters[r];
    span = SpanFrom(span, batch.function_count - 1, p, u, batch.knots);
    const double* basis = chunk_basis.Evaluate(span, u);
    if (rational) {
      RationalBasis(batch, span, top, basis, homogeneous.data(),
                    projected.data());
    }
    const double* local = rational ? projected.data() : basis;
    for (int k = 0; k <= max_order; ++k) {
      double* row = batch.output[k] + r * count;
      std::fill_n(row, count, 0.0);
      if (rational || k <= top) {
        std::copy_n(local + k * (p + 1), p + 1, row + (span - p));
      }
    }
  }
}

absl::Status ValidateDegree(int p) {
  if (p < 0) {
    return InvalidFieldError("degree", absl::StrCat("must be >= 0, got ", p));
  }
  return absl::OkStatus();
}

// Knots must be finite and non-decreasing.
absl::Status ValidateKnotOrder(absl::Span<const double> knots) {
  RETURN_IF_ERROR(ValidateFinite(knots, "knots"));
  for (size_t i = 1; i < knots.size(); ++i) {
    if (knots[i] < knots[i - 1]) {
      return InvalidFieldError(
          IndexedField("knots", i),
          absl::StrCat("knots must be non-decreasing, got ", knots[i],
                       " after ", knots[i - 1]));
    }
  }
  return absl::OkStatus();
}

// A value strictly inside the domain may appear at most p times (the curve
// stays continuous; once for degree 0, whose curve is a step function), any
// other value at most p + 1 times (every basis
// function is nonzero somewhere: the knot vector is (p + 1)-regular,
// docs/references.md, 'Cox-de Boor recurrence'). Names the first knot beyond
// the allowed multiplicity.
absl::Status ValidateMultiplicities(int p, int n,
                                    absl::Span<const double> knots) {
  const double start = knots[p];
  const double end = knots[n + 1];
  size_t run = 0;  // first index of the current run of equal knots
  for (size_t i = 1; i <= knots.size(); ++i) {
    if (i < knots.size() && knots[i] == knots[run]) continue;
    const double value = knots[run];
    const bool interior = start < value && value < end;
    const size_t allowed = interior ? static_cast<size_t>(std::max(p, 1))
                                    : static_cast<size_t>(p) + 1;
    if (i - run > allowed) {
      return InvalidFieldError(
          IndexedField("knots", run + allowed),
          absl::StrCat("knot value ", value, " appears ", i - run,
                       " times; a degree ", p, " curve allows at most ",
                       allowed,
                       interior && p > 0 ? " inside the domain (more would "
                                           "make it discontinuous)"
                       : interior        ? " inside the domain"
                                         : ""));
    }
    run = i;
  }
  return absl::OkStatus();
}

// n + p + 2 knots whose count has been checked.
absl::Status ValidateKnots(int p, int n, absl::Span<const double> knots) {
  RETURN_IF_ERROR(ValidateKnotOrder(knots));
  RETURN_IF_ERROR(ValidateMultiplicities(p, n, knots));
  if (!(knots[p] < knots[n + 1])) {
    return InvalidFieldError(
        "knots", absl::StrCat("the domain [u_p, u_{n+1}] = [", knots[p], ", ",
                              knots[n + 1], "] is empty"));
  }
  return absl::OkStatus();
}

// The denominator sum_i w_i N_{i,p} must be positive at both ends of every
// non-empty span, as evaluation computes it there; inside a span every
// N_{s-p..s,p} is positive, so it is then positive on the whole domain.
absl::Status ValidateDenominator(int p, int n, absl::Span<const double> knots,
                                 absl::Span<const double> weights) {
  std::vector<double> basis(static_cast<size_t>(p) + 1);
  std::vector<double> scratch(BasisScratchSize(p));
  for (int s = p; s <= n; ++s) {
    if (!(knots[s] < knots[s + 1])) continue;
    for (const double u : {knots[s], knots[s + 1]}) {
      BasisFunctions(s, u, p, knots, absl::MakeSpan(basis),
                     absl::MakeSpan(scratch));
      double denominator = 0.0;
      for (int j = 0; j <= p; ++j) denominator += weights[s - p + j] * basis[j];
      if (denominator > 0.0) continue;
      const auto largest = std::max_element(basis.begin(), basis.end());
      return InvalidFieldError(
          IndexedField("weights", s - p + (largest - basis.begin())),
          absl::StrCat("the curve is infinite at u = ", u,
                       ": the control points whose basis functions are "
                       "nonzero there all have weight 0"));
    }
  }
  return absl::OkStatus();
}

absl::Status ValidateWeights(int p, int n, absl::Span<const double> knots,
                             absl::Span<const double> weights,
                             absl::string_view owners) {
  const size_t count = static_cast<size_t>(n) + 1;
  if (weights.size() != count) {
    return InvalidFieldError(
        "weights", absl::StrCat("has ", weights.size(), " weights for ", count,
                                " ", owners));
  }
  RETURN_IF_ERROR(ValidateWeightValues(weights));
  return ValidateDenominator(p, n, knots, weights);
}

// The rules shared by curves and bases, once the knot count n + p + 2 is
// right; `owners` names what the weights belong to.
absl::Status ValidateKnotsAndWeights(int p, int n,
                                     absl::Span<const double> knots,
                                     absl::Span<const double> weights,
                                     absl::string_view owners) {
  RETURN_IF_ERROR(ValidateKnots(p, n, knots));
  if (weights.empty()) return absl::OkStatus();
  return ValidateWeights(p, n, knots, weights, owners);
}

}  // namespace

absl::Status ValidateBSplineCurve(const BSplineCurveView& curve) {
  const int p = curve.degree;
  RETURN_IF_ERROR(ValidateDegree(p));
  RETURN_IF_ERROR(ValidatePoints(curve.control_points, "control_points"));
  const size_t count = curve.control_points.size();
  if (count < static_cast<size_t>(p) + 1) {
    return InvalidFieldError(
        "control_points.coordinates",
        absl::StrCat("a degree ", p, " curve needs at least ", p + 1,
                     " control points, got ", count));
  }
  const size_t expected = count + static_cast<size_t>(p) + 1;
  if (curve.knots.size() != expected) {
    return InvalidFieldError(
        "knots", absl::StrCat("expected ", expected, " knots (", count,
                              " control points + degree ", p, " + 1), got ",
                              curve.knots.size()));
  }
  return ValidateKnotsAndWeights(p, static_cast<int>(count) - 1, curve.knots,
                                 curve.weights, "control points");
}

absl::Status ValidateBSplineBasis(int p, absl::Span<const double> knots,
                                  absl::Span<const double> weights) {
  RETURN_IF_ERROR(ValidateDegree(p));
  const size_t minimum = 2 * (static_cast<size_t>(p) + 1);
  if (knots.size() < minimum) {
    return InvalidFieldError(
        "knots", absl::StrCat("a degree ", p, " basis needs at least ", minimum,
                              " knots, got ", knots.size()));
  }
  const int n = static_cast<int>(knots.size()) - p - 2;
  return ValidateKnotsAndWeights(p, n, knots, weights, "basis functions");
}

ParameterDomain BSplineDomain(const BSplineCurveView& curve) {
  const size_t n = curve.control_points.size() - 1;
  return {.start = curve.knots[static_cast<size_t>(curve.degree)],
          .end = curve.knots[n + 1]};
}

int FindSpan(int n, int p, double u, absl::Span<const double> knots) {
  return SpanOf(n, p, u, knots.data());
}

int FindSpanFrom(int hint, int n, int p, double u,
                 absl::Span<const double> knots) {
  return SpanFrom(hint, n, p, u, knots.data());
}

void BasisFunctions(int span, double u, int p, absl::Span<const double> knots,
                    absl::Span<double> values, absl::Span<double> scratch) {
  const BasisWorkspace work = MakeWorkspace(scratch.data(), p);
  InverseKnotDifferences<kAnyDegree>(knots.data(), span, p, work.inverse);
  BasisFunctionsOf<kAnyDegree>(knots.data(), span, u, p, work, values.data(),
                               nullptr);
}

void BasisFunctionDerivatives(int span, double u, int p, int max_order,
                              absl::Span<const double> knots,
                              absl::Span<double> ders,
                              absl::Span<double> scratch) {
  const int top = std::min(max_order, p);
  const BasisWorkspace work = MakeWorkspace(scratch.data(), p);
  InverseKnotDifferences<kAnyDegree>(knots.data(), span, p, work.inverse);
  BasisDerivativesOf<kAnyDegree>(knots.data(), span, u, p, top, work,
                                 ders.data());
  std::fill(ders.begin() + (top + 1) * (p + 1),
            ders.begin() + (max_order + 1) * (p + 1), 0.0);
}

absl::Status EvaluateBSplineCurve(const BSplineCurveView& curve,
                                  absl::Span<const double> parameters,
                                  CurveOutput output,
                                  const ExecutionContext& context) {
  RETURN_IF_ERROR(ValidateBSplineCurve(curve));
  return internal::EvaluateValidBSplineCurve(curve, parameters, output,
                                             context);
}

namespace {

// Which code evaluates the chunks of a batch.
enum class CurveKernel {
  kLanes,   // simd/curve_simd.h where it applies (non-rational curves)
  kScalar,  // EvaluateCurveChunk, point by point
};

absl::Status EvaluateBSplineBatch(const BSplineCurveView& curve,
                                  absl::Span<const double> parameters,
                                  CurveOutput output,
                                  const ExecutionContext& context,
                                  CurveKernel kernel) {
  const ParameterDomain domain = BSplineDomain(curve);
  const int dimension = curve.control_points.dimension;
  // The parameters are checked chunk by chunk (checked_chunks.h).
  RETURN_IF_ERROR(ValidateCurveOutput(output, parameters.size(), dimension));
  const auto in_domain_chunks =
      [&](absl::FunctionRef<void(size_t, size_t)> body) {
        return internal::ParallelForInRange(
            parameters, domain.start, domain.end, "parameters", context, body);
      };
  const std::vector<double> homogeneous =
      curve.rational() ? HomogeneousPoints(curve.control_points, curve.weights)
                       : std::vector<double>();
  const CurveBatch batch{
      .p = curve.degree,
      .n = static_cast<int>(curve.control_points.size()) - 1,
      .dimension = dimension,
      .work_dimension = curve.rational() ? dimension + 1 : dimension,
      .max_order = static_cast<int>(output.size()) - 1,
      .control = curve.rational() ? homogeneous.data()
                                  : curve.control_points.coordinates.data(),
      .knots = curve.knots.data(),
      .parameters = parameters.data(),
      .output = OutputBuffers(output)};
  if (kernel == CurveKernel::kLanes && !curve.rational()) {
    const simd::BSplineLanesBatch lanes{.p = batch.p,
                                        .n = batch.n,
                                        .dimension = dimension,
                                        .max_order = batch.max_order,
                                        .control = batch.control,
                                        .knots = batch.knots,
                                        .parameters = batch.parameters,
                                        .output = batch.output.data()};
    return in_domain_chunks([&](size_t begin, size_t end) {
      simd::EvaluateBSplineChunk(lanes, begin, end);
    });
  }
  return in_domain_chunks([&](size_t begin, size_t end) {
    WithDegree(batch.p, [&]<int kDegree>() {
      EvaluateCurveChunk<kDegree>(batch, begin, end);
    });
  });
}

}  // namespace

namespace internal {

absl::Status EvaluateValidBSplineCurve(const BSplineCurveView& curve,
                                       absl::Span<const double> parameters,
                                       CurveOutput output,
                                       const ExecutionContext& context) {
  return EvaluateBSplineBatch(curve, parameters, output, context,
                              CurveKernel::kLanes);
}

absl::Status EvaluateBSplineCurveScalar(const BSplineCurveView& curve,
                                        absl::Span<const double> parameters,
                                        CurveOutput output) {
  RETURN_IF_ERROR(ValidateBSplineCurve(curve));
  return EvaluateBSplineBatch(curve, parameters, output, {},
                              CurveKernel::kScalar);
}

}  // namespace internal

absl::Status EvaluateBSplineBasis(int degree, absl::Span<const double> knots,
                                  absl::Span<const double> weights,
                                  absl::Span<const double> parameters,
                                  CurveOutput output,
                                  const ExecutionContext& context) {
  RETURN_IF_ERROR(ValidateBSplineBasis(degree, knots, weights));
  return internal::EvaluateValidBSplineBasis(degree, knots, weights, parameters,
                                             output, context);
}

namespace internal {

absl::Status EvaluateValidBSplineBasis(int degree,
                                       absl::Span<const double> knots,
                                       absl::Span<const double> weights,
                                       absl::Span<const double> parameters,
                                       CurveOutput output,
                                       const ExecutionContext& context) {
  const int function_count = static_cast<int>(knots.size()) - degree - 1;
  RETURN_IF_ERROR(ValidateBatch(parameters, knots[static_cast<size_t>(degree)],
                                knots[static_cast<size_t>(function_count)],
                                output, function_count));
  const BasisBatch batch{.p = degree,
                         .function_count = function_count,
                         .max_order = static_cast<int>(output.size()) - 1,
                         .knots = knots.data(),
                         .weights = weights.empty() ? nullptr : weights.data(),
                         .parameters = parameters.data(),
                         .output = OutputBuffers(output)};
  return ParallelFor(parameters.size(), context, [&](size_t begin, size_t end) {
    WithDegree(batch.p, [&]<int kDegree>() {
      EvaluateBasisChunk<kDegree>(batch, begin, end);
    });
  });
}

}  // namespace internal

}  // namespace freeform
