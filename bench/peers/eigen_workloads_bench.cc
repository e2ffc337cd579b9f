// The curve workloads W1, W2 and W4 of docs/benchmarks.md with Eigen's
// unsupported Splines module (Eigen::Spline<double, 3, 3>: dimension 3,
// degree 3 fixed at compile time), on the same data (workloads.h), for
// scripts/performance.sh. Eigen has no tensor-product surfaces (W3), its
// interpolation (SplineFitting) solves a dense system (W5 at 10^5 points is
// out of reach) and it has no degree elevation (W6).
//
// Built only with -DFREEFORM_PEER_BENCHMARKS=ON when CMake finds Eigen3:
//   build/peers/bench/eigen_workloads_bench [runs]
// Each workload runs `runs` times (default 3); the best wall time counts.
// Output: one RESULT line per figure (peers/peer_result.h).
#include <Eigen/Core>
#include <cstddef>
#include <unsupported/Eigen/Splines>
#include <vector>

#include "peers/peer_result.h"
#include "workloads.h"

namespace {

using freeform::bench::BestSeconds;
using freeform::bench::PrintRate;
using freeform::bench::UniformParameters;
using Spline = Eigen::Spline<double, 3, 3>;

constexpr size_t kCurvePoints = 1'000'000;
constexpr size_t kBezierPoints = 10'000'000;

// SplineOf returns the cubic spline of 3D `points` on the flat `knots`.
Spline SplineOf(const std::vector<double>& points,
                const std::vector<double>& knots) {
  const Eigen::Index count = static_cast<Eigen::Index>(points.size() / 3);
  const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> control(
      points.data(), 3, count);
  const Eigen::Map<const Eigen::Array<double, 1, Eigen::Dynamic>> flat(
      knots.data(), static_cast<Eigen::Index>(knots.size()));
  return Spline(flat, control);
}

// Times `evaluate` (returning its checksum) at every parameter of `t` and
// prints its rate.
template <typename Evaluate>
void Rate(int runs, const char* workload, const char* implementation,
          const std::vector<double>& t, Evaluate&& evaluate) {
  double checksum = 0;
  const double seconds = BestSeconds(runs, [&] {
    checksum = 0;
    for (const double parameter : t) checksum += evaluate(parameter);
  });
  PrintRate(workload, implementation, static_cast<double>(t.size()), seconds,
            checksum);
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = freeform::bench::RunsFromArguments(argc, argv);
  const freeform::bench::SplineData w1 =
      freeform::bench::RandomSpline(1, 100, 3);
  const Spline curve = SplineOf(w1.points, w1.knots);
  const std::vector<double> t = UniformParameters(kCurvePoints);
  Rate(runs, "W1", "eigen:Spline<double,3,3>", t,
       [&](double u) { return curve(u).sum(); });
  Rate(runs, "W2", "eigen:Spline<double,3,3>::derivatives<1>", t,
       [&](double u) { return curve.derivatives<1>(u).sum(); });

  const Spline bezier = SplineOf(freeform::bench::RandomPoints(3, 4, 3),
                                 {0, 0, 0, 0, 1, 1, 1, 1});
  Rate(runs, "W4", "eigen:Spline<double,3,3>", UniformParameters(kBezierPoints),
       [&](double u) { return bezier(u).sum(); });
  return 0;
}
