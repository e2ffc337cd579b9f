// SurfaceService through a real in-process gRPC server and the client
// library: the worked examples of docs/references.md, grid against pairs,
// streams, normals, bases, and the field paths of errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "../core/test_util.h"
#include "in_process_server.h"

namespace freeform::server {
namespace {

using ::freeform::testing_util::RandomValues;

using ::testing::DoubleNear;
using ::testing::Pointwise;

void SetNet(v1::ControlNet* net, int dimension, int count_u, int count_v,
            const std::vector<double>& coordinates) {
  net->set_dimension(static_cast<uint32_t>(dimension));
  net->set_count_u(static_cast<uint32_t>(count_u));
  net->set_count_v(static_cast<uint32_t>(count_v));
  net->mutable_coordinates()->Add(coordinates.begin(), coordinates.end());
}

class SurfaceServiceTest : public InProcessServerTest {
 protected:
  absl::StatusOr<SurfaceEvaluation> AtPoints(const v1::Surface& surface,
                                             std::vector<double> uv,
                                             int order = 0,
                                             bool normals = false) {
    v1::EvaluateSurfaceRequest request;
    *request.mutable_surface() = surface;
    request.mutable_parameters()->mutable_points()->mutable_uv()->Add(
        uv.begin(), uv.end());
    request.set_derivative_order(static_cast<uint32_t>(order));
    request.set_normals(normals);
    return client_->EvaluateSurface(request);
  }
};

// The bi-quadratic patch at (1/2, 1/2) (docs/references.md,
// 'Worked example: the bi-quadratic patch at (1/2, 1/2)').
v1::Surface BiQuadratic() {
  v1::Surface surface;
  SetNet(surface.mutable_bezier()->mutable_control_net(), 3, 3, 3,
         {0, 0, 0, 2, 0, 0, 4, 0, 0,  //
          0, 2, 0, 2, 2, 0, 4, 2, 2,  //
          0, 4, 0, 2, 4, 4, 4, 4, 4});
  return surface;
}

TEST_F(SurfaceServiceTest, BiQuadraticWorkedExample) {
  absl::StatusOr<SurfaceEvaluation> at = AtPoints(BiQuadratic(), {0.5, 0.5});
  ASSERT_TRUE(at.ok()) << at.status();
  EXPECT_THAT(at->Point(0, 0, 0),
              Pointwise(DoubleNear(1e-15), std::vector<double>{2, 2, 1}));
}

// The quadratic triangular patch: S(1/3, 1/3, 1/3) = (2, 2, 3), not the
// (2, 2, 7/3) that two arithmetic slips give (docs/references.md,
// 'Worked example: the quadratic triangular patch at the centroid').
TEST_F(SurfaceServiceTest, TriangularWorkedExample) {
  v1::Surface surface;
  v1::TriangularBezierPatch* patch = surface.mutable_triangular_bezier();
  patch->set_degree(2);
  patch->mutable_control_points()->set_dimension(3);
  // P200, P110, P101, P020, P011, P002.
  Append(patch->mutable_control_points()->mutable_coordinates(),
         {6, 0, 9, 3, 3, 6, 3, 0, 0, 0, 6, 0, 0, 3, 3, 0, 0, 0});
  absl::StatusOr<SurfaceEvaluation> at =
      AtPoints(surface, {1.0 / 3, 1.0 / 3}, 1, true);
  ASSERT_TRUE(at.ok()) << at.status();
  EXPECT_THAT(at->Point(0, 0, 0),
              Pointwise(DoubleNear(1e-14), std::vector<double>{2, 2, 3}));
  ASSERT_EQ(at->normals.size(), 3u);
  EXPECT_NEAR(std::hypot(at->normals[0], at->normals[1], at->normals[2]), 1.0,
              1e-14);
  // A grid makes no sense on a triangle.
  v1::EvaluateSurfaceRequest request;
  *request.mutable_surface() = surface;
  request.mutable_parameters()
      ->mutable_grid()
      ->mutable_u()
      ->mutable_range()
      ->set_count(3);
  request.mutable_parameters()
      ->mutable_grid()
      ->mutable_v()
      ->mutable_range()
      ->set_count(3);
  ExpectInvalid(client_->EvaluateSurface(request).status(), "parameters.grid");
}

TEST_F(SurfaceServiceTest, InterpolatingPatchPassesThroughItsPoints) {
  std::mt19937_64 rng(3);
  const std::vector<double> points = RandomValues(rng, 16 * 3);
  v1::Surface surface;
  SetNet(surface.mutable_bicubic_interpolating()->mutable_points(), 3, 4, 4,
         points);
  std::vector<double> uv;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      uv.push_back(i / 3.0);
      uv.push_back(j / 3.0);
    }
  }
  absl::StatusOr<SurfaceEvaluation> at = AtPoints(surface, uv);
  ASSERT_TRUE(at.ok()) << at.status();
  EXPECT_THAT(at->partials[0].values, Pointwise(DoubleNear(1e-13), points));
}

