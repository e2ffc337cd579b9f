#include "freeform/core/hermite.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "freeform/core/status.h"

namespace freeform {
namespace {

using ::testing::DoubleNear;
using ::testing::Pointwise;

std::vector<std::vector<double>> Evaluate(
    const HermiteCurveView& curve, const std::vector<double>& params,
    int orders, const ExecutionContext& context = {}) {
  std::vector<std::vector<double>> buffers(
      static_cast<size_t>(orders),
      std::vector<double>(params.size() * curve.points.dimension));
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  const absl::Status status =
      EvaluateHermiteCurve(curve, params, output, context);
  EXPECT_TRUE(status.ok()) << status;
  return buffers;
}

// f(t) = (1 - 2t + 3t^2 - t^3, 0.5 + t^3) and its derivatives.
std::vector<double> Cubic(double t, int order) {
  switch (order) {
    case 0:
      return {1 - 2 * t + 3 * t * t - t * t * t, 0.5 + t * t * t};
    case 1:
      return {-2 + 6 * t - 3 * t * t, 3 * t * t};
    case 2:
      return {6 - 6 * t, 6 * t};
    case 3:
      return {-6, 6};
    default:
      return {0, 0};
  }
}

// Sampled with exact derivatives at any nodes, the Hermite spline of a cubic
// is that cubic, with all its derivatives.
TEST(HermiteTest, ReproducesCubicsOnUnevenNodes) {
  const std::vector<double> nodes = {-1.0, -0.2, 0.5, 2.0, 2.25};
  std::vector<double> points, tangents;
  for (double t : nodes) {
    for (double v : Cubic(t, 0)) points.push_back(v);
    for (double v : Cubic(t, 1)) tangents.push_back(v);
  }
  const HermiteCurveView curve{
      .points = {2, points}, .tangents = {2, tangents}, .nodes = nodes};
  std::vector<double> params;
  for (int r = 0; r <= 200; ++r) params.push_back(-1.0 + 3.25 * r / 200.0);
  const auto result = Evaluate(curve, params, 5);
  for (size_t r = 0; r < params.size(); ++r) {
    for (int k = 0; k < 5; ++k) {
      const std::vector<double> expected = Cubic(params[r], k);
      EXPECT_NEAR(result[k][2 * r], expected[0], 1e-12) << k;
      EXPECT_NEAR(result[k][2 * r + 1], expected[1], 1e-12) << k;
    }
  }
}

TEST(HermiteTest, InterpolatesPointsAndTangentsAtNodes) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> uniform(-1, 1);
  std::vector<double> points(5 * 3), tangents(5 * 3);
  for (double& v : points) v = uniform(rng);
  for (double& v : tangents) v = uniform(rng);
  const HermiteCurveView curve{
      .points = {3, points}, .tangents = {3, tangents}, .nodes = {}};
  const std::vector<double> nodes = {0, 1, 2, 3, 4};
  const auto at_nodes = Evaluate(curve, nodes, 2);
  EXPECT_THAT(at_nodes[0], Pointwise(DoubleNear(1e-15), points));
  EXPECT_THAT(at_nodes[1], Pointwise(DoubleNear(1e-14), tangents));
  // Left-hand limits at the interior nodes give the same tangents (C1).
  const auto before = Evaluate(curve, {1 - 1e-9, 2 - 1e-9, 3 - 1e-9}, 2);
  for (int j = 0; j < 9; ++j) {
    EXPECT_NEAR(before[1][j], tangents[3 + j], 1e-7);
  }
}

TEST(HermiteTest, BasisMatchesTheClassicPolynomials) {
  std::vector<double> params;
  for (int r = 0; r <= 50; ++r) params.push_back(r / 50.0);
  std::vector<std::vector<double>> buffers(
      3, std::vector<double>(4 * params.size()));
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  ASSERT_TRUE(EvaluateHermiteBasis(params, output).ok());
  for (size_t r = 0; r < params.size(); ++r) {
    const double t = params[r];
    const double expected[3][4] = {
        {2 * t * t * t - 3 * t * t + 1, -2 * t * t * t + 3 * t * t,
         t * t * t - 2 * t * t + t, t * t * t - t * t},
        {6 * t * t - 6 * t, -6 * t * t + 6 * t, 3 * t * t - 4 * t + 1,
         3 * t * t - 2 * t},
        {12 * t - 6, -12 * t + 6, 6 * t - 4, 6 * t - 2}};
    for (int k = 0; k < 3; ++k) {
      for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(buffers[k][4 * r + i], expected[k][i], 1e-13)
            << "k=" << k << " i=" << i << " t=" << t;
      }
    }
    EXPECT_NEAR(buffers[0][4 * r] + buffers[0][4 * r + 1], 1.0, 1e-15);
  }
}

TEST(HermiteTest, PoolResultsEqualSerialResults) {
  const std::vector<double> points = {0, 0, 1, 2, 3, 1};
  const std::vector<double> tangents = {1, 0, 0, 1, -1, 0};
  const HermiteCurveView curve{
      .points = {2, points}, .tangents = {2, tangents}, .nodes = {}};
  std::vector<double> params(30'001);
  for (size_t r = 0; r < params.size(); ++r) {
    params[r] = 2.0 * static_cast<double>(r) / 30000.0;
  }
  ThreadPool pool(3);
  EXPECT_EQ(Evaluate(curve, params, 3),
            Evaluate(curve, params, 3, {.pool = &pool, .grain = 512}));
}

TEST(HermiteTest, InvalidInputNamesTheField) {
  const std::vector<double> two = {0, 0, 1, 1};
  const std::vector<double> one = {0, 0};
  const std::vector<double> three = {0, 0, 1, 1, 2, 2};
  const std::vector<double> bad = {0, NAN, 1, 1};
  const std::vector<double> nodes_bad = {0, 0};
  const std::vector<double> nodes_three = {0, 1, 2};
  struct Case {
    HermiteCurveView curve;
    std::vector<double> params;
    std::string field;
  };
  const std::vector<Case> cases = {
      {{{2, one}, {2, one}, {}}, {0}, "points.coordinates"},
      {{{2, two}, {2, three}, {}}, {0}, "tangents.coordinates"},
      {{{2, two}, {1, two}, {}}, {0}, "tangents.dimension"},
      {{{2, two}, {2, bad}, {}}, {0}, "tangents.coordinates[1]"},
      {{{2, two}, {2, two}, nodes_three}, {0}, "nodes"},
      {{{2, two}, {2, two}, nodes_bad}, {0}, "nodes[1]"},
      {{{2, two}, {2, two}, {}}, {1.5}, "parameters[0]"},
  };
  for (const Case& c : cases) {
    std::vector<double> out(c.params.size() * 2);
    std::vector<absl::Span<double>> output = {absl::MakeSpan(out)};
    const absl::Status status = EvaluateHermiteCurve(c.curve, c.params, output);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << c.field;
    EXPECT_EQ(FieldPathOf(status).value_or(""), c.field) << status;
  }
}

}  // namespace
}  // namespace freeform
