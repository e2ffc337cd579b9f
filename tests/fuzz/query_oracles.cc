#include "query_oracles.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "absl/types/span.h"
#include "freeform/v1/curve_service.pb.h"
#include "freeform/v1/query.pb.h"
#include "freeform/v1/surface_service.pb.h"
#include "oracle_geometry.h"
#include "prepare_options.h"

namespace freeform::fuzz {
namespace {

using google::protobuf::Message;
using server::ServiceLimits;

using Finding = std::optional<std::string>;

// The defaults of SectionSurfaceRequest (surface_service.proto): the
// tolerance, and the vertex cap when max_points is 0.
constexpr double kDefaultSectionTolerance = 1e-6;
constexpr uint64_t kDefaultSectionPoints = uint64_t{1} << 16;

// Samples of a curve for the closest-point and box checks (and its
// breakpoints), and the most polyline vertices of a length check.
constexpr size_t kCurveSamples = 65;
constexpr size_t kPolylineVertices = 4096;

std::string Num(double x) { return absl::StrFormat("%.17g", x); }

std::string PointText(absl::Span<const double> point) {
  return absl::StrCat(
      "(",
      absl::StrJoin(point, ", ",
                    [](std::string* out, double x) { out->append(Num(x)); }),
      ")");
}

absl::Span<const double> SpanOf(
    const google::protobuf::RepeatedField<double>& f) {
  return absl::MakeConstSpan(f.data(), static_cast<size_t>(f.size()));
}

absl::Span<const double> PointAt(absl::Span<const double> values, size_t index,
                                 int dimension) {
  return values.subspan(index * static_cast<size_t>(dimension),
                        static_cast<size_t>(dimension));
}

// ValueMargin is the rounding margin of values the query computed from
// geometry of size `size` (ulps in the subnormal range are absolute).
double ValueMargin(double size) {
  return kRoundingMargin * size + kAbsoluteMargin;
}

double Tolerance(bool has_value, double value, double fallback) {
  return has_value ? value : fallback;
}

// Unprepared is the finding of geometry the oracle cannot prepare. The one
// exception is geometry whose Bezier form overflows double precision in its
// own units (a Lagrange curve's Bezier points past 1e308): the queries work
// on a copy rescaled by a power of two (scaled_geometry.h), where it does
// not, so an OK answer is possible and is not judged.
Finding Unprepared(const absl::Status& status) {
  if (absl::StrContains(status.message(), "overflow double precision")) {
    return std::nullopt;
  }
  return absl::StrCat(
      "oracle: the geometry of a request answered OK does not prepare: ",
      status.ToString());
}

std::string Unevaluated(absl::string_view what, const absl::Status& status) {
  return absl::StrCat("oracle: ", what,
                      " cannot be evaluated: ", status.ToString());
}

// PolylineLength returns the length of the polyline through `points`.
double PolylineLength(absl::Span<const double> points, int dimension) {
  double length = 0.0;
  const size_t dim = static_cast<size_t>(dimension);
  for (size_t i = dim; i < points.size(); i += dim) {
    length += Distance(&points[i - dim], &points[i], dimension);
  }
  return length;
}

// SignedPlaneDistance returns unit_normal . (x - p), halved first like
// Distance so that nothing overflows.
double SignedPlaneDistance(absl::Span<const double> x,
                           absl::Span<const double> p,
                           absl::Span<const double> unit_normal) {
  double sum = 0.0;
  for (size_t j = 0; j < x.size(); ++j) {
    sum += unit_normal[j] * (0.5 * x[j] - 0.5 * p[j]);
  }
  return 2.0 * sum;
}

// ------------------------------------------------------- closest points --

// What the closest-point check needs of a curve or a surface.
struct ClosestPointGeometry {
  int dimension = 0;
  int parameter_count = 1;
  double scale = 0.0;

