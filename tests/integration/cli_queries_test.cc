// The freeform CLI's query subcommands and curvature combs against the real
// freeformd, on the request files in examples/ whose answers are known: the
// NURBS circle of radius 2 about (1, -1) (examples/*_circle.json), the
// rational sphere patch of radius 2 (examples/sphere_*.json) and the unit
// circle (examples/nurbs_circle_polyline.json).
#include <gmock/gmock.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "cli_test_util.h"

namespace freeform {
namespace {

using ::testing::DoubleNear;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Pointwise;
using ::testing::SizeIs;

constexpr double kPi = std::numbers::pi;

std::string Example(const std::string& name) {
  return absl::StrCat(FREEFORM_SOURCE_DIR, "/examples/", name);
}

// Runs the CLI and expects it to succeed.
std::string Succeeds(const std::string& command) {
  const CommandResult result = RunCommand(command);
  EXPECT_EQ(result.exit_code, 0) << command << "\n" << result.output;
  return result.output;
}

// The CLI's JSON answer as a `Message`.
template <typename Message>
Message FromJson(const std::string& json) {
  Message message;
  const auto status = google::protobuf::util::JsonStringToMessage(
      json, &message, google::protobuf::util::JsonParseOptions());
  EXPECT_TRUE(status.ok()) << status.ToString() << "\n" << json;
  return message;
}

// CSV output as cells: rows[0] is the header.
std::vector<std::vector<std::string>> CsvCells(const std::string& csv) {
  std::vector<std::vector<std::string>> rows;
  for (absl::string_view line : absl::StrSplit(csv, '\n', absl::SkipEmpty())) {
    rows.push_back(absl::StrSplit(line, ','));
  }
  return rows;
}

double Number(const std::string& cell) {
  double value = 0;
  EXPECT_TRUE(absl::SimpleAtod(cell, &value)) << cell;
  return value;
}

// The numbers of a CSV row from column `first` on.
std::vector<double> Numbers(const std::vector<std::string>& row,
                            size_t first = 0) {
  std::vector<double> values;
  for (size_t k = first; k < row.size(); ++k) values.push_back(Number(row[k]));
  return values;
}

// The picture's points of the element with class `label` (a polyline, or
// the segments' ends of a path), in pixels.
std::vector<std::pair<double, double>> SvgPoints(const std::string& svg,
                                                 const std::string& label) {
  const size_t element = svg.find("class=\"" + label + "\"");
  const size_t end = svg.find('>', element);
  size_t start = svg.find(" points=\"", element);
  if (start > end) start = svg.find(" d=\"", element);
  EXPECT_LT(start, end) << label << "\n" << svg;
  if (start > end) return {};
  start = svg.find('"', start) + 1;
  const std::string data = svg.substr(start, svg.find('"', start) - start);
  std::vector<double> values;
  for (absl::string_view field :
       absl::StrSplit(data, absl::ByAnyChar(" ,ML"), absl::SkipEmpty())) {
    values.push_back(Number(std::string(field)));
  }
  std::vector<std::pair<double, double>> points;
  for (size_t k = 0; k + 1 < values.size(); k += 2) {
    points.emplace_back(values[k], values[k + 1]);
  }
  return points;
}

// The distance of each point from `centre`.
std::vector<double> Radii(const std::vector<std::pair<double, double>>& points,
                          std::pair<double, double> centre) {
  std::vector<double> radii;
  for (const auto& [x, y] : points) {
    radii.push_back(std::hypot(x - centre.first, y - centre.second));
  }
  return radii;
}

using CliQueriesTest = ServerAndCliTest;

// From (4, 3) the circle of radius 2 about (1, -1) is nearest at
// (1, -1) + 2 (3, 4) / 5 = (2.2, 0.6), at distance 3, where the first
// quarter's rational parameter is 2 - sqrt(2): t = (2 - sqrt(2)) / 4.
const double kT = (2 - std::sqrt(2.0)) / 4;

TEST_F(CliQueriesTest, ClosestPointOnTheCircleAsJson) {
  const auto answer = FromJson<v1::ClosestPointResponse>(
      Succeeds(Cli("closest --file " + Example("closest_point_circle.json"))));
  EXPECT_EQ(answer.parameter_count(), 1u);
  EXPECT_THAT(answer.distances(), ElementsAre(DoubleNear(3, 1e-9)));
  EXPECT_THAT(answer.minima_counts(), ElementsAre(1));
  EXPECT_THAT(answer.parameters(), ElementsAre(DoubleNear(kT, 1e-9)));
  EXPECT_THAT(answer.points().coordinates(),
              ElementsAre(DoubleNear(2.2, 1e-9), DoubleNear(0.6, 1e-9)));
}

// --points adds queries: (3, -1) is the circle's seam, nearest at t = 0 and
// t = 1; (1, 4) is nearest at the top (1, 1), t = 1/4.
TEST_F(CliQueriesTest, ClosestPointsFromFlagsAsCsv) {
  const auto rows =
      CsvCells(Succeeds(Cli("closest --format csv --points '3,-1;1,4' --file " +
                            Example("closest_point_circle.json"))));
  ASSERT_THAT(rows, SizeIs(5));
  EXPECT_THAT(rows[0], ElementsAre("query", "distance", "t", "x0", "x1"));
  EXPECT_THAT(Numbers(rows[1]),
              Pointwise(DoubleNear(1e-9), {0.0, 3.0, kT, 2.2, 0.6}));
  EXPECT_EQ(rows[2][0], "1");
  EXPECT_EQ(rows[3][0], "1");
  EXPECT_THAT(std::vector<double>({Number(rows[2][2]), Number(rows[3][2])}),
              ::testing::UnorderedElementsAre(DoubleNear(0, 1e-9),
                                              DoubleNear(1, 1e-9)));
  EXPECT_THAT(Numbers(rows[2], 3), Pointwise(DoubleNear(1e-9), {3.0, -1.0}));
  EXPECT_THAT(Numbers(rows[4]),
              Pointwise(DoubleNear(1e-9), {2.0, 3.0, 0.25, 1.0, 1.0}));
}

TEST_F(CliQueriesTest, ClosestPointsFromACsvFileAndOnASurface) {
  const std::string csv = WriteTempFile("x,y\n1,4\n");
  const auto rows = CsvCells(
      Succeeds(Cli(absl::StrCat("closest --format csv --csv ", csv, " < ",
                                Example("closest_point_circle.json")))));
  ASSERT_THAT(rows, SizeIs(3));
  EXPECT_THAT(Numbers(rows[2]),
              Pointwise(DoubleNear(1e-9), {1.0, 3.0, 0.25, 1.0, 1.0}));
  unlink(csv.c_str());

  // The sphere patch of radius 2 is nearest to (2, 2, 2) radially below it,
  // at 2 (1, 1, 1) / sqrt(3), distance 2 sqrt(3) - 2.
  const auto sphere = CsvCells(
      Succeeds(Cli("closest --surface --format csv --points 2,2,2 --file " +
                   Example("sphere_patch.json"))));
  ASSERT_THAT(sphere, SizeIs(2));
  EXPECT_THAT(sphere[0],
              ElementsAre("query", "distance", "u", "v", "x0", "x1", "x2"));
  const double c = 2 / std::sqrt(3.0);
  EXPECT_NEAR(Number(sphere[1][1]), 2 * std::sqrt(3.0) - 2, 1e-9);
  EXPECT_THAT(Numbers(sphere[1], 4), Pointwise(DoubleNear(1e-9), {c, c, c}));
}

TEST_F(CliQueriesTest, ClosestRejectsBadPointsAndReportsServerErrors) {
  const std::string file = Example("closest_point_circle.json");
  CommandResult result =
      RunCommand(Cli("closest --points '1,x' --file " + file));
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_THAT(result.output, HasSubstr("--points"));
  result = RunCommand(Cli("closest --points '1,2,3' --file " + file));
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_THAT(result.output, HasSubstr("has 3 coordinates"));
  // Queries of the wrong dimension are the server's to refuse.
  const std::string bad = WriteTempFile(R"({"curve": {"bezier": {
      "control_points": {"dimension": 2, "coordinates": [0, 0, 1, 1]}}},
      "queries": {"dimension": 3, "coordinates": [0, 0, 0]}})");
  result = RunCommand(Cli("closest --file " + bad));
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("INVALID_ARGUMENT"));
  EXPECT_THAT(result.output, HasSubstr("field queries"));
  unlink(bad.c_str());
}

