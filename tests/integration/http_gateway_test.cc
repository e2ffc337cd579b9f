// The HTTP/JSON gateway (--http_listen, docs/http.md) of the real
// freeformd: the Connect protocol's unary and streaming forms against the
// gRPC answers, its errors, bounds, deadline, CORS, metrics, TLS rules and
// shutdown.
#include <gmock/gmock.h>
#include <google/protobuf/util/json_util.h>
#include <google/protobuf/util/message_differencer.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"
#include "cli_test_util.h"
#include "freeform/v1/curve_service.grpc.pb.h"
#include "google/rpc/error_details.pb.h"
#include "http_client.h"
#include "metrics_scrape.h"
#include "nlohmann/json.hpp"
#include "server_process.h"

namespace freeform {
namespace {

using ::google::protobuf::util::MessageDifferencer;
using ::testing::HasSubstr;
using ::testing::Optional;
using Clock = std::chrono::steady_clock;

constexpr char kEvaluatePath[] = "/freeform.v1.CurveService/Evaluate";
constexpr char kEvaluateStreamPath[] =
    "/freeform.v1.CurveService/EvaluateStream";

std::string ReadFile(const std::string& path) {
  std::ifstream file(path);
  std::stringstream contents;
  contents << file.rdbuf();
  return contents.str();
}

std::string CubicJson() {
  return ReadFile(FREEFORM_SOURCE_DIR "/examples/cubic_bezier.json");
}

template <typename Message>
Message FromJson(const std::string& json) {
  Message message;
  EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(json, &message).ok())
      << json;
  return message;
}

// A Bezier curve of degree 60 at 2,000,000 parameters: about a second of
// work.
std::string HeavyEvaluateJson() {
  nlohmann::json coordinates = nlohmann::json::array();
  for (int i = 0; i < 3 * 61; ++i) coordinates.push_back((i * 37 % 101) / 7.0);
  return nlohmann::json{
      {"curve",
       {{"bezier",
         {{"control_points",
           {{"dimension", 3}, {"coordinates", coordinates}}}}}}},
      {"parameters", {{"range", {{"count", 2000000}}}}}}
      .dump();
}

class HttpGatewayTest : public ::testing::Test {
 protected:
  HttpGatewayTest()
      : server_({"--http_listen=127.0.0.1:0", "--metrics_listen=127.0.0.1:0",
                 "--http_cors_origins=https://app.example"}),
        stub_(v1::CurveService::NewStub(grpc::CreateChannel(
            server_.address(), grpc::InsecureChannelCredentials()))) {}

  std::string Url(absl::string_view path) const {
    return absl::StrCat("http://127.0.0.1:", server_.http_port(), path);
  }

