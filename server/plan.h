// Helpers every RPC handler uses to plan its call before any work: the
// memory an answer of a known size needs, and when work counts as heavy.
// Thread-compatible.
#ifndef FREEFORM_SERVER_PLAN_H_
#define FREEFORM_SERVER_PLAN_H_

#include <cstdint>

#include "freeform/core/saturating.h"
#include "rpc.h"
#include "service_limits.h"

namespace freeform::server {

// AnswerPlan returns the plan of a call whose answer holds `answer_values`
// doubles and whose work needs `work_bytes` besides: the answer counts twice
// (the message and its serialized copy); work over a few thousand values is
// heavy and goes to the pool.
inline CallPlan AnswerPlan(uint64_t answer_values, uint64_t work_bytes,
                           const ServiceLimits& limits) {
  return {.memory_bytes = 2 * 8 * answer_values + work_bytes + 4096,
          .heavy = answer_values + work_bytes / 8 > 4 * limits.grain};
}

// UnaryAnswerCheck checks an answer of `values` doubles against the output
// limit and the message limit, naming `field`.
inline absl::Status UnaryAnswerCheck(uint64_t values,
                                     const ServiceLimits& limits,
                                     absl::string_view field,
                                     absl::string_view hint = "") {
  if (absl::Status status = CheckOutputLimit(values, limits, field);
      !status.ok()) {
    return status;
  }
  return CheckMessageLimit(values, limits, hint, field);
}

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_PLAN_H_
