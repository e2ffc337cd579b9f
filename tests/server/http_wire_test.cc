// The HTTP gateway's wire pieces without a server: the proto3 JSON writer
// (proto_json.h) against protobuf's reader, the Connect protocol's codes,
// errors, envelopes and timeouts (connect_protocol.h), and the CORS origins
// (cors_policy.h).
#include <dirent.h>
#include <gmock/gmock.h>
#include <google/protobuf/util/json_util.h>
#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "absl/strings/match.h"
#include "connect_protocol.h"
#include "cors_policy.h"
#include "errors.h"
#include "freeform/core/status.h"
#include "freeform/v1/curve_service.pb.h"
#include "freeform/v1/surface_service.pb.h"
#include "proto_json.h"

namespace freeform::server {
namespace {

using ::google::protobuf::util::MessageDifferencer;
using ::testing::HasSubstr;

template <typename Message>
Message ReadBack(const std::string& json) {
  Message message;
  EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(json, &message).ok())
      << json;
  return message;
}

template <typename Message>
void ExpectRoundTrip(const Message& message) {
  absl::StatusOr<std::string> json = MessageJson(message);
  ASSERT_TRUE(json.ok()) << json.status();
  EXPECT_TRUE(MessageDifferencer::Equals(ReadBack<Message>(*json), message))
      << *json;
}

// Every example request of the repository reads back equal from the JSON
// the writer makes of it.
TEST(ProtoJson, ExampleRequestsReadBackEqual) {
  const std::string examples = FREEFORM_SOURCE_DIR "/examples";
  int checked = 0;
  for (const char* name :
       {"cubic_bezier.json", "nurbs_circle.json", "bspline_basis.json",
        "closest_point_circle.json", "intersect_curves.json"}) {
    std::ifstream file(examples + "/" + name);
    std::stringstream text;
    text << file.rdbuf();
    v1::EvaluateCurveRequest evaluate;
    if (google::protobuf::util::JsonStringToMessage(text.str(), &evaluate)
            .ok()) {
      ExpectRoundTrip(evaluate);
      ++checked;
    }
  }
  EXPECT_GE(checked, 2);
}

TEST(ProtoJson, WritesProto3sCanonicalForms) {
  v1::EvaluateCurveResponse response;
  response.set_dimension(2);
  response.set_first_index(uint64_t{1} << 60);  // 64-bit: a string
  v1::Points* points = response.add_derivatives();
  points->set_dimension(2);
  for (double value : {0.0, -0.0, 0.1, 1e300, -2.5e-310, 4.0, 1.0 / 3}) {
    points->add_coordinates(value);
  }
  absl::StatusOr<std::string> json = MessageJson(response);
  ASSERT_TRUE(json.ok());
  EXPECT_THAT(*json, HasSubstr(R"("firstIndex":"1152921504606846976")"));
  EXPECT_THAT(*json, HasSubstr(R"("coordinates":[0,-0,0.1,1e+300,)"));
  // count is 0, its default: left out, as protobuf's writer does.
  EXPECT_FALSE(absl::StrContains(*json, "count"));
  ExpectRoundTrip(response);

  points->add_coordinates(std::numeric_limits<double>::quiet_NaN());
  points->add_coordinates(-std::numeric_limits<double>::infinity());
  json = MessageJson(response);
  ASSERT_TRUE(json.ok());
  EXPECT_THAT(*json, HasSubstr(R"("NaN","-Infinity"])"));
}

TEST(ProtoJson, WritesEnumsByNameAndOptionalsWhenSet) {
  v1::EvaluateCurveRequest request;
  request.mutable_parameters()->mutable_range()->set_start(0);  // set: kept
  request.mutable_parameters()->mutable_range()->set_count(3);
  request.set_bezier_algorithm(v1::BEZIER_ALGORITHM_DE_CASTELJAU);
  absl::StatusOr<std::string> json = MessageJson(request);
  ASSERT_TRUE(json.ok());
  EXPECT_THAT(*json, HasSubstr(R"("range":{"start":0,"count":3})"));
  EXPECT_THAT(
      *json, HasSubstr(R"("bezierAlgorithm":"BEZIER_ALGORITHM_DE_CASTELJAU")"));
  ExpectRoundTrip(request);
}

TEST(ProtoJson, EscapesStrings) {
  std::string out;
  AppendJsonString("a\"b\\c\nd\x01\xc3\xa9", out);
  EXPECT_EQ(out, "\"a\\\"b\\\\c\\nd\\u0001\xc3\xa9\"");
}

TEST(ConnectProtocol, MapsCodesAsTheSpecifications) {
  using grpc::StatusCode;
  EXPECT_EQ(connect::HttpStatusOf(StatusCode::INVALID_ARGUMENT), 400);
  EXPECT_EQ(connect::HttpStatusOf(StatusCode::RESOURCE_EXHAUSTED), 429);
  EXPECT_EQ(connect::HttpStatusOf(StatusCode::DEADLINE_EXCEEDED), 504);
  EXPECT_EQ(connect::HttpStatusOf(StatusCode::UNIMPLEMENTED), 501);
  EXPECT_EQ(connect::HttpStatusOf(StatusCode::UNAVAILABLE), 503);
  EXPECT_EQ(connect::HttpStatusOf(StatusCode::CANCELLED), 499);
  EXPECT_EQ(connect::HttpStatusOf(StatusCode::FAILED_PRECONDITION), 400);
  EXPECT_EQ(connect::HttpStatusOf(StatusCode::INTERNAL), 500);
  EXPECT_EQ(connect::HttpStatusOf(StatusCode::UNAUTHENTICATED), 401);
  EXPECT_EQ(connect::CodeName(StatusCode::CANCELLED), "canceled");
  EXPECT_EQ(connect::CodeName(StatusCode::DEADLINE_EXCEEDED),
            "deadline_exceeded");
}

TEST(ConnectProtocol, ErrorCarriesTheBadRequestDetail) {
  const grpc::Status status =
      ToGrpcStatus(InvalidFieldError("knots[2]", "decreases"), "curve.bspline");
  const std::string json = connect::ErrorJson(status);
  EXPECT_THAT(json, HasSubstr(R"({"code":"invalid_argument","message":)"));
  EXPECT_THAT(json, HasSubstr(R"("type":"google.rpc.BadRequest","value":")"));
  EXPECT_THAT(json, HasSubstr(R"("debug":{"fieldViolations":[{"field":)"
                              R"("curve.bspline.knots[2]","description":)"));
  EXPECT_FALSE(absl::StrContains(json, "=\""));  // unpadded base64
  EXPECT_EQ(connect::EndStreamJson(grpc::Status::OK), "{}");
  EXPECT_EQ(
      connect::EndStreamJson(grpc::Status(grpc::StatusCode::UNAVAILABLE, "")),
      R"({"error":{"code":"unavailable"}})");
}

TEST(ConnectProtocol, EnvelopesRoundTrip) {
  std::string body;
  connect::AppendEnvelope(0, "{\"a\":1}", body);
  ASSERT_EQ(body.size(), 5u + 7u);
  EXPECT_EQ(body[4], 7);
  absl::StatusOr<absl::string_view> message =
      connect::SingleEnvelopedMessage(body);
  ASSERT_TRUE(message.ok());
  EXPECT_EQ(*message, "{\"a\":1}");
  EXPECT_FALSE(connect::SingleEnvelopedMessage(body + "x").ok());
  EXPECT_FALSE(connect::SingleEnvelopedMessage(body.substr(0, 4)).ok());
  std::string compressed;
  connect::AppendEnvelope(connect::kCompressedFlag, "x", compressed);
  EXPECT_FALSE(connect::SingleEnvelopedMessage(compressed).ok());
}

TEST(ConnectProtocol, TimeoutIsAPositiveIntegerOfTenDigitsAtMost) {
  EXPECT_EQ(*connect::ParseTimeout("250"), absl::Milliseconds(250));
  EXPECT_EQ(*connect::ParseTimeout("9999999999"),
            absl::Milliseconds(9999999999));
  for (const char* bad : {"", "0", "-5", "12345678901", "1.5", "5s", " 5"}) {
    EXPECT_FALSE(connect::ParseTimeout(bad).ok()) << bad;
  }
}

TEST(CorsPolicy, AllowsListedOriginsOrAny) {
  absl::StatusOr<CorsPolicy> none = CorsPolicy::Make({});
  ASSERT_TRUE(none.ok());
  EXPECT_EQ(none->AllowOriginHeader("https://a.example"), std::nullopt);
  absl::StatusOr<CorsPolicy> listed =
      CorsPolicy::Make({"https://a.example", "http://[::1]:8080"});
  ASSERT_TRUE(listed.ok());
  EXPECT_EQ(listed->AllowOriginHeader("https://a.example"),
            "https://a.example");
  EXPECT_EQ(listed->AllowOriginHeader("http://[::1]:8080"),
            "http://[::1]:8080");
  EXPECT_EQ(listed->AllowOriginHeader("https://b.example"), std::nullopt);
  EXPECT_EQ(listed->AllowOriginHeader(""), std::nullopt);
  absl::StatusOr<CorsPolicy> any = CorsPolicy::Make({"*"});
  ASSERT_TRUE(any.ok());
  EXPECT_EQ(any->AllowOriginHeader("https://b.example"), "*");
  for (const char* bad :
       {"a.example", "https://a.example/", "ftp://a", "https://a.example:0",
        "https://a.example:65536", "https://", "https://a b"}) {
    EXPECT_FALSE(CorsPolicy::Make({bad}).ok()) << bad;
  }
  EXPECT_FALSE(CorsPolicy::Make({"*", "https://a.example"}).ok());
}

}  // namespace
}  // namespace freeform::server