  ServerProcess server_;
  std::unique_ptr<v1::CurveService::Stub> stub_;
  HttpClient http_;
};

TEST_F(HttpGatewayTest, UnaryJsonMatchesTheGrpcAnswer) {
  ASSERT_GT(server_.http_port(), 0);
  const HttpReply reply =
      http_.Post(Url(kEvaluatePath), "application/json", CubicJson());
  ASSERT_EQ(reply.status, 200) << reply.curl_error << reply.body;
  EXPECT_EQ(reply.headers.at("content-type"), "application/json");
  EXPECT_THAT(reply.body, HasSubstr("[0,0,2,1.5,4,0]"));
  EXPECT_THAT(reply.body, HasSubstr("[3,6,4.5,0,3,-6]"));

  grpc::ClientContext context;
  v1::EvaluateCurveResponse grpc_answer;
  ASSERT_TRUE(stub_
                  ->Evaluate(&context,
                             FromJson<v1::EvaluateCurveRequest>(CubicJson()),
                             &grpc_answer)
                  .ok());
  EXPECT_TRUE(MessageDifferencer::Equals(
      FromJson<v1::EvaluateCurveResponse>(reply.body), grpc_answer));

  // The same call as binary proto.
  const HttpReply proto = http_.Post(
      Url(kEvaluatePath), "application/proto",
      FromJson<v1::EvaluateCurveRequest>(CubicJson()).SerializeAsString());
  ASSERT_EQ(proto.status, 200) << proto.body;
  v1::EvaluateCurveResponse proto_answer;
  ASSERT_TRUE(proto_answer.ParseFromString(proto.body));
  EXPECT_TRUE(MessageDifferencer::Equals(proto_answer, grpc_answer));
}

TEST_F(HttpGatewayTest, InvalidRequestIs400WithTheFieldPath) {
  const HttpReply reply = http_.Post(
      Url(kEvaluatePath), "application/json",
      R"({"curve":{"bezier":{"control_points":{"dimension":2,)"
      R"("coordinates":[0,0,1]}}},"parameters":{"list":{"values":[0.5]}}})");
  ASSERT_EQ(reply.status, 400) << reply.body;
  EXPECT_EQ(reply.headers.at("content-type"), "application/json");
  const nlohmann::json error = nlohmann::json::parse(reply.body);
  EXPECT_EQ(error["code"], "invalid_argument");
  ASSERT_EQ(error["details"].size(), 1u) << reply.body;
  const nlohmann::json& detail = error["details"][0];
  EXPECT_EQ(detail["type"], "google.rpc.BadRequest");
  EXPECT_EQ(detail["debug"]["fieldViolations"][0]["field"],
            "curve.bezier.control_points.coordinates");
  // "value" is the BadRequest's binary proto in unpadded base64.
  std::string bytes;
  ASSERT_TRUE(absl::Base64Unescape(detail["value"].get<std::string>(), &bytes));
  google::rpc::BadRequest bad_request;
  ASSERT_TRUE(bad_request.ParseFromString(bytes));
  EXPECT_EQ(bad_request.field_violations(0).field(),
            "curve.bezier.control_points.coordinates");

  // JSON that is not the request message.
  const HttpReply garbage =
      http_.Post(Url(kEvaluatePath), "application/json", R"({"curv": 1})");
  EXPECT_EQ(garbage.status, 400);
  EXPECT_THAT(garbage.body, HasSubstr("freeform.v1.EvaluateCurveRequest"));
}

// OversizedBody sends a Content-Length of 10^11 with a two-byte body over a
// plain socket and returns what came back before the server closed the
// connection, or "" after 5 s.
std::string OversizedBodyAnswer(int port, std::chrono::milliseconds& took) {
  const std::string request = absl::StrCat(
      "POST ", kEvaluatePath,
      " HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
      "Content-Length: 100000000000\r\n\r\n{}");
  const auto start = Clock::now();
  const LoopbackAnswer answer = SendOnLoopback(port, request, 5);
  took = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() -
                                                               start);
  return answer.closed ? answer.bytes : "";
}

TEST_F(HttpGatewayTest, OversizedBodyIsRefusedWithoutBeingRead) {
  std::chrono::milliseconds took{};
  const std::string answer = OversizedBodyAnswer(server_.http_port(), took);
  // The answer and the end of the connection come at once: the server
  // neither waited for the 10^11 bytes nor drained them.
  EXPECT_LT(took, std::chrono::seconds(2));
  EXPECT_THAT(answer, HasSubstr("HTTP/1.1 429 "));
  EXPECT_THAT(answer, HasSubstr("Connection: close"));
  EXPECT_THAT(answer, HasSubstr(R"("code":"resource_exhausted")"));
  EXPECT_THAT(answer, HasSubstr("--http_max_request_bytes"));
}

TEST(HttpGateway, ChunkedBodyIsCutOffAtTheBound) {
  ServerProcess server(
      {"--http_listen=127.0.0.1:0", "--http_max_request_bytes=1000"});
  HttpClient http;
  const std::string url =
      absl::StrCat("http://127.0.0.1:", server.http_port(), kEvaluatePath);
  const std::string large(5000, ' ');
  const HttpReply chunked = http.Post(url, "application/json", large + "{}",
                                      {"Transfer-Encoding: chunked"});
  EXPECT_EQ(chunked.status, 429) << chunked.body;
  EXPECT_THAT(chunked.body, HasSubstr("resource_exhausted"));
  // Under the bound, chunked or not, the call goes through.
  EXPECT_EQ(http.Post(url, "application/json", CubicJson(),
                      {"Transfer-Encoding: chunked"})
                .status,
            200);
}

