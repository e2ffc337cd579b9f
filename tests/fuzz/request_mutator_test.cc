// Tests of the structure-aware mutator (request_mutator.h): a mutation is a
// function of the input and the seed, never larger than the size it is
// given, mostly at the structure level, and the geometry mutations keep
// the sizes the proto rules tie together consistent (points * dimension
// coordinates, count + degree + 1 knots, one weight per point, ...), so
// that they reach the work behind the validation: degree-0 splines among
// them.
#include "request_mutator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "freeform/v1/curve_service.pb.h"
#include "freeform/v1/surface_service.pb.h"
#include "geometry_arrays.h"
#include "geometry_mutations.h"
#include "parse_text.h"
#include "prepare.h"

namespace freeform::fuzz {
namespace {

// A stand-in for libFuzzer's byte mutator: flips the first byte and
// counts its calls.
size_t byte_mutations = 0;

size_t FlipFirstByte(uint8_t* data, size_t size, size_t max_size) {
  ++byte_mutations;
  if (size == 0) return 0;
  data[0] ^= 0x5a;
  return std::min(size, max_size);
}

// The CurveService.RemoveKnots seed inserted_knot (a knot inserted into a
// cubic Bezier curve).
v1::RemoveCurveKnotsRequest InsertedKnot() {
  return ParseText<v1::RemoveCurveKnotsRequest>(R"pb(
    curve {
      bspline {
        degree: 3
        control_points {
          dimension: 2
          coordinates: [ 0, 0, 0.5, 1, 2, 2, 3.5, 1, 4, 0 ]
        }
        knots: [ 0, 0, 0, 0, 0.5, 1, 1, 1, 1 ]
      }
    }
    tolerance: 1e-9
    knot: 0.5)pb");
}

// Mutated runs MutateRequest on `request`'s bytes in a buffer of
// max(max_size, size) bytes.
std::string Mutated(const google::protobuf::Message& request, uint64_t seed,
                    size_t max_size) {
  std::string bytes = request.SerializeAsString();
  const size_t size = bytes.size();
  bytes.resize(std::max(max_size, size));
  const size_t new_size =
      MutateRequest(request, reinterpret_cast<uint8_t*>(bytes.data()), size,
                    std::max(max_size, size), seed, &FlipFirstByte);
  bytes.resize(new_size);
  return bytes;
}

TEST(RequestMutatorTest, IsAFunctionOfTheInputAndTheSeed) {
  const v1::RemoveCurveKnotsRequest request = InsertedKnot();
  for (uint64_t seed = 0; seed < 500; ++seed) {
    EXPECT_EQ(Mutated(request, seed, 4096), Mutated(request, seed, 4096))
        << "seed " << seed;
  }
}

TEST(RequestMutatorTest, NeverExceedsTheMaximumSize) {
  const v1::RemoveCurveKnotsRequest request = InsertedKnot();
  const size_t size = request.ByteSizeLong();
  for (size_t max_size : {size, size + 8, size + 64, size_t{4096}}) {
    for (uint64_t seed = 0; seed < 1000; ++seed) {
      EXPECT_LE(Mutated(request, seed, max_size).size(), max_size)
          << "seed " << seed;
    }
  }
}

TEST(RequestMutatorTest, MutatesBytesThatDoNotParseAsBytes) {
  const std::string garbage = "\xff\xff\xff\xff";
  for (uint64_t seed = 0; seed < 100; ++seed) {
    std::string bytes = garbage;
    byte_mutations = 0;
    const size_t size =
        MutateRequest(v1::RemoveCurveKnotsRequest::default_instance(),
                      reinterpret_cast<uint8_t*>(bytes.data()), bytes.size(),
                      bytes.size(), seed, &FlipFirstByte);
    EXPECT_EQ(byte_mutations, 1u);
    EXPECT_EQ(size, garbage.size());
  }
}

TEST(RequestMutatorTest, MostMutationsAreRequestsOfAnotherStructure) {
  const v1::RemoveCurveKnotsRequest request = InsertedKnot();
  const std::string original = request.SerializeAsString();
  byte_mutations = 0;
  int parsed = 0, changed = 0;
  constexpr int kSeeds = 2000;
  for (uint64_t seed = 0; seed < kSeeds; ++seed) {
    const std::string bytes = Mutated(request, seed, 4096);
    v1::RemoveCurveKnotsRequest mutant;
    parsed += mutant.ParseFromString(bytes) ? 1 : 0;
    changed += bytes != original ? 1 : 0;
  }
  // One call in kByteMutationOneIn (20%) is a byte mutation, plus the few
  // whose four structure mutants were too large or unchanged.
  EXPECT_LE(byte_mutations, kSeeds * 3 / 10);
  EXPECT_GE(byte_mutations, kSeeds / 10);
  EXPECT_GE(parsed, kSeeds * 7 / 10);
  EXPECT_EQ(changed, kSeeds);
}

TEST(RequestMutatorTest, ReachesValidDegreeZeroSplines) {
  // Issue 30's crash needs a B-spline of degree 0 with count + 1 knots:
  // byte mutations of the seeds almost never make one.
  const v1::RemoveCurveKnotsRequest request = InsertedKnot();
  const server::ServiceLimits limits;
  int valid_degree_zero = 0;
  for (uint64_t seed = 0; seed < 500; ++seed) {
    v1::RemoveCurveKnotsRequest mutant;
    if (!mutant.ParseFromString(Mutated(request, seed, 4096)) ||
        !mutant.curve().has_bspline() ||
        mutant.curve().bspline().degree() != 0) {
      continue;
    }
    valid_degree_zero +=
        server::PrepareCurve(mutant.curve(), limits).ok() ? 1 : 0;
  }
  EXPECT_GE(valid_degree_zero, 5);
}

// ------------------------------------------------ consistent geometry --

int PointCount(const v1::Points& points) {
  return points.dimension() == 0
             ? -1
             : (points.coordinates_size() %
                            static_cast<int>(points.dimension()) ==
                        0
                    ? points.coordinates_size() /
                          static_cast<int>(points.dimension())
                    : -1);
}

int NetCount(const v1::ControlNet& net) {
  const uint64_t points = uint64_t{net.count_u()} * net.count_v();
  return static_cast<uint64_t>(net.coordinates_size()) ==
                 points * net.dimension()
             ? static_cast<int>(points)
             : -1;
}

bool WeightsFit(int weights, int count) {
  return weights == 0 || weights == count;
}

bool NonDecreasing(const google::protobuf::RepeatedField<double>& knots) {
  return std::is_sorted(knots.begin(), knots.end());
}

// SizesAgree returns what breaks the size rules of geometry.proto in
// `curve`, or "" when none does.
std::string SizesAgree(const v1::Curve& curve) {
  switch (curve.kind_case()) {
    case v1::Curve::kBezier: {
      const int count = PointCount(curve.bezier().control_points());
      if (count < 1) return "bezier points";
      return WeightsFit(curve.bezier().weights_size(), count)
                 ? ""
                 : "bezier weights";
    }
    case v1::Curve::kBspline: {
      const v1::BSplineCurve& b = curve.bspline();
      const int count = PointCount(b.control_points());
      if (count < static_cast<int>(b.degree()) + 1) return "bspline points";
      if (b.knots_size() != count + static_cast<int>(b.degree()) + 1) {
        return "bspline knots";
      }
      if (!NonDecreasing(b.knots())) return "bspline knots order";
      return WeightsFit(b.weights_size(), count) ? "" : "bspline weights";
    }
    case v1::Curve::kLagrange: {
      const int count = PointCount(curve.lagrange().points());
      if (count < 1) return "lagrange points";
      return WeightsFit(curve.lagrange().nodes_size(), count)
                 ? ""
                 : "lagrange nodes";
    }
    case v1::Curve::kHermite: {
      const v1::HermiteCurve& h = curve.hermite();
      const int count = PointCount(h.points());
      if (count < 2 || PointCount(h.tangents()) != count ||
          h.tangents().dimension() != h.points().dimension()) {
        return "hermite points and tangents";
      }
      return WeightsFit(h.nodes_size(), count) ? "" : "hermite nodes";
    }
    case v1::Curve::kPower:
      return PointCount(curve.power().coefficients()) >= 1 ? ""
                                                           : "power points";
    case v1::Curve::KIND_NOT_SET:
      break;
  }
  return "no kind";
}

std::string SizesAgree(const v1::Surface& surface) {
  switch (surface.kind_case()) {
    case v1::Surface::kBezier: {
      const int count = NetCount(surface.bezier().control_net());
      if (count < 1) return "bezier net";
      return WeightsFit(surface.bezier().weights_size(), count)
                 ? ""
                 : "bezier weights";
    }
    case v1::Surface::kBspline: {
      const v1::BSplineSurface& b = surface.bspline();
      const int count = NetCount(b.control_net());
      const v1::ControlNet& net = b.control_net();
      if (count < 1 || net.count_u() < b.degree_u() + 1 ||
          net.count_v() < b.degree_v() + 1) {
        return "bspline net";
      }
      if (b.knots_u_size() !=
              static_cast<int>(net.count_u() + b.degree_u() + 1) ||
          b.knots_v_size() !=
              static_cast<int>(net.count_v() + b.degree_v() + 1)) {
        return "bspline knots";
      }
      if (!NonDecreasing(b.knots_u()) || !NonDecreasing(b.knots_v())) {
        return "bspline knots order";
      }
      return WeightsFit(b.weights_size(), count) ? "" : "bspline weights";
    }
    case v1::Surface::kBicubicInterpolating: {
      const v1::ControlNet& net = surface.bicubic_interpolating().points();
      return net.count_u() == 4 && net.count_v() == 4 && NetCount(net) == 16
                 ? ""
                 : "interpolating net";
    }
    case v1::Surface::kBicubicHermite: {
      const v1::BicubicHermitePatch& h = surface.bicubic_hermite();
      for (const v1::ControlNet* net :
           {&h.positions(), &h.derivatives_u(), &h.derivatives_v()}) {
        if (NetCount(*net) != 4 || net->count_u() != 2 ||
            net->dimension() != h.positions().dimension()) {
          return "hermite nets";
        }
      }
      return "";
    }
    case v1::Surface::kTriangularBezier: {
      const v1::TriangularBezierPatch& t = surface.triangular_bezier();
      const int n = static_cast<int>(t.degree());
      const int count = PointCount(t.control_points());
      if (count != (n + 1) * (n + 2) / 2) return "triangular points";
      return WeightsFit(t.weights_size(), count) ? "" : "triangular weights";
    }
    case v1::Surface::KIND_NOT_SET:
      break;
  }
  return "no kind";
}

const char* const kCurves[] = {
    R"pb(bspline {
           degree: 3
           control_points {
             dimension: 2
             coordinates: [ 0, 0, 1, 2, 2, 0, 3, 2, 4, 0 ]
           }
           knots: [ 0, 0, 0, 0, 1, 2, 2, 2, 2 ]
         })pb",
    R"pb(bspline {
           degree: 2
           control_points {
             dimension: 2
             coordinates: [ 1, 0, 1, 1, 0, 1, -1, 1, -1, 0 ]
           }
           knots: [ 0, 0, 0, 0.5, 0.5, 1, 1, 1 ]
           weights: [ 1, 0.7071067811865476, 1, 0.7071067811865476, 1 ]
         })pb",
    R"pb(bezier {
           control_points {
             dimension: 2
             coordinates: [ 1, 0, 0, 1, -1, 0 ]
           }
           weights: [ 1, 0, 1 ]
         })pb",
    R"pb(lagrange {
           points {
             dimension: 2
             coordinates: [ 0, 0, 1, 1, 2, 0, 3, 1 ]
           }
           nodes: [ 0, 0.25, 0.75, 1 ]
         })pb",
    R"pb(hermite {
           points {
             dimension: 2
             coordinates: [ 0, 0, 1, 1, 2, 0 ]
           }
           tangents {
             dimension: 2
             coordinates: [ 1, 0, 1, 1, 0, -1 ]
           }
           nodes: [ 0, 1, 3 ]
         })pb",
    R"pb(power {
           coefficients {
             dimension: 2
             coordinates: [ 1, 0, 0, 2, 1, -1 ]
           }
         })pb"};

