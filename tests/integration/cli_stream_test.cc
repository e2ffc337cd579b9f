// The freeform CLI's streamed answers against the real freeformd: a cubic
// Bezier curve in 3D with first derivatives at 10^6 parameters, written as
// CSV while the chunks arrive (every row checked against the closed form,
// the CLI's peak resident memory bounded), and as JSON lines and one JSON
// document (parsed, complete, correct). Surfaces stream the same way.
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "cli_test_util.h"
#include "nlohmann/json.hpp"
#include "sanitizers.h"

namespace freeform {
namespace {

using ::testing::HasSubstr;

// The cubic Bezier curve with these control points (x, y, z each).
constexpr double kControl[4][3] = {{0, 0, 0}, {1, 2, -1}, {3, 2, 4}, {4, 0, 1}};

// The request for the cubic at `count` uniform parameters on [0, 1] with
// first derivatives.
std::string CubicRequest(size_t count) {
  return absl::StrCat(R"({"curve": {"bezier": {"controlPoints": {
      "dimension": 3, "coordinates": [0, 0, 0, 1, 2, -1, 3, 2, 4, 4, 0, 1]}}},
      "parameters": {"range": {"count": )",
                      count, R"(}}, "derivativeOrder": 1})");
}

// Parameter k of a uniform range of `count` on [0, 1], as the server
// computes it (numpy.linspace: k * step, the last exactly 1).
double Parameter(size_t k, size_t count) {
  if (k + 1 == count) return 1.0;
  return static_cast<double>(k) * (1.0 / static_cast<double>(count - 1));
}

// The cubic's point and first derivative at t (Bernstein form).
std::array<double, 6> Cubic(double t) {
  const double s = 1 - t;
  const double b[4] = {s * s * s, 3 * s * s * t, 3 * s * t * t, t * t * t};
  const double d[3] = {3 * s * s, 6 * s * t, 3 * t * t};
  std::array<double, 6> value{};
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 4; ++i) value[j] += b[i] * kControl[i][j];
    for (int i = 0; i < 3; ++i) {
      value[3 + j] += d[i] * (kControl[i + 1][j] - kControl[i][j]);
    }
  }
  return value;
}

struct Measured {
  int exit_code = -1;
  long max_rss_kib = -1;  // ru_maxrss of the child
  std::string error;      // its stderr
};

// Runs `arguments` (argv[0] the program) with stdout read line by line into
// `on_line` as it comes, and returns the exit code, stderr and ru_maxrss.
// ru_maxrss also counts the forked copy of this test process before exec,
// so it bounds the program's peak from above.
Measured RunMeasured(const std::vector<std::string>& arguments,
                     const std::function<void(std::string_view)>& on_line) {
  Measured measured;
  const std::string error_path = WriteTempFile("");
  int out[2];
  if (pipe(out) != 0) return measured;
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(out[1], STDOUT_FILENO);
    const int error = open(error_path.c_str(), O_WRONLY | O_TRUNC);
    dup2(error, STDERR_FILENO);
    close(out[0]);
    close(out[1]);
    std::vector<char*> argv;
    for (const std::string& argument : arguments) {
      argv.push_back(const_cast<char*>(argument.c_str()));
    }
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(out[1]);
  std::string pending;
  std::vector<char> buffer(1 << 16);
  ssize_t got = 0;
  while ((got = read(out[0], buffer.data(), buffer.size())) > 0) {
    pending.append(buffer.data(), static_cast<size_t>(got));
    size_t start = 0;
    for (size_t end; (end = pending.find('\n', start)) != std::string::npos;
         start = end + 1) {
      on_line(std::string_view(pending).substr(start, end - start));
    }
    pending.erase(0, start);
  }
  if (!pending.empty()) on_line(pending);
  close(out[0]);
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  measured.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  measured.max_rss_kib = usage.ru_maxrss;
  std::ifstream error_file(error_path);
  measured.error.assign(std::istreambuf_iterator<char>(error_file), {});
  return measured;
}

// The resident memory of this process in KiB (VmRSS).
long OwnResidentKiB() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  }
  return -1;
}

