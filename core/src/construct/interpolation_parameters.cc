#include "construct/interpolation_parameters.h"

#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "construct/interpolation_knots.h"
#include "freeform/core/bspline.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"

namespace freeform {
namespace internal {
namespace {

// CumulativeParameters returns chord-length (exponent 1) or centripetal
// (exponent 1/2) parameters of the open sequence (NURBS Book eqs. 9.5-9.6),
// normalized to [0, 1]; with `closed`, one more value for the chord back to
// the first point (the period is then 1).
absl::StatusOr<std::vector<double>> CumulativeParameters(
    const PointsView& points, double exponent, bool closed) {
  const size_t count = points.size();
  const size_t intervals = closed ? count : count - 1;
  std::vector<double> t(intervals + 1, 0.0);
  for (size_t k = 1; k <= intervals; ++k) {
    const double chord = PointDistance(points.point(k % count),
                                       points.point(k - 1), points.dimension);
    if (!(chord > 0)) {
      const size_t repeated = k % count == 0 ? count - 1 : k;
      return InvalidFieldError(
          IndexedField("points.coordinates",
                       repeated * static_cast<size_t>(points.dimension)),
          k % count == 0
              ? "the last point repeats the first; a closed curve must not "
                "repeat it"
              : "a point equals its predecessor (chord length and centripetal "
                "parameters need distinct consecutive points)");
    }
    t[k] = t[k - 1] + (exponent == 1.0 ? chord : std::sqrt(chord));
  }
  const double total = t[intervals];
  for (double& value : t) value /= total;
  t[intervals] = 1.0;
  return t;
}

// BasisSlope returns N'_{i,p}(u) and N''_{i,p}(u) (right-hand limits).
std::pair<double, double> BasisSlope(int i, int p, double u,
                                     absl::Span<const double> knots) {
  const int n = static_cast<int>(knots.size()) - p - 2;
  const int span = FindSpan(n, p, u, knots);
  if (i < span - p || i > span) return {0.0, 0.0};
  std::vector<double> ders(3 * (static_cast<size_t>(p) + 1));
  std::vector<double> scratch(BasisDerivativesScratchSize(p));
  BasisFunctionDerivatives(span, u, p, 2, knots, absl::MakeSpan(ders),
                           absl::MakeSpan(scratch));
  const size_t j = static_cast<size_t>(i - span + p);
  return {ders[static_cast<size_t>(p) + 1 + j],
          ders[2 * (static_cast<size_t>(p) + 1) + j]};
}

// BasisArgmax returns the maximum of the unimodal N_{i,p} inside its support
// [lo, hi]: Newton on N' = 0 safeguarded by the bracket (N' > 0 left of the
// maximum, <= 0 right of it), which also converges to the kink of p = 1.
double BasisArgmax(int i, int p, double lo, double hi,
                   absl::Span<const double> knots) {
  double x = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 200 && hi - lo > 1e-16; ++iteration) {
    const auto [slope, curvature] = BasisSlope(i, p, x, knots);
    if (slope > 0) {
      lo = x;
    } else {
      hi = x;
    }
    if (slope == 0.0 && curvature < 0) break;
    double next = curvature < 0 ? x - slope / curvature : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) <= 1e-17) break;
    x = next;
  }
  return x;
}

}  // namespace

std::vector<double> UniformValues(size_t intervals) {
  std::vector<double> t(intervals + 1);
  for (size_t k = 0; k <= intervals; ++k) {
    t[k] = static_cast<double>(k) / static_cast<double>(intervals);
  }
  return t;
}

