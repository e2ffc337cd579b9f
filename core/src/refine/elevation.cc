#include "freeform/core/elevation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

#include "absl/types/span.h"
#include "base/homogeneous.h"
#include "base/point_array.h"
#include "freeform/core/bspline.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "kinds/bspline_spans.h"
#include "refine/knot_insertion.h"
#include "refine/knots.h"

namespace freeform {
namespace {

using internal::DegreeOf;
using internal::kAnyDegree;
using internal::Lift;
using internal::PointArray;
using internal::ProjectAllowingDirections;
using internal::Spline;
using internal::TransposeBlocks;
using internal::WithDegree;

absl::Status CheckPositive(int value, absl::string_view field) {
  if (value < 1) return InvalidFieldError(field, "must be at least 1");
  return absl::OkStatus();
}

// ElevationCoefficients returns the (p+by+1) x (p+1) matrix of eq. 5.36,
// a[i][j] = C(p,j) C(by,i-j) / C(p+by,i) (zero outside j in
// [max(0,i-by), min(p,i)]), row-major. The binomials are long double so
// that they stay finite and accurate for any practical degree.
std::vector<double> ElevationCoefficients(int p, int by) {
  const int ph = p + by;
  std::vector<long double> binomial(static_cast<size_t>(ph + 1) * (ph + 1), 0);
  auto choose = [&](int n, int k) -> long double& {
    return binomial[static_cast<size_t>(n) * (ph + 1) + k];
  };
  for (int n = 0; n <= ph; ++n) {
    choose(n, 0) = 1;
    for (int k = 1; k <= n; ++k)
      choose(n, k) = choose(n, k - 1) * (n - k + 1) / k;
  }
  std::vector<double> a(static_cast<size_t>(ph + 1) * (p + 1), 0.0);
  for (int i = 0; i <= ph; ++i) {
    for (int j = std::max(0, i - by); j <= std::min(p, i); ++j) {
      a[static_cast<size_t>(i) * (p + 1) + j] =
          static_cast<double>(choose(p, j) * choose(by, i - j) / choose(ph, i));
    }
  }
  return a;
}

// out[i] = sum_j a[i][j] in[j] for i in [first, p + by] (eq. 5.36), with
// `a` from ElevationCoefficients(p, by) and points of `dim` values; `poll`
// (may be null) is told the work of every point.
absl::Status ElevateSegment(const std::vector<double>& a, int p, int by,
                            int dim, const double* in, int first, double* out,
                            CancellationPoll* poll = nullptr) {
  for (int i = first; i <= p + by; ++i) {
    if (poll != nullptr) {
      RETURN_IF_ERROR(poll->Done(static_cast<size_t>(p + 1) * dim));
    }
    double* q = out + static_cast<size_t>(i) * dim;
    std::fill(q, q + dim, 0.0);
    for (int j = std::max(0, i - by); j <= std::min(p, i); ++j) {
      const double c = a[static_cast<size_t>(i) * (p + 1) + j];
      const double* point = in + static_cast<size_t>(j) * dim;
      for (int x = 0; x < dim; ++x) q[x] += c * point[x];
    }
  }
  return absl::OkStatus();
}

// ElevateBezierPoints raises the Bezier control polygon `points` by `by`.
absl::StatusOr<PointArray> ElevateBezierPoints(
    const PointArray& points, int by, const CancellationToken* cancel) {
  const int p = static_cast<int>(points.count()) - 1;
  PointArray result{points.dim,
                    std::vector<double>((points.count() + by) * points.dim)};
  CancellationPoll poll(cancel);
  RETURN_IF_ERROR(ElevateSegment(ElevationCoefficients(p, by), p, by,
                                 points.dim, points.values.data(), 0,
                                 result.values.data(), &poll));
  return result;
}

bool IsClamped(absl::Span<const double> knots, int p) {
  const size_t last = knots.size() - 1;
  for (int i = 1; i <= p; ++i) {
    if (knots[i] != knots[0] || knots[last - i] != knots[last]) return false;
  }
  return true;
}

// KnotsToClamp returns the knots that raise the multiplicity of the domain
// ends a = u_p and b = u_{n+1} of a spline of degree p to p.
std::vector<double> KnotsToClamp(const Spline& spline) {
  const int p = spline.degree;
  const double a = spline.knots[p];
  const double b = spline.knots[spline.points.count()];
  std::vector<double> x;
  for (int s = internal::Multiplicity(spline.knots, a); s < p; ++s) {
    x.push_back(a);
  }
  for (int s = internal::Multiplicity(spline.knots, b); s < p; ++s) {
    x.push_back(b);
  }
  return x;
}

// Clamp rewrites an unclamped spline with the same curve on its domain
// [a, b] = [u_p, u_{n+1}] and knots a (p + 1 times), the knots strictly
// inside the domain, b (p + 1 times). Knot insertion raises the
// multiplicity of a and b to at least p; then only the control points whose
// basis functions reach into the domain are kept: from index e - p, where e
// is the last knot equal to a (the knots before the run of a do not affect
// those functions on the domain), to index f - 1, where f is the first knot
// equal to b.
absl::Status Clamp(Spline& spline, const CancellationToken* cancel) {
  const int p = spline.degree;
  const double a = spline.knots[p];
  const double b = spline.knots[spline.points.count()];
  absl::StatusOr<Spline> refined =
      internal::RefineKnots(spline, KnotsToClamp(spline), cancel);
  if (!refined.ok()) return refined.status();
  const std::vector<double>& knots = refined->knots;
  const int e =
      static_cast<int>(std::upper_bound(knots.begin(), knots.end(), a) -
                       knots.begin()) -
      1;
  const int f = static_cast<int>(
      std::lower_bound(knots.begin(), knots.end(), b) - knots.begin());
  const int first = e - p;
  const int last = f - 1;
  const int dim = refined->points.dim;
  Spline clamped{.degree = p};
  clamped.knots.assign(knots.begin() + first, knots.begin() + last + p + 2);
  clamped.knots.front() = a;
  clamped.knots.back() = b;
  clamped.points.dim = dim;
  clamped.points.values.assign(refined->points.at(first),
                               refined->points.at(last + 1));
  spline = std::move(clamped);
  return absl::OkStatus();
}

// ElevatedKnots returns the clamped `knots` with the multiplicity of every
// distinct value raised by `by`.
std::vector<double> ElevatedKnots(const std::vector<double>& knots, int by) {
  std::vector<double> result;
  result.reserve(knots.size() * static_cast<size_t>(by + 1));
  for (size_t i = 0; i < knots.size(); ++i) {
    result.push_back(knots[i]);
    if (i + 1 == knots.size() || knots[i + 1] != knots[i]) {
      result.insert(result.end(), by, knots[i]);
    }
  }
  return result;
}

// BlossomElevator computes the control points of a clamped spline raised
// from degree p to ph = p + by by blossoming (Ramshaw, "Blossoms are polar
// forms", CAGD 6 (1989); docs/references.md, 'Degree elevation of B-spline
// curves by blossoming'): on every knot span the elevated piece has the
// blossom F(x_1..x_ph) = average over the p-subsets S of f(x_S), f the
// piece's blossom, and the control point Q_i is F at the new knots
// Uh_{i+1}..Uh_{i+ph} on any non-empty span of its support. F is linear in
// the span's p + 1 control points, so each Q_i is one weighted sum of them:
// the weights come from running the de Boor steps of F backwards on
// scalars (each step transposed), from the weight 1 on the last level down
// to the control points. The points are touched once, so the cost hardly
// grows with the point size. Every step is a knot-insertion-like
// combination, so nothing is extrapolated beyond what evaluation does,
// unlike the knot removal of The NURBS Book's A5.9, which loses up to 6
// digits at degree 11 (measured on uniform knots).
// kDegree, kDim and kBy are the degree p, the point size and the
// elevation compiled in (the steps then unroll and the weights stay on the
// stack), or kAnyDegree and 0 for values known only at run time; the
// arithmetic is the same.
template <int kDegree, int kDim, int kBy = 0>
class BlossomElevator {
 public:
  BlossomElevator(const Spline& spline, int by)
      : p_(DegreeOf<kDegree>(spline.degree)),
        ph_(spline.degree + by),
        dim_(kDim > 0 ? kDim : spline.points.dim),
        knots_(spline.knots),
        points_(spline.points),
        inverse_(InverseDifferences(knots_, p_)) {
    if constexpr (kDegree == kAnyDegree) {
      const size_t triangle = static_cast<size_t>(p_ + 1) * (p_ + 2) / 2;
      shared_.resize(triangle);
      nested_.resize(triangle);
    }
  }

