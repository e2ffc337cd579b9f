// Views of the arrays of freeform.v1 messages: request arrays as core
// views (SpanOf, ViewOf) and response arrays for the core to fill in place
// (UninitializedArray). Nothing is copied or validated here: the prepare
// step (prepare.h, prepare_options.h, prepare_samples.h) checks the request,
// and a view must not outlive its message. Thread-compatible: no shared
// state.
#ifndef FREEFORM_SERVER_CONVERT_H_
#define FREEFORM_SERVER_CONVERT_H_

#include <cstddef>

#include "absl/types/span.h"
#include "freeform/core/bezier.h"
#include "freeform/core/points.h"
#include "freeform/v1/geometry.pb.h"

namespace freeform::server {

// SpanOf views a repeated double field (no copy).
inline absl::Span<const double> SpanOf(
    const google::protobuf::RepeatedField<double>& values) {
  return absl::MakeConstSpan(values.data(), values.size());
}

// ViewOf returns a view of `points` (no copy, no validation).
PointsView ViewOf(const v1::Points& points);

// ViewOf returns a view of a Bezier curve (no copy, no validation).
BezierCurveView ViewOf(const v1::BezierCurve& curve);

// UninitializedArray grows `field` by `size` values left for the caller to
// write and returns them: response arrays are filled in place by the core,
// without zero-filling or copying.
absl::Span<double> UninitializedArray(
    google::protobuf::RepeatedField<double>& field, size_t size);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_CONVERT_H_