// The line x = 1 from (1, -4) to (1, 2) meets the circle at its bottom
// (1, -3) (t = 1/6; the circle's 3/4) and top (1, 1) (t = 5/6; 1/4).
TEST_F(CliQueriesTest, IntersectsTwoCurves) {
  const auto answer = FromJson<v1::IntersectCurvesResponse>(
      Succeeds(Cli("intersect --file " + Example("intersect_curves.json"))));
  EXPECT_THAT(answer.first_parameters(),
              Pointwise(DoubleNear(1e-9), {1.0 / 6, 5.0 / 6}));
  EXPECT_THAT(answer.second_parameters(),
              Pointwise(DoubleNear(1e-9), {0.75, 0.25}));
  EXPECT_THAT(answer.points().coordinates(),
              Pointwise(DoubleNear(1e-9), {1.0, -3.0, 1.0, 1.0}));
}

// The diagonal from the origin leaves the sphere patch at 2 (1, 1, 1) /
// sqrt(3), a third of the way along the segment to (2 sqrt(3), ...).
TEST_F(CliQueriesTest, IntersectsACurveWithASurface) {
  std::string sphere = RunCommand("cat " + Example("sphere_patch.json")).output;
  sphere = sphere.substr(0, sphere.rfind('}'));
  const std::string file = WriteTempFile(absl::StrCat(
      sphere, R"(, "curve": {"bezier": {"control_points": {"dimension": 3,
      "coordinates": [0, 0, 0, 2, 2, 2]}}}})"));
  const auto answer = FromJson<v1::IntersectCurveSurfaceResponse>(
      Succeeds(Cli("intersect --surface --file " + file)));
  const double c = 2 / std::sqrt(3.0);
  EXPECT_THAT(answer.curve_parameters(),
              ElementsAre(DoubleNear(1 / std::sqrt(3.0), 1e-9)));
  EXPECT_THAT(answer.points().coordinates(),
              Pointwise(DoubleNear(1e-9), {c, c, c}));
  unlink(file.c_str());
}