  absl::StatusOr<Spline> Run(const CancellationToken* cancel) {
    Spline result{ph_, ElevatedKnots(knots_, ph_ - p()), PointArray{dim_, {}}};
    const std::vector<double>& uh = result.knots;
    const int count = static_cast<int>(uh.size()) - ph_ - 1;
    result.points.values.resize(static_cast<size_t>(count) * dim_);
    CancellationPoll poll(cancel);
    const size_t work_per_point =
        static_cast<size_t>(ph_) * (p() + 1) * (p() + 1) +
        static_cast<size_t>(p() + 1) * dim_;
    int span = p();
    for (int i = 0; i < count; ++i) {
      RETURN_IF_ERROR(poll.Done(work_per_point));
      span = SpanFor(uh, i, span);
      const double* weights = ph() == p() + 1
                                  ? LeaveOneOutWeights(span, &uh[i + 1])
                                  : AveragingWeights(span, &uh[i + 1]);
      WeightedSum(span, weights, result.points.at(i));
    }
    return result;
  }

 private:
  int p() const { return DegreeOf<kDegree>(p_); }
  int ph() const { return kDegree != kAnyDegree && kBy > 0 ? p() + kBy : ph_; }
  int dim() const { return kDim > 0 ? kDim : dim_; }

  // InverseDifferences returns 1 / (U_{i+p+1-c} - U_i) at i * (p + 1) + c
  // for c = 1..p (0 where the difference is 0 or runs past the knots): the
  // denominators of the de Boor steps, divided once per knot instead of
  // once per step.
  static std::vector<double> InverseDifferences(
      const std::vector<double>& knots, int p) {
    const size_t stride = static_cast<size_t>(p) + 1;
    std::vector<double> inverse(knots.size() * stride, 0.0);
    for (size_t i = 0; i < knots.size(); ++i) {
      for (int c = 1; c <= p; ++c) {
        const size_t j = i + stride - static_cast<size_t>(c);
        if (j < knots.size() && knots[j] > knots[i]) {
          inverse[i * stride + static_cast<size_t>(c)] =
              1.0 / (knots[j] - knots[i]);
        }
      }
    }
    return inverse;
  }

