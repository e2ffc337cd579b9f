// Every `build/release/client/freeform ...` line of README.md runs as
// written against the real freeformd: the line's 127.0.0.1:50051 becomes
// the test server's address and the binary path this build's CLI; it runs
// in a scratch directory whose examples/ is the repository's, so the files
// it writes (patch.obj, circle.svg, ...) land there.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <fstream>
#include <string>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "cli_test_util.h"

namespace freeform {
namespace {

constexpr char kCli[] = "build/release/client/freeform ";

// The README's lines that start with the CLI's path.
std::vector<std::string> ReadmeCommands() {
  std::ifstream readme(FREEFORM_SOURCE_DIR "/README.md");
  EXPECT_TRUE(readme.good());
  std::vector<std::string> commands;
  std::string line;
  while (std::getline(readme, line)) {
    if (absl::StartsWith(line, kCli)) commands.push_back(line);
  }
  return commands;
}

using ReadmeTest = ServerAndCliTest;

TEST_F(ReadmeTest, EveryCliCommandRunsAsWritten) {
  const std::vector<std::string> commands = ReadmeCommands();
  ASSERT_GE(commands.size(), 20u);
  char pattern[] = "/tmp/freeform_readme_XXXXXX";
  const std::string scratch = mkdtemp(pattern);
  ASSERT_EQ(RunCommand(absl::StrCat("ln -s ", FREEFORM_SOURCE_DIR, "/examples ",
                                    scratch, "/examples"))
                .exit_code,
            0);
  for (const std::string& command : commands) {
    const std::string runnable = absl::StrReplaceAll(
        command, {{kCli, absl::StrCat(FREEFORM_CLI_PATH, " ")},
                  {"127.0.0.1:50051", server_.address()}});
    const CommandResult result =
        RunCommand(absl::StrCat("cd ", scratch, " && ", runnable));
    EXPECT_EQ(result.exit_code, 0) << command << "\n" << result.output;
    EXPECT_FALSE(result.output.empty()) << command;
  }
  RunCommand("rm -rf " + scratch);
}

}  // namespace
}  // namespace freeform
