#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "freeform/core/surface.h"
#include "freeform/core/tensor_surface.h"
#include "test_util.h"

namespace freeform {
namespace {

using testing_util::RandomValues;

// CheckSurfacePieces checks that every piece at (s, t) is the surface at the
// piece's parameters for (s, t).
void CheckSurfacePieces(const Surface& surface, size_t expected_pieces) {
  const absl::StatusOr<SurfaceDecomposition> pieces = DecomposeSurface(surface);
  ASSERT_TRUE(pieces.ok());
  ASSERT_EQ(pieces->pieces.patches.size(), expected_pieces);
  const std::vector<double> st = {0.0, 0.0, 0.3, 0.7, 1.0,
                                  0.5, 0.6, 1.0, 1.0, 1.0};
  const int dim = DimensionOf(surface);
  for (size_t k = 0; k < expected_pieces; ++k) {
    std::vector<double> uv;
    for (size_t i = 0; i < st.size(); i += 2) {
      const std::array<double, 2> p =
          SurfacePieceParameters(*pieces, k, st[i], st[i + 1]);
      uv.insert(uv.end(), p.begin(), p.end());
    }
    std::vector<double> on_piece(st.size() / 2 * dim),
        on_surface(st.size() / 2 * dim);
    const absl::Span<double> out_piece[] = {absl::MakeSpan(on_piece)};
    const absl::Span<double> out_surface[] = {absl::MakeSpan(on_surface)};
    ASSERT_TRUE(EvaluateBezierSurface(pieces->pieces.patches[k].bezier_view(),
                                      SurfaceSamples::Pairs(st), out_piece)
                    .ok());
    ASSERT_TRUE(
        EvaluateSurface(surface, SurfaceSamples::Pairs(uv), out_surface, {})
            .ok());
    for (size_t i = 0; i < on_piece.size(); ++i) {
      EXPECT_NEAR(on_piece[i], on_surface[i], 1e-13);
    }
  }
}

TEST(DecomposeSurface, PiecesAreTheSurfaceOnTheirRectangles) {
  std::mt19937_64 rng(2);
  const std::vector<double> net = RandomValues(rng, 3 * 30);
  const std::vector<double> weights = RandomValues(rng, 30, 0.3, 3.0);
  CheckSurfacePieces(*BezierSurface::Create({{3, 5, 6, net}, weights}), 1);
  const std::vector<double> ku = {0, 0, 0, 0, 0.4, 1, 1, 1, 1};
  const std::vector<double> kv = {0, 0, 0, 1, 1, 2, 3, 3, 3};
  CheckSurfacePieces(
      *BSplineSurface::Create({3, 2, {3, 5, 6, net}, ku, kv, weights}), 2 * 3);
  const std::vector<double> unclamped = {-2, -1, 0, 1, 2, 3, 4, 5, 6};
  CheckSurfacePieces(*BSplineSurface::Create({3,
                                              3,
                                              {3, 5, 5, {net.data(), 75}},
                                              unclamped,
                                              {unclamped.data(), 9},
                                              {}}),
                     4);
  // Triangular patches: barycentric and on a domain triangle, rational.
  const std::vector<double> triangle = {0, 0, 2, 0, 0, 1};
  CheckSurfacePieces(
      *TriangularPatch::Create({3, {3, {net.data(), 30}}, {}, {}}), 1);
  CheckSurfacePieces(
      *TriangularPatch::Create(
          {2, {3, {net.data(), 18}}, {weights.data(), 6}, triangle}),
      1);
}

// A rational triangle whose weights span 1e20 (one weight 1e20 among
// weights near 1, and one direction of weight 0) keeps its shape in its
// degenerate tensor form: raising a row's degree combines its weights
// with nonnegative coefficients, so a weight 1e-20 of the largest is a
// real weight, not rounding to be snapped to 0 (the snap turned the
// light points into directions: a fuzz finding of issue 30 whose closest
// point was 0.0676 for 0.0665, and whose tensor form was 0.04 off).
TEST(DecomposeSurface, ExtremeTriangleWeightsKeepTheirTensorForm) {
  std::mt19937_64 rng(12);
  const int n = 6;
  const size_t count = static_cast<size_t>((n + 1) * (n + 2) / 2);
  const std::vector<double> net = RandomValues(rng, 2 * count);
  std::vector<double> weights = RandomValues(rng, count, 0.05, 2.0);
  weights[4] = 1e20;
  weights[count / 2] = 0.0;  // an interior direction
  const absl::StatusOr<TriangularPatch> patch =
      TriangularPatch::Create({n, {2, net}, weights, {}});
  ASSERT_TRUE(patch.ok()) << patch.status();
  const absl::StatusOr<SurfaceDecomposition> pieces =
      DecomposeSurface(Surface(*patch));
  ASSERT_TRUE(pieces.ok()) << pieces.status();
  std::vector<double> st, uv;
  for (int i = 0; i <= 10; ++i) {
    for (int j = 0; j <= 10; ++j) {
      const double s_value = i / 10.0, t_value = j / 10.0;
      st.insert(st.end(), {s_value, t_value});
      const std::array<double, 2> p =
          SurfacePieceParameters(*pieces, 0, s_value, t_value);
      uv.insert(uv.end(), p.begin(), p.end());
    }
  }
  std::vector<double> on_piece(st.size()), on_patch(st.size());
  const absl::Span<double> out_piece[] = {absl::MakeSpan(on_piece)};
  const absl::Span<double> out_patch[] = {absl::MakeSpan(on_patch)};
  ASSERT_TRUE(EvaluateBezierSurface(pieces->pieces.patches[0].bezier_view(),
                                    SurfaceSamples::Pairs(st), out_piece)
                  .ok());
  ASSERT_TRUE(
      EvaluateSurface(Surface(*patch), SurfaceSamples::Pairs(uv), out_patch, {})
          .ok());
  for (size_t i = 0; i < on_piece.size(); ++i) {
    // The points lie within the hull of net (coordinates in [-1, 1]).
    EXPECT_NEAR(on_piece[i], on_patch[i], 1e-12) << i;
  }
}

}  // namespace
}  // namespace freeform