  // SpanFor returns the original span of the non-empty new span nearest the
  // middle of Q_i's support [Uh_i, Uh_{i+ph+1}], searched from `hint` (the
  // previous point's span: the spans of consecutive points are close).
  int SpanFor(const std::vector<double>& uh, int i, int hint) const {
    int best = -1;
    for (int j = i; j <= i + ph_; ++j) {
      if (uh[j] < uh[j + 1] &&
          (best < 0 ||
           std::abs(2 * j - 2 * i - ph_) < std::abs(2 * best - 2 * i - ph_))) {
        best = j;
      }
    }
    return FindSpanFrom(hint, static_cast<int>(points_.count()) - 1, p(),
                        uh[best], knots_);
  }

  // Level c (p + 1 - c weights) of a triangle of weights.
  double* Level(double* triangle, int c) const {
    return triangle + c * (2 * p() + 3 - c) / 2;
  }

  // LeaveOneOutWeights returns the weights for ph = p + 1, where F is the
  // mean of the p + 1 values f(args without args[l]). f without args[l]
  // takes args[0..l-1] at de Boor levels 1..l and args[l+1..p] at levels
  // l+1..p: its weights are S_1(args[0])^T .. S_l(args[l-1])^T T_l, where
  // S_c(x) is the step of level c at x and T_l = S_{l+1}(args[l+1])^T ..
  // S_p(args[p])^T [1] is shared. The sum over l then nests like Horner's
  // rule: H_p = [1], H_{c-1} = T_{c-1} + S_c(args[c-1])^T H_c, and
  // H_0 / (p + 1) holds the weights. That is p(p+1) combinations of scalars
  // (12 for a cubic) where the averaging makes 20.
  const double* LeaveOneOutWeights(int s, const double* args) {
    const int p = this->p();
    double* shared = shared_.data();  // T_c at Level(shared, c)
    double* nested = nested_.data();  // H_c
    *Level(shared, p) = 1;
    *Level(nested, p) = 1;
#pragma GCC unroll 8
    for (int c = p; c >= 1; --c) {
      std::fill_n(Level(shared, c - 1), p + 2 - c, 0.0);
      AddStepTransposed(s, c, args[c], 1.0, Level(shared, c),
                        Level(shared, c - 1));
      std::copy_n(Level(shared, c - 1), p + 2 - c, Level(nested, c - 1));
      AddStepTransposed(s, c, args[c - 1], 1.0, Level(nested, c),
                        Level(nested, c - 1));
    }
    const double mean = 1.0 / (p + 1);
#pragma GCC unroll 8
    for (int j = 0; j <= p; ++j) nested[j] *= mean;
    return nested;
  }