class CliStreamTest : public ServerAndCliTest {
 protected:
  // The CLI's argv for `arguments` against this server, reading `request`.
  std::vector<std::string> Argv(std::vector<std::string> arguments,
                                const std::string& request) const {
    arguments.insert(arguments.begin(), FREEFORM_CLI_PATH);
    for (const std::string& more : {std::string("--address"), server_.address(),
                                    std::string("--file"), request}) {
      arguments.push_back(more);
    }
    return arguments;
  }

  // Expects `values` to be the cubic's point and derivative at parameter
  // `index` of `count`, to 1e-12.
  static void ExpectRow(size_t index, size_t count,
                        const std::vector<double>& values, int& failures) {
    const std::array<double, 6> expected = Cubic(Parameter(index, count));
    for (size_t j = 0; j < 6; ++j) {
      if (failures < 10 && std::abs(values[j] - expected[j]) > 1e-12) {
        ADD_FAILURE() << "row " << index << " value " << j << ": " << values[j]
                      << " != " << expected[j];
        ++failures;
      }
    }
  }
};

TEST_F(CliStreamTest, CsvOfAMillionPointsInConstantMemory) {
  constexpr size_t kCount = 1'000'000;
  const std::string request = WriteTempFile(CubicRequest(kCount));
  size_t rows = 0;
  int failures = 0;
  std::string header;
  std::vector<double> values(6);
  const long own_kib = OwnResidentKiB();
  const Measured run =
      RunMeasured(Argv({"eval", "--stream", "--format", "csv"}, request),
                  [&](std::string_view line) {
                    if (header.empty()) {
                      header = line;
                      return;
                    }
                    const char* p = line.data();
                    const char* end = line.data() + line.size();
                    size_t index = 0;
                    p = std::from_chars(p, end, index).ptr;
                    for (double& value : values) {
                      if (p < end && *p == ',') ++p;
                      p = std::from_chars(p, end, value).ptr;
                    }
                    if (index != rows && failures < 10) {
                      ADD_FAILURE() << "row " << rows << " has index " << index;
                      ++failures;
                    }
                    ExpectRow(index, kCount, values, failures);
                    ++rows;
                  });
  ASSERT_EQ(run.exit_code, 0) << run.error;
  EXPECT_EQ(header, "index,x0,x1,x2,d1x0,d1x1,d1x2");
  EXPECT_EQ(rows, kCount);
  // Not a terminal: no progress bar, nothing on stderr.
  EXPECT_EQ(run.error, "");
  std::cerr << "freeform eval --stream --format csv, " << kCount
            << " points: ru_maxrss " << run.max_rss_kib
            << " KiB (this test process: " << own_kib << " KiB)\n";
  // Under AddressSanitizer the freed chunk buffers wait in its quarantine
  // (165 MiB measured); collecting the answer instead would take several
  // times more in either build.
  EXPECT_LT(run.max_rss_kib, (kAddressSanitizer ? 2 : 1) * 100 * 1024);
}

// JSON lines: one object per point, {"index", "point", "d1"}.
TEST_F(CliStreamTest, JsonLinesAreCompleteAndCorrect) {
  constexpr size_t kCount = 100'000;
  const std::string request = WriteTempFile(CubicRequest(kCount));
  size_t rows = 0;
  int failures = 0;
  const Measured run = RunMeasured(
      Argv({"eval", "--stream", "--format", "jsonl"}, request),
      [&](std::string_view line) {
        const nlohmann::json row = nlohmann::json::parse(line);
        std::vector<double> values = row.at("point").get<std::vector<double>>();
        for (double d : row.at("d1").get<std::vector<double>>()) {
          values.push_back(d);
        }
        ASSERT_EQ(values.size(), 6u) << line;
        EXPECT_EQ(row.at("index").get<size_t>(), rows);
        ExpectRow(rows, kCount, values, failures);
        ++rows;
      });
  ASSERT_EQ(run.exit_code, 0) << run.error;
  EXPECT_EQ(rows, kCount);
}