// The circle of radius 2 is 4 pi long, pi a quarter; pi and 2 pi along it
// are its top (1, 1) and its left (-1, -1).
TEST_F(CliQueriesTest, ArcLengthsOfTheCircle) {
  const auto lengths = FromJson<v1::ArcLengthResponse>(
      Succeeds(Cli("arc-length --file " + Example("arc_length_circle.json"))));
  EXPECT_THAT(lengths.lengths(), Pointwise(DoubleNear(1e-8), {4 * kPi, kPi}));

  const auto at = FromJson<v1::ParametersAtArcLengthResponse>(
      Succeeds(Cli("at-length --file " + Example("at_length_circle.json"))));
  EXPECT_THAT(at.parameters(), Pointwise(DoubleNear(1e-8), {0.25, 0.5}));
  EXPECT_THAT(at.points().coordinates(),
              Pointwise(DoubleNear(1e-8), {1.0, 1.0, -1.0, -1.0}));
}

// Equal arc lengths on the circle are its quarters; --count overrides the
// file's 5.
TEST_F(CliQueriesTest, SamplesByArcLengthAsCsv) {
  const auto rows = CsvCells(Succeeds(Cli("sample-length --format csv --file " +
                                          Example("sample_circle.json"))));
  ASSERT_THAT(rows, SizeIs(6));
  EXPECT_THAT(rows[0], ElementsAre("t", "x0", "x1"));
  const double expected[5][3] = {
      {0, 3, -1}, {0.25, 1, 1}, {0.5, -1, -1}, {0.75, 1, -3}, {1, 3, -1}};
  for (int k = 0; k < 5; ++k) {
    EXPECT_THAT(Numbers(rows[k + 1]), Pointwise(DoubleNear(1e-8), expected[k]))
        << k;
  }
  const auto three =
      CsvCells(Succeeds(Cli("sample-length --count 3 --format csv --file " +
                            Example("sample_circle.json"))));
  ASSERT_THAT(three, SizeIs(4));
  EXPECT_THAT(Numbers(three[2]),
              Pointwise(DoubleNear(1e-8), {0.5, -1.0, -1.0}));
}

