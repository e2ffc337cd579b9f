// The reference generator of tests/core/occt_interpolate_reference.inc: runs
// OpenCASCADE's GeomAPI_Interpolate on deterministic pseudo-random data
// (the workloads' LCG, workloads.h) and prints, as a C++ include file, every
// input and OpenCASCADE's result (degree, poles, distinct knots with their
// multiplicities and the flat knot sequence). core_test checks that
// InterpolateCurve with KnotRule::kAtParameters reproduces each case
// (docs/references.md, 'Interpolation with knots at the parameters
// (OpenCASCADE rule)').
//
// The cases: N = 2, 3, 4, 5, 7, 20, 200 points, planar (z = 0) and 3D, each
// without tangents, with Load(start, end, Scale) for Scale false and true;
// one-sided tangents (Load(Tangents, TangentFlags, Scale) with one end
// flagged) for N = 3, 7, 20; the caller's parameters (not starting at 0) for
// N = 5, 20; periodic curves (PeriodicFlag) for N = 2, 3, 4, 7, 20 without
// a tangent and with the first point's tangent flagged. Not covered, because
// the core does not reproduce them: a single flagged tangent with N = 2
// (OpenCASCADE then uses the unflagged entry of the tangent array), interior
// tangents, and periodic curves with Load(start, end) (which puts the end
// tangent at the last point, not at the seam).
//
// Built only with -DFREEFORM_PEER_BENCHMARKS=ON when CMake finds
// OpenCASCADE; regenerate the file with
//   options="-DFREEFORM_PEER_BENCHMARKS=ON -DFREEFORM_BUILD_TESTS=OFF"
//   cmake -S . -B build/occt -G Ninja $options
//   cmake --build build/occt --target occt_interpolate_reference
//   output=tests/core/occt_interpolate_reference.inc
//   build/occt/bench/occt_interpolate_reference > $output
#include <GeomAPI_Interpolate.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Standard_Failure.hxx>
#include <Standard_Version.hxx>
#include <TColStd_HArray1OfBoolean.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_Array1OfVec.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>
#include <memory>
#include <string>
#include <vector>

#include "workloads.h"

