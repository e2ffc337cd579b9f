#include "convert.h"

#include <algorithm>
#include <cstdint>

namespace freeform::server {

absl::Span<double> UninitializedArray(
    google::protobuf::RepeatedField<double>& field, size_t size) {
  field.Reserve(field.size() + static_cast<int>(size));
  return absl::MakeSpan(field.AddNAlreadyReserved(static_cast<int>(size)),
                        size);
}

PointsView ViewOf(const v1::Points& points) {
  return PointsView{
      .dimension = static_cast<int>(std::min<uint32_t>(
          points.dimension(), static_cast<uint32_t>(kMaxDimension + 1))),
      .coordinates = absl::MakeConstSpan(points.coordinates().data(),
                                         points.coordinates_size())};
}

BezierCurveView ViewOf(const v1::BezierCurve& curve) {
  return BezierCurveView{.control_points = ViewOf(curve.control_points()),
                         .weights = absl::MakeConstSpan(curve.weights().data(),
                                                        curve.weights_size())};
}

}  // namespace freeform::server
