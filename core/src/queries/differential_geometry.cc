#include "freeform/core/differential_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "base/scaled.h"
#include "base/vectors.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/curve_output.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/surface_output.h"
#include "geometry/scaled_geometry.h"

namespace freeform {
namespace {

// A Taylor term below this fraction of the curve's motion counts as zero.
constexpr double kNegligible = 1e-12;
// |S_u x S_v| below this fraction of E + G is a singular first fundamental
// form: the threshold of normals.h, so that a point is kSingular exactly
// where ComputeUnitNormals takes the limit.
constexpr double kSingularSurface = 1e-10;
// Principal curvatures closer than this fraction of their size are equal.
constexpr double kUmbilic = 1e-10;

using internal::Cross;
using internal::Dot;

// Norm is |a|, its squares scaled so that they neither underflow nor
// overflow (scaled.h).
double Norm(const double* a, int d) { return internal::ScaledNorm(a, d); }

// ---------------------------------------------------------------- curves --

// The Frenet quantities of one curve point.
struct CurvePoint {
  CurvePointStatus status = CurvePointStatus::kSingular;
  std::array<double, kMaxDimension> tangent{};
  std::array<double, kMaxDimension> normal{};
  std::array<double, 3> binormal{};
  double curvature = 0.0;
  double torsion = 0.0;
};

// FrenetPoint computes the Frenet quantities from r', r'', r''' of a curve
// whose domain has width `width` (see differential_geometry.h).
CurvePoint FrenetPoint(const double* d1, const double* d2, const double* d3,
                       int d, double width) {
  CurvePoint point;
  const double speed = Norm(d1, d);
  const double motion = speed * width + Norm(d2, d) * width * width / 2 +
                        Norm(d3, d) * width * width * width / 6;
  if (!(speed * width > kNegligible * motion)) return point;
  for (int j = 0; j < d; ++j) point.tangent[j] = d1[j] / speed;
  point.status = CurvePointStatus::kStraight;
  const double along = Dot(d2, point.tangent.data(), d);
  std::array<double, kMaxDimension> across{};
  for (int j = 0; j < d; ++j) across[j] = d2[j] - along * point.tangent[j];
  const double bend = Norm(across.data(), d);
  if (!(bend * width * width / 2 > kNegligible * motion)) return point;
  point.status = CurvePointStatus::kRegular;
  point.curvature = bend / speed / speed;
  for (int j = 0; j < d; ++j) point.normal[j] = across[j] / bend;
  if (d == 3) {
    Cross(point.tangent.data(), point.normal.data(), point.binormal.data());
    // r' x r'' = |r'| |r''_perp| B, so the torsion is B . r''' / (|r'|
    // |r''_perp|), without the products that would overflow.
    point.torsion = Dot(point.binormal.data(), d3, 3) / speed / bend;
  }
  return point;
}

// CheckBuffer accepts an empty buffer (not wanted) or one of `size` values.
template <typename T>
absl::Status CheckBuffer(absl::Span<T> buffer, size_t size,
                         absl::string_view name, bool required = false) {
  if (buffer.size() == size || (buffer.empty() && !required)) {
    return absl::OkStatus();
  }
  return absl::InvalidArgumentError(
      absl::StrCat(name, " holds ", buffer.size(), " values, expected ", size));
}

absl::Status CheckFrenetOutput(const FrenetFrameOutput& output, int dimension,
                               size_t count) {
  const FrenetFrameSizes sizes = FrenetSizes(dimension, count);
  for (absl::Status status :
       {CheckBuffer(output.tangents, sizes.tangents, "tangents"),
        CheckBuffer(output.normals, sizes.normals, "normals"),
        CheckBuffer(output.binormals, sizes.binormals, "binormals"),
        CheckBuffer(output.curvatures, sizes.curvatures, "curvatures"),
        CheckBuffer(output.torsions, sizes.torsions, "torsions"),
        CheckBuffer(output.statuses, sizes.statuses, "statuses", true)}) {
    if (!status.ok()) return status;
  }
  return absl::OkStatus();
}

// The derivatives 0..3 of a curve at every parameter, evaluated on its copy
// rescaled by powers of two (scaled_geometry.h), the width of that copy's
// domain, and the exponent e of its coordinates (the curve's curvature and
// torsion are the copy's times 2^-e).
struct CurveDerivatives {
  int dimension = 0;
  double width = 0.0;
  int coordinate_exponent = 0;
  std::array<std::vector<double>, 4> orders;