namespace {

using freeform::bench::Lcg;

// Which tangents a case loads.
enum class Tangents { kNone, kBoth, kStartOnly, kEndOnly };

struct Case {
  std::string name;
  int dimension = 3;
  bool closed = false;
  bool scale = false;
  Tangents tangents = Tangents::kNone;
  std::vector<double> points;      // dimension per point
  std::vector<double> parameters;  // empty: OpenCASCADE's chord lengths
  std::vector<double> start_tangent, end_tangent;
};

// A random walk turning by at most one radian per step, steps of length
// 0.5 to 1.5 (plus a z step in 3D), so consecutive points stay apart.
std::vector<double> Walk(uint64_t seed, int count, int dimension) {
  Lcg lcg(seed);
  std::vector<double> points;
  double x = lcg.Next(), y = lcg.Next(), z = dimension == 3 ? lcg.Next() : 0;
  double heading = 3.0 * lcg.Next();
  for (int k = 0; k < count; ++k) {
    points.push_back(x);
    points.push_back(y);
    if (dimension == 3) points.push_back(z);
    heading += lcg.Next();
    const double step = 1.0 + 0.5 * lcg.Next();
    x += step * std::cos(heading);
    y += step * std::sin(heading);
    if (dimension == 3) z += 0.5 * lcg.Next();
  }
  return points;
}

std::vector<double> RandomVector(Lcg& lcg, int dimension) {
  std::vector<double> vector;
  for (int c = 0; c < dimension; ++c) vector.push_back(2.0 * lcg.Next());
  return vector;
}

// Strictly increasing parameters from 2, steps in [0.5, 1.5).
std::vector<double> RandomParameters(Lcg& lcg, int count) {
  std::vector<double> parameters = {2.0};
  for (int k = 1; k < count; ++k) {
    parameters.push_back(parameters.back() + 1.0 + 0.5 * lcg.Next());
  }
  return parameters;
}

gp_Pnt PointOf(const std::vector<double>& values, size_t k, int dimension) {
  const size_t at = k * static_cast<size_t>(dimension);
  return gp_Pnt(values[at], values[at + 1],
                dimension == 3 ? values[at + 2] : 0.0);
}

gp_Vec VectorOf(const std::vector<double>& values, int dimension) {
  return gp_Vec(values[0], values[1], dimension == 3 ? values[2] : 0.0);
}

// Runs GeomAPI_Interpolate on the case; null when it fails.
Handle(Geom_BSplineCurve) Run(const Case& c) {
  const int n = static_cast<int>(c.points.size()) / c.dimension;
  Handle(TColgp_HArray1OfPnt) points = new TColgp_HArray1OfPnt(1, n);
  for (int k = 0; k < n; ++k) {
    points->SetValue(k + 1,
                     PointOf(c.points, static_cast<size_t>(k), c.dimension));
  }
  try {
    std::unique_ptr<GeomAPI_Interpolate> interpolate;
    if (c.parameters.empty()) {
      interpolate =
          std::make_unique<GeomAPI_Interpolate>(points, c.closed, 1e-9);
    } else {
      Handle(TColStd_HArray1OfReal) parameters =
          new TColStd_HArray1OfReal(1, static_cast<int>(c.parameters.size()));
      for (size_t k = 0; k < c.parameters.size(); ++k) {
        parameters->SetValue(static_cast<int>(k) + 1, c.parameters[k]);
      }
      interpolate = std::make_unique<GeomAPI_Interpolate>(points, parameters,
                                                          c.closed, 1e-9);
    }
    if (c.tangents == Tangents::kBoth) {
      interpolate->Load(VectorOf(c.start_tangent, c.dimension),
                        VectorOf(c.end_tangent, c.dimension), c.scale);
    } else if (c.tangents != Tangents::kNone) {
      TColgp_Array1OfVec tangents(1, n);
      Handle(TColStd_HArray1OfBoolean) flags =
          new TColStd_HArray1OfBoolean(1, n);
      for (int k = 1; k <= n; ++k) {
        tangents.SetValue(k, gp_Vec(0, 0, 0));
        flags->SetValue(k, Standard_False);
      }
      const bool start = c.tangents == Tangents::kStartOnly;
      const int at = start ? 1 : n;
      tangents.SetValue(
          at, VectorOf(start ? c.start_tangent : c.end_tangent, c.dimension));
      flags->SetValue(at, Standard_True);
      interpolate->Load(tangents, flags, c.scale);
    }
    interpolate->Perform();
    if (!interpolate->IsDone()) return nullptr;
    return interpolate->Curve();
  } catch (const Standard_Failure&) {
    return nullptr;
  }
}

void PrintValues(const char* field, const std::vector<double>& values) {
  std::printf("      .%s = {", field);
  for (size_t i = 0; i < values.size(); ++i) {
    std::printf("%s%s%.17g", i == 0 ? "" : ",", i % 3 == 0 ? "\n        " : " ",
                values[i]);
  }
  std::printf("},\n");
}

void PrintCase(const Case& c, const Geom_BSplineCurve& curve) {
  std::vector<double> poles, knots, flat;
  std::vector<int> multiplicities;
  for (int i = 1; i <= curve.NbPoles(); ++i) {
    const gp_Pnt pole = curve.Pole(i);
    poles.push_back(pole.X());
    poles.push_back(pole.Y());
    if (c.dimension == 3) {
      poles.push_back(pole.Z());
    } else if (pole.Z() != 0.0) {  // planar data must stay planar
      std::fprintf(stderr, "%s: pole %d has z = %g\n", c.name.c_str(), i,
                   pole.Z());
      std::exit(1);
    }
  }
  for (int i = 1; i <= curve.NbKnots(); ++i) {
    knots.push_back(curve.Knot(i));
    multiplicities.push_back(curve.Multiplicity(i));
  }
  const TColStd_Array1OfReal& sequence = curve.KnotSequence();
  for (int i = sequence.Lower(); i <= sequence.Upper(); ++i) {
    flat.push_back(sequence(i));
  }
  std::printf("  {.name = \"%s\",\n", c.name.c_str());
  std::printf("      .dimension = %d,\n      .closed = %s,\n", c.dimension,
              c.closed ? "true" : "false");
  std::printf("      .scale = %s,\n", c.scale ? "true" : "false");
  PrintValues("points", c.points);
  PrintValues("parameters", c.parameters);
  PrintValues("start_tangent", c.start_tangent);
  PrintValues("end_tangent", c.end_tangent);
  std::printf("      .degree = %d,\n", curve.Degree());
  PrintValues("poles", poles);
  PrintValues("knots", knots);
  std::printf("      .multiplicities = {");
  for (size_t i = 0; i < multiplicities.size(); ++i) {
    std::printf("%s%s%d", i == 0 ? "" : ",", i % 20 == 0 ? "\n        " : " ",
                multiplicities[i]);
  }
  std::printf("},\n");
  PrintValues("flat_knots", flat);
  std::printf("  },\n");
}

const char* TangentName(Tangents tangents) {
  switch (tangents) {
    case Tangents::kNone:
      return "estimated";
    case Tangents::kBoth:
      return "both";
    case Tangents::kStartOnly:
      return "start";
    case Tangents::kEndOnly:
      return "end";
  }
  return "";
}

// A case of `count` points from `seed` with the given tangents.
Case MakeCase(uint64_t seed, int count, int dimension, bool closed,
              Tangents tangents, bool scale, bool given_parameters) {
  Case c;
  c.dimension = dimension;
  c.closed = closed;
  c.tangents = tangents;
  c.scale = scale && tangents != Tangents::kNone;
  c.points = Walk(seed, count, dimension);
  Lcg lcg(seed + 1000);
  if (given_parameters) c.parameters = RandomParameters(lcg, count + closed);
  if (tangents == Tangents::kBoth || tangents == Tangents::kStartOnly) {
    c.start_tangent = RandomVector(lcg, dimension);
  }
  if (tangents == Tangents::kBoth || tangents == Tangents::kEndOnly) {
    c.end_tangent = RandomVector(lcg, dimension);
  }
  c.name =
      std::string(closed ? "closed" : "open") + " N=" + std::to_string(count) +
      " " + std::to_string(dimension) + "D " + TangentName(tangents) +
      (tangents == Tangents::kNone ? "" : (c.scale ? " scaled" : " unscaled")) +
      (given_parameters ? " given parameters" : "");
  return c;
}

std::vector<Case> Cases() {
  std::vector<Case> cases;
  uint64_t seed = 1;
  for (int count : {2, 3, 4, 5, 7, 20, 200}) {
    for (int dimension : {2, 3}) {
      cases.push_back(MakeCase(seed, count, dimension, false, Tangents::kNone,
                               false, false));
      for (bool scale : {false, true}) {
        cases.push_back(MakeCase(seed, count, dimension, false, Tangents::kBoth,
                                 scale, false));
      }
      ++seed;
    }
  }
  for (int count : {3, 7, 20}) {
    for (Tangents tangents : {Tangents::kStartOnly, Tangents::kEndOnly}) {
      for (bool scale : {false, true}) {
        cases.push_back(
            MakeCase(seed, count, 3, false, tangents, scale, false));
      }
    }
    ++seed;
  }
  for (int count : {5, 20}) {
    cases.push_back(
        MakeCase(seed, count, 3, false, Tangents::kNone, false, true));
    for (bool scale : {false, true}) {
      cases.push_back(
          MakeCase(seed, count, 3, false, Tangents::kBoth, scale, true));
    }
    ++seed;
  }
  for (int count : {2, 3, 4, 7, 20}) {
    for (int dimension : {2, 3}) {
      if (count != 2) {
        cases.push_back(MakeCase(seed, count, dimension, true, Tangents::kNone,
                                 false, false));
      }
      for (bool scale : {false, true}) {
        cases.push_back(MakeCase(seed, count, dimension, true,
                                 Tangents::kStartOnly, scale, false));
      }
      ++seed;
    }
  }
  cases.push_back(MakeCase(seed, 2, 3, true, Tangents::kNone, false, false));
  cases.push_back(MakeCase(seed + 1, 7, 3, true, Tangents::kNone, false, true));
  return cases;
}

}  // namespace

