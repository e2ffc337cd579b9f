// The real freeformd binary on a free port, driven through the client
// library and through the freeform CLI.
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "cli_test_util.h"
#include "freeform/client.h"
#include "grpc/reflection/v1alpha/reflection.grpc.pb.h"
#include "nlohmann/json.hpp"
#include "server_process.h"

namespace freeform {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr char kCubicRequest[] = R"({
  "curve": {"bezier": {"control_points": {
      "dimension": 2, "coordinates": [0, 0, 1, 2, 3, 2, 4, 0]}}},
  "parameters": {"list": {"values": [0, 0.5, 1]}},
  "derivative_order": 1
})";

using FreeformdTest = ServerAndCliTest;

// --help lists the server's own flags with their defaults and --version
// prints the version; both exit 0 without serving.
TEST(FreeformdFlags, HelpAndVersionExitZero) {
  const CommandResult help =
      RunCommand(absl::StrCat(FREEFORMD_PATH, " --help"));
  EXPECT_EQ(help.exit_code, 0) << help.output;
  EXPECT_THAT(help.output, HasSubstr("Usage: freeformd"));
  EXPECT_THAT(help.output, HasSubstr("--listen  Address to listen on"));
  EXPECT_THAT(help.output, HasSubstr("(default: 0.0.0.0:50051)"));
  EXPECT_THAT(help.output, HasSubstr("--max_simplify_moves"));
  EXPECT_THAT(help.output,
              HasSubstr("--max_query_work  Work one intersection"));
  EXPECT_THAT(help.output, HasSubstr("--reflection  Serve gRPC server "
                                     "reflection"));
  EXPECT_THAT(help.output, HasSubstr("--tls_allowed_clients  Comma-separated "
                                     "client identities"));
  EXPECT_THAT(help.output,
              HasSubstr("--metrics_listen  Address of the Prometheus metrics"));
  EXPECT_THAT(help.output,
              HasSubstr("--max_connection_age  Age after which a client "
                        "connection is sent GOAWAY"));
  EXPECT_THAT(help.output, HasSubstr("--max_connection_age_grace  Time calls "
                                     "in flight"));
  EXPECT_THAT(help.output, ::testing::Not(HasSubstr("No flags matched")));
  const CommandResult version =
      RunCommand(absl::StrCat(FREEFORMD_PATH, " --version"));
  EXPECT_EQ(version.exit_code, 0) << version.output;
  EXPECT_THAT(version.output,
              ::testing::MatchesRegex("freeformd [0-9]+\\.[0-9]+\\.[0-9]+\n"));
}

TEST_F(FreeformdTest, ClientEvaluatesTheWorkedCubic) {
  absl::StatusOr<CurveSamples> samples =
      client_->EvaluateBezier(2, {0, 0, 1, 2, 3, 2, 4, 0}, {0.0, 0.5, 1.0}, 1);
  ASSERT_TRUE(samples.ok()) << samples.status();
  EXPECT_THAT(samples->derivatives[0], ElementsAre(0, 0, 2, 1.5, 4, 0));
  EXPECT_THAT(samples->Point(1, 0), ElementsAre(3, 6));
}

TEST_F(FreeformdTest, CliEvalPrintsPointsAndDerivatives) {
  const std::string file = WriteTempFile(kCubicRequest);
  CommandResult json = RunCommand(Cli(absl::StrCat("eval --file ", file)));
  EXPECT_EQ(json.exit_code, 0) << json.output;
  EXPECT_EQ(json.output, R"({"dimension":2,"count":3,"derivatives":[)"
                         R"({"dimension":2,"coordinates":[0,0,2,1.5,4,0]},)"
                         R"({"dimension":2,"coordinates":[3,6,4.5,0,3,-6]}]})"
                         "\n");

  CommandResult csv =
      RunCommand(Cli(absl::StrCat("eval --format csv < ", file)));
  EXPECT_EQ(csv.exit_code, 0) << csv.output;
  EXPECT_EQ(csv.output,
            "index,x0,x1,d1x0,d1x1\n0,0,0,3,6\n1,2,1.5,4.5,0\n2,4,0,3,-6\n");
  unlink(file.c_str());
}