  const double* at(int order, size_t r) const {
    return orders[order].data() + r * static_cast<size_t>(dimension);
  }
};

absl::StatusOr<CurveDerivatives> EvaluateDerivatives(
    const Curve& curve, absl::Span<const double> parameters,
    const ExecutionContext& context) {
  const ParameterDomain original = DomainOf(curve);
  RETURN_IF_ERROR(
      ValidateInRange(parameters, original.start, original.end, "parameters"));
  const internal::ScaledCurve scaled = internal::ScaledCurve::Of(curve);
  std::vector<double> scaled_parameters;
  absl::Span<const double> at = parameters;
  if (scaled.scale().u_exponent != 0) {
    scaled_parameters.resize(parameters.size());
    for (size_t r = 0; r < parameters.size(); ++r) {
      scaled_parameters[r] = scaled.ToScaled(parameters[r]);
    }
    at = scaled_parameters;
  }
  const ParameterDomain domain = DomainOf(scaled.curve());
  CurveDerivatives derivatives{
      .dimension = DimensionOf(curve),
      .width = domain.end - domain.start,
      .coordinate_exponent = scaled.scale().coordinate_exponent,
      .orders = {}};
  std::array<absl::Span<double>, 4> output;
  for (size_t k = 0; k < output.size(); ++k) {
    derivatives.orders[k].resize(parameters.size() *
                                 static_cast<size_t>(derivatives.dimension));
    output[k] = absl::MakeSpan(derivatives.orders[k]);
  }
  RETURN_IF_ERROR(EvaluateCurve(scaled.curve(), at, output, context));
  return derivatives;
}

CurvePoint FrenetAt(const CurveDerivatives& derivatives, size_t r) {
  CurvePoint point = FrenetPoint(derivatives.at(1, r), derivatives.at(2, r),
                                 derivatives.at(3, r), derivatives.dimension,
                                 derivatives.width);
  const internal::PowerOfTwoScale back(-derivatives.coordinate_exponent);
  point.curvature = back(point.curvature);
  point.torsion = back(point.torsion);
  return point;
}

// MovingAt is FrenetAt for a point that must have a tangent.
absl::StatusOr<CurvePoint> MovingAt(const CurveDerivatives& derivatives,
                                    size_t r) {
  CurvePoint point = FrenetAt(derivatives, r);
  if (point.status != CurvePointStatus::kSingular) return point;
  return InvalidFieldError(IndexedField("parameters", r),
                           "the curve stands still here: no tangent");
}

// Copy writes `count` values of `from` at slot r of `to` (when wanted).
void Copy(const double* from, size_t count, size_t r, absl::Span<double> to) {
  if (to.empty()) return;
  std::copy(from, from + count, to.begin() + r * count);
}

void StoreFrenet(const CurvePoint& point, int d, size_t r,
                 const FrenetFrameOutput& output) {
  const size_t dim = static_cast<size_t>(d);
  Copy(point.tangent.data(), dim, r, output.tangents);
  Copy(point.normal.data(), dim, r, output.normals);
  Copy(point.binormal.data(), 3, r, output.binormals);
  Copy(&point.curvature, 1, r, output.curvatures);
  Copy(&point.torsion, 1, r, output.torsions);
  output.statuses[r] = point.status;
}

// InitialReference returns the first reference vector of a rotation-
// minimizing frame at a point with tangent `point.tangent`.
absl::StatusOr<std::array<double, kMaxDimension>> InitialReference(
    const CurvePoint& point, absl::Span<const double> given, int d) {
  const double* t = point.tangent.data();
  std::array<double, kMaxDimension> reference{};
  if (!given.empty()) {
    if (given.size() != static_cast<size_t>(d)) {
      return InvalidFieldError(
          "initial_reference",
          absl::StrCat("has ", given.size(), " values, not the dimension ", d));
    }
    RETURN_IF_ERROR(ValidateFinite(given, "initial_reference"));
    std::copy(given.begin(), given.end(), reference.begin());
  } else if (point.status == CurvePointStatus::kRegular) {
    return point.normal;
  } else {
    int axis = 0;
    for (int j = 1; j < d; ++j) {
      if (std::abs(t[j]) < std::abs(t[axis])) axis = j;
    }
    reference[axis] = 1.0;
  }
  const double size = Norm(reference.data(), d);
  const double along = Dot(reference.data(), t, d);
  for (int j = 0; j < d; ++j) reference[j] -= along * t[j];
  const double across = Norm(reference.data(), d);
  if (!(across > 1e-12 * size)) {
    return InvalidFieldError("initial_reference",
                             "lies along the tangent at parameters[0]");
  }
  for (int j = 0; j < d; ++j) reference[j] /= across;
  return reference;
}

// Reflect reflects `vectors` in the hyperplane orthogonal to `normal`
// (skipped when `normal` vanishes), the normal first divided by the power
// of two at or above its largest component so that its square cannot
// underflow for points close together.
void Reflect(const double* normal, int d,
             std::initializer_list<double*> vectors) {
  double largest = 0.0;
  for (int j = 0; j < d; ++j) largest = std::max(largest, std::abs(normal[j]));
  if (!(largest > 0.0) || !std::isfinite(largest)) return;
  const int e = internal::ExponentAbove(largest);
  std::array<double, kMaxDimension> unit{};
  for (int j = 0; j < d; ++j) unit[j] = std::ldexp(normal[j], -e);
  const double c = Dot(unit.data(), unit.data(), d);
  for (double* v : vectors) {
    const double f = 2.0 * Dot(unit.data(), v, d) / c;
    for (int j = 0; j < d; ++j) v[j] -= f * unit[j];
  }
}

// DoubleReflection advances the reference vector `r` from the point x0
// with tangent t0 to x1 with tangent t1 (Wang et al. 2008, Algorithm 1),
// then removes the rounding's drift from orthonormality.
void DoubleReflection(const double* x0, const double* t0, const double* x1,
                      const double* t1, int d, double* r) {
  std::array<double, kMaxDimension> v{}, t{};
  for (int j = 0; j < d; ++j) v[j] = x1[j] - x0[j];
  std::copy(t0, t0 + d, t.begin());
  Reflect(v.data(), d, {r, t.data()});
  for (int j = 0; j < d; ++j) v[j] = t1[j] - t[j];
  Reflect(v.data(), d, {r});
  const double along = Dot(r, t1, d);
  for (int j = 0; j < d; ++j) r[j] -= along * t1[j];
  const double size = Norm(r, d);
  for (int j = 0; j < d; ++j) r[j] /= size;
}

absl::Status CheckRotationMinimizingOutput(
    const RotationMinimizingFrameOutput& output, int dimension, size_t count) {
  const RotationMinimizingFrameSizes sizes =
      RotationMinimizingSizes(dimension, count);
  for (absl::Status status :
       {CheckBuffer(output.tangents, sizes.tangents, "tangents"),
        CheckBuffer(output.references, sizes.references, "references"),
        CheckBuffer(output.third, sizes.third, "third")}) {
    if (!status.ok()) return status;
  }
  return absl::OkStatus();
}

// -------------------------------------------------------------- surfaces --

// The curvatures of one surface point.
struct SurfacePoint {
  SurfacePointStatus status = SurfacePointStatus::kSingular;
  double gaussian = 0.0;
  double mean = 0.0;
  std::array<double, 2> principal{};
  std::array<double, 6> directions{};
};

const double* PartialAt(SurfaceOutput partials, int k, int l, size_t r) {
  return partials[PartialIndex(k, l)].data() + 3 * r;
}

// SecondForm returns II(a, b) for tangent vectors with parameter
// coordinates a and b.
double SecondForm(const std::array<double, 3>& lmn,
                  const std::array<double, 2>& a,
                  const std::array<double, 2>& b) {
  return lmn[0] * a[0] * b[0] + lmn[1] * (a[0] * b[1] + a[1] * b[0]) +
         lmn[2] * a[1] * b[1];
}

// UnitPartials holds the partials S_u, S_v, S_uu, S_uv, S_vv of one point
// after the reparameterization (u, v) -> (u, v) / c, c = 2^e with e the
// SafeExponent of the largest component of S_u and S_v (scaled.h): the
// first partials are divided by c, the second by c^2, so that E, F, G and
// the products below stay within the double range whatever the geometry's
// scale, and the curvatures do not change.
struct UnitPartials {
  // p[a] points at partial a: the evaluated one when e = 0, else its
  // scaled copy in `scaled`.
  std::array<const double*, 5> p{};
  std::array<std::array<double, 3>, 5> scaled{};