int main() {
  std::printf(
      "// GeomAPI_Interpolate results of OpenCASCADE %s, generated by\n"
      "// bench/peers/occt_interpolate_reference.cc (see its header for the "
      "cases):\n"
      "//   options=\"-DFREEFORM_PEER_BENCHMARKS=ON "
      "-DFREEFORM_BUILD_TESTS=OFF\"\n"
      "//   cmake -S . -B build/occt -G Ninja $options\n"
      "//   cmake --build build/occt --target occt_interpolate_reference\n"
      "//   output=tests/core/occt_interpolate_reference.inc\n"
      "//   build/occt/bench/occt_interpolate_reference > $output\n"
      "// Do not edit. Planar cases (dimension 2) had z = 0 in OpenCASCADE;\n"
      "// closed cases list the periodic curve's poles once (no repeats).\n"
      "// clang-format off\n\n",
      OCC_VERSION_COMPLETE);
  std::printf(
      "struct OcctInterpolateCase {\n"
      "  const char* name;\n"
      "  int dimension;\n"
      "  bool closed;  // PeriodicFlag\n"
      "  bool scale;   // Load(..., Scale)\n"
      "  std::vector<double> points;\n"
      "  std::vector<double> parameters;  // empty: chord lengths\n"
      "  std::vector<double> start_tangent, end_tangent;  // empty: not "
      "loaded\n"
      "  int degree;\n"
      "  std::vector<double> poles;\n"
      "  std::vector<double> knots;\n"
      "  std::vector<int> multiplicities;\n"
      "  std::vector<double> flat_knots;\n"
      "};\n\n"
      "inline const std::vector<OcctInterpolateCase>& OcctInterpolateCases() "
      "{\n"
      "  static const auto* const cases = new "
      "std::vector<OcctInterpolateCase>{\n");
  int failures = 0;
  for (const Case& c : Cases()) {
    const Handle(Geom_BSplineCurve) curve = Run(c);
    if (curve.IsNull()) {
      std::fprintf(stderr, "%s: GeomAPI_Interpolate failed\n", c.name.c_str());
      ++failures;
      continue;
    }
    PrintCase(c, *curve);
  }
  std::printf("  };\n  return *cases;\n}\n// clang-format on\n");
  return failures == 0 ? 0 : 1;
}
