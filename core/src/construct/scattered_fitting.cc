// Surfaces fitted to scattered points by penalized least squares
// (FitScatteredSurface, EstimateScatteredFit); docs/references.md,
// 'Scattered-data surface fitting'.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "construct/fitting_checks.h"
#include "freeform/core/bspline.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/fitting.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/tensor_surface.h"
#include "linalg/banded_cholesky.h"

namespace freeform {
namespace {

using internal::BandedCholesky;

constexpr size_t kSizeMax = std::numeric_limits<size_t>::max();

size_t Product(size_t a, size_t b) {
  return (a != 0 && b > kSizeMax / a) ? kSizeMax : a * b;
}
size_t Sum(size_t a, size_t b) { return b > kSizeMax - a ? kSizeMax : a + b; }
size_t Count(int value) { return value > 0 ? static_cast<size_t>(value) : 0; }

// The ordering of the unknowns: P[i][j] is unknown i * count_v + j
// (u-major) or j * count_u + i, whichever gives the narrower band.
struct Ordering {
  bool u_major = true;
  size_t count_u = 0, count_v = 0;
  size_t bandwidth = 0;

  size_t index(size_t i, size_t j) const {
    return u_major ? i * count_v + j : j * count_u + i;
  }
  // The net position (i, j) of unknown `row`.
  std::pair<size_t, size_t> position(size_t row) const {
    return u_major ? std::pair{row / count_v, row % count_v}
                   : std::pair{row % count_u, row / count_u};
  }
};

// The band of one ordering: a data point couples P[i..i+p][j..j+q], the
// second differences couple rows two apart.
size_t Band(size_t p, size_t q, size_t count_v) {
  return std::max(Sum(Product(p, count_v), q), Product(2, count_v));
}

Ordering ChooseOrdering(const ScatteredFitOptions& options) {
  Ordering ordering{.count_u = Count(options.control_count_u),
                    .count_v = Count(options.control_count_v)};
  const size_t p = Count(options.degree_u), q = Count(options.degree_v);
  const size_t u_major = Band(p, q, ordering.count_v);
  const size_t v_major = Band(q, p, ordering.count_u);
  ordering.u_major = u_major <= v_major;
  ordering.bandwidth = std::min(u_major, v_major);
  return ordering;
}

absl::Status ValidateScatteredOptions(const PointsView& points,
                                      const ScatteredFitOptions& options) {
  RETURN_IF_ERROR(internal::ValidateDegreeAndCount(
      options.degree_u, options.control_count_u, "u", "control_count_u",
      "control points"));
  RETURN_IF_ERROR(internal::ValidateDegreeAndCount(
      options.degree_v, options.control_count_v, "v", "control_count_v",
      "control points"));
  RETURN_IF_ERROR(ValidatePoints(points, "points"));
  const size_t controls =
      Product(Count(options.control_count_u), Count(options.control_count_v));
  if (points.size() < controls) {
    return InvalidFieldError(
        "points", absl::StrCat("needs at least as many points as control "
                               "points (",
                               controls, "), got ", points.size()));
  }
  if (!(options.smoothing >= 0) || !std::isfinite(options.smoothing)) {
    return InvalidFieldError(
        "smoothing",
        absl::StrCat("must be >= 0 and finite, got ", options.smoothing));
  }
  if (options.parameters.empty()) return absl::OkStatus();
  if (options.parameters.size() != Product(2, points.size())) {
    return InvalidFieldError("parameters",
                             absl::StrCat("needs 2 values (u, v) per point (",
                                          Product(2, points.size()), "), got ",
                                          options.parameters.size()));
  }
  return ValidateInRange(options.parameters, 0.0, 1.0, "parameters");
}

absl::Status CheckWork(const PointsView& points,
                       const ScatteredFitOptions& options) {
  const ScatteredFitWork work =
      EstimateScatteredFit(points.size(), points.dimension, options);
  if (work.operations <= options.max_operations) return absl::OkStatus();
  const absl::string_view field =
      work.point_operations > options.max_operations       ? "points"
      : options.control_count_u >= options.control_count_v ? "control_count_u"
                                                           : "control_count_v";
  return ExhaustedFieldError(
      field,
      absl::StrCat("the fit needs about ", work.operations,
                   " operations, above the limit of ", options.max_operations));
}

// ClampedUniformKnots returns the clamped knots on [0, 1] of `count`
// functions of degree p with equally spaced interior knots.
std::vector<double> ClampedUniformKnots(int count, int p) {
  std::vector<double> knots(static_cast<size_t>(p) + 1, 0.0);
  const int spans = count - p;
  for (int j = 1; j < spans; ++j) {
    knots.push_back(static_cast<double>(j) / spans);
  }
  knots.insert(knots.end(), static_cast<size_t>(p) + 1, 1.0);
  return knots;
}

// The nonzero basis functions of one direction at one parameter.
struct Basis1D {
  size_t first = 0;
  std::vector<double> values, scratch;
};

void EvaluateBasis(int p, absl::Span<const double> knots, double u,
                   Basis1D& basis) {
  const int n = static_cast<int>(knots.size()) - p - 2;
  const int span = FindSpan(n, p, u, knots);
  basis.first = static_cast<size_t>(span - p);
  BasisFunctions(span, u, p, knots, absl::MakeSpan(basis.values),
                 absl::MakeSpan(basis.scratch));
}

// AddData adds B^T B to `normal` and B^T Q to `rhs` (unknowns x
// dimension), B_k = N_i(u_k) N_j(v_k) the data rows.
absl::Status AddData(const PointsView& points, absl::Span<const double> uv,
                     const SurfaceData& surface, const Ordering& ordering,
                     BandedCholesky& normal, std::vector<double>& rhs,
                     const CancellationToken* cancel) {
  const size_t d = static_cast<size_t>(points.dimension);
  const size_t wu = static_cast<size_t>(surface.degree_u) + 1;
  const size_t wv = static_cast<size_t>(surface.degree_v) + 1;
  Basis1D bu{
      .values = std::vector<double>(wu),
      .scratch = std::vector<double>(BasisScratchSize(surface.degree_u))};
  Basis1D bv{
      .values = std::vector<double>(wv),
      .scratch = std::vector<double>(BasisScratchSize(surface.degree_v))};
  std::vector<size_t> index(wu * wv);
  std::vector<double> value(wu * wv);
  CancellationPoll poll(cancel);
  for (size_t k = 0; k < points.size(); ++k) {
    RETURN_IF_ERROR(poll.Done(index.size() * (index.size() + d)));
    EvaluateBasis(surface.degree_u, surface.knots_u, uv[2 * k], bu);
    EvaluateBasis(surface.degree_v, surface.knots_v, uv[2 * k + 1], bv);
    for (size_t a = 0; a < wu; ++a) {
      for (size_t b = 0; b < wv; ++b) {
        index[a * wv + b] = ordering.index(bu.first + a, bv.first + b);
        value[a * wv + b] = bu.values[a] * bv.values[b];
      }
    }
    for (size_t r = 0; r < index.size(); ++r) {
      for (size_t c = 0; c < index.size(); ++c) {
        if (index[c] <= index[r]) {
          normal.lower(index[r], index[c]) += value[r] * value[c];
        }
      }
      double* row = rhs.data() + index[r] * d;
      for (size_t x = 0; x < d; ++x) row[x] += value[r] * points.point(k)[x];
    }
  }
  return absl::OkStatus();
}

// A second difference of the net: coefficients at up to four net points.
struct Stencil {
  size_t size = 0;
  size_t i[4] = {}, j[4] = {};
  double coefficient[4] = {};
};

void AddStencil(const Stencil& stencil, double weight, const Ordering& ordering,
                BandedCholesky& normal) {
  for (size_t r = 0; r < stencil.size; ++r) {
    const size_t row = ordering.index(stencil.i[r], stencil.j[r]);
    for (size_t c = 0; c < stencil.size; ++c) {
      const size_t column = ordering.index(stencil.i[c], stencil.j[c]);
      if (column <= row) {
        normal.lower(row, column) +=
            weight * stencil.coefficient[r] * stencil.coefficient[c];
      }
    }
  }
}

// Greville returns the Greville abscissae (u_{i+1} + ... + u_{i+p}) / p of
// the `count` functions of degree p on `knots`: a net P_i = a + b xi_i gives
// the line a + b u (linear precision), and they increase strictly for
// knots of multiplicity <= p inside the domain.
std::vector<double> Greville(absl::Span<const double> knots, int p,
                             size_t count) {
  std::vector<double> xi(count);
  for (size_t i = 0; i < count; ++i) {
    double sum = 0;
    for (size_t r = 1; r <= static_cast<size_t>(p); ++r) sum += knots[i + r];
    xi[i] = sum / p;
  }
  return xi;
}

// SecondDifference returns the coefficients (c_{i-1}, c_i, c_{i+1}) of the
// second divided difference at xi_{i-1}, xi_i, xi_{i+1}.
std::array<double, 3> SecondDifference(absl::Span<const double> xi, size_t i) {
  const double left = xi[i] - xi[i - 1], right = xi[i + 1] - xi[i];
  const double lo = 2 / ((left + right) * left);
  const double hi = 2 / ((left + right) * right);
  return {lo, -(lo + hi), hi};
}

// Share returns the length of the parameter interval owned by abscissa i:
// half-way to its neighbours (the first and last own half a gap).
double Share(absl::Span<const double> xi, size_t i) {
  const double lo = i == 0 ? xi[0] : 0.5 * (xi[i - 1] + xi[i]);
  const double hi = i + 1 == xi.size() ? xi[i] : 0.5 * (xi[i] + xi[i + 1]);
  return hi - lo;
}

// AddSmoothing adds `lambda` times the thin-plate energy of the net
// (FitScatteredSurface) to `normal`: squared second divided differences
// over the Greville abscissae, each weighted by the area it stands for.
absl::Status AddSmoothing(double lambda, const SurfaceData& surface,
                          const Ordering& ordering, BandedCholesky& normal,
                          const CancellationToken* cancel) {
  const size_t nu = ordering.count_u, nv = ordering.count_v;
  const std::vector<double> xi =
      Greville(surface.knots_u, surface.degree_u, nu);
  const std::vector<double> eta =
      Greville(surface.knots_v, surface.degree_v, nv);
  CancellationPoll poll(cancel);
  for (size_t i = 0; i < nu; ++i) {
    RETURN_IF_ERROR(poll.Done(nv * 48));
    for (size_t j = 0; j < nv; ++j) {
      if (i > 0 && i + 1 < nu) {
        const std::array<double, 3> c = SecondDifference(xi, i);
        AddStencil({.size = 3,
                    .i = {i - 1, i, i + 1},
                    .j = {j, j, j},
                    .coefficient = {c[0], c[1], c[2]}},
                   lambda * Share(xi, i) * Share(eta, j), ordering, normal);
      }
      if (j > 0 && j + 1 < nv) {
        const std::array<double, 3> c = SecondDifference(eta, j);
        AddStencil({.size = 3,
                    .i = {i, i, i},
                    .j = {j - 1, j, j + 1},
                    .coefficient = {c[0], c[1], c[2]}},
                   lambda * Share(xi, i) * Share(eta, j), ordering, normal);
      }
      if (i + 1 < nu && j + 1 < nv) {
        const double area = (xi[i + 1] - xi[i]) * (eta[j + 1] - eta[j]);
        AddStencil({.size = 4,
                    .i = {i, i + 1, i, i + 1},
                    .j = {j, j, j + 1, j + 1},
                    .coefficient = {1 / area, -1 / area, -1 / area, 1 / area}},
                   2 * lambda * area, ordering, normal);
      }
    }
  }
  return absl::OkStatus();
}

// Residuals fills the per-point distances and their max and rms.
absl::Status Residuals(const PointsView& points, ScatteredFit& fit,
                       const CancellationToken* cancel) {
  std::vector<double> values(points.coordinates.size());
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(values)};
  if (absl::Status status = EvaluateBSplineSurface(
          fit.surface.bspline_view(), SurfaceSamples::Pairs(fit.parameters),
          output, ExecutionContext{.cancellation = cancel});
      !status.ok()) {
    return status;
  }
  const size_t d = static_cast<size_t>(points.dimension);
  fit.residuals.resize(points.size());
  double squares = 0;
  for (size_t k = 0; k < points.size(); ++k) {
    double sum = 0;
    for (size_t c = 0; c < d; ++c) {
      const double difference = values[k * d + c] - points.point(k)[c];
      sum += difference * difference;
    }
    fit.residuals[k] = std::sqrt(sum);
    fit.max_residual = std::max(fit.max_residual, fit.residuals[k]);
    squares += sum;
  }
  fit.rms_residual = std::sqrt(squares / static_cast<double>(points.size()));
  return absl::OkStatus();
}

// SolveNet builds and solves the normal equations of FitScatteredSurface
// for the net of fit.surface (knots set) at fit.parameters.
double LargestDiagonal(BandedCholesky& normal) {
  double largest = 0.0;
  for (size_t i = 0; i < normal.size(); ++i) {
    largest = std::max(largest, normal.lower(i, i));
  }
  return largest;
}

// The Cholesky factorization takes a pivot below 1e-12 of its diagonal as
// singular. The thin-plate energy vanishes on planes, which only the data
// term fixes: once the smoothing term's diagonal outgrows the data term's
// by 1/kSmoothingRatio, those directions are lost in rounding and the
// system is singular to working precision. Such a smoothing is refused,
// naming the largest that keeps them.
constexpr double kSmoothingRatio = 1e-12;

absl::Status CheckSmoothingKeepsTheData(double smoothing, double data_diagonal,
                                        double smoothing_diagonal) {
  if (smoothing_diagonal * kSmoothingRatio <= data_diagonal) {
    return absl::OkStatus();
  }
  const double largest =
      std::isfinite(smoothing_diagonal) && smoothing_diagonal > 0.0
          ? smoothing * (data_diagonal / kSmoothingRatio / smoothing_diagonal)
          : 0.0;
  return InvalidFieldError(
      "smoothing",
      absl::StrCat(smoothing,
                   " outweighs the data by more than 10^12 (the data would be "
                   "lost in rounding); for these points use at most ",
                   largest > 0.0 ? absl::StrCat(largest)
                                 : std::string("a finite smoothing"),
                   " (a large smoothing tends to the least-squares plane)"));
}

absl::Status SolveNet(const PointsView& points,
                      const ScatteredFitOptions& options, ScatteredFit& fit) {
  SurfaceData& surface = fit.surface;
  const Ordering ordering = ChooseOrdering(options);
  const size_t unknowns = ordering.count_u * ordering.count_v;
  const size_t d = static_cast<size_t>(points.dimension);
  BandedCholesky normal(unknowns, ordering.bandwidth);
  std::vector<double> rhs(unknowns * d, 0.0);
  RETURN_IF_ERROR(AddData(points, fit.parameters, surface, ordering, normal,
                          rhs, options.cancel));
  // The data term is summed, not averaged: scale lambda by N instead.
  if (options.smoothing > 0) {
    const double data = LargestDiagonal(normal);
    RETURN_IF_ERROR(
        AddSmoothing(options.smoothing * static_cast<double>(points.size()),
                     surface, ordering, normal, options.cancel));
    RETURN_IF_ERROR(CheckSmoothingKeepsTheData(options.smoothing, data,
                                               LargestDiagonal(normal) - data));
  }
  if (absl::Status status = normal.Factor(options.cancel); !status.ok()) {
    if (!absl::IsFailedPrecondition(status)) return status;
    const auto singular = ordering.position(normal.failed_row());
    return InvalidFieldError(
        options.parameters.empty() ? "points" : "parameters",
        absl::StrCat(
            "the least-squares system is singular (detected at control "
            "point (",
            singular.first, ", ", singular.second,
            ")): without smoothing every control point needs data in its "
            "support; with smoothing the data must still "
            "fix a plane (three points not on one line in (u, v))"));
  }
  RETURN_IF_ERROR(normal.Solve(rhs.data(), d, options.cancel));
  surface.coordinates.resize(unknowns * d);
  for (size_t i = 0; i < ordering.count_u; ++i) {
    for (size_t j = 0; j < ordering.count_v; ++j) {
      std::copy_n(rhs.data() + ordering.index(i, j) * d, d,
                  surface.coordinates.data() + (i * ordering.count_v + j) * d);
    }
  }
  return absl::OkStatus();
}

}  // namespace

