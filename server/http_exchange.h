// HttpExchange: one HTTP request and its answer on a civetweb connection,
// for the HTTP gateway (http_gateway.h): the request's line and headers,
// its body read within a bound, and the answer (a whole body, a Connect
// error, or a chunked stream), each with the request's CORS headers.
//
// Not thread-safe: one exchange belongs to the civetweb worker serving it.
#ifndef FREEFORM_SERVER_HTTP_EXCHANGE_H_
#define FREEFORM_SERVER_HTTP_EXCHANGE_H_

#include <grpcpp/support/status.h>

#include <cstdint>
#include <optional>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "cors_policy.h"

struct mg_connection;

namespace freeform::server {

class HttpExchange {
 public:
  HttpExchange(mg_connection* connection, const CorsPolicy& cors);

  absl::string_view method() const { return method_; }
  absl::string_view path() const { return path_; }
  // The request's HTTP client as the access log names peers
  // ("ipv4:127.0.0.1:40000", "ipv6:[::1]:40000").
  const std::string& client() const { return client_; }
  // header returns the value of the request header `name` (any case), or
  // "" when it has none.
  absl::string_view header(const char* name) const;
  // declared_body_bytes returns the request's Content-Length, nullopt when
  // it declared none (a chunked body).
  std::optional<uint64_t> declared_body_bytes() const;
  // answered is true once an answer has begun.
  bool answered() const { return status_ != 0; }
  // status returns the HTTP status of the answer, 0 before one.
  int status() const { return status_; }

  // ReadBody reads the whole body; RESOURCE_EXHAUSTED once it grows past
  // `max_bytes` (what was read is dropped), UNAVAILABLE when the client
  // stops sending.
  absl::StatusOr<std::string> ReadBody(uint64_t max_bytes);

  // Answer sends `body` with `http_status` and `content_type`.
  void Answer(int http_status, absl::string_view content_type,
              absl::string_view body);
  // AnswerError sends the Connect error of `status` with its code's HTTP
  // status, or `http_status` when not 0; `close` also ends the connection
  // (its body was not read).
  void AnswerError(const grpc::Status& status, bool close = false,
                   int http_status = 0);
  // AnswerFile sends an embedded file (static_files.h): 200 with its
  // content type, revalidated by the browser on every load (the files
  // change with the binary), with `with_body` false (HEAD) its headers only;
  // `close` also ends the connection (a body the request carried is not
  // read).
  void AnswerFile(absl::string_view content_type, absl::string_view body,
                  bool with_body, bool close);
  // AnswerPreflight answers a CORS preflight (OPTIONS): 204, with the CORS
  // headers when the origin is allowed.
  void AnswerPreflight();

  // StartStream sends 200 with `content_type` and a chunked body.
  void StartStream(absl::string_view content_type);
  // WriteChunk sends `bytes` as one chunk; false when the client is gone.
  bool WriteChunk(absl::string_view bytes);
  // EndStream sends the last (empty) chunk.
  void EndStream();

 private:
  // StartAnswer begins an answer: its status line and the CORS headers.
  void StartAnswer(int http_status);
  void AddHeader(const char* name, absl::string_view value);
  // AddContentHeaders adds Content-Type and Content-Length.
  void AddContentHeaders(absl::string_view content_type, size_t bytes);
  // CloseAfterAnswer makes civetweb close the connection once the answer
  // sent is done, without reading the rest of the request's body.
  void CloseAfterAnswer();

  mg_connection* const connection_;
  const CorsPolicy& cors_;
  absl::string_view method_;
  absl::string_view path_;
  std::string client_;
  long long content_length_ = -1;
  int status_ = 0;
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_HTTP_EXCHANGE_H_
