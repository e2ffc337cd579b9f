// The evaluation of a prepared surface plan into an EvaluateSurfaceResponse,
// shared by SurfaceService.Evaluate / EvaluateStream and FaceService.Evaluate
// (surface_service.cc). Thread-safe: chunks of one plan may be evaluated at
// once into different responses.
#ifndef FREEFORM_SERVER_SURFACE_EVALUATION_H_
#define FREEFORM_SERVER_SURFACE_EVALUATION_H_

#include <cstddef>
#include <cstdint>

#include "absl/status/status.h"
#include "freeform/core/thread_pool.h"
#include "freeform/v1/surface_service.pb.h"
#include "prepare_samples.h"
#include "rpc.h"
#include "service_limits.h"

namespace freeform::server {

// EvaluationMemory returns the plan of evaluating `points` points of the
// plan: the answer, and the partials the normals need besides.
CallPlan EvaluationMemory(const SurfacePlan& plan, uint64_t points,
                          const ServiceLimits& limits);

// EvaluateChunk evaluates points [first, last) of the plan into `response`.
absl::Status EvaluateChunk(const SurfacePlan& plan, size_t first, size_t last,
                           const ExecutionContext& execution,
                           v1::EvaluateSurfaceResponse& response);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_SURFACE_EVALUATION_H_
