#include "http_exchange.h"

#include <civetweb.h>

#include <algorithm>
#include <limits>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "connect_protocol.h"

namespace freeform::server {
namespace {

// Bytes read from the connection at a time (mg_read returns an int).
constexpr uint64_t kReadStep = 1 << 20;

absl::string_view OrEmpty(const char* text) {
  return text == nullptr ? absl::string_view() : absl::string_view(text);
}

std::string ClientOf(const mg_request_info& request) {
  const absl::string_view address = request.remote_addr;
  if (absl::StrContains(address, ':')) {
    return absl::StrCat("ipv6:[", address, "]:", request.remote_port);
  }
  return absl::StrCat("ipv4:", address, ":", request.remote_port);
}

}  // namespace

HttpExchange::HttpExchange(mg_connection* connection, const CorsPolicy& cors)
    : connection_(connection), cors_(cors) {
  const mg_request_info* request = mg_get_request_info(connection);
  if (request != nullptr) {
    method_ = OrEmpty(request->request_method);
    path_ = OrEmpty(request->local_uri_raw);
    client_ = ClientOf(*request);
    content_length_ = request->content_length;
  }
}

absl::string_view HttpExchange::header(const char* name) const {
  return OrEmpty(mg_get_header(connection_, name));
}

std::optional<uint64_t> HttpExchange::declared_body_bytes() const {
  if (content_length_ < 0) return std::nullopt;
  return static_cast<uint64_t>(content_length_);
}

absl::StatusOr<std::string> HttpExchange::ReadBody(uint64_t max_bytes) {
  const std::optional<uint64_t> declared = declared_body_bytes();
  const auto too_large = [max_bytes] {
    return absl::ResourceExhaustedError(
        absl::StrCat("the request body is larger than the gateway's limit of ",
                     max_bytes, " bytes (--http_max_request_bytes)"));
  };
  if (declared.has_value() && *declared > max_bytes) return too_large();
  // A body of unknown length is read to one byte past the bound, which
  // tells one that is too large.
  const uint64_t limit = declared.value_or(
      max_bytes == std::numeric_limits<uint64_t>::max() ? max_bytes
                                                        : max_bytes + 1);
  std::string body;
  if (declared.has_value()) body.reserve(static_cast<size_t>(*declared));
  while (body.size() < limit) {
    const uint64_t step = std::min<uint64_t>(kReadStep, limit - body.size());
    const size_t offset = body.size();
    body.resize(offset + static_cast<size_t>(step));
    const int read =
        mg_read(connection_, body.data() + offset, static_cast<size_t>(step));
    body.resize(offset + static_cast<size_t>(std::max(read, 0)));
    if (read < 0) {
      return absl::UnavailableError("the client stopped sending the body");
    }
    if (read == 0) break;
  }
  if (body.size() > max_bytes) return too_large();
  if (declared.has_value() && body.size() != *declared) {
    return absl::UnavailableError(
        absl::StrCat("the client sent ", body.size(), " of the ", *declared,
                     " bytes its Content-Length announced"));
  }
  return body;
}

void HttpExchange::StartAnswer(int http_status) {
  status_ = http_status;
  mg_response_header_start(connection_, http_status);
  if (const std::optional<std::string> allowed =
          cors_.AllowOriginHeader(header("Origin"));
      allowed.has_value()) {
    AddHeader("Access-Control-Allow-Origin", *allowed);
    if (*allowed != "*") AddHeader("Vary", "Origin");
  }
}

void HttpExchange::AddHeader(const char* name, absl::string_view value) {
  mg_response_header_add(connection_, name, value.data(),
                         static_cast<int>(value.size()));
}

void HttpExchange::AddContentHeaders(absl::string_view content_type,
                                     size_t bytes) {
  AddHeader("Content-Type", content_type);
  AddHeader("Content-Length", absl::StrCat(bytes));
}

void HttpExchange::Answer(int http_status, absl::string_view content_type,
                          absl::string_view body) {
  StartAnswer(http_status);
  AddContentHeaders(content_type, body.size());
  mg_response_header_send(connection_);
  mg_write(connection_, body.data(), body.size());
}

void HttpExchange::AnswerFile(absl::string_view content_type,
                              absl::string_view body, bool with_body,
                              bool close) {
  constexpr int kOk = 200;
  StartAnswer(kOk);
  AddContentHeaders(content_type, body.size());
  AddHeader("Cache-Control", "no-cache");
  AddHeader("X-Content-Type-Options", "nosniff");
  if (close) AddHeader("Connection", "close");
  mg_response_header_send(connection_);
  if (with_body) mg_write(connection_, body.data(), body.size());
  if (close) CloseAfterAnswer();
}

void HttpExchange::AnswerError(const grpc::Status& status, bool close,
                               int http_status) {
  const std::string body = connect::ErrorJson(status);
  StartAnswer(http_status != 0 ? http_status
                               : connect::HttpStatusOf(status.error_code()));
  AddContentHeaders("application/json", body.size());
  if (close) AddHeader("Connection", "close");
  mg_response_header_send(connection_);
  mg_write(connection_, body.data(), body.size());
  if (close) CloseAfterAnswer();
}

void HttpExchange::CloseAfterAnswer() {
  // civetweb drains a body its handler left unread, to keep the connection
  // for the next request: with a Content-Length of 10^11 that is 10^11
  // bytes read, or a worker held while the client waits. Its public API
  // has one way to end the connection instead: mg_send_http_error marks
  // it to be closed before it tries to answer, and after an answer it
  // sends nothing more (civetweb 1.15: its headers are refused once sent,
  // and 304 has no body). tests/integration/http_gateway_test.cc checks
  // that the connection does end at once.
  constexpr int kNotModified = 304;
  mg_send_http_error(connection_, kNotModified, "%s", "");
}

void HttpExchange::AnswerPreflight() {
  constexpr int kNoContent = 204;
  StartAnswer(kNoContent);
  AddHeader("Allow", kCorsAllowedMethods);
  if (cors_.AllowOriginHeader(header("Origin")).has_value()) {
    AddHeader("Access-Control-Allow-Methods", kCorsAllowedMethods);
    AddHeader("Access-Control-Allow-Headers", kCorsAllowedHeaders);
    AddHeader("Access-Control-Max-Age", kCorsMaxAgeSeconds);
  }
  AddHeader("Content-Length", "0");
  mg_response_header_send(connection_);
}

void HttpExchange::StartStream(absl::string_view content_type) {
  constexpr int kOk = 200;
  StartAnswer(kOk);
  AddHeader("Content-Type", content_type);
  AddHeader("Transfer-Encoding", "chunked");
  mg_response_header_send(connection_);
}

bool HttpExchange::WriteChunk(absl::string_view bytes) {
  return mg_send_chunk(connection_, bytes.data(),
                       static_cast<unsigned int>(bytes.size())) > 0;
}

void HttpExchange::EndStream() { mg_send_chunk(connection_, "", 0); }

}  // namespace freeform::server