TEST_F(HttpGatewayTest, ConnectTimeoutMsIsTheCallsDeadline) {
  const auto start = Clock::now();
  const HttpReply reply =
      http_.Post(Url(kEvaluatePath), "application/json", HeavyEvaluateJson(),
                 {"Connect-Timeout-Ms: 50"});
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(2));
  EXPECT_EQ(reply.status, 504) << reply.body.substr(0, 300);
  EXPECT_THAT(reply.body, HasSubstr(R"("code":"deadline_exceeded")"));

  const HttpReply malformed =
      http_.Post(Url(kEvaluatePath), "application/json", CubicJson(),
                 {"Connect-Timeout-Ms: 12345678901"});
  EXPECT_EQ(malformed.status, 400);
  EXPECT_THAT(malformed.body, HasSubstr("Connect-Timeout-Ms"));
}

TEST_F(HttpGatewayTest, StreamEnvelopesCarryTheGrpcStreamsMessages) {
  const std::string request_json =
      R"({"curve":{"bezier":{"control_points":{"dimension":2,)"
      R"("coordinates":[0,0,1,2,3,2,4,0]}}},)"
      R"("parameters":{"range":{"count":300000}},"derivative_order":1})";
  const HttpReply reply =
      http_.Post(Url(kEvaluateStreamPath), "application/connect+json",
                 ConnectEnvelope(request_json));
  ASSERT_EQ(reply.status, 200) << reply.body.substr(0, 300);
  EXPECT_EQ(reply.headers.at("content-type"), "application/connect+json");
  std::vector<Envelope> envelopes;
  ASSERT_TRUE(ConnectEnvelopes(reply.body, envelopes));
  ASSERT_GE(envelopes.size(), 3u);  // two messages or more, then the end
  EXPECT_EQ(envelopes.back().flags, 0x02);
  EXPECT_EQ(envelopes.back().message, "{}");

  grpc::ClientContext context;
  auto reader = stub_->EvaluateStream(
      &context, FromJson<v1::EvaluateCurveRequest>(request_json));
  std::vector<v1::EvaluateCurveResponse> grpc_messages;
  v1::EvaluateCurveResponse message;
  while (reader->Read(&message)) grpc_messages.push_back(message);
  ASSERT_TRUE(reader->Finish().ok());
  ASSERT_EQ(envelopes.size(), grpc_messages.size() + 1);
  for (size_t i = 0; i < grpc_messages.size(); ++i) {
    EXPECT_EQ(envelopes[i].flags, 0);
    EXPECT_TRUE(MessageDifferencer::Equals(
        FromJson<v1::EvaluateCurveResponse>(envelopes[i].message),
        grpc_messages[i]))
        << "message " << i;
  }

  // An error ends the stream with an EndStreamResponse, still 200.
  const HttpReply failed =
      http_.Post(Url(kEvaluateStreamPath), "application/connect+json",
                 ConnectEnvelope(R"({"curve":{"bezier":{"control_points":)"
                                 R"({"dimension":2,"coordinates":[0,0,1]}}},)"
                                 R"("parameters":{"list":{"values":[0.5]}}})"));
  ASSERT_EQ(failed.status, 200);
  envelopes.clear();
  ASSERT_TRUE(ConnectEnvelopes(failed.body, envelopes));
  ASSERT_EQ(envelopes.size(), 1u);
  EXPECT_EQ(envelopes[0].flags, 0x02);
  const nlohmann::json end = nlohmann::json::parse(envelopes[0].message);
  EXPECT_EQ(end["error"]["code"], "invalid_argument");
  EXPECT_EQ(end["error"]["details"][0]["debug"]["fieldViolations"][0]["field"],
            "curve.bezier.control_points.coordinates");

  // A unary content type on a streaming method is not the protocol.
  EXPECT_EQ(
      http_.Post(Url(kEvaluateStreamPath), "application/json", request_json)
          .status,
      415);
}

