#include "convert.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"

namespace freeform::server {
namespace {

absl::Status CheckCount(size_t count, size_t max_count,
                        absl::string_view field) {
  if (count == 0) {
    return InvalidFieldError(field, "needs at least one parameter");
  }
  if (count > max_count) {
    return ExhaustedFieldError(
        field, absl::StrCat(count, " parameters exceed the server's limit of ",
                            max_count, " (--max_parameters)"));
  }
  return absl::OkStatus();
}

absl::StatusOr<double> RangeEnd(bool has_value, double value, double fallback,
                                double lo, double hi, absl::string_view field) {
  if (!has_value) return fallback;
  if (!std::isfinite(value)) {
    return InvalidFieldError(field,
                             absl::StrCat("must be finite, got ", value));
  }
  if (value < lo || value > hi) {
    return InvalidFieldError(
        field,
        absl::StrCat(value, " is outside the domain [", lo, ", ", hi, "]"));
  }
  return value;
}

}  // namespace

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

absl::StatusOr<ParameterSet> ParameterSet::Resolve(
    const v1::Parameters& parameters, double lo, double hi, size_t max_count) {
  ParameterSet set;
  switch (parameters.kind_case()) {
    case v1::Parameters::kList: {
      const auto& values = parameters.list().values();
      RETURN_IF_ERROR(CheckCount(static_cast<size_t>(values.size()), max_count,
                                 "list.values"));
      set.list_ = absl::MakeConstSpan(values.data(), values.size());
      RETURN_IF_ERROR(ValidateInRange(set.list_, lo, hi, "list.values"));
      set.count_ = set.list_.size();
      return set;
    }
    case v1::Parameters::kRange: {
      const v1::UniformRange& range = parameters.range();
      RETURN_IF_ERROR(CheckCount(range.count(), max_count, "range.count"));
      absl::StatusOr<double> start =
          RangeEnd(range.has_start(), range.start(), lo, lo, hi, "range.start");
      if (!start.ok()) return start.status();
      absl::StatusOr<double> end =
          RangeEnd(range.has_end(), range.end(), hi, lo, hi, "range.end");
      if (!end.ok()) return end.status();
      set.is_range_ = true;
      set.start_ = *start;
      set.end_ = *end;
      set.count_ = range.count();
      return set;
    }
    case v1::Parameters::KIND_NOT_SET:
      break;
  }
  return InvalidFieldError("", "set either a parameter list or a range");
}

absl::Span<const double> ParameterSet::Values(size_t begin, size_t end,
                                              ParameterStorage& storage) const {
  if (!is_range_) return list_.subspan(begin, end - begin);
  const size_t count = end - begin;
  if (storage.capacity < count) {
    storage.values.reset(new double[count]);
    storage.capacity = count;
  }
  double* values = storage.values.get();
  // numpy.linspace's values: start + k step, the last one exactly `end`
  // (kept inside the range against rounding).
  const double step =
      count_ > 1 ? (end_ - start_) / static_cast<double>(count_ - 1) : 0.0;
  const double lo = std::min(start_, end_);
  const double hi = std::max(start_, end_);
  // The index counts in a double (exact below 2^53, far above any count
  // allowed): converting a size_t per value costs more than the rest.
  double index = static_cast<double>(begin);
  for (size_t k = 0; k < count; ++k, index += 1.0) {
    values[k] = std::min(std::max(start_ + index * step, lo), hi);
  }
  if (count_ > 1 && end == count_) values[count - 1] = end_;
  return absl::MakeConstSpan(values, count);
}

}  // namespace freeform::server
