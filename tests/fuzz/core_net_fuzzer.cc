// libFuzzer target of the core's tensor-product control nets: a Bezier or
// B-spline/NURBS surface (BezierSurface::Create, BSplineSurface::Create), a
// bicubic interpolating patch or a bicubic Hermite patch (FromInterpolating-
// Patch, FromHermitePatch) from fuzzed net sizes, coordinates, degrees,
// knot vectors and weights. A refusal must name its field. Accepted
// surfaces are evaluated (partials up to order 2, normals in 3D) on a grid
// or at pairs of their domain; with moderate values (core_fuzz_input.h) the
// answers must be finite, the tensor-product basis must sum to 1 and give
// the polynomial surfaces from their nets, and the patches must interpolate
// their nets (at i/3, j/3) and their corner positions.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core_fuzz_input.h"
#include "freeform/core/basis.h"
#include "freeform/core/surface.h"

namespace freeform::fuzz {
namespace {

// A fuzzed control net: count_u x count_v points, or a wrong number of
// coordinates.
struct Net {
  Net(CoreFuzzInput& input, int net_dimension, int u, int v)
      : dimension(net_dimension),
        count_u(u),
        count_v(v),
        coordinates(input.Values(
            input.Count(u * v * net_dimension, u * v * net_dimension + 3))) {}

  ControlNetView view() const {
    return {.dimension = dimension,
            .count_u = count_u,
            .count_v = count_v,
            .coordinates = coordinates};
  }