TEST_F(HttpGatewayTest, UnknownMethodsAre404Unimplemented) {
  for (const char* path :
       {"/freeform.v1.CurveService/Nope", "/grpc.health.v1.Health/Check",
        "/grpc.reflection.v1alpha.ServerReflection/ServerReflectionInfo", "/",
        "/freeform.v1.CurveService/Evaluate/extra"}) {
    const HttpReply reply = http_.Post(Url(path), "application/json", "{}");
    EXPECT_EQ(reply.status, 404) << path;
    EXPECT_THAT(reply.body, HasSubstr(R"("code":"unimplemented")")) << path;
  }
}

TEST_F(HttpGatewayTest, CorsPreflightAnswersOnlyAllowedOrigins) {
  const std::vector<std::string> preflight = {
      "Access-Control-Request-Method: POST",
      "Access-Control-Request-Headers: content-type,connect-timeout-ms"};
  std::vector<std::string> allowed = preflight;
  allowed.push_back("Origin: https://app.example");
  const HttpReply yes = http_.Send("OPTIONS", Url(kEvaluatePath), allowed);
  EXPECT_EQ(yes.status, 204) << yes.curl_error;
  EXPECT_EQ(yes.headers.at("access-control-allow-origin"),
            "https://app.example");
  EXPECT_THAT(yes.headers.at("access-control-allow-methods"),
              HasSubstr("POST"));
  EXPECT_THAT(yes.headers.at("access-control-allow-headers"),
              HasSubstr("Connect-Timeout-Ms"));

  std::vector<std::string> other = preflight;
  other.push_back("Origin: https://elsewhere.example");
  const HttpReply no = http_.Send("OPTIONS", Url(kEvaluatePath), other);
  EXPECT_EQ(no.status, 204);
  EXPECT_FALSE(no.headers.contains("access-control-allow-origin"));
  EXPECT_FALSE(no.headers.contains("access-control-allow-methods"));

  // The call itself carries the header for the allowed origin only.
  EXPECT_EQ(http_
                .Post(Url(kEvaluatePath), "application/json", CubicJson(),
                      {"Origin: https://app.example"})
                .headers.at("access-control-allow-origin"),
            "https://app.example");
  EXPECT_FALSE(http_
                   .Post(Url(kEvaluatePath), "application/json", CubicJson(),
                         {"Origin: https://elsewhere.example"})
                   .headers.contains("access-control-allow-origin"));
}

TEST(HttpGateway, NoCorsHeadersWithoutOrigins) {
  ServerProcess server({"--http_listen=127.0.0.1:0"});
  HttpClient http;
  const std::string url =
      absl::StrCat("http://127.0.0.1:", server.http_port(), kEvaluatePath);
  const HttpReply preflight = http.Send(
      "OPTIONS", url,
      {"Origin: https://app.example", "Access-Control-Request-Method: POST"});
  EXPECT_EQ(preflight.status, 204);
  const HttpReply call = http.Post(url, "application/json", CubicJson(),
                                   {"Origin: https://app.example"});
  EXPECT_EQ(call.status, 200);
  for (const HttpReply* reply : {&preflight, &call}) {
    for (const auto& [name, value] : reply->headers) {
      EXPECT_FALSE(absl::StartsWith(name, "access-control-")) << name;
    }
  }
}