const char* const kSurfaces[] = {
    R"pb(bspline {
           degree_u: 1
           degree_v: 2
           control_net {
             dimension: 3
             count_u: 2
             count_v: 4
             coordinates: [
               0, 0, 0, 0, 1, 1, 0, 2, 1, 0, 3, 0,
               1, 0, 0, 1, 1, 1, 1, 2, 1, 1, 3, 0
             ]
           }
           knots_u: [ 0, 0, 1, 1 ]
           knots_v: [ 0, 0, 0, 0.5, 1, 1, 1 ]
           weights: [ 1, 2, 2, 1, 1, 2, 2, 1 ]
         })pb",
    R"pb(bezier {
           control_net {
             dimension: 3
             count_u: 2
             count_v: 2
             coordinates: [ 0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 1 ]
           }
         })pb",
    R"pb(triangular_bezier {
           degree: 1
           control_points {
             dimension: 3
             coordinates: [ 1, 0, 0, 0, 1, 0, 0, 0, 1 ]
           }
         })pb",
    R"pb(bicubic_hermite {
           positions {
             dimension: 3
             count_u: 2
             count_v: 2
             coordinates: [ 0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0 ]
           }
           derivatives_u {
             dimension: 3
             count_u: 2
             count_v: 2
             coordinates: [ 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0 ]
           }
           derivatives_v {
             dimension: 3
             count_u: 2
             count_v: 2
             coordinates: [ 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0 ]
           }
         })pb"};

