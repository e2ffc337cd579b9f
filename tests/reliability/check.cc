// The Checker's bookkeeping and the proto helpers of check.h.
#include "check.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"

namespace freeform::reliability {

Checker::Checker(const google::protobuf::Message& request, double scale)
    : request_(request), scale_(std::max(1.0, scale)) {}

void Checker::set_scale(double scale) { scale_ = std::max(1.0, scale); }

bool Checker::True(bool fact, absl::string_view what) {
  ++checks_;
  if (!fact) Fail(what);
  return fact;
}

bool Checker::Near(double actual, double expected, double tolerance,
                   absl::string_view what) {
  ++checks_;
  if (std::abs(actual - expected) <= tolerance * scale_) return true;
  Fail(absl::StrCat(what, ": got ", actual, ", want ", expected, " within ",
                    tolerance * scale_));
  return false;
}

bool Checker::NearPoint(Coordinates actual, Coordinates expected,
                        double tolerance, absl::string_view what, double at) {
  ++checks_;
  bool near = actual.size() == expected.size();
  for (size_t j = 0; near && j < actual.size(); ++j) {
    near = std::abs(actual[j] - expected[j]) <= tolerance * scale_;
  }
  if (!near) {
    Fail(absl::StrCat(what, " at ", at, ": got (", absl::StrJoin(actual, ", "),
                      "), want (", absl::StrJoin(expected, ", "), ") within ",
                      tolerance * scale_));
  }
  return near;
}

void Checker::Fail(absl::string_view what) {
  if (!mismatch_.empty()) return;
  mismatch_ = absl::StrCat(what, "\n  request: ", request_.ShortDebugString());
}

CallResult Checker::Result(const absl::Status& status, size_t chunks) const {
  CallResult result;
  result.status = status;
  result.chunks = chunks;
  if (status.ok()) {
    result.mismatch = mismatch_;
    result.checks = checks_;
  }
  return result;
}

void CheckSameCurve(Checker& check, std::mt19937_64& rng, int samples,
                    const PointAt& actual, double actual_start,
                    double actual_end, const PointAt& expected,
                    double expected_start, double expected_end,
                    absl::string_view what) {
  std::uniform_real_distribution<double> uniform(0, 1);
  for (int k = -2; k < samples; ++k) {
    const double s = k == -2 ? 0.0 : k == -1 ? 1.0 : uniform(rng);
    const double t = actual_start + s * (actual_end - actual_start);
    if (!check.NearPoint(
            actual(t),
            expected(expected_start + s * (expected_end - expected_start)),
            kTight, what, t)) {
      return;
    }
  }
}

Values Flat(const v1::Points& points) {
  return Values(points.coordinates().begin(), points.coordinates().end());
}

void SetPoints(int dimension, Coordinates coordinates, v1::Points* points) {
  points->set_dimension(static_cast<uint32_t>(dimension));
  points->mutable_coordinates()->Add(coordinates.begin(), coordinates.end());
}

void AddValues(Coordinates values,
               google::protobuf::RepeatedField<double>* field) {
  field->Add(values.begin(), values.end());
}

Values Linspace(double start, double end, uint32_t count) {
  Values values(count);
  if (count == 1) return {start};
  const double h = (end - start) / (count - 1);
  for (uint32_t k = 0; k < count; ++k) values[k] = start + k * h;
  values.back() = end;
  return values;
}

}  // namespace freeform::reliability