ScatteredFitWork EstimateScatteredFit(size_t point_count, int dimension,
                                      const ScatteredFitOptions& options) {
  const Ordering ordering = ChooseOrdering(options);
  const size_t unknowns = Product(ordering.count_u, ordering.count_v);
  const size_t d = Count(dimension);
  const size_t band = Sum(ordering.bandwidth, 1);
  const size_t active =
      Product(Sum(Count(options.degree_u), 1), Sum(Count(options.degree_v), 1));
  ScatteredFitWork work{.bandwidth = ordering.bandwidth};
  // Per point: the normal equations and right-hand side, the residual, and
  // the best-fit plane when parameters are computed.
  work.point_operations = Product(
      point_count, Sum(Sum(Product(active, active), Product(2 * active, d)),
                       options.parameters.empty() ? Product(d, d) : 0));
  const size_t factor = Product(unknowns, Product(band, band) / 2);
  const size_t solve = Product(Product(unknowns, band), 2 * d);
  work.operations = Sum(Sum(work.point_operations, factor), solve);
  const size_t doubles =
      Sum(Sum(Product(unknowns, band), Product(unknowns, 2 * d)),
          Product(point_count, Sum(3, d)));
  work.memory_bytes = Product(doubles, sizeof(double));
  return work;
}

absl::StatusOr<ScatteredFit> FitScatteredSurface(
    const PointsView& points, const ScatteredFitOptions& options) {
  RETURN_IF_ERROR(ValidateScatteredOptions(points, options));
  RETURN_IF_ERROR(CheckWork(points, options));
  ScatteredFit fit;
  if (options.parameters.empty()) {
    absl::StatusOr<std::vector<double>> uv =
        PlaneParameters(points, options.cancel);
    if (!uv.ok()) return uv.status();
    fit.parameters = *std::move(uv);
  } else {
    fit.parameters.assign(options.parameters.begin(), options.parameters.end());
  }
  SurfaceData& surface = fit.surface;
  surface = {
      .degree_u = options.degree_u,
      .degree_v = options.degree_v,
      .dimension = points.dimension,
      .count_u = options.control_count_u,
      .count_v = options.control_count_v,
      .knots_u = ClampedUniformKnots(options.control_count_u, options.degree_u),
      .knots_v =
          ClampedUniformKnots(options.control_count_v, options.degree_v)};
  RETURN_IF_ERROR(SolveNet(points, options, fit));
  RETURN_IF_ERROR(Residuals(points, fit, options.cancel));
  return fit;
}

}  // namespace freeform