// The circle of radius 2 bends by 1/2 everywhere, its normal towards
// (1, -1): at t = 0, (3, -1), the tangent is (0, 1) and the normal (-1, 0).
TEST_F(CliQueriesTest, CurvatureOfTheCircleAsCsv) {
  const auto rows = CsvCells(Succeeds(Cli("curvature --format csv --file " +
                                          Example("curvature_circle.json"))));
  ASSERT_THAT(rows, SizeIs(4));
  EXPECT_THAT(rows[0], ElementsAre("index", "curvature", "status", "t0", "t1",
                                   "n0", "n1"));
  for (size_t k = 1; k < rows.size(); ++k) {
    EXPECT_NEAR(Number(rows[k][1]), 0.5, 1e-9);
    EXPECT_EQ(rows[k][2], "REGULAR");
  }
  EXPECT_THAT(Numbers(rows[1], 3),
              Pointwise(DoubleNear(1e-9), {0.0, 1.0, -1.0, 0.0}));
  // t = 1/2 is the left (-1, -1): tangent (0, -1), normal (1, 0).
  EXPECT_THAT(Numbers(rows[3], 3),
              Pointwise(DoubleNear(1e-9), {0.0, -1.0, 1.0, 0.0}));
}

// The sphere patch of radius 2 (S_u x S_v inwards): K = 1/4, H = 1/2, every
// point an umbilic.
TEST_F(CliQueriesTest, CurvatureOfTheSpherePatch) {
  std::string sphere = RunCommand("cat " + Example("sphere_patch.json")).output;
  sphere = sphere.substr(0, sphere.rfind('}'));
  const std::string file = WriteTempFile(absl::StrCat(
      sphere, R"(, "parameters": {"points": {"uv": [0.5, 0.5, 0.2, 0.7]}}})"));
  const auto rows = CsvCells(
      Succeeds(Cli("curvature --surface --format csv --file " + file)));
  ASSERT_THAT(rows, SizeIs(3));
  EXPECT_EQ(rows[0][1], "gaussian");
  for (size_t k = 1; k < rows.size(); ++k) {
    EXPECT_THAT(std::vector<double>({Number(rows[k][1]), Number(rows[k][2]),
                                     Number(rows[k][3]), Number(rows[k][4])}),
                Pointwise(DoubleNear(1e-9), {0.25, 0.5, 0.5, 0.5}));
    EXPECT_EQ(rows[k][5], "UMBILIC");
  }
  unlink(file.c_str());
}

// In the plane the rotation-minimizing frame is the tangent and a unit
// vector across it.
TEST_F(CliQueriesTest, FramesAlongTheCircle) {
  const auto frames = FromJson<v1::RotationMinimizingFramesResponse>(
      Succeeds(Cli("frames --file " + Example("frames_circle.json"))));
  ASSERT_EQ(frames.tangents().coordinates_size(), 10);
  ASSERT_EQ(frames.references().coordinates_size(), 10);
  for (int k = 0; k < 10; k += 2) {
    const double tx = frames.tangents().coordinates(k);
    const double ty = frames.tangents().coordinates(k + 1);
    const double rx = frames.references().coordinates(k);
    const double ry = frames.references().coordinates(k + 1);
    EXPECT_NEAR(std::hypot(tx, ty), 1, 1e-9);
    EXPECT_NEAR(std::hypot(rx, ry), 1, 1e-9);
    EXPECT_NEAR(tx * rx + ty * ry, 0, 1e-9);
  }
}

// The cubic (0,0) (1,3) (2,3) (3,0) peaks at 9/4 though its polygon reaches
// 3; the sphere patch of radius 2 fills [0, 2]^3.
TEST_F(CliQueriesTest, BoundingBoxes) {
  const std::string file = WriteTempFile(R"({"curve": {"bezier": {
      "control_points": {"dimension": 2,
                         "coordinates": [0, 0, 1, 3, 2, 3, 3, 0]}}}})");
  const auto box =
      FromJson<v1::BoundingBoxResponse>(Succeeds(Cli("bbox --file " + file)));
  EXPECT_THAT(box.lower(), Pointwise(DoubleNear(1e-9), {0.0, 0.0}));
  EXPECT_THAT(box.upper(), Pointwise(DoubleNear(1e-9), {3.0, 2.25}));
  unlink(file.c_str());
  const auto sphere = FromJson<v1::BoundingBoxResponse>(
      Succeeds(Cli("bbox --surface --file " + Example("sphere_patch.json"))));
  EXPECT_THAT(sphere.lower(), Pointwise(DoubleNear(1e-9), {0.0, 0.0, 0.0}));
  EXPECT_THAT(sphere.upper(), Pointwise(DoubleNear(1e-9), {2.0, 2.0, 2.0}));
}