  std::function<absl::StatusOr<Evaluation>(absl::Span<const double>)> evaluate;
  // Parameters of samples of the geometry and their points.
  std::vector<double> sample_parameters;
  std::vector<double> sample_points;
};

Finding CheckClosestPointSizes(const v1::ClosestPointResponse& answer,
                               size_t queries, int dimension,
                               int parameter_count) {
  const auto same = [queries](int size) {
    return static_cast<size_t>(size) == queries;
  };
  if (!same(answer.distances_size()) || !same(answer.lower_bounds_size()) ||
      !same(answer.minima_counts_size()) || !same(answer.complete_size())) {
    return absl::StrCat(
        "ClosestPoint: ", queries, " queries, but the answer has ",
        answer.distances_size(), " distances, ", answer.lower_bounds_size(),
        " lower bounds, ", answer.minima_counts_size(), " minima counts and ",
        answer.complete_size(), " complete flags");
  }
  const size_t minima = std::accumulate(
      answer.minima_counts().begin(), answer.minima_counts().end(), size_t{0});
  if (answer.parameter_count() != static_cast<uint32_t>(parameter_count) ||
      static_cast<size_t>(answer.parameters_size()) !=
          minima * static_cast<size_t>(parameter_count) ||
      static_cast<size_t>(answer.points().coordinates_size()) !=
          minima * static_cast<size_t>(dimension) ||
      (minima > 0 &&
       answer.points().dimension() != static_cast<uint32_t>(dimension))) {
    return absl::StrCat(
        "ClosestPoint: ", minima, " minima of ", parameter_count,
        " parameters in dimension ", dimension,
        ", but the answer has parameter_count ", answer.parameter_count(), ", ",
        answer.parameters_size(), " parameters and ",
        answer.points().coordinates_size(), " coordinates of dimension ",
        answer.points().dimension());
  }
  return std::nullopt;
}

Finding CheckClosestPoints(const v1::Points& queries,
                           const v1::ClosestPointOptions& options,
                           const v1::ClosestPointResponse& answer,
                           const ClosestPointGeometry& geometry) {
  const int dim = geometry.dimension;
  const int pc = geometry.parameter_count;
  const absl::Span<const double> q_all = SpanOf(queries.coordinates());
  const size_t count = q_all.size() / static_cast<size_t>(dim);
  if (Finding sizes = CheckClosestPointSizes(answer, count, dim, pc)) {
    return sizes;
  }
  const double tolerance =
      Tolerance(options.has_tolerance(), options.tolerance(),
                server::kDefaultQueryTolerance);
  const absl::StatusOr<Evaluation> evaluated =
      geometry.evaluate(SpanOf(answer.parameters()));
  if (!evaluated.ok()) {
    return Unevaluated("ClosestPoint: the minima's parameters",
                       evaluated.status());
  }
  const absl::Span<const double> points = SpanOf(answer.points().coordinates());
  const absl::Span<const double> params = SpanOf(answer.parameters());
  size_t k = 0;
  for (size_t r = 0; r < count; ++r) {
    const absl::Span<const double> q = PointAt(q_all, r, dim);
    const double margin =
        ValueMargin(std::max(geometry.scale, LargestMagnitude(q)));
    const double distance = answer.distances(static_cast<int>(r));
    const double lower = answer.lower_bounds(static_cast<int>(r));
    const std::string query = absl::StrCat(
        "ClosestPoint query ", r, " ", PointText(q), " (distance ",
        Num(distance), ", lower bound ", Num(lower), ", tolerance ",
        Num(tolerance), ", margin ", Num(margin), "): ");
    if (lower > distance + margin) {
      return absl::StrCat(query, "the lower bound exceeds the distance");
    }
    if (answer.complete(static_cast<int>(r)) &&
        distance - lower > tolerance + margin) {
      return absl::StrCat(query,
                          "complete, but the lower bound is not within the "
                          "tolerance of the distance");
    }
    for (uint32_t c = 0; c < answer.minima_counts(static_cast<int>(r));
         ++c, ++k) {
      const absl::Span<const double> point = PointAt(points, k, dim);
      const std::string minimum = absl::StrCat(
          query, "minimum ", c, " at ", PointText(PointAt(params, k, pc)),
          " is ", PointText(point), ", and there the geometry is ",
          PointText(evaluated->Point(k)));
      const double off = evaluated->DistanceTo(k, point);
      if (off > margin + evaluated->Slack(k)) {
        return absl::StrCat(minimum, ": ", Num(off), " apart");
      }
      // The point is the geometry's (within the margin): its distance.
      const double reached = Distance(q.data(), point.data(), dim);
      if (reached > distance + tolerance + margin ||
          reached < distance - margin) {
        return absl::StrCat(minimum, ", at distance ", Num(reached),
                            ", not within the tolerance above the distance");
      }
    }
    const absl::Span<const double> samples = geometry.sample_points;
    for (size_t s = 0; s < samples.size() / static_cast<size_t>(dim); ++s) {
      const absl::Span<const double> sample = PointAt(samples, s, dim);
      const double reached = Distance(q.data(), sample.data(), dim);
      if (AllFinite(sample) && reached < lower - margin) {
        return absl::StrCat(
            query, "the geometry at ",
            PointText(PointAt(geometry.sample_parameters, s, pc)), " is ",
            PointText(sample), ", at distance ", Num(reached),
            ", below the certified lower bound");
      }
    }
  }
  return std::nullopt;
}

Finding CheckCurveClosestPoint(const v1::CurveClosestPointRequest& request,
                               const v1::ClosestPointResponse& answer,
                               const ServiceLimits& limits) {
  absl::StatusOr<OracleCurve> curve =
      OracleCurve::Create(request.curve(), limits, "curve");
  if (!curve.ok()) return Unprepared(curve.status());
  const ParameterDomain domain = curve->domain();
  ClosestPointGeometry geometry{
      .dimension = curve->dimension(),
      .parameter_count = 1,
      .scale = curve->scale(),
      .evaluate =
          [&](absl::Span<const double> t) { return curve->EvaluateSides(t); },
      .sample_parameters =
          curve->Samples(domain.start, domain.end, kCurveSamples, true)};
  absl::StatusOr<std::vector<double>> samples =
      curve->Evaluate(geometry.sample_parameters);
  if (!samples.ok())
    return Unevaluated("the curve's samples", samples.status());
  geometry.sample_points = *std::move(samples);
  return CheckClosestPoints(request.queries(), request.options(), answer,
                            geometry);
}

Finding CheckSurfaceClosestPoint(const v1::SurfaceClosestPointRequest& request,
                                 const v1::ClosestPointResponse& answer,
                                 const ServiceLimits& limits) {
  absl::StatusOr<OracleSurface> surface =
      OracleSurface::Create(request.surface(), limits, "surface");
  if (!surface.ok()) return Unprepared(surface.status());
  ClosestPointGeometry geometry{.dimension = surface->dimension(),
                                .parameter_count = 2,
                                .scale = surface->scale(),
                                .evaluate =
                                    [&](absl::Span<const double> uv) {
                                      return surface->EvaluateSides(uv);
                                    },
                                .sample_parameters = surface->Samples()};
  absl::StatusOr<std::vector<double>> samples =
      surface->Evaluate(geometry.sample_parameters);
  if (!samples.ok()) {
    return Unevaluated("the surface's samples", samples.status());
  }
  geometry.sample_points = *std::move(samples);
  return CheckClosestPoints(request.queries(), request.options(), answer,
                            geometry);
}

// --------------------------------------------------------- intersections --

// CheckCoincident checks that points 0..count-1 of `a` and `b` are within
// tolerance + margin of each other; `what(k)` names pair k.
Finding CheckCoincident(const Evaluation& a, const Evaluation& b, size_t count,
                        double tolerance, double margin,
                        const std::function<std::string(size_t)>& what) {
  for (size_t k = 0; k < count; ++k) {
    const double gap = a.Gap(k, b, k);
    if (gap > tolerance + margin + a.Slack(k) + b.Slack(k)) {
      return absl::StrCat(what(k), ": the inputs there are ",
                          PointText(a.Point(k)), " and ", PointText(b.Point(k)),
                          ", ", Num(gap), " apart, over the tolerance ",
                          Num(tolerance), " + margin ", Num(margin));
    }
  }
  return std::nullopt;
}

// CheckSamePoints checks the answer's `count` points against the
// geometry's there.
Finding CheckSamePoints(absl::Span<const double> reported,
                        const Evaluation& evaluated, size_t count, int dim,
                        double margin,
                        const std::function<std::string(size_t)>& what) {
  for (size_t k = 0; k < count; ++k) {
    const absl::Span<const double> point = PointAt(reported, k, dim);
    const double off = evaluated.DistanceTo(k, point);
    if (off > margin + evaluated.Slack(k)) {
      return absl::StrCat(what(k), ": the answer's point ", PointText(point),
                          " is not the input's point there ",
                          PointText(evaluated.Point(k)), " (", Num(off),
                          " apart)");
    }
  }
  return std::nullopt;
}

Finding CheckCurveIntersections(const v1::IntersectCurvesRequest& request,
                                const v1::IntersectCurvesResponse& answer,
                                const ServiceLimits& limits) {
  absl::StatusOr<OracleCurve> first =
      OracleCurve::Create(request.first(), limits, "first");
  if (!first.ok()) return Unprepared(first.status());
  absl::StatusOr<OracleCurve> second =
      OracleCurve::Create(request.second(), limits, "second");
  if (!second.ok()) return Unprepared(second.status());
  const int dim = first->dimension();
  const size_t count = static_cast<size_t>(answer.first_parameters_size());
  if (static_cast<size_t>(answer.second_parameters_size()) != count ||
      static_cast<size_t>(answer.points().coordinates_size()) !=
          count * static_cast<size_t>(dim) ||
      answer.first_intervals_size() != answer.second_intervals_size() ||
      answer.first_intervals_size() % 2 != 0) {
    return absl::StrCat(
        "Intersect: the answer's arrays disagree: ", count,
        " first parameters, ", answer.second_parameters_size(), " second, ",
        answer.points().coordinates_size(), " coordinates, intervals ",
        answer.first_intervals_size(), " and ", answer.second_intervals_size());
  }
  if (!std::is_sorted(answer.first_parameters().begin(),
                      answer.first_parameters().end())) {
    return std::string(
        "Intersect: the points are not sorted by the first parameter");
  }
  const double tolerance =
      Tolerance(request.options().has_tolerance(),
                request.options().tolerance(), server::kDefaultQueryTolerance);
  const double margin = ValueMargin(std::max(first->scale(), second->scale()));
  // The points, then the overlaps' starts and ends, as parameter lists.
  std::vector<double> s(answer.first_parameters().begin(),
                        answer.first_parameters().end());
  std::vector<double> t(answer.second_parameters().begin(),
                        answer.second_parameters().end());
  s.insert(s.end(), answer.first_intervals().begin(),
           answer.first_intervals().end());
  t.insert(t.end(), answer.second_intervals().begin(),
           answer.second_intervals().end());
  const absl::StatusOr<Evaluation> a = first->EvaluateSides(s);
  if (!a.ok())
    return Unevaluated("Intersect: the first parameters", a.status());
  const absl::StatusOr<Evaluation> b = second->EvaluateSides(t);
  if (!b.ok()) {
    return Unevaluated("Intersect: the second parameters", b.status());
  }
  const auto what = [&](size_t k) {
    if (k < count) {
      return absl::StrCat("Intersect point ", k, " at first ", Num(s[k]),
                          ", second ", Num(t[k]));
    }
    const size_t overlap = (k - count) / 2;
    return absl::StrCat("Intersect overlap ", overlap,
                        (k - count) % 2 == 0 ? " start" : " end", " at first ",
                        Num(s[k]), ", second ", Num(t[k]));
  };
  for (size_t k = count; k + 1 < s.size(); k += 2) {
    if (s[k] > s[k + 1]) {
      return absl::StrCat(what(k), ": the first interval decreases to ",
                          Num(s[k + 1]));
    }
  }
  if (Finding apart =
          CheckCoincident(*a, *b, s.size(), tolerance, margin, what)) {
    return apart;
  }
  return CheckSamePoints(SpanOf(answer.points().coordinates()), *a, count, dim,
                         margin, what);
}

Finding CheckCurveSurfaceIntersections(
    const v1::IntersectCurveSurfaceRequest& request,
    const v1::IntersectCurveSurfaceResponse& answer,
    const ServiceLimits& limits) {
  absl::StatusOr<OracleCurve> curve =
      OracleCurve::Create(request.curve(), limits, "curve");
  if (!curve.ok()) return Unprepared(curve.status());
  absl::StatusOr<OracleSurface> surface =
      OracleSurface::Create(request.surface(), limits, "surface");
  if (!surface.ok()) return Unprepared(surface.status());
  const int dim = curve->dimension();
  const size_t count = static_cast<size_t>(answer.curve_parameters_size());
  if (static_cast<size_t>(answer.surface_parameters_size()) != 2 * count ||
      static_cast<size_t>(answer.points().coordinates_size()) !=
          count * static_cast<size_t>(dim)) {
    return absl::StrCat("IntersectCurve: the answer's arrays disagree: ", count,
                        " curve parameters, ", answer.surface_parameters_size(),
                        " surface parameters, ",
                        answer.points().coordinates_size(), " coordinates");
  }
  const double tolerance =
      Tolerance(request.options().has_tolerance(),
                request.options().tolerance(), server::kDefaultQueryTolerance);
  const double margin = ValueMargin(std::max(curve->scale(), surface->scale()));
  const absl::StatusOr<Evaluation> c =
      curve->EvaluateSides(SpanOf(answer.curve_parameters()));
  if (!c.ok()) {
    return Unevaluated("IntersectCurve: the curve parameters", c.status());
  }
  const absl::StatusOr<Evaluation> s =
      surface->EvaluateSides(SpanOf(answer.surface_parameters()));
  if (!s.ok()) {
    return Unevaluated("IntersectCurve: the surface parameters", s.status());
  }
  const auto what = [&](size_t k) {
    return absl::StrCat(
        "IntersectCurve point ", k, " at curve ",
        Num(answer.curve_parameters(static_cast<int>(k))), ", surface (",
        Num(answer.surface_parameters(static_cast<int>(2 * k))), ", ",
        Num(answer.surface_parameters(static_cast<int>(2 * k + 1))), ")");
  };
  if (Finding apart = CheckCoincident(*c, *s, count, tolerance, margin, what)) {
    return apart;
  }
  return CheckSamePoints(SpanOf(answer.points().coordinates()), *c, count, dim,
                         margin, what);
}

// --------------------------------------------------------------- section --

Finding CheckSection(const v1::SectionSurfaceRequest& request,
                     const v1::SectionSurfaceResponse& answer,
                     const ServiceLimits& limits) {
  absl::StatusOr<OracleSurface> surface =
      OracleSurface::Create(request.surface(), limits, "surface");
  if (!surface.ok()) return Unprepared(surface.status());
  const int dim = surface->dimension();
  const double tolerance = Tolerance(
      request.has_tolerance(), request.tolerance(), kDefaultSectionTolerance);
  const uint64_t cap = request.max_points() > 0 ? uint64_t{request.max_points()}
                                                : kDefaultSectionPoints;
  const absl::Span<const double> p = SpanOf(request.plane_point());
  const absl::Span<const double> n = SpanOf(request.plane_normal());
  // Divided by its largest component first: a subnormal normal (5e-324)
  // has a norm Norm's halving rounds to 0.
  const double largest_component = LargestMagnitude(n);
  std::vector<double> unit(n.begin(), n.end());
  for (double& x : unit) x /= largest_component;
  const double length = Norm(unit.data(), dim);
  for (double& x : unit) x /= length;
  const double margin =
      ValueMargin(std::max(surface->scale(), LargestMagnitude(p)));
  uint64_t vertices = 0;
  for (int k = 0; k < answer.polylines_size(); ++k) {
    const v1::SectionPolyline& polyline = answer.polylines(k);
    const absl::Span<const double> points =
        SpanOf(polyline.points().coordinates());
    const size_t count = points.size() / static_cast<size_t>(dim);
    if (static_cast<size_t>(polyline.parameters_size()) != 2 * count ||
        points.size() != count * static_cast<size_t>(dim)) {
      return absl::StrCat("Section polyline ", k, ": ", points.size(),
                          " coordinates of dimension ", dim, " and ",
                          polyline.parameters_size(), " parameters");
    }
    vertices += count;
    const absl::StatusOr<Evaluation> on_surface =
        surface->EvaluateSides(SpanOf(polyline.parameters()));
    if (!on_surface.ok()) {
      return Unevaluated(
          absl::StrCat("Section polyline ", k, ": the parameters"),
          on_surface.status());
    }
    for (size_t i = 0; i < count; ++i) {
      const absl::Span<const double> x = PointAt(points, i, dim);
      const std::string vertex = absl::StrCat(
          "Section polyline ", k, " vertex ", i, " ", PointText(x), " at (",
          Num(polyline.parameters(static_cast<int>(2 * i))), ", ",
          Num(polyline.parameters(static_cast<int>(2 * i + 1))),
          ") (tolerance ", Num(tolerance), ", margin ", Num(margin), "): ");
      const double off_plane = std::abs(SignedPlaneDistance(x, p, unit));
      if (!(off_plane <= tolerance + margin)) {
        return absl::StrCat(vertex, "it is ", Num(off_plane), " off the plane");
      }
      const double off_surface = on_surface->DistanceTo(i, x);
      if (off_surface > tolerance + margin + on_surface->Slack(i)) {
        return absl::StrCat(vertex, "the surface there is ",
                            PointText(on_surface->Point(i)), ", ",
                            Num(off_surface), " away");
      }
    }
    if (polyline.closed() && count > 0 &&
        Distance(&points[0], &points[(count - 1) * static_cast<size_t>(dim)],
                 dim) > margin) {
      return absl::StrCat("Section polyline ", k,
                          " is closed but does not end at its start");
    }
  }
  if (vertices > cap) {
    return absl::StrCat("Section: ", vertices, " vertices, over max_points ",
                        cap);
  }
  return std::nullopt;
}

// ------------------------------------------------------------ arc length --

// CheckLengthBounds returns what is wrong with `length` as the length of
// the curve over [a, b]: shorter than an inscribed polyline of `vertices`
// (a continuous curve whose points there do not overflow), or (polynomial
// curves) longer than the control polygons of its pieces. `slack` is how
// much the length may change with the rounding of b (a parameter the
// query found).
Finding CheckLengthBounds(const OracleCurve& curve, double a, double b,
                          double length, double tolerance, double slack,
                          size_t vertices, absl::string_view what) {
  double polyline = std::numeric_limits<double>::quiet_NaN();
  if (curve.continuous()) {
    const absl::StatusOr<std::vector<double>> points =
        curve.Evaluate(curve.Samples(a, b, vertices, false));
    if (!points.ok()) return Unevaluated(what, points.status());
    if (AllFinite(*points)) {
      polyline = PolylineLength(*points, curve.dimension());
    }
  }
  const double margin =
      ValueMargin(std::max({curve.scale(), std::abs(length),
                            std::isnan(polyline) ? 0.0 : polyline})) +
      slack;
  const std::string context = absl::StrCat(
      what, " over [", Num(a), ", ", Num(b), "] is ", Num(length),
      " (tolerance ", Num(tolerance), ", margin ", Num(margin), "): ");
  if (polyline > length + tolerance + margin) {
    return absl::StrCat(context, "shorter than an inscribed polyline of ",
                        vertices, " vertices, ", Num(polyline));
  }
  if (curve.polynomial()) {
    const double polygons = curve.PolygonLength(a, b);
    if (length > polygons + tolerance + margin) {
      return absl::StrCat(context,
                          "longer than the control polygons of its pieces, ",
                          Num(polygons));
    }
  }
  return std::nullopt;
}

Finding CheckArcLength(const v1::ArcLengthRequest& request,
                       const v1::ArcLengthResponse& answer,
                       const ServiceLimits& limits) {
  absl::StatusOr<OracleCurve> curve =
      OracleCurve::Create(request.curve(), limits, "curve");
  if (!curve.ok()) return Unprepared(curve.status());
  const ParameterDomain domain = curve->domain();
  const size_t count =
      std::max<size_t>(1, static_cast<size_t>(request.intervals_size()));
  if (static_cast<size_t>(answer.lengths_size()) != count) {
    return absl::StrCat("ArcLength: ", count, " intervals, ",
                        answer.lengths_size(), " lengths");
  }
  const double tolerance =
      Tolerance(request.has_tolerance(), request.tolerance(),
                server::kDefaultQueryTolerance);
  const size_t vertices = std::clamp<size_t>(kPolylineVertices / count, 2, 257);
  for (size_t i = 0; i < count; ++i) {
    v1::ParameterInterval interval;
    if (request.intervals_size() > 0) {
      interval = request.intervals(static_cast<int>(i));
    }
    const double a = interval.has_start() ? interval.start() : domain.start;
    const double b = interval.has_end() ? interval.end() : domain.end;
    if (Finding wrong = CheckLengthBounds(
            *curve, a, b, answer.lengths(static_cast<int>(i)), tolerance,
            /*slack=*/0.0, vertices, absl::StrCat("ArcLength ", i))) {
      return wrong;
    }
  }
  return std::nullopt;
}

Finding CheckParametersAtArcLength(
    const v1::ParametersAtArcLengthRequest& request,
    const v1::ParametersAtArcLengthResponse& answer,
    const ServiceLimits& limits) {
  absl::StatusOr<OracleCurve> curve =
      OracleCurve::Create(request.curve(), limits, "curve");
  if (!curve.ok()) return Unprepared(curve.status());
  const int dim = curve->dimension();
  const size_t count = static_cast<size_t>(request.lengths_size());
  if (static_cast<size_t>(answer.parameters_size()) != count ||
      static_cast<size_t>(answer.points().coordinates_size()) !=
          count * static_cast<size_t>(dim)) {
    return absl::StrCat("ParametersAtArcLength: ", count, " lengths, ",
                        answer.parameters_size(), " parameters, ",
                        answer.points().coordinates_size(), " coordinates");
  }
  const double start =
      request.has_start() ? request.start() : curve->domain().start;
  const double tolerance =
      Tolerance(request.has_tolerance(), request.tolerance(),
                server::kDefaultQueryTolerance);
  const absl::StatusOr<Evaluation> points =
      curve->EvaluateSides(SpanOf(answer.parameters()));
  if (!points.ok()) {
    return Unevaluated("ParametersAtArcLength: the parameters",
                       points.status());
  }
  const double margin = ValueMargin(curve->scale());
  if (Finding off = CheckSamePoints(
          SpanOf(answer.points().coordinates()), *points, count, dim, margin,
          [](size_t k) { return absl::StrCat("ParametersAtArcLength ", k); })) {
    return off;
  }
  const size_t vertices = std::clamp<size_t>(
      kPolylineVertices / std::max<size_t>(count, 1), 2, 257);
  for (size_t i = 0; i < count; ++i) {
    const double t = answer.parameters(static_cast<int>(i));
    if (t < start) {
      return absl::StrCat("ParametersAtArcLength ", i, ": parameter ", Num(t),
                          " before the start ", Num(start));
    }
    if (Finding wrong = CheckLengthBounds(
            *curve, start, t, request.lengths(static_cast<int>(i)), tolerance,
            points->Slack(i), vertices,
            absl::StrCat("ParametersAtArcLength ", i,
                         ": the requested length"))) {
      return wrong;
    }
  }
  return std::nullopt;
}

Finding CheckSampleByArcLength(const v1::SampleByArcLengthRequest& request,
                               const v1::SampleByArcLengthResponse& answer,
                               const ServiceLimits& limits) {
  absl::StatusOr<OracleCurve> curve =
      OracleCurve::Create(request.curve(), limits, "curve");
  if (!curve.ok()) return Unprepared(curve.status());
  const int dim = curve->dimension();
  const ParameterDomain domain = curve->domain();
  const double start = request.interval().has_start()
                           ? request.interval().start()
                           : domain.start;
  const double end =
      request.interval().has_end() ? request.interval().end() : domain.end;
  const size_t count = request.count();
  const double tolerance =
      Tolerance(request.has_tolerance(), request.tolerance(),
                server::kDefaultQueryTolerance);
  if (static_cast<size_t>(answer.parameters_size()) != count ||
      static_cast<size_t>(answer.points().coordinates_size()) !=
          count * static_cast<size_t>(dim)) {
    return absl::StrCat("SampleByArcLength: count ", count, ", ",
                        answer.parameters_size(), " parameters, ",
                        answer.points().coordinates_size(), " coordinates");
  }
  const auto& t = answer.parameters();
  if (count >= 2 && (t[0] != start || t[static_cast<int>(count) - 1] != end)) {
    return absl::StrCat("SampleByArcLength: the samples run from ", Num(t[0]),
                        " to ", Num(t[static_cast<int>(count) - 1]),
                        ", not from ", Num(start), " to ", Num(end));
  }
  // The lengths at the samples are k L / (count - 1) within the tolerance,
  // so the parameters increase when that spacing exceeds twice the
  // tolerance, as it does when an inscribed polyline's share does.
  if (!std::is_sorted(t.begin(), t.end()) && curve->continuous()) {
    const absl::StatusOr<std::vector<double>> polyline_points =
        curve->Evaluate(curve->Samples(start, end, kPolylineVertices, false));
    if (!polyline_points.ok()) {
      return Unevaluated("SampleByArcLength", polyline_points.status());
    }
    const double spacing = AllFinite(*polyline_points)
                               ? PolylineLength(*polyline_points, dim) /
                                     static_cast<double>(count - 1)
                               : 0.0;
    if (spacing > 2.0 * tolerance + ValueMargin(curve->scale())) {
      return absl::StrCat(
          "SampleByArcLength: the parameters decrease, with "
          "samples at least ",
          Num(spacing), " apart along the curve (tolerance ", Num(tolerance),
          ")");
    }
  }
  const absl::StatusOr<Evaluation> points = curve->EvaluateSides(SpanOf(t));
  if (!points.ok()) {
    return Unevaluated("SampleByArcLength: the parameters", points.status());
  }
  return CheckSamePoints(SpanOf(answer.points().coordinates()), *points, count,
                         dim, ValueMargin(curve->scale()), [](size_t k) {
                           return absl::StrCat("SampleByArcLength ", k);
                         });
}

// ---------------------------------------------------------- bounding box --

// What the box check needs of a curve or a surface.
struct BoxGeometry {
  int dimension = 0;
  double scale = 0.0;
  double underflow = 0.0;  // OracleCurve::underflow

