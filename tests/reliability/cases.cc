// AllCases: every method of every service.
#include "cases.h"

namespace freeform::reliability {

std::vector<RpcCase> AllCases(StreamSize stream) {
  std::vector<RpcCase> cases;
  for (std::vector<RpcCase> group :
       {CurveEvaluationCases(stream), CurveRefinementCases(),
        CurveConstructionCases(), SurfaceEvaluationCases(stream),
        SurfaceRefinementCases(), SurfaceTessellationCases(), QueryCases(),
        ApproximationCases(), FaceCases()}) {
    for (RpcCase& c : group) cases.push_back(std::move(c));
  }
  return cases;
}

}  // namespace freeform::reliability