// The plane z = 1 cuts the sphere patch of radius 2 in a quarter circle of
// radius sqrt(3) at height 1.
TEST_F(CliQueriesTest, SectionOfTheSpherePatch) {
  const auto section = FromJson<v1::SectionSurfaceResponse>(
      Succeeds(Cli("section --file " + Example("sphere_section.json"))));
  ASSERT_EQ(section.polylines_size(), 1);
  const auto& points = section.polylines(0).points().coordinates();
  ASSERT_GE(points.size(), 9);
  for (int k = 0; k < points.size(); k += 3) {
    EXPECT_NEAR(std::hypot(points[k], points[k + 1]), std::sqrt(3.0), 1e-6);
    EXPECT_NEAR(points[k + 2], 1, 1e-9);
  }
}

// Drawn on (x, y), the quarter circle fills the picture: its box is
// [0, sqrt(3)]^2, 760 pixels wide after the 20-pixel margins, so every
// vertex is 760 pixels from the centre's (20, 780).
TEST_F(CliQueriesTest, SectionDrawnAsSvg) {
  const std::string svg =
      Succeeds(Cli("section --svg - --file " + Example("sphere_section.json")));
  EXPECT_THAT(svg, HasSubstr("<svg"));
  const auto points = SvgPoints(svg, "section");
  ASSERT_GE(points.size(), 3u);
  for (double radius : Radii(points, {20, 780})) {
    EXPECT_NEAR(radius, 760, 0.01);
  }
}

// The unit circle's comb: curvature 1 everywhere, so every tip lies on a
// circle of radius 1 + scale. The default scale makes the longest tooth
// 15% of the drawing (the control polygon's box, 2 wide): 0.3.
TEST_F(CliQueriesTest, TessellateDrawsCurvatureCombs) {
  const std::string command = "tessellate --svg - --combs --file " +
                              Example("nurbs_circle_polyline.json");
  for (const auto& [flags, radius] :
       std::vector<std::pair<std::string, double>>{
           {"", 1.3}, {" --comb-scale 0.5", 1.5}}) {
    const std::string svg = Succeeds(Cli(command + flags));
    const auto curve = SvgPoints(svg, "curve");
    const auto tips = SvgPoints(svg, "envelope");
    const auto teeth = SvgPoints(svg, "comb");
    ASSERT_GE(curve.size(), 8u);
    ASSERT_EQ(tips.size(), curve.size());
    ASSERT_EQ(teeth.size(), 2 * curve.size());
    // The control polygon is the square about the circle's centre.
    const auto control = SvgPoints(svg, "control");
    ASSERT_EQ(control.size(), 9u);
    const std::pair<double, double> centre = {
        (control[0].first + control[4].first) / 2,
        (control[2].second + control[6].second) / 2};
    const double pixels = Radii(curve, centre)[0];
    for (double r : Radii(curve, centre)) EXPECT_NEAR(r, pixels, 0.05);
    for (double r : Radii(tips, centre)) {
      EXPECT_NEAR(r / pixels, radius, 1e-3) << flags;
    }
  }
}

TEST_F(CliQueriesTest, CombsRefuseCurvesThatAreNotPlanar) {
  const std::string file = WriteTempFile(R"({"curve": {"bezier": {
      "control_points": {"dimension": 3,
                         "coordinates": [0, 0, 0, 1, 2, 1, 3, 2, 0]}}},
      "tolerance": 0.01})");
  const CommandResult result =
      RunCommand(Cli("tessellate --svg - --combs --file " + file));
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_THAT(result.output, HasSubstr("2D curves only"));
  EXPECT_THAT(result.output, HasSubstr("dimension 3"));
  unlink(file.c_str());
}