  int dimension;
  int count_u;
  int count_v;
  std::vector<double> coordinates;
};

// What a fuzzed surface was made from.
struct Made {
  absl::StatusOr<Surface> surface = absl::UnknownError("not made");
  // The net whose points the surface takes at `nodes` x `nodes` (the
  // interpolating and Hermite patches).
  const Net* interpolated = nullptr;
  std::vector<double> nodes;
  // The curve bases whose tensor product is the surface's basis (Bezier
  // and B-spline surfaces), and whether the surface is that basis times
  // its net (no weights).
  std::optional<CurveBasis> basis_u;
  std::optional<CurveBasis> basis_v;
  const Net* net = nullptr;
  bool polynomial = false;
};

template <typename Kind>
absl::StatusOr<Surface> AsSurface(absl::StatusOr<Kind> kind) {
  if (!kind.ok()) return kind.status();
  return Surface(*std::move(kind));
}

template <typename Basis>
std::optional<CurveBasis> AsBasis(absl::StatusOr<Basis> basis) {
  Check(basis.ok(), absl::StrCat("a surface is accepted, its basis is not: ",
                                 basis.status().ToString()));
  return CurveBasis(*std::move(basis));
}

// Checks the values of a grid of nodes x nodes against the net's points.
void CheckInterpolates(const Surface& surface, const Net& net,
                       absl::Span<const double> nodes) {
  const SurfaceSamples samples = SurfaceSamples::Grid(nodes, nodes);
  OutputBuffers values(1, net.coordinates.size());
  const absl::Status status = EvaluateSurface(surface, samples, values.spans,
                                              /*normals=*/{});
  Check(status.ok(), status.ToString());
  double scale = 0;
  for (const double x : net.coordinates) scale = std::max(scale, std::abs(x));
  for (size_t k = 0; k < net.coordinates.size(); ++k) {
    CheckNear(values.storage[0][k], net.coordinates[k], scale,
              absl::StrCat("the patch at its node of coordinate ", k));
  }
}

void Run(const uint8_t* data, size_t size) {
  CoreFuzzInput input(data, size);
  const int dimension = input.Int(0, 4);
  // Every net lives until the end of the run: surfaces view them.
  std::vector<std::unique_ptr<Net>> nets;
  auto net = [&](int count_u, int count_v) -> const Net& {
    nets.push_back(std::make_unique<Net>(input, dimension, count_u, count_v));
    return *nets.back();
  };
  std::vector<double> weights;
  std::vector<double> knots_u;
  std::vector<double> knots_v;
  Made made;
  switch (input.Int(0, 3)) {
    case 0: {
      const Net& points = net(input.Int(0, 7), input.Int(0, 7));
      weights = input.Weights(points.count_u * points.count_v);
      made.surface = AsSurface(BezierSurface::Create(
          {.control_net = points.view(), .weights = weights}));
      if (made.surface.ok()) {
        made.basis_u = AsBasis(BernsteinFunctions::Create(points.count_u - 1,
                                                          /*weights=*/{}));
        made.basis_v = AsBasis(BernsteinFunctions::Create(points.count_v - 1,
                                                          /*weights=*/{}));
      }
      made.net = &points;
      break;
    }
    case 1: {
      const int degree_u = input.Int(-1, 5);
      const int degree_v = input.Int(-1, 5);
      const Net& points = net(input.Int(0, 7), input.Int(0, 7));
      knots_u = input.Knots(input.Count(points.count_u + degree_u + 1, 16));
      knots_v = input.Knots(input.Count(points.count_v + degree_v + 1, 16));
      weights = input.Weights(points.count_u * points.count_v);
      made.surface =
          AsSurface(BSplineSurface::Create({.degree_u = degree_u,
                                            .degree_v = degree_v,
                                            .control_net = points.view(),
                                            .knots_u = knots_u,
                                            .knots_v = knots_v,
                                            .weights = weights}));
      if (made.surface.ok()) {
        made.basis_u = AsBasis(BSplineFunctions::Create(degree_u, knots_u,
                                                        /*weights=*/{}));
        made.basis_v = AsBasis(BSplineFunctions::Create(degree_v, knots_v,
                                                        /*weights=*/{}));
      }
      made.net = &points;
      break;
    }
    case 2: {
      const Net& points = net(input.Count(4, 6), input.Count(4, 6));
      made.surface =
          AsSurface(BezierSurface::FromInterpolatingPatch(points.view()));
      made.interpolated = &points;
      made.nodes = {0.0, 1.0 / 3, 2.0 / 3, 1.0};
      break;
    }
    case 3: {
      const Net& positions = net(input.Count(2, 3), input.Count(2, 3));
      const Net& derivatives_u = net(input.Count(2, 3), input.Count(2, 3));
      const Net& derivatives_v = net(input.Count(2, 3), input.Count(2, 3));
      const Net& twists =
          input.Bool() ? net(0, 0) : net(input.Count(2, 3), input.Count(2, 3));
      ControlNetView twists_view = twists.view();
      if (twists.coordinates.empty()) twists_view = {};
      made.surface = AsSurface(BezierSurface::FromHermitePatch(
          positions.view(), derivatives_u.view(), derivatives_v.view(),
          twists_view));
      made.interpolated = &positions;
      made.nodes = {0.0, 1.0};
      break;
    }
  }
  made.polynomial = weights.empty();
  if (!made.surface.ok()) return CheckRefusal(made.surface.status(), "a net");
  const Surface& surface = *made.surface;

  const SurfaceDomain domain = DomainOf(surface);
  const bool grid = input.Bool();
  std::vector<double> us;
  std::vector<double> vs;
  std::vector<double> uv;
  for (int i = input.Int(1, grid ? 4 : 6); i > 0; --i) {
    const double u = input.Parameter(domain.u_start, domain.u_end);
    const double v = input.Parameter(domain.v_start, domain.v_end);
    if (grid) {
      us.push_back(u);
      if (input.Bool()) vs.push_back(v);
    } else {
      uv.insert(uv.end(), {u, v});
    }
  }
  if (grid && vs.empty()) vs.push_back(domain.v_end);
  const SurfaceSamples samples =
      grid ? SurfaceSamples::Grid(us, vs) : SurfaceSamples::Pairs(uv);
  const int order = input.Int(0, 2);
  const size_t d = static_cast<size_t>(dimension);
  OutputBuffers partials(PartialCount(order), samples.size() * d);
  std::vector<double> normals;
  if (dimension == 3 && order >= 1 && input.Bool()) {
    normals.resize(3 * samples.size());
  }
  const absl::Status status = EvaluateSurface(surface, samples, partials.spans,
                                              absl::MakeSpan(normals));
  Check(status.ok(), status.ToString());
  if (input.wild()) return;

  for (const std::vector<double>& partial : partials.storage) {
    CheckFinite(partial, "a partial");
  }
  CheckFinite(normals, "the normals");
  if (made.interpolated != nullptr) {
    CheckInterpolates(surface, *made.interpolated, made.nodes);
  }
  if (made.basis_u.has_value()) {
    const size_t functions =
        static_cast<size_t>(FunctionCountOf(*made.basis_u)) *
        static_cast<size_t>(FunctionCountOf(*made.basis_v));
    std::vector<double> basis(samples.size() * functions);
    const absl::Status basis_status = EvaluateTensorBasis(
        *made.basis_u, *made.basis_v, samples, absl::MakeSpan(basis));
    Check(basis_status.ok(), basis_status.ToString());
    CheckFinite(basis, "the tensor basis");
    CheckSumsTo(basis, samples.size(), functions, 1.0,
                "the sum of the tensor basis");
    if (made.polynomial) {
      CheckBasisTimesPoints(partials.storage[0], basis, made.net->coordinates,
                            dimension, samples.size(), functions,
                            "the surface");
    }
  }
}

}  // namespace
}  // namespace freeform::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  freeform::fuzz::Run(data, size);
  return 0;
}
