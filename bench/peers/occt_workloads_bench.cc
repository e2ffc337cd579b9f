// The core workloads W1-W6 of docs/benchmarks.md with OpenCASCADE, on the
// same data (workloads.h), for scripts/performance.sh:
//
//   W1  positions of the W1 curve at 10^6 parameters: Geom_BSplineCurve::D0
//       (span search and basis per call) and GeomAdaptor_Curve::D0 (its
//       per-span polynomial cache)
//   W2  the same with the first derivative (D1), both ways
//   W3  the W3 surface on the 1000 x 1000 grid: Geom_BSplineSurface::D0
//       and GeomAdaptor_Surface::D0
//   W4  the W4 cubic Bezier at 10^7 parameters: Geom_BezierCurve::D0 and
//       GeomAdaptor_Curve::D0
//   W5  GeomAPI_Interpolate of the 10^5 W5 points (chord-length parameters,
//       knots at the parameters: another knot rule than freeform's
//       averaging, so the checksum, the sum of the poles' coordinates,
//       differs)
//   W6  Geom_BSplineCurve::IncreaseDegree by 1 of the W1 curve, the time of
//       Copy() + IncreaseDegree less that of Copy() alone; checksum: the sum
//       of the poles' coordinates
//
// Built only with -DFREEFORM_PEER_BENCHMARKS=ON when CMake finds
// OpenCASCADE:
//   build/peers/bench/occt_workloads_bench [runs]
// Each workload runs `runs` times (default 3); the best wall time counts.
// Output: one RESULT line per figure (peers/peer_result.h).
#include <GeomAPI_Interpolate.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierCurve.hxx>
#include <Standard_Failure.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <cstddef>
#include <cstdio>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>
#include <vector>

#include "peers/occt_geometry.h"
#include "peers/peer_result.h"
#include "workloads.h"