v1::Surface RandomBSplineSurface(std::mt19937_64& rng) {
  v1::Surface surface;
  v1::BSplineSurface* bspline = surface.mutable_bspline();
  bspline->set_degree_u(3);
  bspline->set_degree_v(2);
  SetNet(bspline->mutable_control_net(), 3, 6, 5, RandomValues(rng, 6 * 5 * 3));
  Append(bspline->mutable_knots_u(), {0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1});
  Append(bspline->mutable_knots_v(), {0, 0, 0, 0.5, 0.5, 1, 1, 1});
  std::vector<double> weights = RandomValues(rng, 30);
  for (double& weight : weights) bspline->add_weights(1.5 + 0.5 * weight);
  return surface;
}

// The grid equals the same points asked as pairs, partials and normals too.
TEST_F(SurfaceServiceTest, GridEqualsPairsAndStreamEqualsUnary) {
  std::mt19937_64 rng(21);
  const v1::Surface surface = RandomBSplineSurface(rng);
  v1::EvaluateSurfaceRequest grid;
  *grid.mutable_surface() = surface;
  grid.mutable_parameters()
      ->mutable_grid()
      ->mutable_u()
      ->mutable_range()
      ->set_count(7);
  Append(grid.mutable_parameters()
             ->mutable_grid()
             ->mutable_v()
             ->mutable_list()
             ->mutable_values(),
         {0.0, 0.2, 0.5, 0.7, 1.0});
  grid.set_derivative_order(2);
  grid.set_normals(true);
  absl::StatusOr<SurfaceEvaluation> on_grid = client_->EvaluateSurface(grid);
  ASSERT_TRUE(on_grid.ok()) << on_grid.status();
  std::vector<double> uv;
  for (int i = 0; i < 7; ++i) {
    for (double v : {0.0, 0.2, 0.5, 0.7, 1.0}) {
      uv.push_back(i / 6.0);
      uv.push_back(v);
    }
  }
  absl::StatusOr<SurfaceEvaluation> at_pairs = AtPoints(surface, uv, 2, true);
  ASSERT_TRUE(at_pairs.ok()) << at_pairs.status();
  ASSERT_EQ(on_grid->partials.size(), 6u);
  for (size_t k = 0; k < 6; ++k) {
    EXPECT_THAT(on_grid->partials[k].values,
                Pointwise(DoubleNear(1e-11), at_pairs->partials[k].values))
        << k;
  }
  EXPECT_THAT(on_grid->normals,
              Pointwise(DoubleNear(1e-12), at_pairs->normals));

  grid.mutable_parameters()
      ->mutable_grid()
      ->mutable_u()
      ->mutable_range()
      ->set_count(301);
  grid.set_chunk_size(1000);
  absl::StatusOr<SurfaceEvaluation> unary = client_->EvaluateSurface(grid);
  absl::StatusOr<SurfaceEvaluation> streamed =
      client_->EvaluateSurfaceStreamed(grid);
  ASSERT_TRUE(unary.ok()) << unary.status();
  ASSERT_TRUE(streamed.ok()) << streamed.status();
  EXPECT_EQ(streamed->count, 301u * 5);
  for (size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(unary->partials[k].values, streamed->partials[k].values);
  }
  EXPECT_EQ(unary->normals, streamed->normals);
}

