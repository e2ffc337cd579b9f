#include "freeform/core/bezier.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "absl/strings/str_cat.h"
#include "base/binomial.h"
#include "base/checked_chunks.h"
#include "base/homogeneous.h"
#include "freeform/core/rational.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "kinds/scalar_reference.h"
#include "kinds/simd/curve_simd.h"
#include "kinds/validated_bezier.h"

namespace freeform {

absl::Status ValidateBezierCurve(const BezierCurveView& curve) {
  RETURN_IF_ERROR(ValidatePoints(curve.control_points, "control_points"));
  if (!curve.rational()) return absl::OkStatus();
  const size_t count = curve.control_points.size();
  if (curve.weights.size() != count) {
    return InvalidFieldError(
        "weights", absl::StrCat("has ", curve.weights.size(), " weights for ",
                                count, " control points"));
  }
  RETURN_IF_ERROR(ValidateWeightValues(curve.weights));
  if (curve.weights.front() == 0 || curve.weights.back() == 0) {
    const size_t end = curve.weights.front() == 0 ? 0 : count - 1;
    return InvalidFieldError(
        IndexedField("weights", end),
        absl::StrCat("an end weight must be positive: with weight 0 the "
                     "curve is infinite at t = ",
                     end == 0 ? 0 : 1));
  }
  return absl::OkStatus();
}

void DeCasteljauDerivatives(const double* control, int n, int dimension,
                            double t, int max_order, double* scratch,
                            double* derivatives) {
  const size_t dim = static_cast<size_t>(dimension);
  double* levels = scratch;
  double* differences = scratch + static_cast<size_t>(n + 1) * dim;
  std::copy(control, control + static_cast<size_t>(n + 1) * dim, levels);
  const int top = std::min(max_order, n);
  std::fill(derivatives + static_cast<size_t>(top + 1) * dim,
            derivatives + static_cast<size_t>(max_order + 1) * dim, 0.0);
  const double s = 1.0 - t;
  for (int m = n;; --m) {
    // `levels` now holds the m + 1 de Casteljau points of level n - m.
    if (m <= top) {
      const size_t points = static_cast<size_t>(m + 1) * dim;
      std::copy(levels, levels + points, differences);
      double factor = 1.0;
      for (int r = 1; r <= m; ++r) {
        factor *= n - r + 1;
        for (size_t x = 0; x < static_cast<size_t>(m + 1 - r) * dim; ++x) {
          differences[x] = differences[x + dim] - differences[x];
        }
      }
      double* out = derivatives + static_cast<size_t>(m) * dim;
      for (size_t j = 0; j < dim; ++j) out[j] = factor * differences[j];
    }
    if (m == 0) break;
    for (size_t x = 0; x < static_cast<size_t>(m) * dim; ++x) {
      levels[x] = s * levels[x] + t * levels[x + dim];
    }
  }
}

void BernsteinBasis(int n, double t, absl::Span<double> values) {
  const double s = 1.0 - t;
  values[0] = 1.0;
  for (int j = 1; j <= n; ++j) {
    double carry = 0.0;  // t * B(j-1, i-1)
    for (int i = 0; i < j; ++i) {
      const double previous = values[static_cast<size_t>(i)];
      values[static_cast<size_t>(i)] = s * previous + carry;
      carry = t * previous;
    }
    values[static_cast<size_t>(j)] = carry;
  }
}

namespace {

// The k-th hodograph of control points P (n + 1 points): the Bezier control
// points n!/(n-k)! Delta^k P_i, i = 0..n-k, of the k-th derivative (the
// rule Q_i = n (P_{i+1} - P_i) applied k times), each multiplied by
// binom(n-k, i) for the O(n) schemes. Index [k][i * dimension + j].
std::vector<std::vector<double>> ScaledHodographs(const double* control, int n,
                                                  int dimension, int top) {
  const size_t dim = static_cast<size_t>(dimension);
  std::vector<double> differences(control,
                                  control + static_cast<size_t>(n + 1) * dim);
  std::vector<std::vector<double>> hodographs;
  for (int k = 0; k <= top; ++k) {
    const int degree = n - k;
    if (k > 0) {
      for (size_t x = 0; x < static_cast<size_t>(degree + 1) * dim; ++x) {
        differences[x] = (degree + 1) * (differences[x + dim] - differences[x]);
      }
    }
    std::vector<double> scaled(differences.begin(),
                               differences.begin() + (degree + 1) * dim);
    double binomial = 1.0;  // binom(degree, i)
    for (int i = 0; i <= degree; ++i) {
      if (i > 0) binomial = binomial * (degree - i + 1) / i;
      for (size_t j = 0; j < dim; ++j) scaled[i * dim + j] *= binomial;
    }
    hodographs.push_back(std::move(scaled));
  }
  return hodographs;
}

}  // namespace

void HornerBezierPoint(const double* scaled, int n, int dimension, double t,
                       double* point) {
  const size_t dim = static_cast<size_t>(dimension);
  const double s = 1.0 - t;
  // Factor out (1-t)^n or t^n so the Horner variable stays in [0, 1].
  const bool from_start = t < 0.5;
  const double ratio = from_start ? t / s : s / t;
  double scale = 1.0;
  for (int i = 0; i < n; ++i) scale *= from_start ? s : t;
  for (size_t j = 0; j < dim; ++j) {
    double sum =
        from_start ? scaled[static_cast<size_t>(n) * dim + j] : scaled[j];
    for (int i = 1; i <= n; ++i) {
      const size_t index = from_start ? static_cast<size_t>(n - i) : i;
      sum = sum * ratio + scaled[index * dim + j];
    }
    point[j] = sum * scale;
  }
}

void LadderBezierPoint(const double* scaled, int n, int dimension, double t,
                       double* point) {
  const size_t dim = static_cast<size_t>(dimension);
  const double s = 1.0 - t;
  for (size_t j = 0; j < dim; ++j) point[j] = scaled[j];
  double power = 1.0;  // t^k
  for (int k = 1; k <= n; ++k) {
    power *= t;
    const double* rung = scaled + static_cast<size_t>(k) * dim;
    for (size_t j = 0; j < dim; ++j) point[j] = s * point[j] + power * rung[j];
  }
}

BezierAlgorithm ResolveBezierAlgorithm(BezierAlgorithm algorithm, int degree) {
  if (algorithm != BezierAlgorithm::kAuto) return algorithm;
  return degree <= kLinearMaxAutoDegree ? BezierAlgorithm::kLadder
                                        : BezierAlgorithm::kDeCasteljau;
}

std::vector<double> PowerToBezier(const PointsView& coefficients) {
  const size_t dim = static_cast<size_t>(coefficients.dimension);
  const int n = static_cast<int>(coefficients.size()) - 1;
  std::vector<double> control(coefficients.coordinates.size(), 0.0);
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= i; ++j) {
      const double factor = internal::Binomial(i, j) / internal::Binomial(n, j);
      const double* a = coefficients.point(static_cast<size_t>(j));
      for (size_t x = 0; x < dim; ++x) control[i * dim + x] += factor * a[x];
    }
  }
  return control;
}

