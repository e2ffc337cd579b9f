// The freeformd flags that docker/compose.yaml and docker/k8s/deployment.yaml
// pass are flags freeformd accepts: each set starts a real freeformd that
// serves a call and, where the set turns metrics on, its metrics endpoint.
// A renamed or mistyped flag in a manifest fails here rather than at a
// user's rollout. The Kubernetes manifests also keep the unauthenticated
// metrics to the pod's address and, by their NetworkPolicy, to the
// monitoring namespace, and kustomization.yaml lists every manifest.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
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

// The Kubernetes metrics listen on the pod's own address, from the
// downward API, not on 0.0.0.0.
TEST(DeploymentManifests, KubernetesMetricsListenOnThePodAddress) {
  const std::string deployment = ReadSourceFile("docker/k8s/deployment.yaml");
  const std::vector<std::string> flags =
      FlagsBetween(deployment, "args:", "env:");
  EXPECT_THAT(flags, ::testing::Contains("--metrics_listen=$(POD_IP):9464"));
  const std::regex pod_ip(
      R"(- name: POD_IP\s+valueFrom:\s+fieldRef:\s+fieldPath: status\.podIP)");
  EXPECT_TRUE(std::regex_search(deployment, pod_ip));
  // No Service publishes the metrics port.
  EXPECT_EQ(ReadSourceFile("docker/k8s/service.yaml").find("9464"),
            std::string::npos);
}

// The pods age their connections, so that clients of the headless Service
// re-resolve its name and find new pods, and the age's grace covers the
// longest call (--max_call_time's default, 60 s). docs/operations.md says
// why.
TEST(DeploymentManifests, KubernetesConnectionsAgeSoClientsFindNewPods) {
  const std::vector<std::string> flags = FlagsBetween(
      ReadSourceFile("docker/k8s/deployment.yaml"), "args:", "env:");
  EXPECT_THAT(flags, ::testing::Contains("--max_connection_age=30s"));
  EXPECT_THAT(flags, ::testing::Contains("--max_connection_age_grace=60s"));
  EXPECT_THAT(ReadSourceFile("docker/k8s/service.yaml"),
              ::testing::HasSubstr("clusterIP: None"));
}

// The ingress rules of networkpolicy.yaml, each from its "- ports:" line to
// the next.
std::vector<std::string> IngressRules(const std::string& policy) {
  std::vector<std::string> rules;
  const std::string rule_start = "\n    - ports:";
  size_t begin = policy.find(rule_start, policy.find("\n  ingress:"));
  while (begin != std::string::npos) {
    const size_t end = policy.find(rule_start, begin + 1);
    rules.push_back(policy.substr(
        begin, end == std::string::npos ? std::string::npos : end - begin));
    begin = end;
  }
  return rules;
}

// The NetworkPolicy selects freeformd's pods, admits gRPC from clients and
// the metrics port from the monitoring namespace only, and nothing else.
TEST(DeploymentManifests, NetworkPolicyAdmitsMetricsOnlyFromMonitoring) {
  const std::string policy = ReadSourceFile("docker/k8s/networkpolicy.yaml");
  ASSERT_FALSE(policy.empty());
  EXPECT_THAT(policy, ::testing::HasSubstr("kind: NetworkPolicy"));
  EXPECT_THAT(policy,
              ::testing::HasSubstr("podSelector:\n    matchLabels:\n"
                                   "      app.kubernetes.io/name: freeformd"));
  EXPECT_THAT(policy, ::testing::HasSubstr("policyTypes:\n    - Ingress"));
  const std::vector<std::string> rules = IngressRules(policy);
  ASSERT_EQ(rules.size(), 2u) << policy;
  EXPECT_THAT(rules[0], ::testing::HasSubstr("port: 50051"));
  EXPECT_EQ(rules[0].find("9464"), std::string::npos);
  const std::string& metrics = rules[1];
  EXPECT_THAT(metrics, ::testing::HasSubstr("port: 9464"));
  EXPECT_EQ(metrics.find("50051"), std::string::npos);
  // Its only source: the namespace named monitoring, every pod of it.
  EXPECT_THAT(metrics,
              ::testing::HasSubstr("from:\n        - namespaceSelector:\n"
                                   "            matchLabels:\n"
                                   "              kubernetes.io/metadata.name: "
                                   "monitoring\n"));
  EXPECT_EQ(metrics.find("podSelector"), std::string::npos);
  EXPECT_EQ(metrics.find("ipBlock"), std::string::npos);
  EXPECT_EQ(metrics.find("{}"), std::string::npos);
}

// kustomization.yaml applies every manifest of docker/k8s.
TEST(DeploymentManifests, KustomizationListsEveryManifest) {
  const std::string kustomization =
      ReadSourceFile("docker/k8s/kustomization.yaml");
  int manifests = 0;
  for (const auto& entry : std::filesystem::directory_iterator(
           std::filesystem::path(FREEFORM_SOURCE_DIR) / "docker/k8s")) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".yaml" || name == "kustomization.yaml") {
      continue;
    }
    ++manifests;
    EXPECT_THAT(kustomization, ::testing::HasSubstr("\n  - " + name + "\n"))
        << name;
  }
  EXPECT_GE(manifests, 4);
}

}  // namespace
}  // namespace freeform
