// libFuzzer target of the core's triangular indexing: a triangular Bezier
// patch (TriangularPatch::Create) from a fuzzed degree, control points (a
// count that may not be (n+1)(n+2)/2), weights and domain triangle. A
// refusal must name its field. An accepted patch is evaluated with partials
// up to order 2 (normals in 3D) at points of its triangle; with moderate
// values (core_fuzz_input.h) the answers must be finite, the patch must pass
// through P(n,0,0), P(0,n,0) and P(0,0,n) at its corners (where
// TriangularIndex stores them), and without weights it must be the
// triangular Bernstein basis, which sums to 1, times its points.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core_fuzz_input.h"
#include "freeform/core/surface.h"
#include "freeform/core/triangular.h"

namespace freeform::fuzz {
namespace {

// The three corners (u, v) = (1, 0), (0, 1), (0, 0).
constexpr double kCorners[] = {1, 0, 0, 1, 0, 0};

// Checks the patch's corners against the points TriangularIndex names.
void CheckCorners(const Surface& patch, int degree,
                  absl::Span<const double> points, int dimension) {
  const size_t d = static_cast<size_t>(dimension);
  OutputBuffers corners(1, 3 * d);
  const absl::Status status =
      EvaluateSurface(patch, SurfaceSamples::Pairs(kCorners), corners.spans,
                      /*normals=*/{});
  Check(status.ok(), status.ToString());
  const size_t indices[] = {TriangularIndex(degree, degree, 0),
                            TriangularIndex(degree, 0, degree),
                            TriangularIndex(degree, 0, 0)};
  double scale = 0;
  for (const double x : points) scale = std::max(scale, std::abs(x));
  for (size_t c = 0; c < 3; ++c) {
    for (size_t j = 0; j < d; ++j) {
      CheckNear(corners.storage[0][c * d + j], points[indices[c] * d + j],
                scale, absl::StrCat("corner ", c, ", coordinate ", j));
    }
  }
}

void Run(const uint8_t* data, size_t size) {
  CoreFuzzInput input(data, size);
  const int degree = input.Int(-1, 12);
  const int dimension = input.Int(0, 4);
  const int count =
      input.Count(static_cast<int>(TriangularPointCount(degree)), 100);
  const std::vector<double> points =
      input.Values(input.Count(count * dimension, count * dimension + 3));
  const std::vector<double> weights = input.Weights(count);
  std::vector<double> triangle;
  if (input.Bool()) triangle = input.Values(input.Count(6, 8));
  const absl::StatusOr<TriangularPatch> made = TriangularPatch::Create(
      {.degree = degree,
       .control_points = {.dimension = dimension, .coordinates = points},
       .weights = weights,
       .domain_triangle = triangle});
  if (!made.ok()) return CheckRefusal(made.status(), "a triangular patch");
  const Surface patch = *made;

  // Points of the triangle: barycentric (u, v), or on a domain triangle
  // A, B, C the point u A + v B + w C.
  std::vector<double> uv;
  for (int i = input.Int(1, 6); i > 0; --i) {
    const double u = input.Probability();
    const double v = input.Probability() * (1 - u);
    if (triangle.empty()) {
      uv.insert(uv.end(), {u, v});
    } else {
      const double w = 1 - u - v;
      uv.insert(uv.end(),
                {u * triangle[0] + v * triangle[2] + w * triangle[4],
                 u * triangle[1] + v * triangle[3] + w * triangle[5]});
    }
  }
  const size_t n = uv.size() / 2;
  const size_t d = static_cast<size_t>(dimension);
  const int order = input.Int(0, 2);
  OutputBuffers partials(PartialCount(order), n * d);
  std::vector<double> normals;
  if (dimension == 3 && order >= 1 && input.Bool()) normals.resize(3 * n);
  const absl::Status status =
      EvaluateSurface(patch, SurfaceSamples::Pairs(uv), partials.spans,
                      absl::MakeSpan(normals));
  if (!triangle.empty() && !status.ok()) {
    // Rounding may put a point of a thin triangle just outside it.
    return CheckRefusal(status, "a point of the domain triangle");
  }
  Check(status.ok(), status.ToString());
  if (input.wild()) return;

  for (const std::vector<double>& partial : partials.storage) {
    CheckFinite(partial, "a partial");
  }
  CheckFinite(normals, "the normals");
  if (!triangle.empty()) return;
  CheckCorners(patch, degree, points, dimension);
  const size_t functions = TriangularPointCount(degree);
  std::vector<double> basis(n * functions);
  const absl::Status basis_status =
      EvaluateTriangularBasis(degree, uv, absl::MakeSpan(basis));
  Check(basis_status.ok(), basis_status.ToString());
  CheckFinite(basis, "the triangular basis");
  CheckSumsTo(basis, n, functions, 1.0, "the sum of the triangular basis");
  if (weights.empty()) {
    CheckBasisTimesPoints(partials.storage[0], basis, points, dimension, n,
                          functions, "the patch");
  }
}

}  // namespace
}  // namespace freeform::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  freeform::fuzz::Run(data, size);
  return 0;
}