std::vector<double> BezierToPower(const PointsView& control_points) {
  const size_t dim = static_cast<size_t>(control_points.dimension);
  const int n = static_cast<int>(control_points.size()) - 1;
  std::vector<double> coefficients(control_points.coordinates.size(), 0.0);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= j; ++i) {
      const double sign = (j - i) % 2 == 0 ? 1.0 : -1.0;
      const double factor =
          sign * internal::Binomial(n, j) * internal::Binomial(j, i);
      const double* p = control_points.point(static_cast<size_t>(i));
      for (size_t x = 0; x < dim; ++x) {
        coefficients[j * dim + x] += factor * p[x];
      }
    }
  }
  return coefficients;
}

namespace {

// BernsteinDerivatives writes B(n,i)^(k)(t) for k = 0..max_order into
// out[k * (n + 1) + i]. The triangle of every degree's Bernstein values
// (levels[m (m + 1) / 2 + i] = B(m,i)(t)) gives order k from degree n - k by
// the derivative rule B(m,i)' = m (B(m-1,i-1) - B(m-1,i)) applied k times.
// `levels` holds (n + 1)(n + 2) / 2 doubles. O(n^2 + max_order^2 n).
void BernsteinDerivatives(int n, double t, int max_order, double* levels,
                          double* out) {
  const double s = 1.0 - t;
  levels[0] = 1.0;
  for (int m = 1; m <= n; ++m) {
    const double* previous = levels + (m - 1) * m / 2;
    double* level = levels + m * (m + 1) / 2;
    level[0] = s * previous[0];
    for (int i = 1; i < m; ++i)
      level[i] = s * previous[i] + t * previous[i - 1];
    level[m] = t * previous[m - 1];
  }
  const size_t count = static_cast<size_t>(n) + 1;
  for (int k = 0; k <= max_order; ++k) {
    double* row = out + static_cast<size_t>(k) * count;
    std::fill(row, row + count, 0.0);
    if (k > n) continue;
    const int m = n - k;
    std::copy_n(levels + m * (m + 1) / 2, m + 1, row);
    // Apply the rule k times; the row grows by one entry each time.
    for (int degree = m + 1; degree <= n; ++degree) {
      for (int i = degree; i >= 0; --i) {
        const double left = i > 0 ? row[i - 1] : 0.0;
        const double right = i < degree ? row[i] : 0.0;
        row[i] = degree * (left - right);
      }
    }
  }
}

}  // namespace

