#include "freeform/core/normals.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "base/scaled.h"
#include "freeform/core/status_macros.h"

namespace freeform {
namespace {

struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

Vec3 operator+(const Vec3& a, const Vec3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
Vec3 operator*(double s, const Vec3& a) { return {s * a.x, s * a.y, s * a.z}; }
double Dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec3 Cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// S_u x S_v counts as vanishing below this fraction of |S_u|^2 + |S_v|^2:
// far above the rounding of a collapsed edge's S_v (~1e-16 of the net's
// scale), far below the sine of any angle a real patch makes.
constexpr double kDegenerate = 1e-10;

// Partial returns the partial (k, l) of point r times 2^-e.
Vec3 Partial(SurfaceOutput partials, int k, int l, size_t r, int e) {
  const double* p = partials[PartialIndex(k, l)].data() + 3 * r;
  if (e == 0) return {p[0], p[1], p[2]};
  return {std::ldexp(p[0], -e), std::ldexp(p[1], -e), std::ldexp(p[2], -e)};
}

double Length(const Vec3& a) {
  const double values[] = {a.x, a.y, a.z};
  return internal::ScaledNorm(values, 3);
}

// The unit normal of point r, degenerate points approached by
// (sign_u h, sign_v h), h > 0 (see normals.h). Partials too large or too
// small to square (|S_u|^2 + |S_v|^2 outside [2^-480, 2^500]) are first
// divided by the power of two at or above their largest component (exact,
// and the normal's direction does not change), so that a surface of size
// 1e160 or 1e-160 gets its normal.
Vec3 UnitNormal(SurfaceOutput partials, size_t r, double sign_u,
                double sign_v) {
  int e = 0;
  Vec3 su = Partial(partials, 1, 0, r, e);
  Vec3 sv = Partial(partials, 0, 1, r, e);
  double size = Dot(su, su) + Dot(sv, sv);
  if (!(size >= 0x1p-480 && size <= 0x1p500) && size != 0.0) {
    e = internal::ExponentAbove(
        std::max({std::abs(su.x), std::abs(su.y), std::abs(su.z),
                  std::abs(sv.x), std::abs(sv.y), std::abs(sv.z)}));
    su = Partial(partials, 1, 0, r, e);
    sv = Partial(partials, 0, 1, r, e);
    size = Dot(su, su) + Dot(sv, sv);
  }
  Vec3 normal = Cross(su, sv);
  double length = Length(normal);
  if (!(length > kDegenerate * size)) {
    if (MaxOrderOf(partials) < 2) return {};
    const Vec3 suu = Partial(partials, 2, 0, r, e);
    const Vec3 suv = Partial(partials, 1, 1, r, e);
    const Vec3 svv = Partial(partials, 0, 2, r, e);
    const Vec3 along_u = Cross(su, suv) + Cross(suu, sv);
    const Vec3 along_v = Cross(suv, sv) + Cross(su, svv);
    const bool use_u = Length(along_u) >= Length(along_v);
    normal = use_u ? sign_u * along_u : sign_v * along_v;
    length = Length(normal);
    if (!(length > 0.0) || !std::isfinite(length)) return {};
  }
  return (1.0 / length) * normal;
}

absl::Status ValidateNormalBuffers(SurfaceOutput partials, size_t count,
                                   absl::Span<double> normals) {
  if (absl::Status status = ValidateSurfaceOutput(partials, count, 3);
      !status.ok()) {
    return absl::InvalidArgumentError(
        absl::StrCat("partials must be 3D: ", status.message()));
  }
  if (MaxOrderOf(partials) < 1) {
    return absl::InvalidArgumentError(
        "partials must include the first derivatives (max order >= 1)");
  }
  if (normals.size() != 3 * count) {
    return absl::InvalidArgumentError(absl::StrCat(
        "normals holds ", normals.size(), " values, expected ", 3 * count));
  }
  return absl::OkStatus();
}

void Store(const Vec3& normal, size_t r, absl::Span<double> normals) {
  normals[3 * r] = normal.x;
  normals[3 * r + 1] = normal.y;
  normals[3 * r + 2] = normal.z;
}

// -1 at the end of a non-empty interval (approach from below), else +1.
double SideOf(double t, double start, double end) {
  return t >= end && end > start ? -1.0 : 1.0;
}

}  // namespace

absl::Status ComputeUnitNormals(SurfaceOutput partials, size_t count,
                                absl::Span<double> normals) {
  RETURN_IF_ERROR(ValidateNormalBuffers(partials, count, normals));
  for (size_t r = 0; r < count; ++r) {
    Store(UnitNormal(partials, r, 1.0, 1.0), r, normals);
  }
  return absl::OkStatus();
}

absl::Status ComputeUnitNormals(SurfaceOutput partials,
                                const SurfaceSamples& samples,
                                const SurfaceDomain& domain,
                                absl::Span<double> normals) {
  const size_t count = samples.size();
  RETURN_IF_ERROR(ValidateNormalBuffers(partials, count, normals));
  const size_t count_v = samples.v.size();
  for (size_t r = 0; r < count; ++r) {
    const double u = samples.grid ? samples.u[r / count_v] : samples.uv[2 * r];
    const double v =
        samples.grid ? samples.v[r % count_v] : samples.uv[2 * r + 1];
    const double sign_u = SideOf(u, domain.u_start, domain.u_end);
    const double sign_v = SideOf(v, domain.v_start, domain.v_end);
    Store(UnitNormal(partials, r, sign_u, sign_v), r, normals);
  }
  return absl::OkStatus();
}

}  // namespace freeform
