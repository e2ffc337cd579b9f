// HttpClient: a small HTTP/1.1 client on libcurl for the HTTP gateway's
// tests and benchmark: POST or OPTIONS with headers, on one connection kept
// alive across calls, and the answer's status, headers and body. Connect
// envelopes of a streamed answer are split by ConnectEnvelopes.
#ifndef FREEFORM_TESTS_HTTP_CLIENT_H_
#define FREEFORM_TESTS_HTTP_CLIENT_H_

#include <curl/curl.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "absl/strings/strip.h"

namespace freeform {

struct HttpReply {
  // 0 when no answer came (curl_error says why).
  long status = 0;
  // Header names in lower case.
  absl::flat_hash_map<std::string, std::string> headers;
  std::string body;
  std::string curl_error;
};

class HttpClient {
 public:
  HttpClient() : curl_(curl_easy_init()) {}
  ~HttpClient() { curl_easy_cleanup(curl_); }
  HttpClient(const HttpClient&) = delete;
  HttpClient& operator=(const HttpClient&) = delete;

  // Send makes one request of `method` ("POST", "OPTIONS") to `url` with
  // `headers` ("Name: value") and `body`, and returns the answer.
  HttpReply Send(const std::string& method, const std::string& url,
                 const std::vector<std::string>& headers,
                 const std::string& body = "", long timeout_ms = 30000) {
    HttpReply reply;
    curl_slist* list = nullptr;
    // curl waits a second for "100 Continue" before a large body; the
    // gateway does not send one.
    list = curl_slist_append(list, "Expect:");
    for (const std::string& header : headers) {
      list = curl_slist_append(list, header.c_str());
    }
    curl_easy_setopt(curl_, CURLOPT_URL, url.c_str());
    curl_easy_setopt(curl_, CURLOPT_HTTPHEADER, list);
    if (method == "POST") {
      curl_easy_setopt(curl_, CURLOPT_POSTFIELDS, body.data());
      curl_easy_setopt(curl_, CURLOPT_POSTFIELDSIZE_LARGE,
                       static_cast<curl_off_t>(body.size()));
      curl_easy_setopt(curl_, CURLOPT_NOBODY, 0L);
    } else {
      curl_easy_setopt(curl_, CURLOPT_HTTPGET, 1L);
    }
    curl_easy_setopt(curl_, CURLOPT_CUSTOMREQUEST, method.c_str());
    curl_easy_setopt(curl_, CURLOPT_TIMEOUT_MS, timeout_ms);
    curl_easy_setopt(curl_, CURLOPT_WRITEFUNCTION, &HttpClient::OnBody);
    curl_easy_setopt(curl_, CURLOPT_WRITEDATA, &reply.body);
    curl_easy_setopt(curl_, CURLOPT_HEADERFUNCTION, &HttpClient::OnHeader);
    curl_easy_setopt(curl_, CURLOPT_HEADERDATA, &reply.headers);
    const CURLcode code = curl_easy_perform(curl_);
    curl_slist_free_all(list);
    if (code != CURLE_OK) {
      reply.curl_error = curl_easy_strerror(code);
      return reply;
    }
    curl_easy_getinfo(curl_, CURLINFO_RESPONSE_CODE, &reply.status);
    return reply;
  }

  HttpReply Post(const std::string& url, const std::string& content_type,
                 const std::string& body, std::vector<std::string> headers = {},
                 long timeout_ms = 30000) {
    headers.push_back("Content-Type: " + content_type);
    return Send("POST", url, headers, body, timeout_ms);
  }

 private:
  static size_t OnBody(char* data, size_t size, size_t count, void* body) {
    static_cast<std::string*>(body)->append(data, size * count);
    return size * count;
  }
  static size_t OnHeader(char* data, size_t size, size_t count, void* headers) {
    absl::string_view line(data, size * count);
    const size_t colon = line.find(':');
    if (colon != absl::string_view::npos) {
      (*static_cast<absl::flat_hash_map<std::string, std::string>*>(
          headers))[absl::AsciiStrToLower(line.substr(0, colon))] =
          std::string(absl::StripAsciiWhitespace(line.substr(colon + 1)));
    }
    return size * count;
  }

  CURL* const curl_;
};

// One enveloped message of a Connect stream.
struct Envelope {
  uint8_t flags = 0;
  std::string message;
};

// ConnectEnvelopes splits a streamed body into its envelopes; false when
// the body does not end on an envelope's end.
inline bool ConnectEnvelopes(absl::string_view body,
                             std::vector<Envelope>& envelopes) {
  while (!body.empty()) {
    if (body.size() < 5) return false;
    uint32_t length = 0;
    for (size_t i = 1; i < 5; ++i) {
      length = (length << 8) | static_cast<uint8_t>(body[i]);
    }
    if (body.size() - 5 < length) return false;
    envelopes.push_back(
        {static_cast<uint8_t>(body[0]), std::string(body.substr(5, length))});
    body.remove_prefix(5 + length);
  }
  return true;
}

// ConnectEnvelope returns `message` in an envelope with `flags`.
inline std::string ConnectEnvelope(absl::string_view message,
                                   uint8_t flags = 0) {
  const auto length = static_cast<uint32_t>(message.size());
  std::string out(1, static_cast<char>(flags));
  for (int shift = 24; shift >= 0; shift -= 8) {
    out += static_cast<char>((length >> shift) & 0xff);
  }
  out.append(message.data(), message.size());
  return out;
}

}  // namespace freeform

#endif  // FREEFORM_TESTS_HTTP_CLIENT_H_
