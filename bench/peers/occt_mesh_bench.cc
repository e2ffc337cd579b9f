// The meshing workloads M1 and M2 of bench/mesh_bench.cc with OpenCASCADE's
// BRepMesh_IncrementalMesh, the peer of docs/benchmarks.md, on the same
// geometry:
//
//   M1: the NURBS torus of radii 3 and 1 (9 x 9 rational quadratic net,
//       nine-point circles both ways), meshed within 1e-3.
//   M2: the W3 surface (bicubic B-spline, 20 x 20 points from LCG seed 2,
//       clamped uniform knots; workloads.h), meshed within 1e-3.
//
// Each surface becomes a Geom_BSplineSurface, a face
// (BRepBuilderAPI_MakeFace with Precision::Confusion()) and is meshed by
// BRepMesh_IncrementalMesh with linear deflection 1e-3 (absolute), the
// angular deflection given (1 rad by default: from 1 rad up the node counts
// no longer fall, so the linear deflection governs; at OCC's default 0.5 the
// angle still adds a quarter of M2's nodes, see docs/benchmarks.md),
// single-threaded. Only the meshing is timed; the face is rebuilt before
// every repetition so the mesh is recomputed.
//
// Built only with -DFREEFORM_PEER_BENCHMARKS=ON when CMake finds
// OpenCASCADE:
//   build/release/bench/occt_mesh_bench [repetitions] [M1|M2] [--check]
//       [--angle=RADIANS] [--tolerance=DEFLECTION]
// (5 repetitions, both workloads, angle 1, deflection 1e-3 by default)
// Prints, per workload, the nodes and triangles of the mesh and the best and
// median CPU time over the repetitions. With --check it also measures how
// far the mesh is from the surface: for each triangle, 7 samples (the
// vertices, the edge midpoints, the centroid) at barycentric coordinates b;
// the distance from the surface at the b-combination of the nodes' (u, v)
// to the b-combination of the nodes (the deviation the deflection is meant
// to bound); the maximum and the triangles beyond the deflection. Samples
// beyond it are also projected onto the surface (GeomAPI_ProjectPointOnSurf;
// the smaller of its nearest answer and the deviation, as it can miss the
// nearest point) for their plain distance to the surface; on the torus every
// sample's exact distance to it, |hypot(hypot(x, y) - 3, z) - 1|, is
// measured too.
//
// Debian 12's libocct-foundation-dev (7.6.3+dfsg1-7) does not install
// NCollection_AliasedArray.hxx, which Poly_Triangulation.hxx (and so
// BRep_Tool.hxx) includes, so the program cannot use Poly_Triangulation: it
// reads the face's triangulation (nodes, their (u, v), triangles and OCC's
// own deflection estimate) from BRepTools::Write's text form instead
// (15 significant digits), outside the timed region.
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopTools_FormatVersion.hxx>
#include <TopoDS_Face.hxx>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <gp_Pnt.hxx>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "peers/occt_geometry.h"
#include "workloads.h"