  bool positive_weights = true;
  std::function<double(int)> hull_lower, hull_upper;
  // The box's documented slack beyond the geometry on axis j: twice its
  // margin, 2^-44 of the largest control coordinate on that axis
  // (bounding_box.h).
  std::function<double(int)> axis_scale;
  std::vector<double> sample_points;
};

constexpr double kBoxMargin = 0x1p-44;

Finding CheckBox(const v1::BoundingBoxResponse& answer, double tolerance,
                 const BoxGeometry& geometry) {
  const int dim = geometry.dimension;
  if (answer.dimension() != static_cast<uint32_t>(dim) ||
      answer.lower_size() != dim || answer.upper_size() != dim) {
    return absl::StrCat("BoundingBox: dimension ", dim, ", answer dimension ",
                        answer.dimension(), " with ", answer.lower_size(),
                        " lower and ", answer.upper_size(), " upper values");
  }
  const double margin = ValueMargin(geometry.scale) + geometry.underflow;
  const std::string box =
      absl::StrCat("BoundingBox ", PointText(SpanOf(answer.lower())), " - ",
                   PointText(SpanOf(answer.upper())), " (tolerance ",
                   Num(tolerance), ", margin ", Num(margin), "): ");
  const absl::Span<const double> samples = geometry.sample_points;
  for (size_t s = 0; s < samples.size() / static_cast<size_t>(dim); ++s) {
    const absl::Span<const double> x = PointAt(samples, s, dim);
    if (!AllFinite(x)) continue;  // an evaluation that overflowed
    for (int j = 0; j < dim; ++j) {
      if (x[static_cast<size_t>(j)] < answer.lower(j) - margin ||
          x[static_cast<size_t>(j)] > answer.upper(j) + margin) {
        return absl::StrCat(box, "the geometry's point ", PointText(x),
                            " is outside");
      }
    }
  }
  if (!geometry.positive_weights) return std::nullopt;
  for (int j = 0; j < dim; ++j) {
    const double slack =
        tolerance + margin + 2.0 * kBoxMargin * geometry.axis_scale(j);
    if (answer.lower(j) < geometry.hull_lower(j) - slack ||
        answer.upper(j) > geometry.hull_upper(j) + slack) {
      return absl::StrCat(
          box, "coordinate ", j, " reaches beyond the control points' range [",
          Num(geometry.hull_lower(j)), ", ", Num(geometry.hull_upper(j)), "]");
    }
  }
  return std::nullopt;
}

Finding CheckCurveBox(const v1::CurveBoundingBoxRequest& request,
                      const v1::BoundingBoxResponse& answer,
                      const ServiceLimits& limits) {
  absl::StatusOr<OracleCurve> curve =
      OracleCurve::Create(request.curve(), limits, "curve");
  if (!curve.ok()) return Unprepared(curve.status());
  const ParameterDomain domain = curve->domain();
  absl::StatusOr<std::vector<double>> samples = curve->Evaluate(
      curve->Samples(domain.start, domain.end, kCurveSamples, true));
  if (!samples.ok())
    return Unevaluated("the curve's samples", samples.status());
  const BoxGeometry geometry{
      .dimension = curve->dimension(),
      .scale = curve->scale(),
      .underflow = curve->underflow(),
      .positive_weights = curve->positive_weights(),
      .hull_lower = [&](int j) { return curve->HullLower(j); },
      .hull_upper = [&](int j) { return curve->HullUpper(j); },
      .axis_scale = [&](int j) { return curve->AxisScale(j); },
      .sample_points = *std::move(samples)};
  return CheckBox(answer,
                  Tolerance(request.has_tolerance(), request.tolerance(),
                            server::kDefaultQueryTolerance),
                  geometry);
}

Finding CheckSurfaceBox(const v1::SurfaceBoundingBoxRequest& request,
                        const v1::BoundingBoxResponse& answer,
                        const ServiceLimits& limits) {
  absl::StatusOr<OracleSurface> surface =
      OracleSurface::Create(request.surface(), limits, "surface");
  if (!surface.ok()) return Unprepared(surface.status());
  absl::StatusOr<std::vector<double>> samples =
      surface->Evaluate(surface->Samples());
  if (!samples.ok()) {
    return Unevaluated("the surface's samples", samples.status());
  }
  const BoxGeometry geometry{
      .dimension = surface->dimension(),
      .scale = surface->scale(),
      .underflow = surface->underflow(),
      .positive_weights = surface->positive_weights(),
      .hull_lower = [&](int j) { return surface->HullLower(j); },
      .hull_upper = [&](int j) { return surface->HullUpper(j); },
      .axis_scale = [&](int j) { return surface->AxisScale(j); },
      .sample_points = *std::move(samples)};
  return CheckBox(answer,
                  Tolerance(request.has_tolerance(), request.tolerance(),
                            server::kDefaultQueryTolerance),
                  geometry);
}

// Dispatch runs `check` on the request and answer as their generated
// types.
template <typename Request, typename Response, typename Check>
Finding Dispatch(const Message& request, const Message& answer,
                 const ServiceLimits& limits, Check check) {
  const auto* typed_request =
      google::protobuf::DynamicCastToGenerated<Request>(&request);
  const auto* typed_answer =
      google::protobuf::DynamicCastToGenerated<Response>(&answer);
  if (typed_request == nullptr || typed_answer == nullptr) {
    return std::string("oracle: the request or answer is not of its type");
  }
  return check(*typed_request, *typed_answer, limits);
}

}  // namespace

std::optional<std::string> CheckQueryAnswer(
    const google::protobuf::MethodDescriptor& method, const Message& request,
    const Message& answer, const ServiceLimits& limits) {
  const std::string& name = method.full_name();
  if (name == "freeform.v1.CurveService.ClosestPoint") {
    return Dispatch<v1::CurveClosestPointRequest, v1::ClosestPointResponse>(
        request, answer, limits, CheckCurveClosestPoint);
  }
  if (name == "freeform.v1.SurfaceService.ClosestPoint") {
    return Dispatch<v1::SurfaceClosestPointRequest, v1::ClosestPointResponse>(
        request, answer, limits, CheckSurfaceClosestPoint);
  }
  if (name == "freeform.v1.CurveService.Intersect") {
    return Dispatch<v1::IntersectCurvesRequest, v1::IntersectCurvesResponse>(
        request, answer, limits, CheckCurveIntersections);
  }
  if (name == "freeform.v1.SurfaceService.IntersectCurve") {
    return Dispatch<v1::IntersectCurveSurfaceRequest,
                    v1::IntersectCurveSurfaceResponse>(
        request, answer, limits, CheckCurveSurfaceIntersections);
  }
  if (name == "freeform.v1.SurfaceService.Section") {
    return Dispatch<v1::SectionSurfaceRequest, v1::SectionSurfaceResponse>(
        request, answer, limits, CheckSection);
  }
  if (name == "freeform.v1.CurveService.ArcLength") {
    return Dispatch<v1::ArcLengthRequest, v1::ArcLengthResponse>(
        request, answer, limits, CheckArcLength);
  }
  if (name == "freeform.v1.CurveService.ParametersAtArcLength") {
    return Dispatch<v1::ParametersAtArcLengthRequest,
                    v1::ParametersAtArcLengthResponse>(
        request, answer, limits, CheckParametersAtArcLength);
  }
  if (name == "freeform.v1.CurveService.SampleByArcLength") {
    return Dispatch<v1::SampleByArcLengthRequest,
                    v1::SampleByArcLengthResponse>(request, answer, limits,
                                                   CheckSampleByArcLength);
  }
  if (name == "freeform.v1.CurveService.BoundingBox") {
    return Dispatch<v1::CurveBoundingBoxRequest, v1::BoundingBoxResponse>(
        request, answer, limits, CheckCurveBox);
  }
  if (name == "freeform.v1.SurfaceService.BoundingBox") {
    return Dispatch<v1::SurfaceBoundingBoxRequest, v1::BoundingBoxResponse>(
        request, answer, limits, CheckSurfaceBox);
  }
  return std::nullopt;
}

}  // namespace freeform::fuzz
