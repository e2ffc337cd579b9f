// Curvature combs of plane curves, for `freeform tessellate --svg --combs`:
// at each vertex of a curve's polyline a tooth of length scale * curvature
// along the normal, pointing away from the centre of curvature (so teeth
// do not cross the curve in tight bends), and the envelope through the
// teeth's tips. The curvature comes from CurveService.Curvature.
#ifndef FREEFORM_CLIENT_CLI_CURVATURE_COMB_H_
#define FREEFORM_CLIENT_CLI_CURVATURE_COMB_H_

#include <optional>
#include <vector>

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/client.h"
#include "svg_drawing.h"

namespace freeform::cli {

// The longest tooth of the default comb, as a fraction of the drawing's
// larger side.
inline constexpr double kCombFraction = 0.15;

// CurveDimension returns the dimension of a curve message's points (0 when
// no curve is set).
int CurveDimension(const v1::Curve& curve);

// DefaultCombScale returns the scale that makes the longest tooth
// kCombFraction * extent, or 0 for a curve without curvature.
double DefaultCombScale(absl::Span<const double> curvatures, double extent);

// CombTips returns the tips of the teeth at `points` (2D): point k minus
// scale * curvatures[k] * normals[k], with the unit normals towards the
// centres of curvature (zero where undefined: a zero tooth).
std::vector<double> CombTips(absl::Span<const double> points,
                             absl::Span<const double> normals,
                             absl::Span<const double> curvatures, double scale);

// AddCurvatureComb asks the server for the curvature of the 2D `curve` at
// the polyline's parameters and draws the teeth and their envelope onto
// `drawing`. Without `scale`, the default scale for the drawing so far.
absl::Status AddCurvatureComb(Client& client, const v1::Curve& curve,
                              const v1::TessellateCurveResponse& polyline,
                              std::optional<double> scale, SvgDrawing& drawing);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_CURVATURE_COMB_H_