TEST_F(FreeformdTest, CliReportsFieldViolationsAndServerStaysUp) {
  const std::string bad_requests[] = {
      R"({"curve": {"bezier": {"control_points": {"dimension": 2,
          "coordinates": [0, 0, 1]}}}, "parameters": {"list": {"values": [0]}}})",
      R"({"curve": {"bezier": {"control_points": {"dimension": 2,
          "coordinates": [0, "NaN", 1, 1]}}},
          "parameters": {"list": {"values": [0]}}})",
      R"({"curve": {"bezier": {"control_points": {"dimension": 2}}},
          "parameters": {"list": {"values": [0]}}})",
  };
  const std::string fields[] = {"curve.bezier.control_points.coordinates",
                                "curve.bezier.control_points.coordinates[1]",
                                "curve.bezier.control_points.coordinates"};
  for (size_t i = 0; i < std::size(bad_requests); ++i) {
    const std::string file = WriteTempFile(bad_requests[i]);
    CommandResult result = RunCommand(Cli(absl::StrCat("eval --file ", file)));
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_THAT(result.output, HasSubstr("INVALID_ARGUMENT"));
    EXPECT_THAT(result.output,
                HasSubstr(absl::StrCat("field ", fields[i], ":")));
    unlink(file.c_str());
  }
  EXPECT_TRUE(client_->CheckHealth().ok());
}

TEST_F(FreeformdTest, CliBasisPrintsBlendingFunctions) {
  // The degree-2 B-splines on 0,0,0,1,1,1 at u = 1/2: (1-u)^2, 2u(1-u), u^2.
  const std::string file = WriteTempFile(R"({
    "basis": {"bspline": {"degree": 2, "knots": [0, 0, 0, 1, 1, 1]}},
    "parameters": {"list": {"values": [0.5]}}})");
  CommandResult csv =
      RunCommand(Cli(absl::StrCat("basis --format csv --file ", file)));
  EXPECT_EQ(csv.exit_code, 0) << csv.output;
  EXPECT_EQ(csv.output, "index,f0,f1,f2\n0,0.25,0.5,0.25\n");
  unlink(file.c_str());
}

// The cubic through five planar points from a CSV file (docs/references.md,
// 'Worked example: a cubic B-spline through five planar points'):
// chord-length parameters 0, 5/17, 9/17, 14/17, 1.
TEST_F(FreeformdTest, CliInterpolatesPointsFromCsv) {
  const std::string file = WriteTempFile("x,y\n0,0\n3,4\n-1,4\n-4,0\n-4,-3\n");
  CommandResult result =
      RunCommand(Cli(absl::StrCat("interpolate --degree 3 --csv ", file)));
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_THAT(result.output,
              HasSubstr(R"("parameters":[0,0.29411764705882354,)"
                        R"(0.52941176470588236,0.82352941176470584,1])"));
  EXPECT_THAT(result.output, HasSubstr(R"("bspline":{"degree":3)"));
  unlink(file.c_str());
}

// --svg draws the control polygon and the result of subdivision and
// tessellation, in a picture that scales (a viewBox).
TEST_F(FreeformdTest, CliDrawsSvg) {
  for (const char* command :
       {"subdivide --file " FREEFORM_SOURCE_DIR "/examples/chaikin.json",
        "tessellate --file " FREEFORM_SOURCE_DIR
        "/examples/nurbs_circle_polyline.json"}) {
    CommandResult result = RunCommand(Cli(absl::StrCat(command, " --svg -")));
    EXPECT_EQ(result.exit_code, 0) << result.output;
    EXPECT_THAT(result.output, HasSubstr("<svg"));
    EXPECT_THAT(result.output, HasSubstr("viewBox=\"0 0 800 "));
    EXPECT_THAT(result.output, HasSubstr("</svg>"));
    EXPECT_THAT(result.output, HasSubstr("stroke=\"#1f5fbf\""));
  }
}

TEST_F(FreeformdTest, CliSurfaceBasis) {
  // Bilinear Bernstein products at (1/2, 1/4): (1/2)(3/4), (1/2)(1/4), ...
  const std::string file = WriteTempFile(R"({
    "tensor": {"u": {"bernstein": {"degree": 1}},
               "v": {"bernstein": {"degree": 1}}},
    "parameters": {"points": {"uv": [0.5, 0.25]}}})");
  CommandResult csv = RunCommand(
      Cli(absl::StrCat("basis --surface --format csv --file ", file)));
  EXPECT_EQ(csv.exit_code, 0) << csv.output;
  EXPECT_EQ(csv.output, "index,f0,f1,f2,f3\n0,0.375,0.125,0.375,0.125\n");
  unlink(file.c_str());
}