TEST_F(HttpGatewayTest, MetricsCountHttpCallsUnderTheirTransport) {
  ASSERT_EQ(
      http_.Post(Url(kEvaluatePath), "application/json", CubicJson()).status,
      200);
  grpc::ClientContext context;
  v1::EvaluateCurveResponse answer;
  ASSERT_TRUE(stub_
                  ->Evaluate(&context,
                             FromJson<v1::EvaluateCurveRequest>(CubicJson()),
                             &answer)
                  .ok());
  constexpr char kHttpOk[] =
      R"(freeform_calls_total{code="OK",method="CurveService.Evaluate",)"
      R"(transport="http"})";
  constexpr char kGrpcOk[] =
      R"(freeform_calls_total{code="OK",method="CurveService.Evaluate",)"
      R"(transport="grpc"})";
  std::string text;
  const auto give_up = Clock::now() + std::chrono::seconds(10);
  do {
    absl::StatusOr<std::string> scraped =
        HttpGet(server_.metrics_port(), "/metrics");
    ASSERT_TRUE(scraped.ok()) << scraped.status();
    text = *std::move(scraped);
    if (MetricValue(text, kHttpOk) == 1.0 && MetricValue(text, kGrpcOk) == 1.0)
      break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  } while (Clock::now() < give_up);
  EXPECT_THAT(MetricValue(text, kHttpOk), Optional(1.0)) << text;
  EXPECT_THAT(MetricValue(text, kGrpcOk), Optional(1.0));
}

// A remote gRPC client that sends the gateway's metadata keys is still
// counted as grpc: only the gateway knows the process's token.
TEST_F(HttpGatewayTest, GrpcClientsCannotClaimTheHttpTransport) {
  grpc::ClientContext context;
  context.AddMetadata("freeform-gateway", "0123456789abcdef0123456789abcdef");
  context.AddMetadata("freeform-http-client", "ipv4:10.0.0.1:1");
  v1::EvaluateCurveResponse answer;
  ASSERT_TRUE(stub_
                  ->Evaluate(&context,
                             FromJson<v1::EvaluateCurveRequest>(CubicJson()),
                             &answer)
                  .ok());
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  absl::StatusOr<std::string> text =
      HttpGet(server_.metrics_port(), "/metrics");
  ASSERT_TRUE(text.ok());
  EXPECT_THAT(MetricValue(*text, R"(freeform_calls_total{code="OK",)"
                                 R"(method="CurveService.Evaluate",)"
                                 R"(transport="http"})"),
              Optional(0.0));
}

TEST(HttpGateway, RefusesToStartBesideTlsItWouldBypass) {
  const std::string freeformd = FREEFORMD_PATH;
  // The gateway is plaintext: with TLS, loopback only; with mutual TLS,
  // not at all. The flags are checked before the certificates are read.
  struct Refusal {
    std::string flags;
    std::string names;
  };
  const Refusal refusals[] = {
      {.flags = "--tls_cert=/nonexistent/cert.pem "
                "--tls_key=/nonexistent/key.pem --http_listen=0.0.0.0:0",
       .names = "loopback"},
      {.flags = "--tls_cert=/nonexistent/cert.pem "
                "--tls_key=/nonexistent/key.pem "
                "--tls_client_ca=/nonexistent/ca.pem "
                "--http_listen=127.0.0.1:0",
       .names = "--tls_client_ca"},
      {.flags = "--http_listen=127.0.0.1:0 "
                "--http_cors_origins=app.example/path",
       .names = "--http_cors_origins"}};
  for (const Refusal& refusal : refusals) {
    const CommandResult result =
        RunCommand(freeformd + " --listen=127.0.0.1:0 " + refusal.flags);
    EXPECT_EQ(result.exit_code, 1) << refusal.flags << "\n" << result.output;
    EXPECT_THAT(result.output, HasSubstr(refusal.names)) << refusal.flags;
  }
}

TEST(HttpGateway, StopsWithTheServerOnSigterm) {
  ServerProcess server({"--http_listen=127.0.0.1:0"});
  HttpClient http;
  const std::string url =
      absl::StrCat("http://127.0.0.1:", server.http_port(), kEvaluatePath);
  ASSERT_EQ(http.Post(url, "application/json", CubicJson()).status, 200);
  EXPECT_EQ(server.StopWith(SIGTERM, std::chrono::seconds(5)), 0);
  HttpClient after;
  EXPECT_EQ(after.Post(url, "application/json", CubicJson(), {}, 2000).status,
            0);
}

}  // namespace
}  // namespace freeform
