// PrepareCurve and PrepareBasis: from a request's curve or basis message to
// a validated, ready-to-run core evaluation.
//
// Preparation checks every rule (core validation plus the server's limits)
// before any math runs, with field paths that are full paths into the
// request ("curve.bspline.knots[4]", "basis.lagrange.nodes[2]"). The
// prepared object refers to the request's arrays (or to its own converted
// copy), so it must not outlive the request. Thread-compatible.
#ifndef FREEFORM_SERVER_PREPARED_CURVE_H_
#define FREEFORM_SERVER_PREPARED_CURVE_H_

#include <functional>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/bezier.h"
#include "freeform/core/bspline.h"
#include "freeform/core/curve_output.h"
#include "freeform/core/thread_pool.h"
#include "freeform/v1/curve_service.pb.h"
#include "service_limits.h"

namespace freeform::server {

// Evaluates at parameters (inside the domain) into per-order buffers.
using BatchEvaluator = std::function<absl::Status(
    absl::Span<const double>, CurveOutput, const ExecutionContext&)>;

// A curve (or a set of blending functions, seen as a curve whose
// coordinates are the function values) ready to evaluate.
struct PreparedCurve {
  // Values per point: the curve's dimension, or the number of functions.
  int dimension = 0;
  double domain_start = 0.0;
  double domain_end = 1.0;
  BatchEvaluator evaluate;
};

// ValidatedBezier and ValidatedBSpline check a curve message against the
// core rules and `limits` and return its view. Field paths are relative to
// the message ("control_points.coordinates[3]").
absl::StatusOr<BezierCurveView> ValidatedBezier(const v1::BezierCurve& message,
                                                const ServiceLimits& limits);
absl::StatusOr<BSplineCurveView> ValidatedBSpline(
    const v1::BSplineCurve& message, const ServiceLimits& limits);

// PrepareCurve validates `curve` (the request's field "curve") against the
// core rules and `limits`. `algorithm` applies to Bezier and power forms.
absl::StatusOr<PreparedCurve> PrepareCurve(const v1::Curve& curve,
                                           v1::BezierAlgorithm algorithm,
                                           const ServiceLimits& limits);

// PrepareBasis does the same for a Basis message at `field` of the request
// ("basis", or "tensor.u" in a surface basis request).
absl::StatusOr<PreparedCurve> PrepareBasis(const v1::Basis& basis,
                                           const ServiceLimits& limits,
                                           absl::string_view field = "basis");

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_PREPARED_CURVE_H_
