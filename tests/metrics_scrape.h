// Scraping freeformd's Prometheus metrics in tests: an HTTP/1.0 GET over a
// plain loopback socket (no HTTP library; SendOnLoopback sends any raw
// request), its status line, and the value of one series in the text
// format.
#ifndef FREEFORM_TESTS_METRICS_SCRAPE_H_
#define FREEFORM_TESTS_METRICS_SCRAPE_H_

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <array>
#include <optional>
#include <string>
#include <utility>

#include "absl/status/statusor.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/strings/string_view.h"

namespace freeform {

// The status line ("HTTP/1.1 200 OK") and the body of an HTTP answer.
struct HttpAnswer {
  std::string status_line;
  std::string body;
};

// What came back on a raw loopback exchange, and whether the server closed
// the connection (false: the receive timed out, or nothing connected).
struct LoopbackAnswer {
  std::string bytes;
  bool closed = false;
};

// SendOnLoopback connects to 127.0.0.1:PORT, sends `request` as it is and
// reads until the server closes the connection or nothing comes for
// `timeout_seconds`.
inline LoopbackAnswer SendOnLoopback(int port, absl::string_view request,
                                     int timeout_seconds) {
  LoopbackAnswer answer;
  const int socket_fd = socket(AF_INET, SOCK_STREAM, 0);
  if (socket_fd < 0) return answer;
  const timeval timeout = {.tv_sec = timeout_seconds, .tv_usec = 0};
  setsockopt(socket_fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(socket_fd, reinterpret_cast<const sockaddr*>(&address),
              sizeof(address)) == 0 &&
      send(socket_fd, request.data(), request.size(), MSG_NOSIGNAL) ==
          static_cast<ssize_t>(request.size())) {
    std::array<char, 4096> buffer;
    ssize_t received = 0;
    while ((received = recv(socket_fd, buffer.data(), buffer.size(), 0)) > 0) {
      answer.bytes.append(buffer.data(), static_cast<size_t>(received));
    }
    answer.closed = received == 0;
  }
  close(socket_fd);
  return answer;
}

// HttpExchange sends `GET PATH HTTP/1.0` to 127.0.0.1:PORT and returns the
// answer; UNAVAILABLE when none came within 10 s.
inline absl::StatusOr<HttpAnswer> HttpExchange(int port,
                                               absl::string_view path) {
  const std::string answer =
      SendOnLoopback(
          port,
          absl::StrCat("GET ", path, " HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n"),
          10)
          .bytes;
  const size_t body = answer.find("\r\n\r\n");
  if (body == std::string::npos) {
    return absl::UnavailableError(absl::StrCat(
        "no HTTP answer from 127.0.0.1:", port, path, ": ", answer));
  }
  return HttpAnswer{.status_line = answer.substr(0, answer.find("\r\n")),
                    .body = answer.substr(body + 4)};
}

// HttpGet returns the body of http://127.0.0.1:PORT/PATH when the answer
// is 200 OK.
inline absl::StatusOr<std::string> HttpGet(int port, absl::string_view path) {
  absl::StatusOr<HttpAnswer> answer = HttpExchange(port, path);
  if (!answer.ok()) return answer.status();
  if (!absl::StrContains(answer->status_line, " 200 ")) {
    return absl::UnavailableError(absl::StrCat(
        "GET ", path, ": ", answer->status_line, "\r\n\r\n", answer->body));
  }
  return std::move(answer->body);
}

// MetricValue returns the value of `series` (a name with its labels, as
// written: `freeform_calls_total{code="OK",method="CurveService.Evaluate"}`)
// in a text exposition, or nullopt when it has no such line.
inline std::optional<double> MetricValue(absl::string_view exposition,
                                         absl::string_view series) {
  for (absl::string_view line : absl::StrSplit(exposition, '\n')) {
    if (!absl::ConsumePrefix(&line, series) || !absl::ConsumePrefix(&line, " "))
      continue;
    double value = 0;
    if (absl::SimpleAtod(line, &value)) return value;
  }
  return std::nullopt;
}

}  // namespace freeform

#endif  // FREEFORM_TESTS_METRICS_SCRAPE_H_