std::vector<double> UniversalParameters(int count, int p) {
  const std::vector<double> knots = ClampedUniformKnots(count, p);
  std::vector<double> t(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    const size_t k = static_cast<size_t>(i);
    const double lo = knots[k], hi = knots[k + static_cast<size_t>(p) + 1];
    if (i == 0) {
      t[k] = 0.0;
    } else if (i == count - 1) {
      t[k] = 1.0;
    } else if ((i >= p && i <= count - 1 - p) || 2 * i == count - 1) {
      t[k] = 0.5 * (lo + hi);
    } else if (2 * i > count - 1) {
      t[k] = 1.0 - t[static_cast<size_t>(count - 1 - i)];
    } else {
      t[k] = BasisArgmax(i, p, lo, hi, knots);
    }
  }
  return t;
}

absl::Status ValidateParameters(absl::Span<const double> parameters) {
  RETURN_IF_ERROR(ValidateFinite(parameters, "parameters"));
  for (size_t i = 1; i < parameters.size(); ++i) {
    if (!(parameters[i] > parameters[i - 1])) {
      return InvalidFieldError(IndexedField("parameters", i),
                               "parameters must be strictly increasing");
    }
  }
  return absl::OkStatus();
}

absl::StatusOr<std::vector<double>> ExplicitParameters(
    absl::Span<const double> parameters, size_t count) {
  if (parameters.size() != count) {
    return InvalidFieldError(
        "parameters", absl::StrCat("needs one parameter per point (", count,
                                   "), got ", parameters.size()));
  }
  RETURN_IF_ERROR(ValidateParameters(parameters));
  return std::vector<double>(parameters.begin(), parameters.end());
}

absl::Status ValidatePositiveDegree(int degree, absl::string_view field) {
  if (degree < 1) {
    return InvalidFieldError(field, absl::StrCat("must be >= 1, got ", degree));
  }
  return absl::OkStatus();
}

absl::Status ValidateCurveData(const PointsView& points, int degree) {
  RETURN_IF_ERROR(ValidatePositiveDegree(degree, "degree"));
  return ValidatePoints(points, "points", static_cast<size_t>(degree) + 1);
}

absl::StatusOr<std::vector<double>> OpenParameters(
    const PointsView& points, Parameterization parameterization) {
  switch (parameterization) {
    case Parameterization::kChordLength:
      return CumulativeParameters(points, 1.0, false);
    case Parameterization::kCentripetal:
      return CumulativeParameters(points, 0.5, false);
    case Parameterization::kUniform:
    // Universal parameters are taken before (UniversalParameters) where they
    // apply; elsewhere the uniform ones stand in.
    case Parameterization::kUniversal:
      break;
  }
  return UniformValues(points.size() - 1);
}

absl::StatusOr<std::vector<double>> ClosedParameters(
    const PointsView& points, const CurveInterpolationOptions& options) {
  const size_t count = points.size();
  if (!options.parameters.empty()) {
    if (options.parameters.size() != count &&
        options.parameters.size() != count + 1) {
      return InvalidFieldError(
          "parameters",
          absl::StrCat("a closed curve needs one parameter per point (", count,
                       ") or one more, got ", options.parameters.size()));
    }
    RETURN_IF_ERROR(ValidateParameters(options.parameters));
    std::vector<double> t(options.parameters.begin(), options.parameters.end());
    if (t.size() == count) {
      t.push_back(t.back() +
                  (t.back() - t.front()) / static_cast<double>(count - 1));
    }
    return t;
  }
  switch (options.parameterization) {
    case Parameterization::kChordLength:
      return CumulativeParameters(points, 1.0, true);
    case Parameterization::kCentripetal:
      return CumulativeParameters(points, 0.5, true);
    case Parameterization::kUniform:
    case Parameterization::kUniversal:  // as for an open curve
      break;
  }
  return UniformValues(count);
}

}  // namespace internal

absl::StatusOr<std::vector<double>> InterpolationParameters(
    const PointsView& points, int degree, Parameterization parameterization) {
  RETURN_IF_ERROR(internal::ValidateCurveData(points, degree));
  if (parameterization == Parameterization::kUniversal) {
    return internal::UniversalParameters(static_cast<int>(points.size()),
                                         degree);
  }
  return internal::OpenParameters(points, parameterization);
}

}  // namespace freeform
