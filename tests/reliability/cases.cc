// AllCases: every method of both services.
#include "cases.h"

namespace freeform::reliability {

std::vector<RpcCase> AllCases(StreamSize stream) {
  std::vector<RpcCase> cases;
  for (std::vector<RpcCase> group :
       {CurveEvaluationCases(stream), CurveRefinementCases(),
        CurveConstructionCases(), SurfaceEvaluationCases(stream),
        SurfaceRefinementCases(), SurfaceTessellationCases(), QueryCases(),
        ApproximationCases()}) {
    for (RpcCase& c : group) cases.push_back(std::move(c));
  }
  return cases;
}

}  // namespace freeform::reliability
