// The workloads' geometry (workloads.h) as OpenCASCADE objects, for the peer
// programs: B-spline curves (Geom_BSplineCurve, Geom2d_BSplineCurve) and
// tensor-product surfaces (Geom_BSplineSurface, polynomial or rational).
#ifndef FREEFORM_BENCH_PEERS_OCCT_GEOMETRY_H_
#define FREEFORM_BENCH_PEERS_OCCT_GEOMETRY_H_

#include <Geom2d_BSplineCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <cstddef>
#include <gp_Pnt.hxx>
#include <gp_Pnt2d.hxx>
#include <vector>

#include "core_workloads.h"
#include "peers/occt_knots.h"
#include "workloads.h"

namespace freeform::bench {

// SplineOf returns the OCCT B-spline (Geom_BSplineCurve with gp_Pnt poles,
// or Geom2d_BSplineCurve with gp_Pnt2d) of `data`.
template <typename Spline, typename Poles, typename Point>
Handle(Spline) SplineOf(const SplineData& data) {
  const size_t dim = static_cast<size_t>(data.dimension);
  const int count = static_cast<int>(data.points.size() / dim);
  Poles poles(1, count);
  for (int i = 0; i < count; ++i) {
    Point pole;
    for (size_t x = 0; x < dim; ++x) {
      pole.SetCoord(static_cast<int>(x) + 1, data.points[i * dim + x]);
    }
    poles.SetValue(i + 1, pole);
  }
  const OccKnots knots(data.knots);
  return new Spline(poles, knots.values, knots.multiplicities, data.degree);
}

inline Handle(Geom_BSplineCurve) Curve3d(const SplineData& data) {
  return SplineOf<Geom_BSplineCurve, TColgp_Array1OfPnt, gp_Pnt>(data);
}

inline Handle(Geom2d_BSplineCurve) Curve2d(const SplineData& data) {
  return SplineOf<Geom2d_BSplineCurve, TColgp_Array1OfPnt2d, gp_Pnt2d>(data);
}

// The OCCT surface of a 3D tensor-product net of core_workloads.h: row-major
// with u the row index, no weights for a polynomial surface.
inline Handle(Geom_BSplineSurface) SurfaceOf(const SurfaceData& data) {
  TColgp_Array2OfPnt poles(1, data.count_u, 1, data.count_v);
  TColStd_Array2OfReal weights(1, data.count_u, 1, data.count_v);
  for (int i = 0; i < data.count_u; ++i) {
    for (int j = 0; j < data.count_v; ++j) {
      const size_t k = static_cast<size_t>(i * data.count_v + j);
      poles.SetValue(
          i + 1, j + 1,
          gp_Pnt(data.coordinates[3 * k], data.coordinates[3 * k + 1],
                 data.coordinates[3 * k + 2]));
      weights.SetValue(i + 1, j + 1,
                       data.weights.empty() ? 1.0 : data.weights[k]);
    }
  }
  const OccKnots u(data.knots_u);
  const OccKnots v(data.knots_v);
  if (data.weights.empty()) {
    return new Geom_BSplineSurface(poles, u.values, v.values, u.multiplicities,
                                   v.multiplicities, data.degree_u,
                                   data.degree_v);
  }
  return new Geom_BSplineSurface(poles, weights, u.values, v.values,
                                 u.multiplicities, v.multiplicities,
                                 data.degree_u, data.degree_v);
}

}  // namespace freeform::bench

#endif  // FREEFORM_BENCH_PEERS_OCCT_GEOMETRY_H_
