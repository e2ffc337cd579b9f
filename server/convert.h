// Conversions from freeform.v1 messages to core views, and the parameter
// sets of evaluation requests.
//
// Views point into the request message's own arrays: nothing is copied, so a
// view must not outlive the request. Validation errors carry field paths
// relative to the message converted (the caller adds the prefix).
// Thread-compatible: no shared state.
#ifndef FREEFORM_SERVER_CONVERT_H_
#define FREEFORM_SERVER_CONVERT_H_

#include <cstddef>
#include <memory>
#include <string_view>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "freeform/core/bezier.h"
#include "freeform/core/points.h"
#include "freeform/v1/curve_service.pb.h"
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

// A resolved set of curve parameters: an explicit list (a view into the
// request) or a uniform range generated on demand, chunk by chunk.

// Room for generated parameters, reused from chunk to chunk.
struct ParameterStorage {
  std::unique_ptr<double[]> values;
  size_t capacity = 0;
};

class ParameterSet {
 public:
  // Resolve checks `parameters` against the domain [lo, hi] and the count
  // limit. Field paths are relative to the Parameters message
  // ("list.values[3]", "range.count"); an empty message is an error naming "".
  static absl::StatusOr<ParameterSet> Resolve(const v1::Parameters& parameters,
                                              double lo, double hi,
                                              size_t max_count);

  size_t size() const { return count_; }

  // Values returns parameters [begin, end): a view of the list, or range
  // values generated into `storage` (grown as needed, never zero-filled).
  absl::Span<const double> Values(size_t begin, size_t end,
                                  ParameterStorage& storage) const;

 private:
  absl::Span<const double> list_;
  bool is_range_ = false;
  double start_ = 0;
  double end_ = 0;
  size_t count_ = 0;
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_CONVERT_H_