// The Utah teapot (32 bicubic patches) meshed by the CLI: a valid OBJ with
// every face on existing vertices, unit normals, and vertices on the patches.
TEST_F(FreeformdTest, CliMeshesTheTeapotAsObj) {
  char path[] = "/tmp/freeform_teapot_XXXXXX";
  const int fd = mkstemp(path);
  ASSERT_GE(fd, 0);
  close(fd);
  CommandResult result = RunCommand(Cli(absl::StrCat(
      "mesh --bezier-patches " FREEFORM_SOURCE_DIR "/examples/teapot.json ",
      "--grid 8 --obj ", path)));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::ifstream obj(path);
  std::string line;
  size_t vertices = 0, normals = 0, faces = 0, groups = 0;
  double max_z = -1e300, min_z = 1e300;
  while (std::getline(obj, line)) {
    std::istringstream fields(line);
    std::string kind;
    fields >> kind;
    if (kind == "v") {
      double x, y, z;
      fields >> x >> y >> z;
      max_z = std::max(max_z, z);
      min_z = std::min(min_z, z);
      ++vertices;
    } else if (kind == "vn") {
      double x, y, z;
      fields >> x >> y >> z;
      EXPECT_NEAR(std::sqrt(x * x + y * y + z * z), 1.0, 1e-12) << line;
      ++normals;
    } else if (kind == "f") {
      std::string corner;
      for (int c = 0; c < 3; ++c) {
        fields >> corner;
        const size_t index = std::stoul(corner.substr(0, corner.find('/')));
        EXPECT_GE(index, 1u);
        EXPECT_LE(index, 32u * 64u);
      }
      ++faces;
    } else if (kind == "g") {
      ++groups;
    }
  }
  EXPECT_EQ(vertices, 32u * 8 * 8);
  EXPECT_EQ(normals, vertices);
  EXPECT_EQ(faces, 32u * 2 * 7 * 7);
  EXPECT_EQ(groups, 32u);
  // The lid's knob tops out at z = 3.15 and the bottom sits at z = 0.
  EXPECT_NEAR(max_z, 3.15, 1e-12);
  EXPECT_NEAR(min_z, 0.0, 1e-12);
  unlink(path);
}

TEST_F(FreeformdTest, CliHealth) {
  CommandResult result = RunCommand(Cli("health"));
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(result.output, "SERVING\n");
}

TEST_F(FreeformdTest, LargeBatchStreamsAndMatchesUnary) {
  v1::EvaluateCurveRequest request;
  v1::Points* points =
      request.mutable_curve()->mutable_bezier()->mutable_control_points();
  points->set_dimension(3);
  for (int i = 0; i < 3 * 8; ++i) points->add_coordinates(std::sin(i));
  request.mutable_parameters()->mutable_range()->set_count(1'000'000);
  absl::StatusOr<CurveSamples> unary = client_->EvaluateCurve(request);
  absl::StatusOr<CurveSamples> streamed =
      client_->EvaluateCurveStreamed(request);
  ASSERT_TRUE(unary.ok()) << unary.status();
  ASSERT_TRUE(streamed.ok()) << streamed.status();
  EXPECT_EQ(unary->derivatives, streamed->derivatives);
}

// ListServices asks server reflection on `channel` for the names of the
// services it serves.
absl::StatusOr<std::vector<std::string>> ListServices(
    const std::shared_ptr<grpc::Channel>& channel) {
  namespace reflection = grpc::reflection::v1alpha;
  auto stub = reflection::ServerReflection::NewStub(channel);
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() +
                       std::chrono::seconds(10));
  auto stream = stub->ServerReflectionInfo(&context);
  reflection::ServerReflectionRequest request;
  request.set_list_services("");
  stream->Write(request);
  stream->WritesDone();
  std::vector<std::string> names;
  reflection::ServerReflectionResponse response;
  while (stream->Read(&response)) {
    for (const auto& service : response.list_services_response().service()) {
      names.push_back(service.name());
    }
  }
  const grpc::Status status = stream->Finish();
  if (!status.ok()) {
    return absl::Status(static_cast<absl::StatusCode>(status.error_code()),
                        status.error_message());
  }
  return names;
}

TEST_F(FreeformdTest, ReflectionListsTheServices) {
  absl::StatusOr<std::vector<std::string>> names =
      ListServices(client_->channel());
  ASSERT_TRUE(names.ok()) << names.status();
  EXPECT_THAT(*names, ::testing::IsSupersetOf({"freeform.v1.CurveService",
                                               "freeform.v1.SurfaceService",
                                               "grpc.health.v1.Health"}));
  // Once: the reflection service is registered once per server.
  EXPECT_EQ(std::count(names->begin(), names->end(),
                       "grpc.reflection.v1alpha.ServerReflection"),
            1);
}

// --reflection=false: the reflection service is gone (UNIMPLEMENTED, as
// for any method the server does not have); the rest serves as before.
TEST(FreeformdFlags, ReflectionCanBeTurnedOff) {
  ServerProcess server({"--reflection=false"});
  ASSERT_GT(server.port(), 0);
  auto client = Client::Create({.target = server.address()});
  ASSERT_TRUE(client.ok()) << client.status();
  EXPECT_EQ(ListServices((*client)->channel()).status().code(),
            absl::StatusCode::kUnimplemented);
  EXPECT_TRUE((*client)->CheckHealth().ok());
  absl::StatusOr<CurveSamples> samples =
      (*client)->EvaluateBezier(1, {0, 1}, {0.25});
  ASSERT_TRUE(samples.ok()) << samples.status();
  EXPECT_THAT(samples->derivatives[0], ElementsAre(0.25));
}