TEST(GeometryMutationsTest, KeepTheSizesOfEveryCurveKindConsistent) {
  const MutationLimits limits;
  for (const char* text : kCurves) {
    v1::ArcLengthRequest request;
    *request.mutable_curve() = ParseText<v1::Curve>(text);
    ASSERT_EQ(SizesAgree(request.curve()), "") << text;
    for (uint64_t seed = 0; seed < 2000; ++seed) {
      v1::ArcLengthRequest mutant = request;
      FuzzRandom random(seed);
      MutateGeometry(mutant, limits, random);
      EXPECT_EQ(SizesAgree(mutant.curve()), "")
          << "seed " << seed << ": " << mutant.ShortDebugString();
      if (mutant.curve().has_bspline()) {
        EXPECT_LE(mutant.curve().bspline().degree(),
                  static_cast<uint32_t>(limits.max_degree));
      }
    }
  }
}

TEST(GeometryMutationsTest, KeepTheSizesOfEverySurfaceKindConsistent) {
  const MutationLimits limits;
  for (const char* text : kSurfaces) {
    v1::SurfaceBoundingBoxRequest request;
    *request.mutable_surface() = ParseText<v1::Surface>(text);
    ASSERT_EQ(SizesAgree(request.surface()), "") << text;
    for (uint64_t seed = 0; seed < 2000; ++seed) {
      v1::SurfaceBoundingBoxRequest mutant = request;
      FuzzRandom random(seed);
      MutateGeometry(mutant, limits, random);
      EXPECT_EQ(SizesAgree(mutant.surface()), "")
          << "seed " << seed << ": " << mutant.ShortDebugString();
    }
  }
}