// StlTriangles runs `command` (a tessellate --surface) with --stl to a
// temporary file and returns the triangles it wrote: the facet normal and
// the three corners, 12 floats each.
std::vector<std::array<float, 12>> StlTriangles(const std::string& command) {
  const std::string path = WriteTempFile("");
  const CommandResult result =
      RunCommand(absl::StrCat(command, " --stl ", path));
  EXPECT_EQ(result.exit_code, 0) << result.output;
  std::ifstream file(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(file)),
                          std::istreambuf_iterator<char>());
  unlink(path.c_str());
  if (bytes.size() < 84u) {
    ADD_FAILURE() << "no STL header";
    return {};
  }
  uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  if (bytes.size() != 84u + 50u * count) {
    ADD_FAILURE() << bytes.size() << " bytes for " << count << " triangles";
    return {};
  }
  std::vector<std::array<float, 12>> triangles(count);
  for (uint32_t t = 0; t < count; ++t) {
    std::memcpy(triangles[t].data(), bytes.data() + 84 + 50 * t,
                sizeof(triangles[t]));
  }
  return triangles;
}

// The unit vector from the torus's tube centre circle (radius 3) to p.
std::array<double, 3> AwayFromTube(const float* p) {
  const double ring = std::hypot(p[0], p[1]);
  const double away[3] = {p[0] - 3.0 * p[0] / ring, p[1] - 3.0 * p[1] / ring,
                          p[2]};
  const double length = std::hypot(away[0], away[1], away[2]);
  return {away[0] / length, away[1] / length, away[2] / length};
}

// tessellate --surface --stl writes the closed NURBS torus of
// examples/torus_mesh.json (radii 3 and 1) as binary STL:
// 84 + 50 bytes per triangle, every vertex on the torus (to float
// precision), unit facet normals pointing out of the tube or into it
// consistently.
TEST_F(CliQueriesTest, MeshesATorusAsBinaryStl) {
  const std::vector<std::array<float, 12>> triangles = StlTriangles(
      Cli("tessellate --surface --file " + Example("torus_mesh.json")));
  EXPECT_GT(triangles.size(), 1000u);
  int outward = 0;
  for (const std::array<float, 12>& values : triangles) {
    EXPECT_NEAR(std::hypot(values[0], values[1], values[2]), 1.0, 1e-6);
    float centroid[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      const float* p = values.data() + 3 + 3 * k;
      EXPECT_NEAR(std::hypot(std::hypot(p[0], p[1]) - 3.0, p[2]), 1.0, 1e-5);
      for (int x = 0; x < 3; ++x) centroid[x] += p[x] / 3;
    }
    // Away from the tube's centre circle, or towards it.
    const std::array<double, 3> away = AwayFromTube(centroid);
    outward +=
        away[0] * values[0] + away[1] * values[1] + away[2] * values[2] > 0
            ? 1
            : -1;
  }
  EXPECT_EQ(std::abs(outward), static_cast<int>(triangles.size()));
}

// --max-normal-angle sets the request's limit: more triangles, and the
// torus's exact normals at the ends of every edge within 0.05 rad (to float
// precision); without --surface, or 0, it is refused.
TEST_F(CliQueriesTest, MeshesATorusWithinANormalAngle) {
  const std::string command =
      Cli("tessellate --surface --file " + Example("torus_mesh.json"));
  const size_t plain = StlTriangles(command).size();
  const std::vector<std::array<float, 12>> triangles =
      StlTriangles(command + " --max-normal-angle 0.05");
  EXPECT_GT(triangles.size(), plain);
  double worst = 0.0;
  for (const std::array<float, 12>& values : triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::array<double, 3> a = AwayFromTube(values.data() + 3 + 3 * k);
      const std::array<double, 3> b =
          AwayFromTube(values.data() + 3 + 3 * ((k + 1) % 3));
      const double cross =
          std::hypot(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]);
      worst = std::max(
          worst, std::atan2(cross, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]));
    }
  }
  EXPECT_LE(worst, 0.05 + 1e-5);
  const CommandResult zero = RunCommand(
      Cli(absl::StrCat("tessellate --surface --max-normal-angle 0 --file ",
                       Example("torus_mesh.json"))));
  EXPECT_EQ(zero.exit_code, 1) << zero.output;
  EXPECT_THAT(zero.output, HasSubstr("max_normal_angle"));
  const CommandResult curve =
      RunCommand(Cli(absl::StrCat("tessellate --max-normal-angle 0.05 --file ",
                                  Example("nurbs_circle_polyline.json"))));
  EXPECT_EQ(curve.exit_code, 2) << curve.output;
  EXPECT_THAT(curve.output, HasSubstr("needs --surface"));
}

}  // namespace
}  // namespace freeform