TEST_F(FreeformdTest, SigtermDrainsAndExitsZero) {
  EXPECT_TRUE(client_->CheckHealth().ok());
  EXPECT_EQ(server_.StopWith(SIGTERM, std::chrono::seconds(10)), 0);
}

TEST_F(FreeformdTest, SigintExitsZero) {
  EXPECT_EQ(server_.StopWith(SIGINT, std::chrono::seconds(10)), 0);
}

// With --log_format=json every line freeformd writes is one JSON object:
// the announcement on stdout and the whole log on stderr, including access
// lines whose messages hold quotes (a field violation's text).
TEST(FreeformdLogFormat, JsonLogLinesAllParse) {
  const std::string log_path = absl::StrCat(
      testing::TempDir(), "/freeformd_json_log_", getpid(), ".log");
  std::remove(log_path.c_str());
  {
    ServerProcess server({"--log_format=json", "--log_level=debug"}, log_path);
    ASSERT_GT(server.port(), 0);
    ASSERT_EQ(server.announced().size(), 1u);
    const nlohmann::json announcement =
        nlohmann::json::parse(server.announced()[0]);
    EXPECT_EQ(announcement.at("level"), "info");
    EXPECT_EQ(announcement.at("message"),
              absl::StrCat("freeformd listening on 127.0.0.1:", server.port()));
    auto client =
        Client::Create({.target = absl::StrCat("127.0.0.1:", server.port())});
    ASSERT_TRUE(client.ok()) << client.status();
    // Three coordinates in dimension 2: refused with a quoted reason.
    absl::StatusOr<CurveSamples> refused =
        (*client)->EvaluateBezier(2, {0, 0, 1}, {0.5}, 0);
    EXPECT_FALSE(refused.ok());
    EXPECT_EQ(server.StopWith(SIGTERM, std::chrono::seconds(10)), 0);
  }
  std::ifstream log(log_path);
  std::string line;
  int lines = 0;
  while (std::getline(log, line)) {
    ++lines;
    const nlohmann::json entry = nlohmann::json::parse(line, nullptr, false);
    ASSERT_FALSE(entry.is_discarded()) << "not JSON: " << line;
    EXPECT_TRUE(entry.contains("time") && entry.contains("level") &&
                entry.contains("message"))
        << line;
  }
  EXPECT_GE(lines, 3);  // serving, the refused call, stopped
  std::remove(log_path.c_str());
}

// A connection age or grace gRPC would misread: freeformd exits 1 naming
// the flag, before it listens. A duration that does not parse is Abseil's
// to refuse, also with exit 1.
TEST(FreeformdFlags, BadConnectionAgesRefuseToStart) {
  struct Refusal {
    std::string flags;
    std::string message;
  };
  const Refusal refusals[] = {
      {.flags = "--max_connection_age=-30s",
       .message = "cannot start: INVALID_ARGUMENT: --max_connection_age=-30s "
                  "is negative"},
      {.flags = "--max_connection_age=100ms",
       .message = "--max_connection_age=100ms is under the shortest age, 1s"},
      {.flags = "--max_connection_age=1000h",
       .message = "--max_connection_age=1000h is over the longest gRPC "
                  "accepts"},
      {.flags = "--max_connection_age_grace=5s",
       .message = "--max_connection_age_grace=5s needs --max_connection_age"},
      {.flags = "--max_connection_age=30s --max_connection_age_grace=-1s",
       .message = "--max_connection_age_grace=-1s is negative"},
      {.flags = "--max_connection_age=thirty", .message = "max_connection_age"},
  };
  for (const Refusal& refusal : refusals) {
    const CommandResult result = RunCommand(
        absl::StrCat(FREEFORMD_PATH, " --listen=127.0.0.1:0 ", refusal.flags));
    EXPECT_EQ(result.exit_code, 1) << refusal.flags << "\n" << result.output;
    EXPECT_THAT(result.output, HasSubstr(refusal.message)) << refusal.flags;
    EXPECT_THAT(result.output, ::testing::Not(HasSubstr("listening on")));
  }
}

TEST(FreeformdLogFormat, UnknownFormatIsRefused) {
  ServerProcess server({"--log_format=xml"});
  EXPECT_EQ(server.port(), 0);
  EXPECT_EQ(server.WaitForExit(std::chrono::seconds(10)), 2);
}

}  // namespace
}  // namespace freeform