TEST(GeometryMutationsTest, KeepTwoCurvesOfOneDimension) {
  v1::IntersectCurvesRequest request;
  *request.mutable_first() = ParseText<v1::Curve>(kCurves[0]);
  *request.mutable_second() = ParseText<v1::Curve>(kCurves[2]);
  int dimension_changes = 0;
  for (uint64_t seed = 0; seed < 2000; ++seed) {
    v1::IntersectCurvesRequest mutant = request;
    FuzzRandom random(seed);
    MutateGeometry(mutant, MutationLimits{}, random);
    const uint32_t first =
        mutant.first().bspline().control_points().dimension();
    const uint32_t second =
        mutant.second().bezier().control_points().dimension();
    if (!mutant.first().has_bspline() || !mutant.second().has_bezier() ||
        (first == 2 && second == 2)) {
      continue;
    }
    ++dimension_changes;
    EXPECT_EQ(first, second) << "seed " << seed;
  }
  EXPECT_GT(dimension_changes, 0);
}

TEST(GeometryArraysTest, KnotsFitTheirCountAndDegree) {
  for (uint64_t seed = 0; seed < 200; ++seed) {
    FuzzRandom random(seed);
    for (int degree = 0; degree <= 18; ++degree) {
      const size_t count = static_cast<size_t>(degree) + 1 + random.Below(20);
      const std::vector<double> old = {0, 0, 0.3, 0.7, 1, 1};
      const std::vector<double> knots = MakeKnots(count, degree, old, random);
      EXPECT_EQ(knots.size(), count + static_cast<size_t>(degree) + 1);
      EXPECT_TRUE(std::is_sorted(knots.begin(), knots.end()));
    }
  }
}

TEST(CrossOverTest, MakesOneRequestOfTwo) {
  const std::string first = InsertedKnot().SerializeAsString();
  v1::RemoveCurveKnotsRequest other;
  *other.mutable_curve() = ParseText<v1::Curve>(kCurves[2]);
  other.set_times(3);
  const std::string second = other.SerializeAsString();
  std::string out(4096, '\0');
  int mixed = 0;
  for (uint64_t seed = 0; seed < 200; ++seed) {
    const size_t size = CrossOverRequests(
        v1::RemoveCurveKnotsRequest::default_instance(),
        reinterpret_cast<const uint8_t*>(first.data()), first.size(),
        reinterpret_cast<const uint8_t*>(second.data()), second.size(),
        reinterpret_cast<uint8_t*>(out.data()), out.size(), seed);
    v1::RemoveCurveKnotsRequest child;
    ASSERT_TRUE(child.ParseFromArray(out.data(), static_cast<int>(size)));
    mixed += out.substr(0, size) != first && out.substr(0, size) != second;
  }
  EXPECT_GT(mixed, 0);
  EXPECT_EQ(CrossOverRequests(
                v1::RemoveCurveKnotsRequest::default_instance(),
                reinterpret_cast<const uint8_t*>("\xff\xff"), 2,
                reinterpret_cast<const uint8_t*>(second.data()), second.size(),
                reinterpret_cast<uint8_t*>(out.data()), out.size(), 1),
            0u);
}

}  // namespace
}  // namespace freeform::fuzz