  // AveragingWeights returns the weights for any elevation. Forwards, the
  // average over subsets is built one argument at a time: A_k[c], the
  // average over the c-subsets of the first k arguments of the level-c de
  // Boor points, is (k-c)/k A_{k-1}[c] + c/k S_c(x_k) A_{k-1}[c-1], for
  // c = min(k, p) down to 1, and F = A_ph[p]. Backwards, from the weight 1
  // on level p, each of these updates is undone in the reverse order.
  const double* AveragingWeights(int s, const double* args) {
    const int p = this->p();
    double* weights = nested_.data();
    std::fill_n(weights, (p + 1) * (p + 2) / 2, 0.0);
    *Level(weights, p) = 1;
#pragma GCC unroll 8
    for (int k = ph(); k >= 1; --k) {
      const int levels = std::min(k, p);
#pragma GCC unroll 8
      for (int c = 1; c <= levels; ++c) {
        AddStepTransposed(s, c, args[k - 1], static_cast<double>(c) / k,
                          Level(weights, c), Level(weights, c - 1));
        const double keep = static_cast<double>(k - c) / k;
#pragma GCC unroll 8
        for (int idx = 0; idx <= p - c; ++idx) {
          Level(weights, c)[idx] *= keep;
        }
      }
    }
    return weights;
  }

  // AddStepTransposed adds `scale` times the weights of the p + 2 - c
  // points of level c - 1 that give the same sum as `from`, the weights of
  // the p + 1 - c points of level c, after the de Boor step of level c at
  // x on span s (The NURBS Book eq. 5.15 with x for the knot), to `to`.
  void AddStepTransposed(int s, int c, double x, double scale,
                         const double* from, double* to) const {
    const int p = this->p();
#pragma GCC unroll 8
    for (int idx = 0; idx <= p - c; ++idx) {
      const int i = s - p + c + idx;
      const double alpha =
          (x - knots_[i]) *
          inverse_[static_cast<size_t>(i) * (p + 1) + static_cast<size_t>(c)];
      const double weight = scale * from[idx];
      to[idx] += (1.0 - alpha) * weight;
      to[idx + 1] += alpha * weight;
    }
  }

