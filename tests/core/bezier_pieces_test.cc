#include "freeform/core/bezier_pieces.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "query_shapes.h"
#include "test_util.h"

namespace freeform {
namespace {

using testing_util::RandomValues;

// CheckCurvePieces checks that every piece at s is the curve at the
// piece's parameter for s.
void CheckCurvePieces(const Curve& curve, size_t expected_pieces) {
  const absl::StatusOr<BezierDecomposition> pieces = CurveBezierPieces(curve);
  ASSERT_TRUE(pieces.ok());
  ASSERT_EQ(pieces->segments.size(), expected_pieces);
  ASSERT_EQ(pieces->breakpoints.size(), expected_pieces + 1);
  const int dim = DimensionOf(curve);
  const std::vector<double> s = {0.0, 0.3, 0.5, 0.9, 1.0};
  for (size_t k = 0; k < expected_pieces; ++k) {
    std::vector<double> t;
    const double a = pieces->breakpoints[k], b = pieces->breakpoints[k + 1];
    for (double x : s) t.push_back(x == 1.0 ? b : a + x * (b - a));
    std::vector<double> on_piece(s.size() * dim), on_curve(s.size() * dim);
    const absl::Span<double> out_piece[] = {absl::MakeSpan(on_piece)};
    const absl::Span<double> out_curve[] = {absl::MakeSpan(on_curve)};
    ASSERT_TRUE(
        EvaluateBezierCurve(pieces->segments[k].view(), s, out_piece).ok());
    ASSERT_TRUE(EvaluateCurve(curve, t, out_curve).ok());
    for (size_t i = 0; i < on_piece.size(); ++i) {
      EXPECT_NEAR(on_piece[i], on_curve[i], 1e-13);
    }
  }
}

TEST(BezierPiecesTest, CurvesOfEveryKind) {
  std::mt19937_64 rng(1);
  const std::vector<double> points = RandomValues(rng, 12);
  CheckCurvePieces(*BezierCurve::Create({{2, points}, {}}), 1);
  CheckCurvePieces(*BezierCurve::FromPowerForm({3, points}), 1);
  CheckCurvePieces(*LagrangeCurve::Create({{3, points}, {}}), 1);
  const std::vector<double> nodes = {0, 1, 3};
  CheckCurvePieces(
      *HermiteCurve::Create(
          {{2, {points.data(), 6}}, {2, {points.data() + 6, 6}}, nodes}),
      2);
  const BSplineCurveData circle = testing_util::Circle(2.0, 1.0, 0.0);
  CheckCurvePieces(*BSplineCurve::Create(circle.view()), 4);
}

void CheckSurfacePieces(const Surface& surface, size_t expected_pieces) {
  const absl::StatusOr<SurfacePieces> pieces = SurfaceBezierPieces(surface);
  ASSERT_TRUE(pieces.ok());
  ASSERT_EQ(pieces->patches.size(), expected_pieces);
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
    ASSERT_TRUE(EvaluateBezierSurface(pieces->patches[k].bezier_view(),
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

TEST(BezierPiecesTest, SurfacesOfEveryKind) {
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

}  // namespace
}  // namespace freeform
