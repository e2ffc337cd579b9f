#include "geometry_mutations.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <numbers>
#include <vector>

#include "freeform/v1/curve_service.pb.h"
#include "freeform/v1/geometry.pb.h"
#include "geometry_arrays.h"
#include "google/protobuf/descriptor.h"
#include "google/protobuf/reflection.h"

namespace freeform::fuzz {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using google::protobuf::Reflection;

// The largest dimension a repaired or repacked point set gets (the fuzz
// server accepts 8).
constexpr int kMaxDimension = 9;

// A point sequence read from a message, repaired so that its sizes agree:
// a dimension in [1, kMaxDimension] and a whole number of points.
struct PointArray {
  int dimension = 1;
  std::vector<double> values;

  size_t count() const {
    return values.size() / static_cast<size_t>(dimension);
  }
};

PointArray Read(const v1::Points& points) {
  PointArray array;
  array.dimension = static_cast<int>(std::clamp<uint32_t>(
      points.dimension(), 1, static_cast<uint32_t>(kMaxDimension)));
  array.values.assign(points.coordinates().begin(), points.coordinates().end());
  array.values.resize(array.count() * static_cast<size_t>(array.dimension));
  return array;
}

void Write(const PointArray& array, v1::Points& points) {
  points.set_dimension(static_cast<uint32_t>(array.dimension));
  Assign(*points.mutable_coordinates(), array.values);
}

// A net read from a message, repaired like PointArray, with count_u *
// count_v points (count_v kept when it divides the points).
struct NetArray {
  int dimension = 1;
  size_t count_u = 0;
  size_t count_v = 0;
  std::vector<double> values;
};

NetArray Read(const v1::ControlNet& net) {
  const PointArray points = [&] {
    v1::Points as_points;
    as_points.set_dimension(net.dimension());
    *as_points.mutable_coordinates() = net.coordinates();
    return Read(as_points);
  }();
  NetArray array{.dimension = points.dimension, .values = points.values};
  const size_t count = points.count();
  array.count_v =
      std::clamp<size_t>(net.count_v(), 1, std::max<size_t>(count, 1));
  array.count_u = count / array.count_v;
  if (array.count_u == 0) array.count_v = 0;
  array.values.resize(array.count_u * array.count_v *
                      static_cast<size_t>(array.dimension));
  return array;
}

void Write(const NetArray& array, v1::ControlNet& net) {
  net.set_dimension(static_cast<uint32_t>(array.dimension));
  net.set_count_u(static_cast<uint32_t>(array.count_u));
  net.set_count_v(static_cast<uint32_t>(array.count_v));
  Assign(*net.mutable_coordinates(), array.values);
}

size_t MaxPoints(const MutationLimits& limits, int dimension) {
  return std::max<size_t>(1, static_cast<size_t>(limits.max_repeated) /
                                 static_cast<size_t>(dimension));
}

// The most points a curve may grow to in one mutation.
size_t GrowthCap(size_t count, const MutationLimits& limits, int dimension) {
  return std::min(count + static_cast<size_t>(limits.max_growth),
                  MaxPoints(limits, dimension));
}

int CurrentDegree(uint32_t degree, const MutationLimits& limits) {
  return static_cast<int>(
      std::min<uint32_t>(degree, static_cast<uint32_t>(limits.max_degree)));
}

// NewDegree returns another degree: often 0 (piecewise constant) or 1,
// the neighbours of `degree`, or any up to the limit.
int NewDegree(int degree, const MutationLimits& limits, FuzzRandom& random) {
  switch (random.Below(7)) {
    case 0:
    case 1:
      return 0;
    case 2:
      return 1;
    case 3:
      return std::max(degree - 1, 0);
    case 4:
      return std::min(degree + 1, limits.max_degree);
    case 5:
      return static_cast<int>(random.Between(2, 4));
    default:
      return static_cast<int>(random.Between(0, limits.max_degree));
  }
}

// Resize resamples `points` (and `weights` when it has one per point, by
// the same positions) to `new_count` points.
void Resize(PointArray& points, DoubleField* weights, size_t new_count,
            FuzzRandom& random) {
  const size_t count = points.count();
  if (count == 0 || new_count == count) return;
  const std::vector<double> positions =
      SamplePositions(count, new_count, random);
  points.values = Resample(points.values, points.dimension, positions);
  if (weights != nullptr && static_cast<size_t>(weights->size()) == count) {
    Assign(*weights, Resample(SpanOf(*weights), 1, positions));
  }
}

// ResizeNet resamples a net (and its weights, one per point) to
// new_u x new_v points.
void ResizeNet(NetArray& net, DoubleField* weights, size_t new_u, size_t new_v,
               FuzzRandom& random) {
  if (net.count_u == 0) return;
  const std::vector<double> positions_u =
      SamplePositions(net.count_u, new_u, random);
  const std::vector<double> positions_v =
      SamplePositions(net.count_v, new_v, random);
  if (weights != nullptr &&
      static_cast<size_t>(weights->size()) == net.count_u * net.count_v) {
    Assign(*weights, ResampleNet(SpanOf(*weights), 1, net.count_u, net.count_v,
                                 positions_u, positions_v));
  }
  net.values = ResampleNet(net.values, net.dimension, net.count_u, net.count_v,
                           positions_u, positions_v);
  net.count_u = new_u;
  net.count_v = new_v;
}

// MutateValues changes the numbers of a geometry with its sizes kept: by a
// coin its weights (of `count` points; none when `weights` is null) or the
// coordinates of its points.
bool MutateValues(DoubleField* weights, size_t count, DoubleField& coordinates,
                  int dimension, FuzzRandom& random) {
  if (weights != nullptr && random.OneIn(2)) {
    MutateWeights(*weights, count, random);
  } else {
    MutatePointValues(coordinates, dimension, random);
  }
  return true;
}

// Nodes returns `count` nodes: strictly increasing (uniform, Chebyshev,
// clustered within 1e-9, random) or, now and then, with a repeat.
std::vector<double> Nodes(size_t count, FuzzRandom& random) {
  std::vector<double> nodes(count);
  const double last = static_cast<double>(std::max<size_t>(count, 2) - 1);
  const size_t style = random.Below(5);
  for (size_t i = 0; i < count; ++i) {
    const double x = static_cast<double>(i) / last;
    switch (style) {
      case 0:
        nodes[i] = x;
        break;
      case 1:
        nodes[i] = 0.5 - 0.5 * std::cos(std::numbers::pi * x);
        break;
      case 2:
        nodes[i] = 0.5 + 1e-9 * x;
        break;
      case 3:
        nodes[i] = static_cast<double>(i) + random.Unit();
        break;
      default:
        nodes[i] = std::floor(2.0 * x * last) / 2.0;  // repeats
    }
  }
  return nodes;
}

// SetNodes gives a Lagrange or Hermite curve of `count` points new nodes
// (Nodes), or now and then none (the default nodes).
void SetNodes(DoubleField& nodes, size_t count, FuzzRandom& random) {
  if (random.OneIn(4)) {
    nodes.Clear();
  } else {
    Assign(nodes, Nodes(count, random));
  }
}

// --------------------------------------------------------------- curves --

bool MutateBSplineCurve(v1::BSplineCurve& curve, const MutationLimits& limits,
                        FuzzRandom& random) {
  PointArray points = Read(curve.control_points());
  if (points.count() == 0) return false;
  int degree = CurrentDegree(curve.degree(), limits);
  size_t count = points.count();
  switch (random.Below(6)) {
    case 0:
    case 1: {  // another degree, its knots, more points when it needs them
      degree = NewDegree(degree, limits, random);
      const size_t needed = static_cast<size_t>(degree) + 1;
      if (count < needed) count = needed + random.Below(3);
      break;
    }
    case 2:  // other counts, their knots
      count = NewCount(count, static_cast<size_t>(degree) + 1,
                       GrowthCap(count, limits, points.dimension), random);
      break;
    case 3:  // other knots
      if (count < static_cast<size_t>(degree) + 1) return false;
      break;
    default:
      return MutateValues(
          curve.mutable_weights(), count,
          *curve.mutable_control_points()->mutable_coordinates(),
          points.dimension, random);
  }
  Resize(points, curve.mutable_weights(), count, random);
  Write(points, *curve.mutable_control_points());
  curve.set_degree(static_cast<uint32_t>(degree));
  Assign(*curve.mutable_knots(),
         MakeKnots(count, degree, SpanOf(curve.knots()), random));
  return true;
}

bool MutateBezierCurve(v1::BezierCurve& curve, const MutationLimits& limits,
                       FuzzRandom& random) {
  PointArray points = Read(curve.control_points());
  if (points.count() == 0) return false;
  switch (random.Below(3)) {
    case 0:
      Resize(points, curve.mutable_weights(),
             NewCount(points.count(), 1,
                      static_cast<size_t>(limits.max_degree) + 1, random),
             random);
      Write(points, *curve.mutable_control_points());
      return true;
    default:
      return MutateValues(
          curve.mutable_weights(), points.count(),
          *curve.mutable_control_points()->mutable_coordinates(),
          points.dimension, random);
  }
}

bool MutateLagrangeCurve(v1::LagrangeCurve& curve, const MutationLimits& limits,
                         FuzzRandom& random) {
  PointArray points = Read(curve.points());
  if (points.count() == 0) return false;
  switch (random.Below(3)) {
    case 0:
      Resize(points, nullptr,
             NewCount(points.count(), 1,
                      static_cast<size_t>(limits.max_degree) + 1, random),
             random);
      Write(points, *curve.mutable_points());
      [[fallthrough]];
    case 1:
      SetNodes(*curve.mutable_nodes(), points.count(), random);
      return true;
    default:
      return MutateValues(nullptr, 0,
                          *curve.mutable_points()->mutable_coordinates(),
                          points.dimension, random);
  }
}

bool MutateHermiteCurve(v1::HermiteCurve& curve, const MutationLimits& limits,
                        FuzzRandom& random) {
  PointArray points = Read(curve.points());
  PointArray tangents = Read(curve.tangents());
  if (points.count() == 0) return false;
  if (tangents.dimension != points.dimension ||
      tangents.count() != points.count()) {
    tangents = PointArray{points.dimension,
                          std::vector<double>(points.values.size(), 0.0)};
  }
  switch (random.Below(4)) {
    case 0: {  // points and tangents together, then their nodes
      const size_t count =
          NewCount(points.count(), 2,
                   GrowthCap(points.count(), limits, points.dimension), random);
      const std::vector<double> positions =
          SamplePositions(points.count(), count, random);
      points.values = Resample(points.values, points.dimension, positions);
      tangents.values =
          Resample(tangents.values, tangents.dimension, positions);
      Write(points, *curve.mutable_points());
      Write(tangents, *curve.mutable_tangents());
      SetNodes(*curve.mutable_nodes(), count, random);
      return true;
    }
    case 1:  // tangents zero, or scaled far
      if (random.OneIn(2)) {
        std::fill(tangents.values.begin(), tangents.values.end(), 0.0);
      } else {
        const double scale = ExtremePowerOfTen(random);
        for (double& t : tangents.values) t *= scale;
      }
      Write(tangents, *curve.mutable_tangents());
      return true;
    case 2:
      SetNodes(*curve.mutable_nodes(), points.count(), random);
      return true;
    default:
      return MutateValues(nullptr, 0,
                          *curve.mutable_points()->mutable_coordinates(),
                          points.dimension, random);
  }
}

bool MutatePowerCurve(v1::PowerCurve& curve, const MutationLimits& limits,
                      FuzzRandom& random) {
  PointArray coefficients = Read(curve.coefficients());
  if (coefficients.count() == 0) return false;
  if (random.OneIn(2)) {
    Resize(coefficients, nullptr,
           NewCount(coefficients.count(), 1,
                    static_cast<size_t>(limits.max_degree) + 1, random),
           random);
    Write(coefficients, *curve.mutable_coefficients());
  } else {
    MutatePointValues(*curve.mutable_coefficients()->mutable_coordinates(),
                      coefficients.dimension, random);
  }
  return true;
}

// The control points (and weights) of any curve kind, for a conversion.
// KindCount returns the number of cases of a geometry message's oneof
// `kind`, numbered 1..count: a new kind is drawn too, and the switches below
// (no default) fail to compile until they handle it.
int KindCount(const google::protobuf::Descriptor& message) {
  return message.FindOneofByName("kind")->field_count();
}

struct CurvePoints {
  PointArray points;
  std::vector<double> weights;
};

CurvePoints PointsOf(const v1::Curve& curve) {
  switch (curve.kind_case()) {
    case v1::Curve::kBezier:
      return {
          Read(curve.bezier().control_points()),
          {curve.bezier().weights().begin(), curve.bezier().weights().end()}};
    case v1::Curve::kBspline:
      return {
          Read(curve.bspline().control_points()),
          {curve.bspline().weights().begin(), curve.bspline().weights().end()}};
    case v1::Curve::kLagrange:
      return {Read(curve.lagrange().points()), {}};
    case v1::Curve::kHermite:
      return {Read(curve.hermite().points()), {}};
    case v1::Curve::kPower:
      return {Read(curve.power().coefficients()), {}};
    case v1::Curve::KIND_NOT_SET:
      break;
  }
  return {};
}

// ConvertCurve makes the curve another kind from the same points: a
// Bezier curve (at most max_degree + 1 points), a B-spline with clamped
// knots, a Lagrange curve, a Hermite curve with tangents from the
// neighbours, a power-form curve.
bool ConvertCurve(v1::Curve& curve, const MutationLimits& limits,
                  FuzzRandom& random) {
  CurvePoints from = PointsOf(curve);
  if (from.points.count() == 0) return false;
  const size_t max_polynomial = static_cast<size_t>(limits.max_degree) + 1;
  const auto polynomial_points = [&] {
    if (from.points.count() > max_polynomial) {
      DoubleField weights;
      Assign(weights, from.weights);
      Resize(from.points, &weights, max_polynomial, random);
      from.weights.assign(weights.begin(), weights.end());
    }
  };
  const bool weighted = from.weights.size() == from.points.count();
  const int kinds = KindCount(*v1::Curve::descriptor());
  int kind = static_cast<int>(random.Below(static_cast<size_t>(kinds))) + 1;
  if (kind == curve.kind_case()) kind = kind % kinds + 1;
  switch (static_cast<v1::Curve::KindCase>(kind)) {
    case v1::Curve::kBezier: {
      polynomial_points();
      v1::BezierCurve& bezier = *curve.mutable_bezier();
      Write(from.points, *bezier.mutable_control_points());
      if (weighted) Assign(*bezier.mutable_weights(), from.weights);
      return true;
    }
    case v1::Curve::kBspline: {
      const size_t count = from.points.count();
      const int degree = static_cast<int>(std::min<size_t>(
          count - 1, static_cast<size_t>(random.Between(0, 3))));
      v1::BSplineCurve& bspline = *curve.mutable_bspline();
      Write(from.points, *bspline.mutable_control_points());
      bspline.set_degree(static_cast<uint32_t>(degree));
      Assign(*bspline.mutable_knots(), MakeKnots(count, degree, {}, random));
      if (weighted) Assign(*bspline.mutable_weights(), from.weights);
      return true;
    }
    case v1::Curve::kLagrange:
      polynomial_points();
      Write(from.points, *curve.mutable_lagrange()->mutable_points());
      return true;
    case v1::Curve::kHermite: {
      if (from.points.count() < 2)
        from.points.values.resize(
            2 * static_cast<size_t>(from.points.dimension), 0.0);
      const size_t dim = static_cast<size_t>(from.points.dimension);
      const size_t count = from.points.count();
      PointArray tangents{from.points.dimension,
                          std::vector<double>(from.points.values.size())};
      for (size_t i = 0; i < count; ++i) {
        const size_t a = i == 0 ? 0 : i - 1, b = std::min(i + 1, count - 1);
        for (size_t j = 0; j < dim; ++j) {
          tangents.values[i * dim + j] =
              from.points.values[b * dim + j] - from.points.values[a * dim + j];
        }
      }
      v1::HermiteCurve& hermite = *curve.mutable_hermite();
      Write(from.points, *hermite.mutable_points());
      Write(tangents, *hermite.mutable_tangents());
      return true;
    }
    case v1::Curve::kPower:
      polynomial_points();
      Write(from.points, *curve.mutable_power()->mutable_coefficients());
      return true;
    case v1::Curve::KIND_NOT_SET:
      break;
  }
  return false;
}

// ------------------------------------------------------------- surfaces --

// A direction of a net: u (rows) or v (columns).
size_t& CountIn(NetArray& net, bool u) { return u ? net.count_u : net.count_v; }

void ResizeNetIn(NetArray& net, DoubleField* weights, bool u, size_t count,
                 FuzzRandom& random) {
  ResizeNet(net, weights, u ? count : net.count_u, u ? net.count_v : count,
            random);
}

bool MutateBSplineSurface(v1::BSplineSurface& surface,
                          const MutationLimits& limits, FuzzRandom& random) {
  NetArray net = Read(surface.control_net());
  if (net.count_u == 0) return false;
  const bool u = random.OneIn(2);
  int degree =
      CurrentDegree(u ? surface.degree_u() : surface.degree_v(), limits);
  size_t count = CountIn(net, u);
  // Nets stay within MaxPoints in all.
  const size_t other = u ? net.count_v : net.count_u;
  const size_t cap = std::max<size_t>(
      1, std::min(count + 16, MaxPoints(limits, net.dimension) / other));
  switch (random.Below(6)) {
    case 0:
    case 1:
      degree = NewDegree(degree, limits, random);
      if (count < static_cast<size_t>(degree) + 1) {
        count = static_cast<size_t>(degree) + 1 + random.Below(2);
      }
      break;
    case 2:
      count = NewCount(count, static_cast<size_t>(degree) + 1, cap, random);
      break;
    case 3:
      if (count < static_cast<size_t>(degree) + 1) return false;
      break;
    default:
      return MutateValues(surface.mutable_weights(), net.count_u * net.count_v,
                          *surface.mutable_control_net()->mutable_coordinates(),
                          net.dimension, random);
  }
  ResizeNetIn(net, surface.mutable_weights(), u, count, random);
  Write(net, *surface.mutable_control_net());
  DoubleField& knots =
      u ? *surface.mutable_knots_u() : *surface.mutable_knots_v();
  Assign(knots, MakeKnots(count, degree, SpanOf(knots), random));
  if (u) {
    surface.set_degree_u(static_cast<uint32_t>(degree));
  } else {
    surface.set_degree_v(static_cast<uint32_t>(degree));
  }
  return true;
}

bool MutateBezierSurface(v1::BezierSurface& surface,
                         const MutationLimits& limits, FuzzRandom& random) {
  NetArray net = Read(surface.control_net());
  if (net.count_u == 0) return false;
  switch (random.Below(3)) {
    case 0: {
      const bool u = random.OneIn(2);
      const size_t count =
          NewCount(CountIn(net, u), 1,
                   static_cast<size_t>(limits.max_degree) + 1, random);
      ResizeNetIn(net, surface.mutable_weights(), u, count, random);
      Write(net, *surface.mutable_control_net());
      return true;
    }
    default:
      return MutateValues(surface.mutable_weights(), net.count_u * net.count_v,
                          *surface.mutable_control_net()->mutable_coordinates(),
                          net.dimension, random);
  }
}

// Fixed-size nets (bicubic patches): the values change, or the net is
// repaired to its size.
bool MutateFixedNet(v1::ControlNet& message, size_t count_u, size_t count_v,
                    FuzzRandom& random) {
  NetArray net = Read(message);
  if (net.count_u == 0) return false;
  if (net.count_u != count_u || net.count_v != count_v || random.OneIn(4)) {
    ResizeNet(net, nullptr, count_u, count_v, random);
    Write(net, message);
  }
  MutatePointValues(*message.mutable_coordinates(), net.dimension, random);
  return true;
}

bool MutateHermitePatch(v1::BicubicHermitePatch& patch, FuzzRandom& random) {
  // The net at index 0..3 (created only when it is the one changed).
  const auto net = [&patch](size_t k) -> v1::ControlNet& {
    switch (k) {
      case 0:
        return *patch.mutable_positions();
      case 1:
        return *patch.mutable_derivatives_u();
      case 2:
        return *patch.mutable_derivatives_v();
      default:
        return *patch.mutable_twists();
    }
  };
  switch (random.Below(3)) {
    case 0:  // twists omitted (zero)
      patch.clear_twists();
      return true;
    case 1: {  // derivatives (and twists) zero, of the positions' shape
      const NetArray positions = Read(patch.positions());
      if (positions.count_u == 0) return false;
      NetArray zero = positions;
      std::fill(zero.values.begin(), zero.values.end(), 0.0);
      for (size_t k = 1 + random.Below(3); k < 4; ++k) Write(zero, net(k));
      return true;
    }
    default: {
      const size_t k = random.Below(patch.has_twists() ? 4 : 3);
      return MutateFixedNet(net(k), 2, 2, random);
    }
  }
}

size_t TriangleCount(size_t degree) { return (degree + 1) * (degree + 2) / 2; }

bool MutateTriangularPatch(v1::TriangularBezierPatch& patch,
                           const MutationLimits& limits, FuzzRandom& random) {
  PointArray points = Read(patch.control_points());
  if (points.count() == 0) return false;
  switch (random.Below(4)) {
    case 0: {  // another degree, its points and weights
      const int degree = std::min(
          NewDegree(CurrentDegree(patch.degree(), limits), limits, random), 12);
      Resize(points, patch.mutable_weights(),
             TriangleCount(static_cast<size_t>(degree)), random);
      Write(points, *patch.mutable_control_points());
      patch.set_degree(static_cast<uint32_t>(degree));
      return true;
    }
    case 1: {  // the domain triangle: none, the unit one, degenerate, far
      v1::Points& triangle = *patch.mutable_domain_triangle();
      triangle.set_dimension(2);
      std::vector<double> corners = {0, 0, 1, 0, 0, 1};
      switch (random.Below(4)) {
        case 0:
          patch.clear_domain_triangle();
          return true;
        case 1:
          corners = {0, 0, 1, 1, 2, 2};  // collinear
          break;
        case 2: {
          const double scale = ExtremePowerOfTen(random);
          for (double& c : corners) c *= scale;
          break;
        }
        default:
          for (double& c : corners) c = 4.0 * random.Unit() - 2.0;
      }
      Assign(*triangle.mutable_coordinates(), corners);
      return true;
    }
    default:
      return MutateValues(
          patch.mutable_weights(), points.count(),
          *patch.mutable_control_points()->mutable_coordinates(),
          points.dimension, random);
  }
}

// The net (and weights) of any surface kind, for a conversion; a
// triangular patch's points become a one-row net.
struct SurfaceNet {
  NetArray net;
  std::vector<double> weights;
};

SurfaceNet NetOf(const v1::Surface& surface) {
  switch (surface.kind_case()) {
    case v1::Surface::kBezier:
      return {Read(surface.bezier().control_net()),
              {surface.bezier().weights().begin(),
               surface.bezier().weights().end()}};
    case v1::Surface::kBspline:
      return {Read(surface.bspline().control_net()),
              {surface.bspline().weights().begin(),
               surface.bspline().weights().end()}};
    case v1::Surface::kBicubicInterpolating:
      return {Read(surface.bicubic_interpolating().points()), {}};
    case v1::Surface::kBicubicHermite:
      return {Read(surface.bicubic_hermite().positions()), {}};
    case v1::Surface::kTriangularBezier: {
      const PointArray points =
          Read(surface.triangular_bezier().control_points());
      return {{.dimension = points.dimension,
               .count_u = points.count() == 0 ? size_t{0} : size_t{1},
               .count_v = points.count(),
               .values = points.values},
              {surface.triangular_bezier().weights().begin(),
               surface.triangular_bezier().weights().end()}};
    }
    case v1::Surface::KIND_NOT_SET:
      break;
  }
  return {};
}

// ConvertSurface makes the surface another kind from the same net: a
// Bezier surface, a B-spline with clamped knots, a bicubic interpolating
// (4 x 4) or Hermite (2 x 2, derivatives from the net's differences)
// patch, a triangular patch of the net's points.
bool ConvertSurface(v1::Surface& surface, const MutationLimits& limits,
                    FuzzRandom& random) {
  SurfaceNet from = NetOf(surface);
  NetArray& net = from.net;
  if (net.count_u == 0) return false;
  DoubleField weights;
  Assign(weights, from.weights);
  const bool weighted =
      static_cast<size_t>(weights.size()) == net.count_u * net.count_v;
  const size_t max_count = static_cast<size_t>(limits.max_degree) + 1;
  const int kinds = KindCount(*v1::Surface::descriptor());
  int kind = static_cast<int>(random.Below(static_cast<size_t>(kinds))) + 1;
  if (kind == surface.kind_case()) kind = kind % kinds + 1;
  switch (static_cast<v1::Surface::KindCase>(kind)) {
    case v1::Surface::kBezier: {
      ResizeNet(net, &weights, std::min(net.count_u, max_count),
                std::min(net.count_v, max_count), random);
      v1::BezierSurface& bezier = *surface.mutable_bezier();
      Write(net, *bezier.mutable_control_net());
      if (weighted) *bezier.mutable_weights() = weights;
      return true;
    }
    case v1::Surface::kBspline: {
      v1::BSplineSurface& bspline = *surface.mutable_bspline();
      const int degree_u = static_cast<int>(std::min<size_t>(
          net.count_u - 1, static_cast<size_t>(random.Between(0, 3))));
      const int degree_v = static_cast<int>(std::min<size_t>(
          net.count_v - 1, static_cast<size_t>(random.Between(0, 3))));
      Write(net, *bspline.mutable_control_net());
      bspline.set_degree_u(static_cast<uint32_t>(degree_u));
      bspline.set_degree_v(static_cast<uint32_t>(degree_v));
      Assign(*bspline.mutable_knots_u(),
             MakeKnots(net.count_u, degree_u, {}, random));
      Assign(*bspline.mutable_knots_v(),
             MakeKnots(net.count_v, degree_v, {}, random));
      if (weighted) *bspline.mutable_weights() = weights;
      return true;
    }
    case v1::Surface::kBicubicInterpolating:
      ResizeNet(net, nullptr, 4, 4, random);
      Write(net, *surface.mutable_bicubic_interpolating()->mutable_points());
      return true;
    case v1::Surface::kBicubicHermite: {
      ResizeNet(net, nullptr, 2, 2, random);
      // S_u at corner (i, j) is P[1][j] - P[0][j], S_v is P[i][1] - P[i][0].
      const size_t dim = static_cast<size_t>(net.dimension);
      NetArray du = net, dv = net;
      const auto at = [dim](size_t i, size_t j, size_t c) {
        return (2 * i + j) * dim + c;
      };
      for (size_t i = 0; i < 2; ++i) {
        for (size_t j = 0; j < 2; ++j) {
          for (size_t c = 0; c < dim; ++c) {
            du.values[at(i, j, c)] =
                net.values[at(1, j, c)] - net.values[at(0, j, c)];
            dv.values[at(i, j, c)] =
                net.values[at(i, 1, c)] - net.values[at(i, 0, c)];
          }
        }
      }
      v1::BicubicHermitePatch& patch = *surface.mutable_bicubic_hermite();
      Write(net, *patch.mutable_positions());
      Write(du, *patch.mutable_derivatives_u());
      Write(dv, *patch.mutable_derivatives_v());
      return true;
    }
    case v1::Surface::kTriangularBezier: {
      size_t degree = 0;
      const size_t count = net.count_u * net.count_v;
      while (degree < 8 && TriangleCount(degree + 1) <= count) ++degree;
      PointArray points{net.dimension, net.values};
      Resize(points, &weights, TriangleCount(degree), random);
      v1::TriangularBezierPatch& patch = *surface.mutable_triangular_bezier();
      patch.set_degree(static_cast<uint32_t>(degree));
      Write(points, *patch.mutable_control_points());
      if (weighted) *patch.mutable_weights() = weights;
      return true;
    }
    case v1::Surface::KIND_NOT_SET:
      break;
  }
  return false;
}

// ---------------------------------------------------------------- bases --

bool MutateBSplineBasis(v1::BSplineBasis& basis, const MutationLimits& limits,
                        FuzzRandom& random) {
  const int degree = CurrentDegree(basis.degree(), limits);
  const size_t functions =
      static_cast<size_t>(basis.knots_size()) > static_cast<size_t>(degree) + 1
          ? static_cast<size_t>(basis.knots_size()) -
                static_cast<size_t>(degree) - 1
          : static_cast<size_t>(degree) + 1;
  if (random.OneIn(3)) {
    MutateWeights(*basis.mutable_weights(), functions, random);
    return true;
  }
  const int new_degree = NewDegree(degree, limits, random);
  const size_t count = std::max(NewCount(functions, 1, functions + 16, random),
                                static_cast<size_t>(new_degree) + 1);
  basis.set_degree(static_cast<uint32_t>(new_degree));
  Assign(*basis.mutable_knots(),
         MakeKnots(count, new_degree, SpanOf(basis.knots()), random));
  if (basis.weights_size() > 0) {
    MutateWeights(*basis.mutable_weights(), count, random);
  }
  return true;
}

bool MutateBernsteinBasis(v1::BernsteinBasis& basis,
                          const MutationLimits& limits, FuzzRandom& random) {
  const int degree =
      NewDegree(CurrentDegree(basis.degree(), limits), limits, random);
  basis.set_degree(static_cast<uint32_t>(degree));
  if (basis.weights_size() > 0 || random.OneIn(2)) {
    MutateWeights(*basis.mutable_weights(), static_cast<size_t>(degree) + 1,
                  random);
  }
  return true;
}

bool MutateLagrangeBasis(v1::LagrangeBasis& basis, const MutationLimits& limits,
                         FuzzRandom& random) {
  const size_t count =
      NewCount(static_cast<size_t>(basis.nodes_size()), 1,
               static_cast<size_t>(limits.max_degree) + 1, random);
  Assign(*basis.mutable_nodes(), Nodes(count, random));
  return true;
}

// ----------------------------------------------------------- parameters --

// SwitchParameters turns a list into the range over its smallest and
// largest values with as many values, and a range into its list.
bool SwitchParameters(v1::Parameters& parameters) {
  if (parameters.has_list()) {
    const auto& values = parameters.list().values();
    v1::UniformRange range;
    range.set_count(static_cast<uint32_t>(values.size()));
    if (!values.empty()) {
      range.set_start(*std::min_element(values.begin(), values.end()));
      range.set_end(*std::max_element(values.begin(), values.end()));
    }
    *parameters.mutable_range() = range;
    return true;
  }
  if (!parameters.has_range()) return false;
  const v1::UniformRange range = parameters.range();
  const uint32_t count = std::min<uint32_t>(range.count(), 1024);
  const double start = range.has_start() ? range.start() : 0.0;
  const double end = range.has_end() ? range.end() : 1.0;
  v1::ParameterList& list = *parameters.mutable_list();
  for (uint32_t k = 0; k < count; ++k) {
    list.add_values(count == 1 ? start
                               : start + (end - start) * k / (count - 1));
  }
  return true;
}

// SwitchSurfaceParameters turns pairs into the grid of their u and v
// values (at most 32 each), and a grid of lists into its pairs.
bool SwitchSurfaceParameters(v1::SurfaceParameters& parameters) {
  if (parameters.has_points()) {
    const auto& uv = parameters.points().uv();
    v1::SurfaceGrid grid;
    for (int k = 0; k + 1 < uv.size() && k < 64; k += 2) {
      grid.mutable_u()->mutable_list()->add_values(uv[k]);
      grid.mutable_v()->mutable_list()->add_values(uv[k + 1]);
    }
    *parameters.mutable_grid() = grid;
    return true;
  }
  if (!parameters.has_grid()) return false;
  const v1::SurfaceGrid grid = parameters.grid();
  v1::SurfacePoints& points = *parameters.mutable_points();
  const auto& u = grid.u().list().values();
  const auto& v = grid.v().list().values();
  for (int k = 0; k < std::min(u.size(), v.size()); ++k) {
    points.add_uv(u[k]);
    points.add_uv(v[k]);
  }
  return true;
}

// ------------------------------------------------------------ dimension --

// ChangeDimension repacks every point set and net of `message` to one new
// dimension, so that the request's geometries still agree.
void RepackAll(Message& message, int dimension, FuzzRandom& random) {
  if (auto* points =
          google::protobuf::DynamicCastToGenerated<v1::Points>(&message)) {
    const PointArray array = Read(*points);
    Write({dimension, Repack(array.values, array.dimension, dimension, random)},
          *points);
    return;
  }
  if (auto* net =
          google::protobuf::DynamicCastToGenerated<v1::ControlNet>(&message)) {
    NetArray array = Read(*net);
    array.values = Repack(array.values, array.dimension, dimension, random);
    array.dimension = dimension;
    Write(array, *net);
    return;
  }
  const Descriptor& type = *message.GetDescriptor();
  const Reflection& r = *message.GetReflection();
  for (int i = 0; i < type.field_count(); ++i) {
    const FieldDescriptor* field = type.field(i);
    if (field->cpp_type() != FieldDescriptor::CPPTYPE_MESSAGE) continue;
    if (field->is_repeated()) {
      for (int k = 0; k < r.FieldSize(message, field); ++k) {
        RepackAll(*r.MutableRepeatedMessage(&message, field, k), dimension,
                  random);
      }
    } else if (r.HasField(message, field)) {
      RepackAll(*r.MutableMessage(&message, field), dimension, random);
    }
  }
}

// ---------------------------------------------------------------- sites --

// IsKind is true for the messages of one curve, surface or basis kind:
// their mutations keep their own arrays consistent, so the point sets and
// nets inside them are not sites of their own.
bool IsKind(const Descriptor* type) {
  static const Descriptor* const kinds[] = {
      v1::BezierCurve::descriptor(),
      v1::BSplineCurve::descriptor(),
      v1::LagrangeCurve::descriptor(),
      v1::HermiteCurve::descriptor(),
      v1::PowerCurve::descriptor(),
      v1::BezierSurface::descriptor(),
      v1::BSplineSurface::descriptor(),
      v1::BicubicInterpolatingPatch::descriptor(),
      v1::BicubicHermitePatch::descriptor(),
      v1::TriangularBezierPatch::descriptor(),
      v1::BSplineBasis::descriptor(),
      v1::BernsteinBasis::descriptor(),
      v1::LagrangeBasis::descriptor()};
  return std::find(std::begin(kinds), std::end(kinds), type) != std::end(kinds);
}

// FindGeometry collects the geometry messages inside `message`: curve,
// surface and basis kinds, Curve and Surface (converted to another kind),
// parameter sets and the point sets outside a kind (queries, data points).
void FindGeometry(Message& message, int depth, std::vector<Message*>& found) {
  const Descriptor* type = message.GetDescriptor();
  if (IsKind(type)) {
    found.push_back(&message);
    return;
  }
  if (type == v1::Curve::descriptor() || type == v1::Surface::descriptor() ||
      type == v1::Parameters::descriptor() ||
      type == v1::SurfaceParameters::descriptor() ||
      type == v1::Points::descriptor()) {
    found.push_back(&message);
  }
  if (depth >= 8) return;
  const Reflection& r = *message.GetReflection();
  for (int i = 0; i < type->field_count(); ++i) {
    const FieldDescriptor* field = type->field(i);
    if (field->cpp_type() != FieldDescriptor::CPPTYPE_MESSAGE) continue;
    if (field->is_repeated()) {
      for (int k = 0; k < std::min(r.FieldSize(message, field), 8); ++k) {
        FindGeometry(*r.MutableRepeatedMessage(&message, field, k), depth + 1,
                     found);
      }
    } else if (r.HasField(message, field)) {
      FindGeometry(*r.MutableMessage(&message, field), depth + 1, found);
    }
  }
}

template <typename T>
T* As(Message* message) {
  return google::protobuf::DynamicCastToGenerated<T>(message);
}

// MutateSite applies a mutation of its kind to one geometry message;
// false when it has none that applies.
bool MutateSite(Message* site, const MutationLimits& limits,
                FuzzRandom& random) {
  if (auto* m = As<v1::BSplineCurve>(site)) {
    return MutateBSplineCurve(*m, limits, random);
  }
  if (auto* m = As<v1::BezierCurve>(site)) {
    return MutateBezierCurve(*m, limits, random);
  }
  if (auto* m = As<v1::LagrangeCurve>(site)) {
    return MutateLagrangeCurve(*m, limits, random);
  }
  if (auto* m = As<v1::HermiteCurve>(site)) {
    return MutateHermiteCurve(*m, limits, random);
  }
  if (auto* m = As<v1::PowerCurve>(site)) {
    return MutatePowerCurve(*m, limits, random);
  }
  if (auto* m = As<v1::Curve>(site)) return ConvertCurve(*m, limits, random);
  if (auto* m = As<v1::BSplineSurface>(site)) {
    return MutateBSplineSurface(*m, limits, random);
  }
  if (auto* m = As<v1::BezierSurface>(site)) {
    return MutateBezierSurface(*m, limits, random);
  }
  if (auto* m = As<v1::BicubicInterpolatingPatch>(site)) {
    return MutateFixedNet(*m->mutable_points(), 4, 4, random);
  }
  if (auto* m = As<v1::BicubicHermitePatch>(site)) {
    return MutateHermitePatch(*m, random);
  }
  if (auto* m = As<v1::TriangularBezierPatch>(site)) {
    return MutateTriangularPatch(*m, limits, random);
  }
  if (auto* m = As<v1::Surface>(site)) {
    return ConvertSurface(*m, limits, random);
  }
  if (auto* m = As<v1::BSplineBasis>(site)) {
    return MutateBSplineBasis(*m, limits, random);
  }
  if (auto* m = As<v1::BernsteinBasis>(site)) {
    return MutateBernsteinBasis(*m, limits, random);
  }
  if (auto* m = As<v1::LagrangeBasis>(site)) {
    return MutateLagrangeBasis(*m, limits, random);
  }
  if (auto* m = As<v1::Parameters>(site)) return SwitchParameters(*m);
  if (auto* m = As<v1::SurfaceParameters>(site)) {
    return SwitchSurfaceParameters(*m);
  }
  if (auto* m = As<v1::Points>(site)) {
    PointArray points = Read(*m);
    if (points.count() == 0) return false;
    if (random.OneIn(2)) {
      Resize(
          points, nullptr,
          NewCount(points.count(), 1,
                   GrowthCap(points.count(), limits, points.dimension), random),
          random);
      Write(points, *m);
    } else {
      MutatePointValues(*m->mutable_coordinates(), points.dimension, random);
    }
    return true;
  }
  return false;
}

}  // namespace

bool MutateGeometry(Message& message, const MutationLimits& limits,
                    FuzzRandom& random) {
  if (random.OneIn(16)) {
    RepackAll(message, static_cast<int>(random.Between(1, 4)), random);
    return true;
  }
  std::vector<Message*> sites;
  FindGeometry(message, 0, sites);
  // A few tries: some sites (an empty point set, a UniformRange) have no
  // mutation of their own.
  for (int attempt = 0; attempt < 4 && !sites.empty(); ++attempt) {
    if (MutateSite(sites[random.Below(sites.size())], limits, random)) {
      return true;
    }
  }
  return false;
}

}  // namespace freeform::fuzz
