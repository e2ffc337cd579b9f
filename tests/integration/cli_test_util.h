// What the CLI integration tests share: running a shell command and
// collecting its output, temporary request files, and a fixture that starts
// the real freeformd on a free port with a client and the freeform CLI's
// command line for it.
#ifndef FREEFORM_TESTS_INTEGRATION_CLI_TEST_UTIL_H_
#define FREEFORM_TESTS_INTEGRATION_CLI_TEST_UTIL_H_

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "freeform/client.h"
#include "server_process.h"

namespace freeform {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout, then stderr
};

// RunCommand runs `command` with sh and returns its exit code and output
// (stderr joined to stdout).
inline CommandResult RunCommand(const std::string& command) {
  CommandResult result;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  size_t read = 0;
  while ((read = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
    result.output.append(buffer.data(), read);
  }
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// The files WriteTempFile made, removed when the test program exits.
inline std::vector<std::string>& TempFiles() {
  static std::vector<std::string>* const files = [] {
    auto* made = new std::vector<std::string>();
    std::atexit([] {
      for (const std::string& path : TempFiles()) unlink(path.c_str());
    });
    return made;
  }();
  return *files;
}

// WriteTempFile writes `contents` to a new file in /tmp and returns its
// path; the file goes when the test program exits.
inline std::string WriteTempFile(const std::string& contents) {
  char path[] = "/tmp/freeform_request_XXXXXX";
  const int fd = mkstemp(path);
  EXPECT_GE(fd, 0);
  EXPECT_EQ(write(fd, contents.data(), contents.size()),
            static_cast<ssize_t>(contents.size()));
  close(fd);
  TempFiles().push_back(path);
  return path;
}

// A freeformd on a free port, a client of it, and Cli() to build a freeform
// command line that talks to it.
class ServerAndCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_GT(server_.port(), 0) << "freeformd did not report its port";
    ClientOptions options;
    options.target = server_.address();
    options.timeout = std::chrono::seconds(10);
    auto client = Client::Create(options);
    ASSERT_TRUE(client.ok()) << client.status();
    client_ = *std::move(client);
  }

  // The freeform CLI with `arguments` and this server's address.
  std::string Cli(const std::string& arguments) const {
    return absl::StrCat(FREEFORM_CLI_PATH, " ", arguments, " --address ",
                        server_.address());
  }

  ServerProcess server_;
  std::unique_ptr<Client> client_;
};

}  // namespace freeform

#endif  // FREEFORM_TESTS_INTEGRATION_CLI_TEST_UTIL_H_
