// Piecewise cubic Hermite curves and the cubic Hermite basis.
//
// Segment k runs from points[k] to points[k+1] over [t_k, t_{k+1}] with end
// derivatives tangents[k] and tangents[k+1] (with respect to t). Each
// segment is the cubic Bezier curve P_k, P_k + h T_k / 3, P_{k+1} - h T_{k+1}
// / 3, P_{k+1} with h = t_{k+1} - t_k, evaluated with the Bezier machinery
// and the chain rule. At an interior node values and derivatives are the
// right-hand limits (left-hand at the end of the domain), as for B-splines.
// Thread-safe.
#ifndef FREEFORM_CORE_HERMITE_H_
#define FREEFORM_CORE_HERMITE_H_

#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/curve_output.h"
#include "freeform/core/points.h"
#include "freeform/core/thread_pool.h"

namespace freeform {

struct HermiteCurveView {
  PointsView points;
  PointsView tangents;
  // Empty: nodes 0, 1, ..., K-1. Otherwise K strictly increasing nodes.
  absl::Span<const double> nodes;
};

// ValidateHermiteCurve checks at least two finite points ("points..."), as
// many tangents of the same dimension ("tangents..."), and the nodes
// ("nodes": count; "nodes[i]": finite, strictly increasing).
absl::Status ValidateHermiteCurve(const HermiteCurveView& curve);

// HermiteNodes returns the nodes, filling in the default 0, 1, ..., K-1.
std::vector<double> HermiteNodes(const HermiteCurveView& curve);

// HermiteDomain returns [t_0, t_{K-1}] of a valid curve.
std::pair<double, double> HermiteDomain(const HermiteCurveView& curve);

// HermiteSegmentBezier returns the 4 Bezier control points of segment k.
std::vector<double> HermiteSegmentBezier(const HermiteCurveView& curve,
                                         absl::Span<const double> nodes,
                                         size_t segment);

// EvaluateHermiteCurve writes derivatives 0..output.size()-1 at every
// parameter (which must lie in the domain, "parameters[i]").
absl::Status EvaluateHermiteCurve(const HermiteCurveView& curve,
                                  absl::Span<const double> parameters,
                                  CurveOutput output,
                                  const ExecutionContext& context = {});

// EvaluateHermiteBasis writes the four cubic Hermite functions on [0, 1],
// H0 = 2t^3 - 3t^2 + 1, H1 = -2t^3 + 3t^2, H2 = t^3 - 2t^2 + t,
// H3 = t^3 - t^2 (weights of P0, P1, T0, T1), and their derivatives:
// output[k][r * 4 + i].
absl::Status EvaluateHermiteBasis(absl::Span<const double> parameters,
                                  CurveOutput output,
                                  const ExecutionContext& context = {});

}  // namespace freeform

#endif  // FREEFORM_CORE_HERMITE_H_