namespace {

using freeform::SurfaceData;
using freeform::bench::NurbsTorus;
using freeform::bench::SurfaceOf;
using freeform::bench::W3Surface;

double CpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Options {
  int repetitions = 5;
  std::string only;
  bool check = false;
  double angle = 1.0;
  double deflection = 1e-3;
};

// A face's triangulation as BRepTools::Write prints it (1-based node
// indices in `triangles`).
struct Triangulation {
  std::vector<gp_Pnt> nodes;
  std::vector<std::array<double, 2>> uv;  // empty without (u, v) nodes
  std::vector<std::array<int, 3>> triangles;
  double deflection = 0.0;  // OCC's estimate, Poly_Triangulation::Deflection
};

// The triangulation of the meshed single-face `face` (see the header), or
// nothing when it has none.
std::optional<Triangulation> TriangulationOf(const TopoDS_Face& face) {
  std::ostringstream out;
  BRepTools::Write(face, out, /*theWithTriangles=*/Standard_True,
                   /*theWithNormals=*/Standard_False,
                   TopTools_FormatVersion_VERSION_3);
  const std::string text = out.str();
  const size_t at = text.find("\nTriangulations ");
  if (at == std::string::npos) return std::nullopt;
  std::istringstream in(text.substr(at + 1));
  std::string keyword;
  int count = 0;
  in >> keyword >> count;
  if (count != 1) return std::nullopt;
  // Version 3: nodes, triangles, has (u, v), has normals, deflection.
  int nodes = 0, triangles = 0, has_uv = 0, has_normals = 0;
  Triangulation result;
  in >> nodes >> triangles >> has_uv >> has_normals >> result.deflection;
  if (!in || nodes <= 0 || triangles <= 0 || has_normals != 0) {
    return std::nullopt;
  }
  result.nodes.resize(static_cast<size_t>(nodes));
  for (gp_Pnt& p : result.nodes) {
    double x = 0, y = 0, z = 0;
    in >> x >> y >> z;
    p.SetCoord(x, y, z);
  }
  if (has_uv != 0) {
    result.uv.resize(static_cast<size_t>(nodes));
    for (auto& uv : result.uv) in >> uv[0] >> uv[1];
  }
  result.triangles.resize(static_cast<size_t>(triangles));
  for (auto& t : result.triangles) {
    in >> t[0] >> t[1] >> t[2];
    for (const int n : t) {
      if (n < 1 || n > nodes) return std::nullopt;
    }
  }
  if (!in) return std::nullopt;
  return result;
}

// How far the mesh is from the surface (see the header).
void Check(const Handle(Geom_BSplineSurface) & surface,
           const Triangulation& mesh, const Options& options, bool torus) {
  static constexpr double kBary[7][3] = {{1, 0, 0},
                                         {0, 1, 0},
                                         {0, 0, 1},
                                         {0.5, 0.5, 0},
                                         {0, 0.5, 0.5},
                                         {0.5, 0, 0.5},
                                         {1.0 / 3, 1.0 / 3, 1.0 / 3}};
  const double tol = options.deflection;
  double max_deviation = 0.0;
  int over = 0;
  int samples_over = 0;
  double max_projected = 0.0;  // over the samples beyond `tol` only
  int projected_over = 0;      // triangles with a projection beyond `tol`
  int projection_failures = 0;
  double max_torus = 0.0;  // exact distance to the torus, every sample
  int torus_over = 0;
  double max_node_offset = 0.0;  // node against the surface at its (u, v)
  GeomAPI_ProjectPointOnSurf projector;
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  surface->Bounds(u0, u1, v0, v1);
  projector.Init(surface, u0, u1, v0, v1);
  for (const auto& t : mesh.triangles) {
    bool triangle_over = false;
    bool triangle_projected_over = false;
    bool triangle_torus_over = false;
    for (const auto& b : kBary) {
      gp_XYZ flat(0, 0, 0);
      double u = 0, v = 0;
      for (int k = 0; k < 3; ++k) {
        const size_t n = static_cast<size_t>(t[k] - 1);
        flat += b[k] * mesh.nodes[n].XYZ();
        u += b[k] * mesh.uv[n][0];
        v += b[k] * mesh.uv[n][1];
      }
      const gp_Pnt q(flat);
      const double deviation = surface->Value(u, v).Distance(q);
      if (b[0] == 1 || b[1] == 1 || b[2] == 1) {
        max_node_offset = std::max(max_node_offset, deviation);
      }
      max_deviation = std::max(max_deviation, deviation);
      if (deviation > tol) {
        triangle_over = true;
        ++samples_over;
        projector.Perform(q);
        if (projector.NbPoints() > 0) {
          // The extrema may miss the nearest point; the surface point at
          // the sample's (u, v) bounds the distance from above.
          const double d = std::min(projector.LowerDistance(), deviation);
          max_projected = std::max(max_projected, d);
          triangle_projected_over |= d > tol;
        } else {
          ++projection_failures;
        }
      }
      if (torus) {
        const double d =
            std::abs(std::hypot(std::hypot(q.X(), q.Y()) - 3.0, q.Z()) - 1.0);
        max_torus = std::max(max_torus, d);
        triangle_torus_over |= d > tol;
      }
    }
    over += triangle_over;
    projected_over += triangle_projected_over;
    torus_over += triangle_torus_over;
  }
  std::printf(
      "  check: largest deviation |S(sum b_k uv_k) - sum b_k P_k| %.3e "
      "(%.2fx the deflection); %d of %zu triangles beyond %g (%d samples); "
      "nodes off the surface at their (u, v) by at most %.1e; OCC's own "
      "deflection estimate %.3e\n",
      max_deviation, max_deviation / tol, over, mesh.triangles.size(), tol,
      samples_over, max_node_offset, mesh.deflection);
  std::printf(
      "  check: those samples projected onto the surface: largest distance "
      "%.3e, %d triangles beyond %g, %d projections failed\n",
      max_projected, projected_over, tol, projection_failures);
  if (torus) {
    std::printf(
        "  check: exact distance of every sample to the torus: largest "
        "%.3e, %d triangles beyond %g\n",
        max_torus, torus_over, tol);
  }
}

// That `surface` is the net of `data`: the surface's corners against the
// net's (clamped knots: S(0, 0) = P[0][0], S(1, 0) = P[count_u - 1][0],
// ...), which a transposed net fails, and the sum of x + y + z over the
// 1000 x 1000 grid of bench/surface_bench (W3: 37374.6 in
// docs/benchmarks.md).
void CheckGeometry(const Handle(Geom_BSplineSurface) & surface,
                   const SurfaceData& data) {
  double corner_error = 0.0;
  for (const int i : {0, data.count_u - 1}) {
    for (const int j : {0, data.count_v - 1}) {
      const size_t k = static_cast<size_t>(i * data.count_v + j);
      const gp_Pnt net(data.coordinates[3 * k], data.coordinates[3 * k + 1],
                       data.coordinates[3 * k + 2]);
      corner_error = std::max(
          corner_error,
          surface->Value(i == 0 ? 0.0 : 1.0, j == 0 ? 0.0 : 1.0).Distance(net));
    }
  }
  const std::vector<double> grid = freeform::bench::UniformParameters(1000);
  double checksum = 0.0;
  for (const double u : grid) {
    for (const double v : grid) {
      const gp_Pnt p = surface->Value(u, v);
      checksum += p.X() + p.Y() + p.Z();
    }
  }
  std::printf(
      "  geometry: corners off the net's by at most %.1e; grid checksum "
      "%.1f\n",
      corner_error, checksum);
}

void Run(const char* name, const SurfaceData& data, const Options& options,
         bool torus) {
  const Handle(Geom_BSplineSurface) surface = SurfaceOf(data);
  std::vector<double> times;
  TopoDS_Face face;
  int status = 0;
  bool done = true;
  for (int r = 0; r < options.repetitions; ++r) {
    // A new face each time: no triangulation is left to reuse.
    face = BRepBuilderAPI_MakeFace(surface, Precision::Confusion()).Face();
    const double start = CpuSeconds();
    BRepMesh_IncrementalMesh mesher(face, options.deflection,
                                    /*isRelative=*/Standard_False,
                                    options.angle,
                                    /*isInParallel=*/Standard_False);
    times.push_back(CpuSeconds() - start);
    status |= mesher.GetStatusFlags();
    done &= mesher.IsDone() == Standard_True;
  }
  std::sort(times.begin(), times.end());
  const std::optional<Triangulation> mesh = TriangulationOf(face);
  if (!mesh) {
    std::printf("%s: no triangulation (done %d, status flags 0x%x)\n", name,
                done, status);
    return;
  }
  std::printf(
      "%s: %zu nodes, %zu triangles; best %.1f ms, median %.1f ms (CPU, %d "
      "runs); done %d, status flags 0x%x\n",
      name, mesh->nodes.size(), mesh->triangles.size(), 1e3 * times.front(),
      1e3 * times[times.size() / 2], options.repetitions, done, status);
  if (options.check) {
    if (mesh->uv.empty()) {
      std::printf("  check: the triangulation has no (u, v) nodes\n");
      return;
    }
    CheckGeometry(surface, data);
    Check(surface, *mesh, options, torus);
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    Options options;
    bool have_repetitions = false;
    for (int a = 1; a < argc; ++a) {
      const std::string arg = argv[a];
      if (arg == "--check") {
        options.check = true;
      } else if (arg.rfind("--angle=", 0) == 0) {
        options.angle = std::atof(arg.c_str() + 8);
      } else if (arg.rfind("--tolerance=", 0) == 0) {
        options.deflection = std::atof(arg.c_str() + 12);
      } else if (arg == "M1" || arg == "M2") {
        options.only = arg;
      } else if (!have_repetitions) {
        options.repetitions = std::max(1, std::atoi(arg.c_str()));
        have_repetitions = true;
      } else {
        std::fprintf(stderr,
                     "usage: %s [repetitions] [M1|M2] [--check] "
                     "[--angle=RADIANS] [--tolerance=DEFLECTION]\n",
                     argv[0]);
        return 2;
      }
    }
    std::printf(
        "BRepMesh_IncrementalMesh: linear deflection %g (absolute), angular "
        "deflection %g rad, single thread\n",
        options.deflection, options.angle);
    if (options.only != "M2") {
      Run("M1 NURBS torus 3/1", NurbsTorus(3.0, 1.0), options, /*torus=*/true);
    }
    if (options.only != "M1") {
      Run("M2 W3 bicubic 20 x 20", W3Surface(), options, /*torus=*/false);
    }
    return 0;
  } catch (const Standard_Failure& failure) {
    std::fprintf(stderr, "OpenCASCADE failure: %s\n",
                 failure.GetMessageString());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
  }
  return 1;
}