// Normals are unit vectors orthogonal to both first partials.
TEST_F(SurfaceServiceTest, NormalsAreUnitAndOrthogonal) {
  std::mt19937_64 rng(5);
  v1::EvaluateSurfaceRequest request;
  *request.mutable_surface() = RandomBSplineSurface(rng);
  request.mutable_parameters()
      ->mutable_grid()
      ->mutable_u()
      ->mutable_range()
      ->set_count(20);
  request.mutable_parameters()
      ->mutable_grid()
      ->mutable_v()
      ->mutable_range()
      ->set_count(20);
  request.set_derivative_order(1);
  request.set_normals(true);
  absl::StatusOr<SurfaceEvaluation> result = client_->EvaluateSurface(request);
  ASSERT_TRUE(result.ok()) << result.status();
  for (size_t r = 0; r < result->count; ++r) {
    const double* n = &result->normals[3 * r];
    const auto su = result->Point(1, 0, r);
    const auto sv = result->Point(0, 1, r);
    EXPECT_NEAR(std::hypot(n[0], n[1], n[2]), 1.0, 1e-14);
    EXPECT_NEAR(n[0] * su[0] + n[1] * su[1] + n[2] * su[2], 0.0,
                1e-13 * std::hypot(su[0], su[1], su[2]));
    EXPECT_NEAR(n[0] * sv[0] + n[1] * sv[1] + n[2] * sv[2], 0.0,
                1e-13 * std::hypot(sv[0], sv[1], sv[2]));
  }
}

TEST_F(SurfaceServiceTest, SurfaceBases) {
  v1::EvaluateSurfaceBasisRequest request;
  request.mutable_tensor()->mutable_u()->mutable_bernstein()->set_degree(2);
  request.mutable_tensor()->mutable_v()->mutable_bernstein()->set_degree(1);
  Append(request.mutable_parameters()->mutable_points()->mutable_uv(),
         {0.5, 0.25});
  grpc::ClientContext context;
  v1::EvaluateSurfaceBasisResponse response;
  ASSERT_TRUE(
      client_->surfaces().EvaluateBasis(&context, request, &response).ok());
  ASSERT_EQ(response.function_count(), 6u);
  const double bu[] = {0.25, 0.5, 0.25};
  const double bv[] = {0.75, 0.25};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 2; ++j) {
      EXPECT_NEAR(response.values(2 * i + j), bu[i] * bv[j], 1e-15);
    }
  }

  v1::EvaluateSurfaceBasisRequest triangular;
  triangular.set_triangular_degree(3);
  Append(triangular.mutable_parameters()->mutable_points()->mutable_uv(),
         {0.2, 0.3, 0.0, 1.0});
  grpc::ClientContext triangular_context;
  ASSERT_TRUE(client_->surfaces()
                  .EvaluateBasis(&triangular_context, triangular, &response)
                  .ok());
  ASSERT_EQ(response.function_count(), 10u);
  for (int r = 0; r < 2; ++r) {
    double sum = 0;
    for (int f = 0; f < 10; ++f) sum += response.values(10 * r + f);
    EXPECT_NEAR(sum, 1.0, 1e-15);
  }
}

TEST_F(SurfaceServiceTest, InvalidSurfacesNameTheField) {
  v1::Surface surface = BiQuadratic();
  surface.mutable_bezier()->mutable_control_net()->add_coordinates(1);
  ExpectInvalid(AtPoints(surface, {0.5, 0.5}).status(),
                "surface.bezier.control_net.coordinates");

  ExpectInvalid(AtPoints(BiQuadratic(), {0.5, 1.5}).status(),
                "parameters.points.uv[1]");

  v1::Surface two_d;
  SetNet(two_d.mutable_bezier()->mutable_control_net(), 2, 2, 2,
         {0, 0, 1, 0, 0, 1, 1, 1});
  ExpectInvalid(AtPoints(two_d, {0.5, 0.5}, 1, true).status(), "normals");

  v1::Surface interpolating;
  SetNet(interpolating.mutable_bicubic_interpolating()->mutable_points(), 1, 3,
         4, std::vector<double>(12, 0.0));
  ExpectInvalid(AtPoints(interpolating, {0.5, 0.5}).status(),
                "surface.bicubic_interpolating.points.count_u");

  std::mt19937_64 rng(1);
  v1::Surface bspline = RandomBSplineSurface(rng);
  bspline.mutable_bspline()->set_knots_u(5, 0.1);  // 0.1 after 0.3
  ExpectInvalid(AtPoints(bspline, {0.5, 0.5}).status(),
                "surface.bspline.knots_u[5]");

  v1::Surface triangle;
  v1::TriangularBezierPatch* patch = triangle.mutable_triangular_bezier();
  patch->set_degree(1);
  patch->mutable_control_points()->set_dimension(1);
  Append(patch->mutable_control_points()->mutable_coordinates(), {1, 2, 3});
  patch->mutable_domain_triangle()->set_dimension(2);
  Append(patch->mutable_domain_triangle()->mutable_coordinates(),
         {0, 0, 1, 1, 2, 2});  // collinear
  ExpectInvalid(AtPoints(triangle, {0.5, 0.5}).status(),
                "surface.triangular_bezier.domain_triangle");

  patch->mutable_domain_triangle()->set_coordinates(5, std::nan(""));
  ExpectInvalid(AtPoints(triangle, {0.5, 0.5}).status(),
                "surface.triangular_bezier.domain_triangle.coordinates[5]");

  ExpectInvalid(AtPoints(v1::Surface(), {0.5, 0.5}).status(), "surface");
}