// --format json with --stream: one document {"dimension", "derivativeOrder",
// "points": [...], "count"}, written as the chunks arrive.
TEST_F(CliStreamTest, JsonDocumentIsCompleteAndCorrect) {
  constexpr size_t kCount = 100'000;
  const std::string request = WriteTempFile(CubicRequest(kCount));
  std::string text;
  const Measured run =
      RunMeasured(Argv({"eval", "--stream", "--format", "json"}, request),
                  [&](std::string_view line) { text.append(line); });
  ASSERT_EQ(run.exit_code, 0) << run.error;
  const nlohmann::json document = nlohmann::json::parse(text);
  EXPECT_EQ(document.at("dimension"), 3);
  EXPECT_EQ(document.at("derivativeOrder"), 1);
  EXPECT_EQ(document.at("count"), kCount);
  const nlohmann::json& points = document.at("points");
  ASSERT_EQ(points.size(), kCount);
  int failures = 0;
  for (size_t k = 0; k < kCount; ++k) {
    std::vector<double> values =
        points[k].at("point").get<std::vector<double>>();
    for (double d : points[k].at("d1").get<std::vector<double>>()) {
      values.push_back(d);
    }
    ASSERT_EQ(values.size(), 6u);
    EXPECT_EQ(points[k].at("index").get<size_t>(), k);
    ExpectRow(k, kCount, values, failures);
  }
}

// Without --stream, csv and jsonl print the same rows as the stream.
TEST_F(CliStreamTest, UnaryAndStreamedRowsAgree) {
  const std::string request = WriteTempFile(CubicRequest(1000));
  for (const char* format : {"csv", "jsonl"}) {
    const CommandResult unary = RunCommand(
        Cli(absl::StrCat("eval --format ", format, " --file ", request)));
    const CommandResult streamed = RunCommand(Cli(
        absl::StrCat("eval --stream --format ", format, " --file ", request)));
    ASSERT_EQ(unary.exit_code, 0) << unary.output;
    EXPECT_EQ(unary.output, streamed.output) << format;
  }
}

// surface --stream: a bilinear patch (x = u, y = v, z = uv) on a 300 x 200
// grid as JSON lines with the point, its partials and the normal.
TEST_F(CliStreamTest, SurfaceStreamsRows) {
  const std::string request = WriteTempFile(R"({"surface": {"bezier": {
      "controlNet": {"dimension": 3, "countU": 2, "countV": 2,
                     "coordinates": [0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 1]}}},
      "parameters": {"grid": {"u": {"range": {"count": 300}},
                              "v": {"range": {"count": 200}}}},
      "derivativeOrder": 1, "normals": true})");
  size_t rows = 0;
  const Measured run = RunMeasured(
      Argv({"surface", "--stream", "--format", "jsonl"}, request),
      [&](std::string_view line) {
        const nlohmann::json row = nlohmann::json::parse(line);
        const size_t index = row.at("index").get<size_t>();
        ASSERT_EQ(index, rows);
        const double u = Parameter(index / 200, 300);
        const double v = Parameter(index % 200, 200);
        const auto point = row.at("point").get<std::vector<double>>();
        const auto du = row.at("du").get<std::vector<double>>();
        const auto dv = row.at("dv").get<std::vector<double>>();
        const auto normal = row.at("normal").get<std::vector<double>>();
        ASSERT_EQ(point.size(), 3u);
        EXPECT_NEAR(point[0], u, 1e-12);
        EXPECT_NEAR(point[1], v, 1e-12);
        EXPECT_NEAR(point[2], u * v, 1e-12);
        EXPECT_NEAR(du[2], v, 1e-12);
        EXPECT_NEAR(dv[2], u, 1e-12);
        // S_u x S_v = (-v, -u, 1), normalized.
        const double length = std::sqrt(u * u + v * v + 1);
        EXPECT_NEAR(normal[0], -v / length, 1e-12);
        EXPECT_NEAR(normal[2], 1 / length, 1e-12);
        ++rows;
      });
  ASSERT_EQ(run.exit_code, 0) << run.error;
  EXPECT_EQ(rows, 300u * 200u);
}

// A stream the server refuses: the error on stderr, exit status 1.
TEST_F(CliStreamTest, ServerErrorsEndTheStream) {
  const std::string request = WriteTempFile(R"({"curve": {"bezier": {
      "controlPoints": {"dimension": 2, "coordinates": [0, 0, 1]}}},
      "parameters": {"range": {"count": 10}}})");
  const CommandResult result = RunCommand(
      Cli(absl::StrCat("eval --stream --format csv --file ", request)));
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("INVALID_ARGUMENT"));
}

}  // namespace
}  // namespace freeform