  // WeightedSum writes the sum of the span's control points P_{s-p+j} times
  // weights[j].
  void WeightedSum(int s, const double* weights, double* out) const {
    const int p = this->p();
    const int d = dim();
    const double* points = points_.at(s - p);
#pragma GCC unroll 4
    for (int e = 0; e < d; ++e) {
      double sum = 0;
#pragma GCC unroll 8
      for (int j = 0; j <= p; ++j) sum += weights[j] * points[j * d + e];
      out[e] = sum;
    }
  }

  const int p_;
  const int ph_;
  const int dim_;
  const std::vector<double>& knots_;
  const PointArray& points_;
  const std::vector<double> inverse_;  // InverseDifferences
  // Two triangles of weights, on the stack when the degree is compiled in.
  static constexpr int kFixedDegree = std::max(kDegree, 0);
  using Triangle = std::conditional_t<
      kDegree == kAnyDegree, std::vector<double>,
      std::array<double, (kFixedDegree + 1) * (kFixedDegree + 2) / 2>>;
  Triangle shared_{};
  Triangle nested_{};
};

// RunBlossomElevator runs BlossomElevator compiled for the spline's degree
// (up to 5) and a point size of 3 (and an elevation by 1) or 4, else for
// any.
absl::StatusOr<Spline> RunBlossomElevator(const Spline& spline, int by,
                                          const CancellationToken* cancel) {
  absl::StatusOr<Spline> result;
  WithDegree(spline.degree, [&]<int kDegree>() {
    if constexpr (kDegree == kAnyDegree) {
      result = BlossomElevator<kAnyDegree, 0>(spline, by).Run(cancel);
    } else if (spline.points.dim == 3 && by == 1) {
      result = BlossomElevator<kDegree, 3, 1>(spline, by).Run(cancel);
    } else if (spline.points.dim == 3) {
      result = BlossomElevator<kDegree, 3>(spline, by).Run(cancel);
    } else if (spline.points.dim == 4) {
      result = BlossomElevator<kDegree, 4>(spline, by).Run(cancel);
    } else {
      result = BlossomElevator<kAnyDegree, 0>(spline, by).Run(cancel);
    }
  });
  return result;
}

// ElevateSpline raises a spline by `by` (see ElevateBSplineCurve).
absl::StatusOr<Spline> ElevateSpline(Spline spline, int by,
                                     const CancellationToken* cancel) {
  if (!IsClamped(spline.knots, spline.degree)) {
    RETURN_IF_ERROR(Clamp(spline, cancel));
  }
  return RunBlossomElevator(spline, by, cancel);
}

absl::Status CheckSurfaceElevation(int by_u, int by_v) {
  if (by_u < 0) return InvalidFieldError("by_u", "must not be negative");
  if (by_v < 0) return InvalidFieldError("by_v", "must not be negative");
  if (by_u == 0 && by_v == 0) {
    return InvalidFieldError("by_u", "by_u and by_v must not both be 0");
  }
  return absl::OkStatus();
}

// A rows x cols net of (homogeneous) points of `dim` values, P[i][j] at
// (i * cols + j) * dim, with its knot vectors (empty for Bezier).
struct NetWithKnots {
  int rows = 0;
  int cols = 0;
  int dim = 0;
  std::vector<double> values;
  std::vector<double> knots_u;
  std::vector<double> knots_v;
};

// ElevateNetU raises the net in u (along its rows index i): the rows are
// the control points, of cols * dim values each, of one curve. `degree` < 0
// means Bezier.
absl::Status ElevateNetU(NetWithKnots& net, int degree, int by,
                         const CancellationToken* cancel) {
  PointArray rows{net.cols * net.dim, std::move(net.values)};
  if (degree < 0) {
    absl::StatusOr<PointArray> elevated = ElevateBezierPoints(rows, by, cancel);
    if (!elevated.ok()) return elevated.status();
    rows = *std::move(elevated);
  } else {
    absl::StatusOr<Spline> spline = ElevateSpline(
        Spline{degree, std::move(net.knots_u), std::move(rows)}, by, cancel);
    if (!spline.ok()) return spline.status();
    net.knots_u = std::move(spline->knots);
    rows = std::move(spline->points);
  }
  net.rows = static_cast<int>(rows.count());
  net.values = std::move(rows.values);
  return absl::OkStatus();
}

// ElevateNetV raises the net in v by transposing it around ElevateNetU.
absl::Status ElevateNetV(NetWithKnots& net, int degree, int by,
                         const CancellationToken* cancel) {
  NetWithKnots transposed{
      net.cols,
      net.rows,
      net.dim,
      TransposeBlocks(net.values, net.rows, net.cols, net.dim),
      std::move(net.knots_v),
      {}};
  RETURN_IF_ERROR(ElevateNetU(transposed, degree, by, cancel));
  net.cols = transposed.rows;
  net.values = TransposeBlocks(transposed.values, transposed.rows,
                               transposed.cols, net.dim);
  net.knots_v = std::move(transposed.knots_u);
  return absl::OkStatus();
}

// ElevateSurface raises a (homogeneous when rational) net; degrees < 0 mean
// Bezier.
absl::StatusOr<SurfaceData> ElevateSurface(const ControlNetView& view,
                                           absl::Span<const double> weights,
                                           absl::Span<const double> knots_u,
                                           absl::Span<const double> knots_v,
                                           int degree_u, int degree_v, int by_u,
                                           int by_v,
                                           const CancellationToken* cancel) {
  PointArray points = Lift({view.dimension, view.coordinates}, weights);
  NetWithKnots net{view.count_u,
                   view.count_v,
                   points.dim,
                   std::move(points.values),
                   std::vector<double>(knots_u.begin(), knots_u.end()),
                   std::vector<double>(knots_v.begin(), knots_v.end())};
  if (by_u > 0) {
    RETURN_IF_ERROR(ElevateNetU(net, degree_u, by_u, cancel));
  }
  if (by_v > 0) {
    RETURN_IF_ERROR(ElevateNetV(net, degree_v, by_v, cancel));
  }
  SurfaceData result;
  result.dimension = view.dimension;
  result.count_u = net.rows;
  result.count_v = net.cols;
  result.degree_u = degree_u < 0 ? net.rows - 1 : degree_u + by_u;
  result.degree_v = degree_v < 0 ? net.cols - 1 : degree_v + by_v;
  // A Bezier net is raised by convex combinations; a B-spline net's
  // elevation subtracts (it removes the knots it inserted).
  const bool bspline = degree_u >= 0 || degree_v >= 0;
  ProjectAllowingDirections(PointArray{net.dim, std::move(net.values)},
                            !weights.empty(), result.coordinates,
                            result.weights,
                            bspline ? internal::ZeroWeights::kWithinRounding
                                    : internal::ZeroWeights::kExact);
  result.knots_u = std::move(net.knots_u);
  result.knots_v = std::move(net.knots_v);
  return result;
}

// ElevateTriangleOnce raises the triangular net of degree n by one (Farin
// 1986; docs/references.md, 'Degree elevation by the product formula'):
// Q_ijk = (i P_{i-1,j,k} + j P_{i,j-1,k} + k P_{i,j,k-1}) / (n + 1).
PointArray ElevateTriangleOnce(const PointArray& points, int n) {
  const int dim = points.dim;
  PointArray result{dim,
                    std::vector<double>(TriangularPointCount(n + 1) * dim)};
  const double scale = 1.0 / (n + 1);
  for (int i = 0; i <= n + 1; ++i) {
    for (int j = 0; i + j <= n + 1; ++j) {
      const int k = n + 1 - i - j;
      double* q = result.at(TriangularIndex(n + 1, i, j));
      auto add = [&](int factor, size_t index) {
        const double c = factor * scale;
        const double* p = points.at(index);
        for (int x = 0; x < dim; ++x) q[x] += c * p[x];
      };
      if (i > 0) add(i, TriangularIndex(n, i - 1, j));
      if (j > 0) add(j, TriangularIndex(n, i, j - 1));
      if (k > 0) add(k, TriangularIndex(n, i, j));
    }
  }
  return result;
}

// SolveLeastSquares returns the x (cols x dim, row-major) minimizing
// |A x - B| for A (rows x cols, row-major, full column rank, rows >= cols)
// and B (rows x dim), by Householder QR (Golub and Van Loan, 5.3).
std::vector<double> SolveLeastSquares(std::vector<double> a, int rows, int cols,
                                      std::vector<double> b, int dim) {
  auto at = [&](int r, int c) -> double& {
    return a[static_cast<size_t>(r) * cols + c];
  };
  auto rhs = [&](int r, int x) -> double& {
    return b[static_cast<size_t>(r) * dim + x];
  };
  std::vector<double> v(rows);
  for (int k = 0; k < cols; ++k) {
    double norm = 0.0;
    for (int r = k; r < rows; ++r) norm = std::hypot(norm, at(r, k));
    if (norm == 0.0) continue;
    const double alpha = at(k, k) > 0 ? -norm : norm;
    double v_norm2 = 0.0;
    for (int r = k; r < rows; ++r) {
      v[r] = at(r, k) - (r == k ? alpha : 0.0);
      v_norm2 += v[r] * v[r];
    }
    auto reflect = [&](auto&& element, int count) {
      for (int c = 0; c < count; ++c) {
        double dot = 0.0;
        for (int r = k; r < rows; ++r) dot += v[r] * element(r, c);
        const double f = 2.0 * dot / v_norm2;
        for (int r = k; r < rows; ++r) element(r, c) -= f * v[r];
      }
    };
    reflect([&](int r, int c) -> double& { return at(r, k + c); }, cols - k);
    reflect(rhs, dim);
  }
  std::vector<double> x(static_cast<size_t>(cols) * dim);
  for (int k = cols - 1; k >= 0; --k) {
    for (int d = 0; d < dim; ++d) {
      double sum = rhs(k, d);
      for (int c = k + 1; c < cols; ++c) sum -= at(k, c) * x[c * dim + d];
      x[static_cast<size_t>(k) * dim + d] = sum / at(k, k);
    }
  }
  return x;
}

// ReducedPoints returns the control points of ReduceBezierCurve's
// approximation of degree m = n - by to the degree-n polygon `p`.
PointArray ReducedPoints(const PointArray& p, int by) {
  const int n = static_cast<int>(p.count()) - 1;
  const int m = n - by;
  const int dim = p.dim;
  const std::vector<double> e = ElevationCoefficients(m, by);
  auto coefficient = [&](int i, int j) { return e[i * (m + 1) + j]; };
  PointArray q{dim, std::vector<double>(static_cast<size_t>(m + 1) * dim)};
  // Fixed end points for m >= 1; the free unknowns are q_first..q_last.
  const int first = m >= 1 ? 1 : 0;
  const int last = m >= 1 ? m - 1 : 0;
  if (m >= 1) {
    std::copy_n(p.at(0), dim, q.at(0));
    std::copy_n(p.at(n), dim, q.at(m));
  }
  const int cols = last - first + 1;
  if (cols <= 0) return q;
  std::vector<double> a(static_cast<size_t>(n + 1) * cols);
  std::vector<double> b(p.values);
  for (int i = 0; i <= n; ++i) {
    for (int j = first; j <= last; ++j)
      a[i * cols + j - first] = coefficient(i, j);
    if (m >= 1) {
      for (int x = 0; x < dim; ++x) {
        b[i * dim + x] -=
            coefficient(i, 0) * q.at(0)[x] + coefficient(i, m) * q.at(m)[x];
      }
    }
  }
  const std::vector<double> x =
      SolveLeastSquares(std::move(a), n + 1, cols, std::move(b), dim);
  std::copy(x.begin(), x.end(), q.at(first));
  return q;
}

}  // namespace

absl::StatusOr<BezierCurveData> ElevateBezierCurve(const BezierCurveView& curve,
                                                   int by) {
  RETURN_IF_ERROR(CheckPositive(by, "by"));
  absl::StatusOr<PointArray> elevated = ElevateBezierPoints(
      Lift(curve.control_points, curve.weights), by, nullptr);
  if (!elevated.ok()) return elevated.status();
  BezierCurveData result;
  result.dimension = curve.control_points.dimension;
  ProjectAllowingDirections(*elevated, curve.rational(), result.coordinates,
                            result.weights, internal::ZeroWeights::kExact);
  return result;
}

absl::StatusOr<BSplineCurveData> ElevateBSplineCurve(
    const BSplineCurveView& curve, int by, const CancellationToken* cancel) {
  RETURN_IF_ERROR(CheckPositive(by, "by"));
  absl::StatusOr<Spline> spline = ElevateSpline(
      Spline{curve.degree,
             std::vector<double>(curve.knots.begin(), curve.knots.end()),
             Lift(curve.control_points, curve.weights)},
      by, cancel);
  if (!spline.ok()) return spline.status();
  BSplineCurveData result;
  result.degree = curve.degree + by;
  result.dimension = curve.control_points.dimension;
  result.knots = std::move(spline->knots);
  ProjectAllowingDirections(spline->points, curve.rational(),
                            result.coordinates, result.weights,
                            internal::ZeroWeights::kWithinRounding);
  return result;
}

absl::StatusOr<ReducedBezierCurve> ReduceBezierCurve(
    const BezierCurveView& curve, int by) {
  const int n = curve.degree();
  if (by < 1 || by > n) {
    return InvalidFieldError("by", "must lie in [1, degree]");
  }
  if (curve.rational()) {
    return InvalidFieldError(
        "weights", "degree reduction of rational curves is not supported");
  }
  const PointArray original = Lift(curve.control_points, {});
  PointArray reduced = ReducedPoints(original, by);
  const PointArray back = *ElevateBezierPoints(reduced, by, nullptr);
  ReducedBezierCurve result;
  for (size_t i = 0; i < original.count(); ++i) {
    double norm = 0.0;
    for (int x = 0; x < original.dim; ++x) {
      norm = std::hypot(norm, original.at(i)[x] - back.at(i)[x]);
    }
    result.error_bound = std::max(result.error_bound, norm);
  }
  result.curve.dimension = original.dim;
  result.curve.coordinates = std::move(reduced.values);
  return result;
}

absl::StatusOr<SurfaceData> ElevateBezierSurface(
    const BezierSurfaceView& surface, int by_u, int by_v,
    const CancellationToken* cancel) {
  RETURN_IF_ERROR(CheckSurfaceElevation(by_u, by_v));
  return ElevateSurface(surface.control_net, surface.weights, {}, {}, -1, -1,
                        by_u, by_v, cancel);
}

absl::StatusOr<SurfaceData> ElevateBSplineSurface(
    const BSplineSurfaceView& surface, int by_u, int by_v,
    const CancellationToken* cancel) {
  RETURN_IF_ERROR(CheckSurfaceElevation(by_u, by_v));
  return ElevateSurface(surface.control_net, surface.weights, surface.knots_u,
                        surface.knots_v, surface.degree_u, surface.degree_v,
                        by_u, by_v, cancel);
}

absl::StatusOr<TriangularPatchData> ElevateTriangularPatch(
    const TriangularPatchView& patch, int by) {
  RETURN_IF_ERROR(CheckPositive(by, "by"));
  PointArray points = Lift(patch.control_points, patch.weights);
  for (int n = patch.degree; n < patch.degree + by; ++n) {
    points = ElevateTriangleOnce(points, n);
  }
  TriangularPatchData result;
  result.degree = patch.degree + by;
  result.dimension = patch.control_points.dimension;
  result.domain_triangle.assign(patch.domain_triangle.begin(),
                                patch.domain_triangle.end());
  ProjectAllowingDirections(points, patch.rational(), result.coordinates,
                            result.weights, internal::ZeroWeights::kExact);
  return result;
}

}  // namespace freeform