// A basis request's errors name its fields: each basis of a tensor, its
// samples against the two bases' domains, and the points a triangular
// basis takes.
TEST_F(SurfaceServiceTest, BasisErrorsNameTheirFields) {
  auto call = [&](const v1::EvaluateSurfaceBasisRequest& request) {
    grpc::ClientContext context;
    v1::EvaluateSurfaceBasisResponse response;
    return FromGrpcStatus(
        client_->surfaces().EvaluateBasis(&context, request, &response));
  };
  v1::EvaluateSurfaceBasisRequest tensor;
  tensor.mutable_tensor()->mutable_u()->mutable_bernstein()->set_degree(2);
  Append(tensor.mutable_parameters()->mutable_points()->mutable_uv(),
         {0.5, 0.25});
  ExpectInvalid(call(tensor), "tensor.v");
  tensor.mutable_tensor()->mutable_v()->mutable_bernstein()->set_degree(1);
  EXPECT_TRUE(call(tensor).ok());
  tensor.mutable_parameters()->mutable_points()->set_uv(1, 1.5);
  ExpectInvalid(call(tensor), "parameters.points.uv[1]");
  v1::SurfaceGrid& grid = *tensor.mutable_parameters()->mutable_grid();
  grid.mutable_u()->mutable_range()->set_count(3);
  grid.mutable_v()->mutable_range()->set_count(0);
  ExpectInvalid(call(tensor), "parameters.grid.v.range.count");
  grid.mutable_v()->mutable_range()->set_count(2);
  EXPECT_TRUE(call(tensor).ok());

  v1::EvaluateSurfaceBasisRequest triangular;
  triangular.set_triangular_degree(2);
  *triangular.mutable_parameters()->mutable_grid() = grid;
  ExpectInvalid(call(triangular), "parameters.points");
  EXPECT_EQ(call(triangular).message(),
            "parameters.points: triangular Bernstein polynomials take (u, v) "
            "points");
  Append(triangular.mutable_parameters()->mutable_points()->mutable_uv(),
         {0.75, 0.5});
  ExpectInvalid(call(triangular), "parameters.points", true);
}

// (u, v) points come in pairs: an odd count is refused, never truncated,
// for every surface kind and for the triangular basis, which also needs at
// least one pair.
TEST_F(SurfaceServiceTest, PointsMustBePairs) {
  ExpectInvalid(AtPoints(BiQuadratic(), {0.5, 0.5, 0.25}).status(),
                "parameters.points.uv");
  v1::Surface triangle;
  v1::TriangularBezierPatch* patch = triangle.mutable_triangular_bezier();
  patch->set_degree(1);
  patch->mutable_control_points()->set_dimension(1);
  Append(patch->mutable_control_points()->mutable_coordinates(), {1, 2, 3});
  ExpectInvalid(AtPoints(triangle, {0.2, 0.3, 0.4}).status(),
                "parameters.points.uv");

  v1::EvaluateSurfaceBasisRequest basis;
  basis.set_triangular_degree(2);
  basis.mutable_parameters()->mutable_points();  // no pairs at all
  v1::EvaluateSurfaceBasisResponse response;
  grpc::ClientContext empty_context;
  ExpectInvalid(FromGrpcStatus(client_->surfaces().EvaluateBasis(
                    &empty_context, basis, &response)),
                "parameters.points.uv");
  Append(basis.mutable_parameters()->mutable_points()->mutable_uv(),
         {0.2, 0.3, 0.4});
  grpc::ClientContext odd_context;
  ExpectInvalid(FromGrpcStatus(client_->surfaces().EvaluateBasis(
                    &odd_context, basis, &response)),
                "parameters.points.uv");
}

}  // namespace
}  // namespace freeform::server
