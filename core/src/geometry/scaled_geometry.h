// Copies of a curve or surface rescaled by powers of two, which is exact:
// the coordinates divided by 2^e, the power of two at or above the largest
// one, the weights by the power of two at or above the largest weight (the
// same geometry), and the parameters of the knot- and node-based kinds by
// 2^k, the power of two at or above the width of their domain (the same
// geometry, reparameterized). In those units a geometry of size 1e-300 or
// 1e300, with knots 1e170 apart or weights of 1e50, has coordinates and
// weights at most 1 and derivatives of the size of its own shape, so the
// queries (arc length, closest points, curvature) run the same arithmetic
// at every scale and scale their answers back (lengths and points by 2^e,
// parameters by 2^k, curvatures by 2^-e): docs/references.md, 'Scale-safe
// norms'. A copy whose scaled values no longer validate (a value so small
// next to the largest that it underflows, changing the geometry) is the
// geometry itself with exponents 0. A bounding box, which treats each axis
// on its own, may use a copy scaled per axis (OfAxes): coordinate j divided
// by the power of two at or above the largest on axis j, an affine image of
// the geometry whose box is the box's image, so that a tiny axis next to a
// huge one keeps its digits in the homogeneous points w P. Internal to the
// core; the copy owns its values (move-only), thread-safe once made.
#ifndef FREEFORM_CORE_SRC_GEOMETRY_SCALED_GEOMETRY_H_
#define FREEFORM_CORE_SRC_GEOMETRY_SCALED_GEOMETRY_H_

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "absl/types/span.h"
#include "freeform/core/curve.h"
#include "freeform/core/surface.h"

namespace freeform::internal {

// The values a scaled copy owns, and its exponents.
struct ScaledValues {
  std::vector<double> coordinates;
  std::vector<double> tangents;
  std::vector<double> weights;
  std::vector<double> knots_u;  // knots or nodes of a curve
  std::vector<double> knots_v;
  int coordinate_exponent = 0;  // e: original coordinates = scaled * 2^e
  // The exponent of each axis of a copy scaled per axis (OfAxes), else
  // empty: every axis has coordinate_exponent.
  std::vector<int> axis_exponents;
  int u_exponent = 0;  // k: original parameter = scaled * 2^k
  int v_exponent = 0;

  // Length returns a length (or point coordinate) of the scaled geometry in
  // the original units, and Unlength the inverse.
  double Length(double scaled) const {
    return std::ldexp(scaled, coordinate_exponent);
  }
  double Unlength(double original) const {
    return std::ldexp(original, -coordinate_exponent);
  }
  // AxisExponent returns the exponent of axis j.
  int AxisExponent(size_t j) const {
    return axis_exponents.empty() ? coordinate_exponent : axis_exponents[j];
  }
};

class ScaledCurve {
 public:
  static ScaledCurve Of(const Curve& curve);
  // OfAxes returns the copy scaled per axis (for boxes only: its shape is
  // not the curve's when the axes' exponents differ).
  static ScaledCurve OfAxes(const Curve& curve);

  ScaledCurve(ScaledCurve&&) = default;
  ScaledCurve& operator=(ScaledCurve&&) = default;

  const Curve& curve() const { return *curve_; }
  const ScaledValues& scale() const { return values_; }
  // ToScaled maps a parameter of the original curve to the copy's, and
  // ToOriginal back.
  double ToScaled(double t) const { return std::ldexp(t, -values_.u_exponent); }
  double ToOriginal(double t) const {
    return std::ldexp(t, values_.u_exponent);
  }

 private:
  ScaledCurve() = default;
  static ScaledCurve Copied(const Curve& curve, bool each_axis);

  ScaledValues values_;
  std::optional<Curve> curve_;
};

class ScaledSurface {
 public:
  static ScaledSurface Of(const Surface& surface);
  // OfAxes returns the copy scaled per axis, as ScaledCurve::OfAxes.
  static ScaledSurface OfAxes(const Surface& surface);

  ScaledSurface(ScaledSurface&&) = default;
  ScaledSurface& operator=(ScaledSurface&&) = default;

  const Surface& surface() const { return *surface_; }
  const ScaledValues& scale() const { return values_; }
  // Samples returns `samples` in the copy's parameters, in `storage` when
  // they change (a B-spline surface whose domain is not within a factor 2
  // of the unit square's), else `samples` itself.
  SurfaceSamples Samples(const SurfaceSamples& samples,
                         std::vector<double>& storage) const;
  // ToOriginal maps parameters (u, v) of the copy back in place.
  void ToOriginal(double* uv) const {
    uv[0] = std::ldexp(uv[0], values_.u_exponent);
    uv[1] = std::ldexp(uv[1], values_.v_exponent);
  }

 private:
  ScaledSurface() = default;
  static ScaledSurface Copied(const Surface& surface, bool each_axis);

  ScaledValues values_;
  std::optional<Surface> surface_;
};

// ScaledCopyBytes bounds, before any work, the memory a ScaledCurve or
// ScaledSurface of the geometry holds: its values twice (the scaled values
// and the copy's own) and the blocks that hold them, or one copy of the
// geometry when the scaled one does not validate.
uint64_t ScaledCopyBytes(const Curve& curve);
uint64_t ScaledCopyBytes(const Surface& surface);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_GEOMETRY_SCALED_GEOMETRY_H_
