// The freeformd flags that docker/compose.yaml and docker/k8s/deployment.yaml
// pass are flags freeformd accepts: each set starts a real freeformd that
// serves a call and, where the set turns metrics on, its metrics endpoint.
// A renamed or mistyped flag in a manifest fails here rather than at a
// user's rollout.
#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "freeform/client.h"
#include "metrics_scrape.h"
#include "server_process.h"

namespace freeform {
namespace {

std::string ReadSourceFile(const std::string& relative_path) {
  std::ifstream file(absl::StrCat(FREEFORM_SOURCE_DIR, "/", relative_path));
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Every "--flag" or "--flag=value" token in `text` between the first line
// containing `from` and the next line containing `to`, quotes stripped.
std::vector<std::string> FlagsBetween(const std::string& text,
                                      const std::string& from,
                                      const std::string& to) {
  const size_t begin = text.find(from);
  EXPECT_NE(begin, std::string::npos) << from;
  const size_t end = text.find(to, begin);
  EXPECT_NE(end, std::string::npos) << to;
  if (begin == std::string::npos || end == std::string::npos) return {};
  const std::string section = text.substr(begin, end - begin);
  std::vector<std::string> flags;
  static const std::regex kFlag(R"(--[a-z_]+(=[^\s",\]]*)?)");
  for (auto it = std::sregex_iterator(section.begin(), section.end(), kFlag);
       it != std::sregex_iterator(); ++it) {
    flags.push_back(it->str());
  }
  return flags;
}

// Makes a manifest's flags runnable on the test machine: the metrics
// endpoint on a free loopback port, Kubernetes' $(VAR) expansion of the
// thread count done by hand. The gRPC address stays the test's.
std::vector<std::string> ForThisMachine(std::vector<std::string> flags) {
  for (std::string& flag : flags) {
    if (flag.rfind("--metrics_listen=", 0) == 0) {
      flag = "--metrics_listen=127.0.0.1:0";
    }
    flag = absl::StrReplaceAll(flag, {{"$(FREEFORM_THREADS)", "2"}});
  }
  return flags;
}

void ExpectServes(const std::vector<std::string>& manifest_flags) {
  ASSERT_FALSE(manifest_flags.empty());
  ServerProcess server(ForThisMachine(manifest_flags));
  ASSERT_GT(server.port(), 0) << "freeformd did not start with "
                              << ::testing::PrintToString(manifest_flags);
  absl::StatusOr<std::unique_ptr<Client>> client =
      Client::Create({.target = server.address()});
  ASSERT_TRUE(client.ok()) << client.status();
  // The midpoint of the line from 0 to 3 is 1.5.
  absl::StatusOr<CurveSamples> answer =
      (*client)->EvaluateBezier(1, {0.0, 3.0}, {0.5});
  ASSERT_TRUE(answer.ok()) << answer.status();
  ASSERT_EQ(answer->count, 1u);
  EXPECT_DOUBLE_EQ(answer->Point(0, 0)[0], 1.5);
  for (const std::string& flag : manifest_flags) {
    if (flag.rfind("--metrics_listen=", 0) != 0) continue;
    ASSERT_GT(server.metrics_port(), 0);
    absl::StatusOr<std::string> metrics =
        HttpGet(server.metrics_port(), "/metrics");
    ASSERT_TRUE(metrics.ok()) << metrics.status();
    EXPECT_NE(metrics->find("freeform_calls_total"), std::string::npos);
  }
}

TEST(DeploymentFlags, ComposeCommandStartsAServer) {
  const std::vector<std::string> flags =
      FlagsBetween(ReadSourceFile("docker/compose.yaml"), "command: [", "]");
  EXPECT_GE(flags.size(), 4u);
  ExpectServes(flags);
}

TEST(DeploymentFlags, KubernetesArgumentsStartAServer) {
  const std::vector<std::string> flags = FlagsBetween(
      ReadSourceFile("docker/k8s/deployment.yaml"), "args:", "env:");
  EXPECT_GE(flags.size(), 5u);
  ExpectServes(flags);
}

}  // namespace
}  // namespace freeform
