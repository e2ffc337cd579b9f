#include "freeform/core/surface.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <tuple>
#include <utility>

#include "absl/strings/str_cat.h"
#include "freeform/core/normals.h"
#include "freeform/core/patches.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "geometry/piece_values.h"
#include "geometry/scaled_evaluation.h"
#include "geometry/variant_dispatch.h"
#include "kinds/validated_tensor_surface.h"
#include "kinds/validated_triangular.h"

namespace freeform {
namespace {

// A 2 x 2 net of `dimension` (or, when `optional`, an empty one).
absl::Status ValidateCornerNet(const ControlNetView& net, int dimension,
                               absl::string_view field, bool optional) {
  if (optional && net.coordinates.empty()) return absl::OkStatus();
  if (net.dimension != dimension) {
    return InvalidFieldError(
        absl::StrCat(field, ".dimension"),
        absl::StrCat("must equal the positions' dimension ", dimension,
                     ", got ", net.dimension));
  }
  if (net.count_u != 2 || net.count_v != 2) {
    return InvalidFieldError(absl::StrCat(field, ".count_u"),
                             "a Hermite patch has 2 x 2 corners");
  }
  return ValidateControlNet(net, field);
}

}  // namespace

absl::StatusOr<BezierSurface> BezierSurface::Create(
    const BezierSurfaceView& view) {
  RETURN_IF_ERROR(ValidateBezierSurface(view));
  return BezierSurface(view, nullptr);
}

BezierSurface BezierSurface::OwnedBicubic(int dimension,
                                          std::vector<double> net) {
  auto owned = std::make_shared<const std::vector<double>>(std::move(net));
  const BezierSurfaceView view{.control_net = {.dimension = dimension,
                                               .count_u = 4,
                                               .count_v = 4,
                                               .coordinates = *owned},
                               .weights = {}};
  return BezierSurface(view, std::move(owned));
}

absl::StatusOr<BezierSurface> BezierSurface::FromInterpolatingPatch(
    const ControlNetView& points) {
  RETURN_IF_ERROR(ValidateControlNet(points, "points"));
  if (points.count_u != 4 || points.count_v != 4) {
    return InvalidFieldError(
        points.count_u != 4 ? "points.count_u" : "points.count_v",
        absl::StrCat("the interpolating patch takes 4 x 4 points, got ",
                     points.count_u, " x ", points.count_v));
  }
  return OwnedBicubic(
      points.dimension,
      InterpolatingToBezierNet(points.dimension, points.coordinates));
}

absl::StatusOr<BezierSurface> BezierSurface::FromHermitePatch(
    const ControlNetView& positions, const ControlNetView& derivatives_u,
    const ControlNetView& derivatives_v, const ControlNetView& twists) {
  const int dimension = positions.dimension;
  for (const auto& [net, field, optional] :
       {std::tuple{&positions, "positions", false},
        std::tuple{&derivatives_u, "derivatives_u", false},
        std::tuple{&derivatives_v, "derivatives_v", false},
        std::tuple{&twists, "twists", true}}) {
    RETURN_IF_ERROR(ValidateCornerNet(*net, dimension, field, optional));
  }
  return OwnedBicubic(
      dimension,
      HermiteToBezierNet(dimension, positions.coordinates,
                         derivatives_u.coordinates, derivatives_v.coordinates,
                         twists.coordinates));
}

absl::Status BezierSurface::Evaluate(const SurfaceSamples& samples,
                                     SurfaceOutput output,
                                     const ExecutionContext& context) const {
  return internal::EvaluateValidBezierSurface(view_, samples, output, context);
}

absl::StatusOr<BSplineSurface> BSplineSurface::Create(
    const BSplineSurfaceView& view) {
  RETURN_IF_ERROR(ValidateBSplineSurface(view));
  return BSplineSurface(view);
}

absl::Status BSplineSurface::Evaluate(const SurfaceSamples& samples,
                                      SurfaceOutput output,
                                      const ExecutionContext& context) const {
  return internal::EvaluateValidBSplineSurface(view_, samples, output, context);
}

absl::StatusOr<TriangularPatch> TriangularPatch::Create(
    const TriangularPatchView& view) {
  RETURN_IF_ERROR(ValidateTriangularPatch(view));
  return TriangularPatch(view);
}

absl::Status TriangularPatch::Evaluate(const SurfaceSamples& samples,
                                       SurfaceOutput output,
                                       const ExecutionContext& context) const {
  if (samples.grid) {
    return InvalidFieldError(
        "grid", "a triangular patch takes (u, v) points, not a grid");
  }
  return internal::EvaluateValidTriangularPatch(view_, samples.uv, output,
                                                context);
}

int DimensionOf(const Surface& surface) {
  return std::visit([](const auto& kind) { return kind.dimension(); }, surface);
}

SurfaceDomain DomainOf(const Surface& surface) {
  return internal::DomainOfKind(surface);
}

uint64_t SurfacePieceValues(const Surface& surface) {
  return std::visit(
      internal::Overloaded{
          [](const BezierSurface& bezier) {
            const BezierSurfaceView& view = bezier.view();
            const ControlNetView& net = view.control_net;
            return internal::PieceValues(1,
                                         static_cast<uint64_t>(net.count_u) *
                                             static_cast<uint64_t>(net.count_v),
                                         net.dimension, view.rational(), 4);
          },
          [](const BSplineSurface& bspline) {
            const BSplineSurfaceView& view = bspline.view();
            const ControlNetView& net = view.control_net;
            const uint64_t spans_u =
                static_cast<uint64_t>(net.count_u - view.degree_u);
            const uint64_t spans_v =
                static_cast<uint64_t>(net.count_v - view.degree_v);
            return internal::PieceValues(
                spans_u * spans_v,
                static_cast<uint64_t>(view.degree_u + 1) *
                    static_cast<uint64_t>(view.degree_v + 1),
                net.dimension, view.rational(), spans_u + spans_v + 2);
          },
          [](const TriangularPatch& triangular) {
            const TriangularPatchView& view = triangular.view();
            const uint64_t side = static_cast<uint64_t>(view.degree) + 1;
            return internal::PieceValues(1, side * side,
                                         view.control_points.dimension,
                                         view.rational(), 4);
          }},
      surface);
}

uint64_t SurfacePieceCount(const Surface& surface) {
  return std::visit(internal::Overloaded{
                        [](const BezierSurface&) -> uint64_t { return 1; },
                        [](const BSplineSurface& bspline) -> uint64_t {
                          const BSplineSurfaceView& view = bspline.view();
                          return static_cast<uint64_t>(
                                     view.control_net.count_u - view.degree_u) *
                                 static_cast<uint64_t>(
                                     view.control_net.count_v - view.degree_v);
                        },
                        [](const TriangularPatch&) -> uint64_t { return 1; }},
                    surface);
}

bool IsTriangular(const Surface& surface) {
  return std::holds_alternative<TriangularPatch>(surface);
}

absl::Status ValidateSamples(const Surface& surface,
                             const SurfaceSamples& samples) {
  const auto in_domain = [&samples](const auto& tensor) {
    const SurfaceDomain domain = tensor.domain();
    return ValidateSurfaceSamples(samples, domain.u_start, domain.u_end,
                                  domain.v_start, domain.v_end);
  };
  return std::visit(
      internal::Overloaded{
          [&](const BezierSurface& bezier) { return in_domain(bezier); },
          [&](const BSplineSurface& bspline) { return in_domain(bspline); },
          [&](const TriangularPatch& patch) {
            if (samples.grid) {
              return InvalidFieldError(
                  "grid", "a triangular patch takes (u, v) points, not a grid");
            }
            return internal::ValidateTriangularPairs(patch.view(), samples.uv);
          }},
      surface);
}

absl::Status EvaluateSurface(const Surface& surface,
                             const SurfaceSamples& samples,
                             SurfaceOutput partials, absl::Span<double> normals,
                             const ExecutionContext& context) {
  const bool scaled = internal::NeedsScaledEvaluation(surface);
  const auto evaluate = [&](SurfaceOutput output) {
    if (scaled) {
      return internal::EvaluateScaledSurface(surface, samples, output, context);
    }
    return internal::EvaluateKind(surface, samples, output, context);
  };
  if (normals.empty()) return evaluate(partials);
  if (DimensionOf(surface) != 3) {
    return InvalidFieldError(
        "normals", absl::StrCat("normals need a 3D surface, this one is ",
                                DimensionOf(surface), "D"));
  }
  const size_t count = samples.size();
  const size_t size = 3 * count;
  // The partials to order 2: the caller's buffers, then scratch.
  std::vector<absl::Span<double>> all(partials.begin(), partials.end());
  std::vector<std::vector<double>> scratch;
  scratch.reserve(PartialCount(2));
  while (all.size() < PartialCount(2)) {
    all.push_back(absl::MakeSpan(scratch.emplace_back(size)));
  }
  RETURN_IF_ERROR(evaluate(all));
  if (IsTriangular(surface)) return ComputeUnitNormals(all, count, normals);
  return ComputeUnitNormals(all, samples, DomainOf(surface), normals);
}

}  // namespace freeform
