// The reliability calls: one RpcCase per method of CurveService,
// SurfaceService and FaceService (proto/freeform/v1/*.proto), streams
// included. Each call draws a fresh request from the caller's random generator,
// sends it through freeform::Client and checks the answer against the
// mathematics (reference.h): worked values from docs/references.md, geometry
// that every representation must reproduce (a line, a plane), shape preserved
// at sample parameters by splitting, knot insertion and degree elevation,
// interpolants through their data, partition of unity, tolerances met.
#ifndef FREEFORM_TESTS_RELIABILITY_CASES_H_
#define FREEFORM_TESTS_RELIABILITY_CASES_H_

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "check.h"
#include "freeform/client.h"
#include "shapes.h"

namespace freeform::reliability {

struct RpcCase {
  // "Service.Method", e.g. "CurveService.EvaluateStream".
  std::string name;
  bool streaming = false;
  std::function<CallResult(Client& client, Rng& rng)> call;
};

// How many points the evaluation streams send (drawn per call).
struct StreamSize {
  uint32_t min_points = 1000;
  uint32_t max_points = 5000;
};

// CurveService, one case per method.
std::vector<RpcCase> CurveEvaluationCases(StreamSize stream = {});
std::vector<RpcCase> CurveRefinementCases();
std::vector<RpcCase> CurveConstructionCases();
// SurfaceService, one case per method.
std::vector<RpcCase> SurfaceEvaluationCases(StreamSize stream = {});
std::vector<RpcCase> SurfaceRefinementCases();
std::vector<RpcCase> SurfaceTessellationCases();
// The queries of both services, one case per method.
std::vector<RpcCase> QueryCases();
// Knot removal and fitting of both services, one case per method.
std::vector<RpcCase> ApproximationCases();
// FaceService, one case per method.
std::vector<RpcCase> FaceCases();

// Every method of every service (42 cases).
std::vector<RpcCase> AllCases(StreamSize stream = {});

// A random set of curve blending functions (Bernstein, B-spline, either
// possibly rational, Lagrange or Hermite) and its reference: shared by the
// curve and the tensor-product basis cases.
struct BasisCase {
  v1::Basis basis;
  double start = 0;
  double end = 1;
  // False for the Hermite functions, which do not sum to one.
  bool partition_of_unity = true;
  // Derivatives 0..orders of every function at t.
  std::function<BasisDerivatives(double t, int orders)> reference;
};
BasisCase RandomBasis(Rng& rng);

// The large answers of the memory test: Evaluate of a cubic B-spline in 3D
// at `points` parameters, checked at every `stride`-th point.
RpcCase LargeCurveEvaluation(uint32_t points, uint32_t stride);

}  // namespace freeform::reliability

#endif  // FREEFORM_TESTS_RELIABILITY_CASES_H_