  UnitPartials(SurfaceOutput partials, size_t r) {
    const std::array<std::pair<int, int>, 5> orders = {
        {{1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}}};
    for (size_t a = 0; a < orders.size(); ++a) {
      p[a] = PartialAt(partials, orders[a].first, orders[a].second, r);
    }
    double largest = 0.0;
    for (int a = 0; a < 2; ++a) {
      for (int j = 0; j < 3; ++j)
        largest = std::max(largest, std::abs(p[a][j]));
    }
    const int e = largest == 0.0 ? 0 : internal::SafeExponent(largest);
    if (e == 0) return;
    for (size_t a = 0; a < orders.size(); ++a) {
      const int order = orders[a].first + orders[a].second;
      for (int j = 0; j < 3; ++j) {
        scaled[a][j] = std::ldexp(p[a][j], -order * e);
      }
      p[a] = scaled[a].data();
    }
  }
};

// CurvaturePoint computes the curvatures of point r from its partials and
// unit normal (see differential_geometry.h).
SurfacePoint CurvaturePoint(SurfaceOutput partials, size_t r, const double* n) {
  SurfacePoint point;
  const UnitPartials unit(partials, r);
  const double* su = unit.p[0];
  const double* sv = unit.p[1];
  const double e = Dot(su, su, 3);
  const double f = Dot(su, sv, 3);
  const double g = Dot(sv, sv, 3);
  std::array<double, 3> cross{};
  Cross(su, sv, cross.data());
  const double area = Norm(cross.data(), 3);
  if (!(area > kSingularSurface * (e + g))) return point;
  const std::array<double, 3> lmn = {Dot(unit.p[2], n, 3), Dot(unit.p[3], n, 3),
                                     Dot(unit.p[4], n, 3)};
  // e1 = S_u / |S_u| and e2 = n x e1 = (E S_v - F S_u) / (|S_u| area) in
  // parameter coordinates.
  const double root_e = std::sqrt(e);
  const std::array<double, 2> e1 = {1.0 / root_e, 0.0};
  const std::array<double, 2> e2 = {-f / (root_e * area), root_e / area};
  const double s11 = SecondForm(lmn, e1, e1);
  const double s12 = SecondForm(lmn, e1, e2);
  const double s22 = SecondForm(lmn, e2, e2);
  point.mean = 0.5 * (s11 + s22);
  // K is exact to a few rounding errors of the shape operator's size
  // squared (those of s11, s22 and s12 themselves); below that it is noise,
  // returned as 0, which on a cylinder of radius 1e-300 would otherwise be
  // scaled back to an overflow.
  const double size = std::max({std::abs(s11), std::abs(s22), std::abs(s12)});
  const double gaussian = s11 * s22 - s12 * s12;
  point.gaussian =
      std::abs(gaussian) <=
              16.0 * std::numeric_limits<double>::epsilon() * size * size
          ? 0.0
          : gaussian;
  const double radius = std::hypot(0.5 * (s11 - s22), s12);
  point.principal = {point.mean + radius, point.mean - radius};
  const bool umbilic =
      !(radius > kUmbilic * (std::abs(s11) + std::abs(s22) + std::abs(s12)));
  point.status =
      umbilic ? SurfacePointStatus::kUmbilic : SurfacePointStatus::kRegular;
  const double angle = umbilic ? 0.0 : 0.5 * std::atan2(2.0 * s12, s11 - s22);
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  for (int j = 0; j < 3; ++j) {
    const double x1 = su[j] / root_e;
    const double x2 = (e * sv[j] - f * su[j]) / (root_e * area);
    point.directions[j] = c * x1 + s * x2;
    point.directions[3 + j] = -s * x1 + c * x2;
  }
  return point;
}

void StoreCurvature(const SurfacePoint& point, const double* normal, size_t r,
                    const SurfaceCurvatureOutput& output) {
  Copy(normal, 3, r, output.normals);
  Copy(&point.gaussian, 1, r, output.gaussian);
  Copy(&point.mean, 1, r, output.mean);
  Copy(point.principal.data(), 2, r, output.principal_curvatures);
  Copy(point.directions.data(), 6, r, output.principal_directions);
  output.statuses[r] = point.status;
}

absl::Status CheckCurvatureOutput(const SurfaceCurvatureOutput& output,
                                  size_t count) {
  const SurfaceCurvatureSizes sizes = CurvatureSizes(count);
  for (absl::Status status :
       {CheckBuffer(output.normals, sizes.normals, "normals"),
        CheckBuffer(output.gaussian, sizes.gaussian, "gaussian"),
        CheckBuffer(output.mean, sizes.mean, "mean"),
        CheckBuffer(output.principal_curvatures, sizes.principal_curvatures,
                    "principal_curvatures"),
        CheckBuffer(output.principal_directions, sizes.principal_directions,
                    "principal_directions"),
        CheckBuffer(output.statuses, sizes.statuses, "statuses", true)}) {
    if (!status.ok()) return status;
  }
  return absl::OkStatus();
}

absl::Status CheckThreeDimensional(const Surface& surface) {
  if (DimensionOf(surface) == 3) return absl::OkStatus();
  return InvalidFieldError(
      IsTriangular(surface) ? "control_points.dimension"
                            : "control_net.dimension",
      absl::StrCat("curvatures need a 3-D surface, this one is ",
                   DimensionOf(surface), "-D"));
}

}  // namespace

FrenetFrameSizes FrenetSizes(int dimension, size_t count) {
  const size_t d = static_cast<size_t>(std::max(dimension, 0));
  const size_t three_d = dimension == 3 ? count : 0;
  return {.tangents = count * d,
          .normals = count * d,
          .binormals = 3 * three_d,
          .curvatures = count,
          .torsions = three_d,
          .statuses = count};
}

absl::Status EvaluateFrenetFrames(const Curve& curve,
                                  absl::Span<const double> parameters,
                                  const FrenetFrameOutput& output,
                                  const ExecutionContext& context) {
  const int d = DimensionOf(curve);
  RETURN_IF_ERROR(CheckFrenetOutput(output, d, parameters.size()));
  absl::StatusOr<CurveDerivatives> derivatives =
      EvaluateDerivatives(curve, parameters, context);
  if (!derivatives.ok()) return derivatives.status();
  return ParallelFor(parameters.size(), context, [&](size_t b, size_t e) {
    for (size_t r = b; r < e; ++r) {
      StoreFrenet(FrenetAt(*derivatives, r), d, r, output);
    }
  });
}

RotationMinimizingFrameSizes RotationMinimizingSizes(int dimension,
                                                     size_t count) {
  const size_t d = static_cast<size_t>(std::max(dimension, 0));
  return {.tangents = count * d,
          .references = count * d,
          .third = dimension == 3 ? 3 * count : 0};
}

absl::Status EvaluateRotationMinimizingFrames(
    const Curve& curve, absl::Span<const double> parameters,
    absl::Span<const double> initial_reference,
    const RotationMinimizingFrameOutput& output,
    const ExecutionContext& context) {
  const int d = DimensionOf(curve);
  if (d < 2) {
    return InvalidFieldError("dimension",
                             "a frame needs a curve of dimension 2 or more");
  }
  if (parameters.empty()) {
    return InvalidFieldError("parameters", "needs at least one parameter");
  }
  RETURN_IF_ERROR(CheckRotationMinimizingOutput(output, d, parameters.size()));
  absl::StatusOr<CurveDerivatives> derivatives =
      EvaluateDerivatives(curve, parameters, context);
  if (!derivatives.ok()) return derivatives.status();
  absl::StatusOr<CurvePoint> previous = MovingAt(*derivatives, 0);
  if (!previous.ok()) return previous.status();
  absl::StatusOr<std::array<double, kMaxDimension>> reference =
      InitialReference(*previous, initial_reference, d);
  if (!reference.ok()) return reference.status();
  CancellationPoll poll(context.cancellation);
  const size_t dim = static_cast<size_t>(d);
  for (size_t r = 0; r < parameters.size(); ++r) {
    absl::StatusOr<CurvePoint> point = MovingAt(*derivatives, r);
    if (!point.ok()) return point.status();
    if (r > 0) {
      DoubleReflection(derivatives->at(0, r - 1), previous->tangent.data(),
                       derivatives->at(0, r), point->tangent.data(), d,
                       reference->data());
    }
    Copy(point->tangent.data(), dim, r, output.tangents);
    Copy(reference->data(), dim, r, output.references);
    if (d == 3 && !output.third.empty()) {
      Cross(point->tangent.data(), reference->data(), &output.third[3 * r]);
    }
    previous = std::move(point);
    RETURN_IF_ERROR(poll.Done(16 * dim));
  }
  return absl::OkStatus();
}

SurfaceCurvatureSizes CurvatureSizes(size_t count) {
  return {.normals = 3 * count,
          .gaussian = count,
          .mean = count,
          .principal_curvatures = 2 * count,
          .principal_directions = 6 * count,
          .statuses = count};
}

absl::Status EvaluateSurfaceCurvatures(const Surface& surface,
                                       const SurfaceSamples& samples,
                                       const SurfaceCurvatureOutput& output,
                                       const ExecutionContext& context) {
  RETURN_IF_ERROR(CheckThreeDimensional(surface));
  const size_t count = samples.size();
  RETURN_IF_ERROR(CheckCurvatureOutput(output, count));
  std::vector<std::vector<double>> buffers(PartialCount(2),
                                           std::vector<double>(3 * count));
  std::vector<absl::Span<double>> partials;
  for (std::vector<double>& buffer : buffers) {
    partials.push_back(absl::MakeSpan(buffer));
  }
  RETURN_IF_ERROR(ValidateSamples(surface, samples));
  // Evaluated on the copy rescaled by powers of two (scaled_geometry.h):
  // its curvatures are the surface's times 2^e.
  const internal::ScaledSurface scaled = internal::ScaledSurface::Of(surface);
  std::vector<double> storage;
  std::vector<double> normals(3 * count);
  RETURN_IF_ERROR(EvaluateSurface(scaled.surface(),
                                  scaled.Samples(samples, storage), partials,
                                  absl::MakeSpan(normals), context));
  const int exponent = scaled.scale().coordinate_exponent;
  const internal::PowerOfTwoScale back(-exponent);
  const internal::PowerOfTwoScale back_squared(-2 * exponent);
  return ParallelFor(count, context, [&](size_t b, size_t e) {
    for (size_t r = b; r < e; ++r) {
      const double* normal = normals.data() + 3 * r;
      SurfacePoint point = CurvaturePoint(partials, r, normal);
      point.mean = back(point.mean);
      point.gaussian = back_squared(point.gaussian);
      for (double& k : point.principal) k = back(k);
      StoreCurvature(point, normal, r, output);
    }
  });
}

}  // namespace freeform
