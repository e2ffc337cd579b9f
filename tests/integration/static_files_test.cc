// The files the real freeformd serves by GET on --http_listen
// (server/static_files.h, docs/http.md "The playground"): the playground
// page's sources as the repository holds them, with their content types;
// HEAD; no path outside the fixed table, whatever its dots; a GET with a
// body answered without reading it. The page in a browser is
// tests/browser/playground_test.mjs.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "absl/strings/str_cat.h"
#include "http_client.h"
#include "metrics_scrape.h"
#include "server_process.h"

namespace freeform {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

std::string SourceFile(const std::string& relative_path) {
  std::ifstream file(absl::StrCat(FREEFORM_SOURCE_DIR, "/", relative_path),
                     std::ios::binary);
  std::stringstream contents;
  contents << file.rdbuf();
  return contents.str();
}

// RawRequest sends `method` `path` as written (no client normalizes its
// dots) with `extra_headers`, and returns what came back before the server
// closed the connection.
std::string RawRequest(int port, absl::string_view method,
                       absl::string_view path,
                       absl::string_view extra_headers = "") {
  return SendOnLoopback(port,
                        absl::StrCat(method, " ", path,
                                     " HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                                     "Connection: close\r\n",
                                     extra_headers, "\r\n"),
                        5)
      .bytes;
}

class StaticFilesTest : public ::testing::Test {
 protected:
  StaticFilesTest() : server_({"--http_listen=127.0.0.1:0"}) {}

  std::string Url(absl::string_view path) const {
    return absl::StrCat("http://127.0.0.1:", server_.http_port(), path);
  }

  ServerProcess server_;
  HttpClient http_;
};

TEST_F(StaticFilesTest, ServesThePlaygroundsSourcesWithTheirTypes) {
  struct Served {
    const char* path;
    const char* content_type;
    const char* source;
  };
  for (const Served& served : {
           Served{"/", "text/html; charset=utf-8", "web/playground/index.html"},
           Served{"/playground.css", "text/css; charset=utf-8",
                  "web/playground/playground.css"},
           Served{"/examples/teapot.json", "application/json",
                  "examples/teapot.json"},
           Served{"/examples/torus_mesh.json", "application/json",
                  "examples/torus_mesh.json"},
       }) {
    const HttpReply reply = http_.Send("GET", Url(served.path), {});
    ASSERT_EQ(reply.status, 200) << served.path << reply.curl_error;
    EXPECT_EQ(reply.headers.at("content-type"), served.content_type);
    EXPECT_EQ(reply.headers.at("x-content-type-options"), "nosniff");
    EXPECT_EQ(reply.headers.at("cache-control"), "no-cache");
    EXPECT_EQ(reply.body, SourceFile(served.source)) << served.path;
  }
  // The bundle: the page's module with three.js, calling the gateway.
  const HttpReply bundle = http_.Send("GET", Url("/playground.js"), {});
  ASSERT_EQ(bundle.status, 200);
  EXPECT_EQ(bundle.headers.at("content-type"),
            "text/javascript; charset=utf-8");
  EXPECT_THAT(bundle.body, HasSubstr("/freeform.v1."));
  EXPECT_THAT(bundle.body, HasSubstr("WebGLRenderer"));
  EXPECT_GT(bundle.body.size(), 100000u);
}

TEST_F(StaticFilesTest, HeadSendsTheHeadersAlone) {
  const std::string answer = RawRequest(server_.http_port(), "HEAD", "/");
  EXPECT_THAT(answer, StartsWith("HTTP/1.1 200 "));
  EXPECT_THAT(answer,
              HasSubstr(absl::StrCat(
                  "Content-Length: ",
                  SourceFile("web/playground/index.html").size(), "\r\n")));
  EXPECT_EQ(answer.find("\r\n\r\n") + 4, answer.size()) << answer;
}

TEST_F(StaticFilesTest, NoPathOutsideTheTable) {
  for (const char* path :
       {"/index.html", "/../README.md", "/%2e%2e/README.md",
        "/examples/../README.md", "/examples/cubic_bezier.json",
        "/web/playground/index.html", "/playground.js/", "//"}) {
    const std::string answer = RawRequest(server_.http_port(), "GET", path);
    EXPECT_THAT(answer, StartsWith("HTTP/1.1 404 ")) << path;
    EXPECT_THAT(answer, HasSubstr(R"("code":"unimplemented")")) << path;
  }
  // The files take GET and HEAD only.
  EXPECT_THAT(RawRequest(server_.http_port(), "DELETE", "/"),
              StartsWith("HTTP/1.1 404 "));
}

TEST_F(StaticFilesTest, GetWithABodyIsAnsweredWithoutReadingIt) {
  const LoopbackAnswer answer =
      SendOnLoopback(server_.http_port(),
                     "GET /playground.css HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                     "Content-Length: 100000000000\r\n\r\nab",
                     5);
  // The server closed the connection after its answer (a server that
  // waited for the 10^11 bytes, or drained them, would not have within the
  // 5 s SendOnLoopback waits).
  EXPECT_TRUE(answer.closed);
  EXPECT_THAT(answer.bytes, StartsWith("HTTP/1.1 200 "));
  EXPECT_THAT(answer.bytes, HasSubstr("Connection: close"));
  EXPECT_THAT(answer.bytes, HasSubstr("#curve-line"));
}

}  // namespace
}  // namespace freeform