absl::Status EvaluateBernsteinBasis(int n, absl::Span<const double> weights,
                                    absl::Span<const double> parameters,
                                    CurveOutput output,
                                    const ExecutionContext& context) {
  if (n < 0) return InvalidFieldError("degree", "must not be negative");
  const size_t count = static_cast<size_t>(n) + 1;
  const std::vector<double> zeros(count, 0.0);
  if (absl::Status status = ValidateBezierCurve(
          {.control_points = {.dimension = 1, .coordinates = zeros},
           .weights = weights});
      !status.ok()) {
    return status;
  }
  RETURN_IF_ERROR(
      ValidateBatch(parameters, 0.0, 1.0, output, static_cast<int>(count)));
  const int max_order = static_cast<int>(output.size()) - 1;
  const size_t orders = output.size();
  const bool rational = !weights.empty();
  return ParallelFor(parameters.size(), context, [&](size_t begin, size_t end) {
    std::vector<double> levels(count * (count + 1) / 2);
    std::vector<double> values(orders * count);
    // Homogeneous basis (w_i B_i^(k), then sum_i w_i B_i^(k)) and its
    // projection, for rational weights.
    std::vector<double> homogeneous(rational ? orders * (count + 1) : 0);
    std::vector<double> projected(rational ? orders * count : 0);
    for (size_t r = begin; r < end; ++r) {
      BernsteinDerivatives(n, parameters[r], max_order, levels.data(),
                           values.data());
      const double* result = values.data();
      if (rational) {
        for (size_t k = 0; k < orders; ++k) {
          double* row = &homogeneous[k * (count + 1)];
          double sum = 0.0;
          for (size_t i = 0; i < count; ++i) {
            row[i] = weights[i] * values[k * count + i];
            sum += row[i];
          }
          row[count] = sum;
        }
        ProjectHomogeneousDerivatives(homogeneous.data(),
                                      static_cast<int>(count), max_order,
                                      projected.data());
        result = projected.data();
      }
      for (size_t k = 0; k < orders; ++k) {
        std::copy_n(result + k * count, count, &output[k][r * count]);
      }
    }
  });
}

BezierPointEvaluator::BezierPointEvaluator(const BezierCurveView& curve,
                                           int max_order,
                                           BezierAlgorithm algorithm)
    : degree_(curve.degree()),
      dimension_(curve.control_points.dimension),
      max_order_(max_order),
      rational_(curve.rational()),
      algorithm_(ResolveBezierAlgorithm(algorithm, curve.degree())) {
  const int work_dimension = rational_ ? dimension_ + 1 : dimension_;
  control_ = internal::LiftedValues(curve.control_points, curve.weights);
  if (algorithm_ != BezierAlgorithm::kDeCasteljau) {
    hodographs_ = ScaledHodographs(control_.data(), degree_, work_dimension,
                                   std::min(max_order_, degree_));
  }
}

size_t BezierPointEvaluator::scratch_size() const {
  const size_t work =
      static_cast<size_t>(rational_ ? dimension_ + 1 : dimension_);
  const size_t orders = static_cast<size_t>(max_order_ + 1);
  return 2 * static_cast<size_t>(degree_ + 1) * work + orders * work;
}

void BezierPointEvaluator::Evaluate(double t, double* scratch,
                                    double* derivatives) const {
  const int work_dimension = rational_ ? dimension_ + 1 : dimension_;
  const size_t work = static_cast<size_t>(work_dimension);
  const size_t levels = 2 * static_cast<size_t>(degree_ + 1) * work;
  // Polynomial curves write straight into `derivatives`.
  double* raw = rational_ ? scratch + levels : derivatives;
  if (algorithm_ == BezierAlgorithm::kDeCasteljau) {
    DeCasteljauDerivatives(control_.data(), degree_, work_dimension, t,
                           max_order_, scratch, raw);
  } else {
    const int top = std::min(max_order_, degree_);
    const auto point_scheme = algorithm_ == BezierAlgorithm::kLadder
                                  ? &LadderBezierPoint
                                  : &HornerBezierPoint;
    for (int k = 0; k <= top; ++k) {
      point_scheme(hodographs_[static_cast<size_t>(k)].data(), degree_ - k,
                   work_dimension, t, raw + static_cast<size_t>(k) * work);
    }
    std::fill(raw + static_cast<size_t>(top + 1) * work,
              raw + static_cast<size_t>(max_order_ + 1) * work, 0.0);
  }
  if (rational_) {
    ProjectHomogeneousDerivatives(raw, dimension_, max_order_, derivatives);
  }
}

