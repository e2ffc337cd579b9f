#include "freeform/core/surface_output.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "freeform/core/curve_output.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"

namespace freeform {

int MaxOrderOf(SurfaceOutput output) {
  for (int order = 0; PartialCount(order) <= output.size(); ++order) {
    if (PartialCount(order) == output.size()) return order;
  }
  return -1;
}

absl::Status ValidateSurfaceOutput(SurfaceOutput output, size_t count,
                                   int dimension) {
  if (MaxOrderOf(output) < 0) {
    return absl::InvalidArgumentError(absl::StrCat(
        "output has ", output.size(),
        " buffers, not the number of partials of some order (1, 3, 6, ...)"));
  }
  // Same buffer sizes as a curve output.
  return ValidateCurveOutput(output, count, dimension);
}

absl::Status ValidateSurfaceSamples(const SurfaceSamples& samples,
                                    double u_start, double u_end,
                                    double v_start, double v_end) {
  if (samples.grid) {
    RETURN_IF_ERROR(ValidateInRange(samples.u, u_start, u_end, "u"));
    return ValidateInRange(samples.v, v_start, v_end, "v");
  }
  if (samples.uv.size() % 2 != 0) {
    return InvalidFieldError("uv", absl::StrCat("holds ", samples.uv.size(),
                                                " values, not (u, v) pairs"));
  }
  for (size_t i = 0; i < samples.uv.size(); ++i) {
    const bool is_u = i % 2 == 0;
    const double value = samples.uv[i];
    // The common case without building the field's name.
    if (std::isfinite(value) && value >= (is_u ? u_start : v_start) &&
        value <= (is_u ? u_end : v_end)) {
      continue;
    }
    if (absl::Status status =
            ValidateInRange(samples.uv.subspan(i, 1), is_u ? u_start : v_start,
                            is_u ? u_end : v_end, IndexedField("uv", i));
        !status.ok()) {
      return InvalidFieldError(IndexedField("uv", i), FieldRuleOf(status));
    }
  }
  return absl::OkStatus();
}

}  // namespace freeform