namespace {

using freeform::bench::BestSeconds;
using freeform::bench::PrintRate;
using freeform::bench::PrintSeconds;
using freeform::bench::UniformParameters;

constexpr size_t kCurvePoints = 1'000'000;
constexpr size_t kBezierPoints = 10'000'000;
constexpr size_t kGrid = 1000;
constexpr size_t kInterpolationPoints = 100'000;
constexpr int kElevations = 20'000;

double Sum(const gp_XYZ& p) { return p.X() + p.Y() + p.Z(); }

// Positions of `curve` (anything with D0(t, point)) at every parameter.
template <typename Curve>
double SumPositions(const Curve& curve, const std::vector<double>& t) {
  double sum = 0;
  gp_Pnt point;
  for (const double parameter : t) {
    curve.D0(parameter, point);
    sum += Sum(point.XYZ());
  }
  return sum;
}

// Positions and first derivatives (D1) at every parameter.
template <typename Curve>
double SumFirstDerivatives(const Curve& curve, const std::vector<double>& t) {
  double sum = 0;
  gp_Pnt point;
  gp_Vec derivative;
  for (const double parameter : t) {
    curve.D1(parameter, point, derivative);
    sum += Sum(point.XYZ()) + Sum(derivative.XYZ());
  }
  return sum;
}

// Positions of `surface` on the grid t x t (u the outer loop).
template <typename Surface>
double SumGrid(const Surface& surface, const std::vector<double>& t) {
  double sum = 0;
  gp_Pnt point;
  for (const double u : t) {
    for (const double v : t) {
      surface.D0(u, v, point);
      sum += Sum(point.XYZ());
    }
  }
  return sum;
}

// Times `evaluate` (returning its checksum) and prints its rate.
template <typename Evaluate>
void Rate(int runs, const char* workload, const char* implementation,
          double points, Evaluate&& evaluate) {
  double checksum = 0;
  const double seconds = BestSeconds(runs, [&] { checksum = evaluate(); });
  PrintRate(workload, implementation, points, seconds, checksum);
}

void RunCurves(int runs) {
  const Handle(Geom_BSplineCurve) curve =
      freeform::bench::Curve3d(freeform::bench::RandomSpline(1, 100, 3));
  const GeomAdaptor_Curve adaptor(curve);
  const std::vector<double> t = UniformParameters(kCurvePoints);
  const double n = static_cast<double>(t.size());
  Rate(runs, "W1", "occt:Geom_BSplineCurve::D0", n,
       [&] { return SumPositions(*curve, t); });
  Rate(runs, "W1", "occt:GeomAdaptor_Curve::D0", n,
       [&] { return SumPositions(adaptor, t); });
  Rate(runs, "W2", "occt:Geom_BSplineCurve::D1", n,
       [&] { return SumFirstDerivatives(*curve, t); });
  Rate(runs, "W2", "occt:GeomAdaptor_Curve::D1", n,
       [&] { return SumFirstDerivatives(adaptor, t); });
}

void RunSurface(int runs) {
  const Handle(Geom_BSplineSurface) surface =
      freeform::bench::SurfaceOf(freeform::bench::W3Surface());
  const GeomAdaptor_Surface adaptor(surface);
  const std::vector<double> t = UniformParameters(kGrid);
  const double n = static_cast<double>(t.size() * t.size());
  Rate(runs, "W3", "occt:Geom_BSplineSurface::D0", n,
       [&] { return SumGrid(*surface, t); });
  Rate(runs, "W3", "occt:GeomAdaptor_Surface::D0", n,
       [&] { return SumGrid(adaptor, t); });
}

void RunBezier(int runs) {
  const std::vector<double> points = freeform::bench::RandomPoints(3, 4, 3);
  TColgp_Array1OfPnt poles(1, 4);
  for (int i = 0; i < 4; ++i) {
    poles.SetValue(i + 1,
                   gp_Pnt(points[3 * i], points[3 * i + 1], points[3 * i + 2]));
  }
  const Handle(Geom_BezierCurve) bezier = new Geom_BezierCurve(poles);
  const GeomAdaptor_Curve adaptor(bezier);
  const std::vector<double> t = UniformParameters(kBezierPoints);
  const double n = static_cast<double>(t.size());
  Rate(runs, "W4", "occt:Geom_BezierCurve::D0", n,
       [&] { return SumPositions(*bezier, t); });
  Rate(runs, "W4", "occt:GeomAdaptor_Curve::D0", n,
       [&] { return SumPositions(adaptor, t); });
}

double SumPoles(const Geom_BSplineCurve& curve) {
  double sum = 0;
  for (int i = 1; i <= curve.NbPoles(); ++i) sum += Sum(curve.Pole(i).XYZ());
  return sum;
}

void RunInterpolation(int runs) {
  const std::vector<double> points =
      freeform::bench::W5Points(kInterpolationPoints);
  const int count = static_cast<int>(kInterpolationPoints);
  const Handle(TColgp_HArray1OfPnt) data = new TColgp_HArray1OfPnt(1, count);
  for (int i = 0; i < count; ++i) {
    data->SetValue(i + 1,
                   gp_Pnt(points[3 * i], points[3 * i + 1], points[3 * i + 2]));
  }
  Handle(Geom_BSplineCurve) result;
  const double seconds = BestSeconds(runs, [&] {
    GeomAPI_Interpolate interpolate(data, /*PeriodicFlag=*/false, 1e-9);
    interpolate.Perform();
    result = interpolate.Curve();
  });
  PrintSeconds("W5", "occt:GeomAPI_Interpolate", seconds, SumPoles(*result));
}

void RunElevation(int runs) {
  const Handle(Geom_BSplineCurve) curve =
      freeform::bench::Curve3d(freeform::bench::RandomSpline(1, 100, 3));
  Handle(Geom_BSplineCurve) copy;
  const double copy_seconds = BestSeconds(runs, [&] {
    for (int r = 0; r < kElevations; ++r) {
      copy = Handle(Geom_BSplineCurve)::DownCast(curve->Copy());
    }
  });
  const double elevate_seconds = BestSeconds(runs, [&] {
    for (int r = 0; r < kElevations; ++r) {
      copy = Handle(Geom_BSplineCurve)::DownCast(curve->Copy());
      copy->IncreaseDegree(curve->Degree() + 1);
    }
  });
  PrintSeconds("W6", "occt:Geom_BSplineCurve::IncreaseDegree",
               (elevate_seconds - copy_seconds) / kElevations, SumPoles(*copy));
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = freeform::bench::RunsFromArguments(argc, argv);
  try {
    RunCurves(runs);
    RunSurface(runs);
    RunBezier(runs);
    RunInterpolation(runs);
    RunElevation(runs);
  } catch (const Standard_Failure& failure) {
    std::fprintf(stderr, "OpenCASCADE: %s\n", failure.GetMessageString());
    return 1;
  }
  return 0;
}
