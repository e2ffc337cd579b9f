// OccKnots: a flat knot vector as OpenCASCADE takes it, distinct values and
// their multiplicities (1-based arrays), for the peer programs.
#ifndef FREEFORM_BENCH_PEERS_OCCT_KNOTS_H_
#define FREEFORM_BENCH_PEERS_OCCT_KNOTS_H_

#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <vector>

namespace freeform::bench {

struct OccKnots {
  explicit OccKnots(const std::vector<double>& knots) {
    std::vector<double> distinct;
    std::vector<int> counts;
    for (const double knot : knots) {
      if (!distinct.empty() && distinct.back() == knot) {
        ++counts.back();
      } else {
        distinct.push_back(knot);
        counts.push_back(1);
      }
    }
    const int n = static_cast<int>(distinct.size());
    values.Resize(1, n, false);
    multiplicities.Resize(1, n, false);
    for (int i = 0; i < n; ++i) {
      values.SetValue(i + 1, distinct[static_cast<size_t>(i)]);
      multiplicities.SetValue(i + 1, counts[static_cast<size_t>(i)]);
    }
  }

  TColStd_Array1OfReal values{1, 1};
  TColStd_Array1OfInteger multiplicities{1, 1};
};

}  // namespace freeform::bench

#endif  // FREEFORM_BENCH_PEERS_OCCT_KNOTS_H_
