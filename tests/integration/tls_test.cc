// freeformd's TLS through the real binary: it serves over TLS and mutual
// TLS; every half-configured TLS refuses to start (never plaintext in its
// place); a key that does not match its certificate, and files that are not
// small regular files, are refused with messages naming the flag; and
// --tls_allowed_clients serves only the listed client identities.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "cli_test_util.h"
#include "freeform/client.h"
#include "server_process.h"
#include "tls_certificates.h"

namespace freeform {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;

std::string ReadLog(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// StartFailure runs freeformd with `flags`, expects it to refuse to start
// (no port announced, exit status 1, not a signal) and returns its log.
std::string StartFailure(const std::vector<std::string>& flags) {
  static int runs = 0;
  const std::string log_path = absl::StrCat(
      testing::TempDir(), "/freeformd_tls_", getpid(), "_", runs++, ".log");
  std::remove(log_path.c_str());
  {
    ServerProcess server(flags, log_path);
    EXPECT_EQ(server.port(), 0)
        << "freeformd served with " << testing::PrintToString(flags);
    EXPECT_EQ(server.WaitForExit(std::chrono::seconds(10)), 1)
        << testing::PrintToString(flags);
  }
  const std::string log = ReadLog(log_path);
  std::remove(log_path.c_str());
  return log;
}

TEST(FreeformdTlsTest, ServesOverTls) {
  Certificates certificates;
  ASSERT_TRUE(certificates.ok());
  ServerProcess server({"--tls_cert=" + certificates.Path("server.pem"),
                        "--tls_key=" + certificates.Path("server.key")});
  ASSERT_GT(server.port(), 0);
  auto client = Client::Create(TlsClientOptions(certificates, server.port()));
  ASSERT_TRUE(client.ok());
  absl::StatusOr<CurveSamples> samples =
      (*client)->EvaluateBezier(1, {0, 1, 2}, {0.5});
  ASSERT_TRUE(samples.ok()) << samples.status();
  EXPECT_THAT(samples->derivatives[0], ElementsAre(1.0));
  // A plaintext client cannot talk to the TLS port.
  ClientOptions plain;
  plain.target = server.address();
  plain.timeout = std::chrono::seconds(2);
  plain.retry_unavailable = false;
  auto plain_client = Client::Create(plain);
  ASSERT_TRUE(plain_client.ok());
  EXPECT_FALSE((*plain_client)->EvaluateBezier(1, {0, 1}, {0.5}).ok());
}

TEST(FreeformdTlsTest, MutualTlsRequiresAClientCertificate) {
  Certificates certificates;
  ASSERT_TRUE(certificates.ok());
  ServerProcess server({"--tls_cert=" + certificates.Path("server.pem"),
                        "--tls_key=" + certificates.Path("server.key"),
                        "--tls_client_ca=" + certificates.Path("ca.pem")});
  ASSERT_GT(server.port(), 0);
  ClientOptions anonymous = TlsClientOptions(certificates, server.port());
  anonymous.timeout = std::chrono::seconds(2);
  anonymous.retry_unavailable = false;
  auto rejected = Client::Create(anonymous);
  ASSERT_TRUE(rejected.ok());
  EXPECT_FALSE((*rejected)->EvaluateBezier(1, {0, 1}, {0.5}).ok());

  auto accepted =
      Client::Create(TlsClientOptions(certificates, server.port(), "client"));
  ASSERT_TRUE(accepted.ok());
  absl::StatusOr<CurveSamples> samples =
      (*accepted)->EvaluateBezier(1, {0, 1}, {0.25});
  ASSERT_TRUE(samples.ok()) << samples.status();
  EXPECT_THAT(samples->derivatives[0], ElementsAre(0.25));
}

// Each TLS option without what it needs: freeformd exits 1 naming the
// flags instead of serving plaintext (--tls_client_ca alone used to start a
// plaintext server that checked no client at all).
TEST(FreeformdTlsConfig, HalfConfiguredTlsRefusesToStart) {
  Certificates certificates;
  ASSERT_TRUE(certificates.ok());
  const std::string cert = "--tls_cert=" + certificates.Path("server.pem");
  const std::string key = "--tls_key=" + certificates.Path("server.key");
  const std::string ca = "--tls_client_ca=" + certificates.Path("ca.pem");
  const std::string allowed = "--tls_allowed_clients=client";
  struct Case {
    std::vector<std::string> flags;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{cert}, "--tls_cert is set without --tls_key"},
      {{key}, "--tls_key is set without --tls_cert"},
      {{ca}, "--tls_client_ca needs --tls_cert and --tls_key"},
      {{ca, cert}, "--tls_cert is set without --tls_key"},
      {{ca, key}, "--tls_key is set without --tls_cert"},
      {{allowed}, "--tls_allowed_clients needs --tls_client_ca"},
      {{cert, key, allowed}, "--tls_allowed_clients needs --tls_client_ca"},
      {{cert, key, ca, "--tls_allowed_clients=client,"},
       "--tls_allowed_clients[1] (\"\") is empty"},
      {{cert, key, ca, "--tls_allowed_clients=client, other"},
       "--tls_allowed_clients[1] (\" other\")"},
  };
  for (const Case& test : cases) {
    const std::string log = StartFailure(test.flags);
    EXPECT_THAT(log, HasSubstr(test.message))
        << testing::PrintToString(test.flags);
    EXPECT_THAT(log, HasSubstr("cannot start: INVALID_ARGUMENT"));
  }
}

// A key of another certificate is reported as what it is, naming both
// files, rather than as an address that cannot be listened on.
TEST(FreeformdTlsConfig, KeyThatDoesNotMatchItsCertificateIsNamed) {
  Certificates certificates;
  ASSERT_TRUE(certificates.ok());
  const std::string log =
      StartFailure({"--tls_cert=" + certificates.Path("server.pem"),
                    "--tls_key=" + certificates.Path("client.key")});
  EXPECT_THAT(
      log, HasSubstr(absl::StrCat(
               "the private key in --tls_key=", certificates.Path("client.key"),
               " does not match the certificate in --tls_cert=",
               certificates.Path("server.pem"))));
  EXPECT_THAT(log, Not(HasSubstr("cannot listen")));
}

// Files whose contents are not what the flag needs.
TEST(FreeformdTlsConfig, FilesWithoutWhatTheFlagNeedsAreNamed) {
  Certificates certificates;
  ASSERT_TRUE(certificates.ok());
  const std::string cert = "--tls_cert=" + certificates.Path("server.pem");
  const std::string key = "--tls_key=" + certificates.Path("server.key");
  const std::string not_pem = WriteTempFile("not a certificate\n");
  EXPECT_THAT(StartFailure({"--tls_cert=" + not_pem, key}),
              HasSubstr(absl::StrCat("--tls_cert=", not_pem,
                                     " holds no PEM certificate")));
  // The server's chain, then a certificate block that does not parse.
  const std::string broken_chain =
      WriteTempFile(ReadLog(certificates.Path("server.pem")) +
                    "-----BEGIN CERTIFICATE-----\nbm90IERFUg==\n"
                    "-----END CERTIFICATE-----\n");
  EXPECT_THAT(StartFailure({"--tls_cert=" + broken_chain, key}),
              HasSubstr(absl::StrCat("--tls_cert=", broken_chain,
                                     " holds a PEM certificate block after "
                                     "certificate 1 that does not parse")));
  // A certificate where the key should be.
  EXPECT_THAT(
      StartFailure({cert, "--tls_key=" + certificates.Path("client.pem")}),
      HasSubstr(absl::StrCat("--tls_key=", certificates.Path("client.pem"),
                             " holds no PEM private key")));
  // A key where the client CA should be.
  EXPECT_THAT(
      StartFailure(
          {cert, key, "--tls_client_ca=" + certificates.Path("ca.key")}),
      HasSubstr(absl::StrCat("--tls_client_ca=", certificates.Path("ca.key"),
                             " holds no PEM certificate")));
}

// Every file the server reads is read as a regular file of at most 1 MiB:
// /dev/zero used to abort the process with std::bad_alloc, and a FIFO would
// have held the start until a writer came.
TEST(FreeformdTlsConfig, FilesThatAreNotSmallRegularFilesAreRefused) {
  Certificates certificates;
  ASSERT_TRUE(certificates.ok());
  const std::string cert = "--tls_cert=" + certificates.Path("server.pem");
  const std::string key = "--tls_key=" + certificates.Path("server.key");
  const std::string ca = "--tls_client_ca=" + certificates.Path("ca.pem");
  EXPECT_THAT(StartFailure({cert, "--tls_key=/dev/zero"}),
              HasSubstr("--tls_key: cannot read /dev/zero: not a regular "
                        "file (a character device)"));
  EXPECT_THAT(StartFailure({"--tls_cert=/dev/zero", key}),
              HasSubstr("--tls_cert: cannot read /dev/zero: not a regular "
                        "file"));
  EXPECT_THAT(StartFailure({cert, key, "--tls_client_ca=/dev/zero"}),
              HasSubstr("--tls_client_ca: cannot read /dev/zero: not a "
                        "regular file"));
  const std::string fifo = certificates.Path("key.fifo");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THAT(StartFailure({cert, "--tls_key=" + fifo}),
              HasSubstr(absl::StrCat("--tls_key: cannot read ", fifo,
                                     ": not a regular file (a FIFO)")));
  EXPECT_THAT(StartFailure({"--tls_cert=" + certificates.Path(""), key}),
              HasSubstr("not a regular file (a directory)"));
  // A CA bundle of 1 MiB + 1 byte: the CA's certificate, padded.
  std::string bundle = ReadLog(certificates.Path("ca.pem"));
  bundle.resize((1 << 20) + 1, '\n');
  const std::string large = WriteTempFile(bundle);
  EXPECT_THAT(StartFailure({cert, key, "--tls_client_ca=" + large}),
              HasSubstr(absl::StrCat("--tls_client_ca: cannot read ", large,
                                     ": it is larger than 1048576 bytes")));
  EXPECT_THAT(StartFailure({cert, key, "--tls_client_ca=/nonexistent.pem"}),
              HasSubstr("--tls_client_ca: cannot read /nonexistent.pem: No "
                        "such file or directory"));
  // The same bundle one byte shorter is read, and serves.
  bundle.resize(1 << 20);
  const std::string largest = WriteTempFile(bundle);
  ServerProcess server({cert, key, "--tls_client_ca=" + largest});
  EXPECT_GT(server.port(), 0);
}

// --tls_allowed_clients: a client certificate the CA signed is served only
// when one of its identities is listed: a URI (exactly) or DNS name
// (ignoring case) among its subject alternative names, or its common name
// (exactly). Any other gets PERMISSION_DENIED on every call, health
// included, and a warning in the log naming its identities.
TEST(FreeformdTlsAllowList, ServesTheListedClientsOnly) {
  Certificates certificates;
  ASSERT_TRUE(certificates.ok());
  ASSERT_TRUE(certificates.AddClient("alpha", "alpha",
                                     "URI:spiffe://freeform.test/alpha"));
  ASSERT_TRUE(certificates.AddClient("beta", "beta", "DNS:beta.freeform.test"));
  ASSERT_TRUE(certificates.AddClient("gamma", "gamma"));
  ASSERT_TRUE(certificates.AddClient(
      "stranger", "stranger",
      "DNS:stranger.freeform.test,URI:spiffe://freeform.test/stranger"));
  // Longer than a listed URI, and a listed common name in other case.
  ASSERT_TRUE(certificates.AddClient("alphabet", "alphabet",
                                     "URI:spiffe://freeform.test/alphabet"));
  ASSERT_TRUE(certificates.AddClient("upper_gamma", "GAMMA"));
  const std::string log_path = absl::StrCat(
      testing::TempDir(), "/freeformd_allow_list_", getpid(), ".log");
  std::remove(log_path.c_str());
  {
    ServerProcess server({"--tls_cert=" + certificates.Path("server.pem"),
                          "--tls_key=" + certificates.Path("server.key"),
                          "--tls_client_ca=" + certificates.Path("ca.pem"),
                          "--tls_allowed_clients=spiffe://freeform.test/alpha,"
                          "BETA.freeform.test,gamma"},
                         log_path);
    ASSERT_GT(server.port(), 0);
    for (const char* allowed : {"alpha", "beta", "gamma"}) {
      auto client = Client::Create(
          TlsClientOptions(certificates, server.port(), allowed));
      ASSERT_TRUE(client.ok());
      // The midpoint of the segment from 0 to 2.
      absl::StatusOr<CurveSamples> samples =
          (*client)->EvaluateBezier(1, {0, 2}, {0.5});
      ASSERT_TRUE(samples.ok()) << allowed << ": " << samples.status();
      EXPECT_THAT(samples->derivatives[0], ElementsAre(1.0)) << allowed;
    }
    for (const char* refused :
         {"stranger", "alphabet", "upper_gamma", "client"}) {
      auto client = Client::Create(
          TlsClientOptions(certificates, server.port(), refused));
      ASSERT_TRUE(client.ok());
      absl::StatusOr<CurveSamples> samples =
          (*client)->EvaluateBezier(1, {0, 2}, {0.5});
      EXPECT_EQ(samples.status().code(), absl::StatusCode::kPermissionDenied)
          << refused << ": " << samples.status();
      EXPECT_EQ((*client)->CheckHealth().code(),
                absl::StatusCode::kPermissionDenied)
          << refused;
    }
    // A round_robin client health-checks each replica (client.cc's
    // ServiceConfig): its health Watch is refused too, so the one replica
    // counts as unhealthy and the call ends UNAVAILABLE, not
    // PERMISSION_DENIED (docs/operations.md, "Scale-out").
    ClientOptions balanced =
        TlsClientOptions(certificates, server.port(), "stranger");
    balanced.round_robin = true;
    auto balanced_client = Client::Create(balanced);
    ASSERT_TRUE(balanced_client.ok());
    EXPECT_EQ(
        (*balanced_client)->EvaluateBezier(1, {0, 2}, {0.5}).status().code(),
        absl::StatusCode::kUnavailable);
    EXPECT_EQ(server.StopWith(SIGTERM, std::chrono::seconds(10)), 0);
  }
  const std::string log = ReadLog(log_path);
  std::remove(log_path.c_str());
  EXPECT_THAT(log, HasSubstr("refused a call to "
                             "/freeform.v1.CurveService/Evaluate: client "
                             "certificate CN=[stranger] "
                             "DNS=[stranger.freeform.test] "
                             "URI=[spiffe://freeform.test/stranger] is not in "
                             "--tls_allowed_clients"));
  EXPECT_THAT(log, HasSubstr("CN=[GAMMA]"));
  EXPECT_THAT(log, Not(HasSubstr("CN=[alpha]")));
}

}  // namespace
}  // namespace freeform
