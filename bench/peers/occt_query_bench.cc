// The query workloads of bench/query_bench.cc with OpenCASCADE, the peer
// of docs/benchmarks.md (issue #12), on the same data (workloads.h):
//
//   Q1: GeomAPI_ProjectPointOnCurve on the W1 curve for 10^5 query points;
//       it returns the orthogonal projections only, so each distance is the
//       smaller of LowerDistance() and the distances to the end points (the
//       nearest point of a clamped curve may be an end).
//   Q2: Geom2dAPI_InterCurveCurve of the two planar 100-point splines. On
//       the whole curves it finds fewer than half of the crossings (it
//       samples each curve as one smooth interval), so the workload runs it
//       the way it answers fully: on every pair of knot spans (trimmed
//       curves) whose control points' boxes overlap, points found twice at
//       span ends merged; the whole-curve call is printed for reference.
//
// Built only with -DFREEFORM_PEER_BENCHMARKS=ON when CMake finds
// OpenCASCADE:
//   build/release/bench/occt_query_bench [repetitions] [Q1|Q2] [tolerance]
// (3 repetitions, both workloads, Q2's tolerance 1e-9 by default)
// Prints, per workload, the best and median CPU time over the repetitions
// and the checksums that bench/query_bench prints (sum of distances;
// number of points and sum of both parameters).
#include <Geom2dAPI_InterCurveCurve.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <IntRes2d_IntersectionPoint.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <gp_Pnt.hxx>
#include <gp_Pnt2d.hxx>
#include <string>
#include <utility>
#include <vector>

#include "peers/occt_geometry.h"
#include "workloads.h"

namespace {

using freeform::bench::Curve2d;
using freeform::bench::Curve3d;
using freeform::bench::PointsInBox;
using freeform::bench::RandomSpline;
using freeform::bench::SplineData;

constexpr size_t kQueries = 100'000;

double CpuSeconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

// Times `run` `repetitions` times and prints the best and median CPU time.
void Report(const char* name, int repetitions,
            const std::function<void()>& run) {
  std::vector<double> times;
  for (int r = 0; r < repetitions; ++r) {
    const double start = CpuSeconds();
    run();
    times.push_back(CpuSeconds() - start);
  }
  std::sort(times.begin(), times.end());
  std::printf("%s: best %.1f ms, median %.1f ms (CPU, %d runs)\n", name,
              1e3 * times.front(), 1e3 * times[times.size() / 2], repetitions);
}

void RunQ1(int repetitions) {
  const SplineData w1 = RandomSpline(1, 100, 3);
  const Handle(Geom_BSplineCurve) curve = Curve3d(w1);
  const std::vector<double> queries =
      PointsInBox(w1.points, 3, 1.1, 11, kQueries);
  const gp_Pnt first = curve->Value(curve->FirstParameter());
  const gp_Pnt last = curve->Value(curve->LastParameter());
  double distance_sum = 0.0;
  Report("Q1 closest points on W1 (GeomAPI_ProjectPointOnCurve)", repetitions,
         [&] {
           GeomAPI_ProjectPointOnCurve projector;
           projector.Init(curve, curve->FirstParameter(),
                          curve->LastParameter());
           distance_sum = 0.0;
           for (size_t r = 0; r < kQueries; ++r) {
             const gp_Pnt q(queries[3 * r], queries[3 * r + 1],
                            queries[3 * r + 2]);
             projector.Perform(q);
             double d = std::min(q.Distance(first), q.Distance(last));
             if (projector.NbPoints() > 0) {
               d = std::min(d, projector.LowerDistance());
             }
             distance_sum += d;
           }
         });
  std::printf("  checksum (sum of distances) %.6f\n", distance_sum);
}

// A knot span of a planar spline: its parameters and its control points'
// box.
struct Span {
  double start = 0.0;
  double end = 0.0;
  double lo[2] = {0.0, 0.0};
  double hi[2] = {0.0, 0.0};
};

std::vector<Span> SpansOf(const SplineData& data) {
  std::vector<Span> spans;
  const int p = data.degree;
  const int count = static_cast<int>(data.points.size() / 2);
  for (int s = p; s < count; ++s) {
    if (!(data.knots[s] < data.knots[s + 1])) continue;
    Span span{.start = data.knots[s], .end = data.knots[s + 1]};
    for (int x = 0; x < 2; ++x) {
      span.lo[x] = span.hi[x] = data.points[2 * (s - p) + x];
      for (int i = s - p; i <= s; ++i) {
        span.lo[x] = std::min(span.lo[x], data.points[2 * i + x]);
        span.hi[x] = std::max(span.hi[x], data.points[2 * i + x]);
      }
    }
    spans.push_back(span);
  }
  return spans;
}

void RunQ2(int repetitions, double tolerance) {
  const SplineData a_data = RandomSpline(1, 100, 2);
  const SplineData b_data = RandomSpline(2, 100, 2);
  const Handle(Geom2d_BSplineCurve) a = Curve2d(a_data);
  const Handle(Geom2d_BSplineCurve) b = Curve2d(b_data);
  const std::vector<Span> a_spans = SpansOf(a_data);
  const std::vector<Span> b_spans = SpansOf(b_data);
  std::printf("Q2 tolerance %g\n", tolerance);
  {
    Geom2dAPI_InterCurveCurve whole(a, b, tolerance);
    std::printf("  on the whole curves: %d points, %d segments\n",
                whole.NbPoints(), whole.NbSegments());
  }
  std::vector<std::pair<double, double>> found;
  int segments = 0;
  Report("Q2 two planar splines (Geom2dAPI_InterCurveCurve per span pair)",
         repetitions, [&] {
           found.clear();
           segments = 0;
           for (const Span& sa : a_spans) {
             const Handle(Geom2d_TrimmedCurve) ta =
                 new Geom2d_TrimmedCurve(a, sa.start, sa.end);
             for (const Span& sb : b_spans) {
               if (sa.lo[0] > sb.hi[0] || sb.lo[0] > sa.hi[0] ||
                   sa.lo[1] > sb.hi[1] || sb.lo[1] > sa.hi[1]) {
                 continue;
               }
               const Handle(Geom2d_TrimmedCurve) tb =
                   new Geom2d_TrimmedCurve(b, sb.start, sb.end);
               Geom2dAPI_InterCurveCurve intersector(ta, tb, tolerance);
               segments += intersector.NbSegments();
               for (int k = 1; k <= intersector.NbPoints(); ++k) {
                 const IntRes2d_IntersectionPoint& point =
                     intersector.Intersector().Point(k);
                 const double u = point.ParamOnFirst();
                 const double v = point.ParamOnSecond();
                 bool seen = false;
                 for (const auto& [fu, fv] : found) {
                   seen |= std::abs(fu - u) < 1e-9 && std::abs(fv - v) < 1e-9;
                 }
                 if (!seen) found.emplace_back(u, v);
               }
             }
           }
         });
  double parameter_sum = 0.0;
  for (const auto& [u, v] : found) parameter_sum += u + v;
  std::printf("  checksum %zu points, %d segments, parameter sum %.6f\n",
              found.size(), segments, parameter_sum);
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const std::string only = argc > 2 ? argv[2] : "";
  const double tolerance = argc > 3 ? std::atof(argv[3]) : 1e-9;

  if (only != "Q2") RunQ1(repetitions);
  if (only != "Q1") RunQ2(repetitions, tolerance);
  return 0;
}