absl::Status EvaluateBezierCurve(const BezierCurveView& curve,
                                 absl::Span<const double> parameters,
                                 CurveOutput output,
                                 const ExecutionContext& context,
                                 BezierAlgorithm algorithm) {
  RETURN_IF_ERROR(ValidateBezierCurve(curve));
  return internal::EvaluateValidBezierCurve(curve, parameters, output, context,
                                            algorithm);
}

namespace {

// Evaluates a polynomial curve by `scheme` (Warren's ladder or Horner's
// rule) with the kernel across parameters (simd/curve_simd.h).
absl::Status EvaluateLanes(const BezierCurveView& curve,
                           absl::Span<const double> parameters,
                           CurveOutput output, const ExecutionContext& context,
                           BezierAlgorithm scheme) {
  const int n = curve.degree();
  const int max_order = static_cast<int>(output.size()) - 1;
  const std::vector<std::vector<double>> hodographs =
      ScaledHodographs(curve.control_points.coordinates.data(), n,
                       curve.control_points.dimension, std::min(max_order, n));
  std::vector<const double*> hodograph_data;
  for (const std::vector<double>& hodograph : hodographs) {
    hodograph_data.push_back(hodograph.data());
  }
  std::vector<double*> buffers;
  for (const absl::Span<double> buffer : output) {
    buffers.push_back(buffer.data());
  }
  const simd::BezierLanesBatch batch{
      .ladder = scheme == BezierAlgorithm::kLadder,
      .n = n,
      .dimension = curve.control_points.dimension,
      .max_order = max_order,
      .hodographs = hodograph_data.data(),
      .parameters = parameters.data(),
      .output = buffers.data()};
  return internal::ParallelForInRange(parameters, 0.0, 1.0, "parameters",
                                      context, [&](size_t begin, size_t end) {
                                        simd::EvaluateBezierChunk(batch, begin,
                                                                  end);
                                      });
}

// Evaluates `curve` point by point with a BezierPointEvaluator.
absl::Status EvaluatePointByPoint(const BezierCurveView& curve,
                                  absl::Span<const double> parameters,
                                  CurveOutput output,
                                  const ExecutionContext& context,
                                  BezierAlgorithm algorithm) {
  const BezierPointEvaluator evaluator(
      curve, static_cast<int>(output.size()) - 1, algorithm);
  const size_t dim = static_cast<size_t>(curve.control_points.dimension);
  const size_t orders = output.size();
  return ParallelFor(parameters.size(), context, [&](size_t begin, size_t end) {
    std::vector<double> scratch(evaluator.scratch_size() + orders * dim);
    double* derivatives = scratch.data() + evaluator.scratch_size();
    for (size_t r = begin; r < end; ++r) {
      if (orders == 1) {  // positions only: write in place
        evaluator.Evaluate(parameters[r], scratch.data(),
                           output[0].data() + r * dim);
        continue;
      }
      evaluator.Evaluate(parameters[r], scratch.data(), derivatives);
      for (size_t k = 0; k < orders; ++k) {
        std::copy(derivatives + k * dim, derivatives + (k + 1) * dim,
                  output[k].data() + r * dim);
      }
    }
  });
}

}  // namespace

namespace internal {

absl::Status EvaluateValidBezierCurve(const BezierCurveView& curve,
                                      absl::Span<const double> parameters,
                                      CurveOutput output,
                                      const ExecutionContext& context,
                                      BezierAlgorithm algorithm) {
  // The lanes check the parameters chunk by chunk (checked_chunks.h).
  RETURN_IF_ERROR(ValidateCurveOutput(output, parameters.size(),
                                      curve.control_points.dimension));
  const BezierAlgorithm scheme =
      ResolveBezierAlgorithm(algorithm, curve.degree());
  if (!curve.rational() && (scheme == BezierAlgorithm::kHorner ||
                            scheme == BezierAlgorithm::kLadder)) {
    return EvaluateLanes(curve, parameters, output, context, scheme);
  }
  RETURN_IF_ERROR(ValidateInRange(parameters, 0.0, 1.0, "parameters"));
  return EvaluatePointByPoint(curve, parameters, output, context, algorithm);
}

absl::Status EvaluateBezierCurveScalar(const BezierCurveView& curve,
                                       absl::Span<const double> parameters,
                                       CurveOutput output,
                                       BezierAlgorithm algorithm) {
  RETURN_IF_ERROR(ValidateBezierCurve(curve));
  RETURN_IF_ERROR(ValidateBatch(parameters, 0.0, 1.0, output,
                                curve.control_points.dimension));
  return EvaluatePointByPoint(curve, parameters, output, {}, algorithm);
}

}  // namespace internal

}  // namespace freeform
