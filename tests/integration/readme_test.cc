// Every `build/release/client/freeform ...` line of README.md runs as
// written against the real freeformd: the line's 127.0.0.1:50051 becomes
// the test server's address and the binary path this build's CLI; it runs
// in a scratch directory whose examples/ is the repository's, so the files
// it writes (patch.obj, circle.svg, ...) land there. So do the commands of
// the README's "Other languages" block (the Python and Node examples; npm
// fetches the Node packages), and the `curl` lines of its "HTTP/JSON
// (Connect)" block against a freeformd with --http_listen.
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
#include "server_process.h"

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

// The lines of the first ```sh block after the heading `heading`.
std::vector<std::string> ReadmeBlock(const std::string& heading) {
  std::ifstream readme(FREEFORM_SOURCE_DIR "/README.md");
  EXPECT_TRUE(readme.good());
  std::vector<std::string> lines;
  std::string line;
  bool under_heading = false, in_block = false;
  while (std::getline(readme, line)) {
    if (in_block) {
      if (line == "```") break;
      lines.push_back(line);
    } else if (line == heading) {
      under_heading = true;
    } else if (under_heading && line == "```sh") {
      in_block = true;
    }
  }
  return lines;
}

// A scratch directory whose examples/ and scripts/ are the repository's.
std::string MakeScratch() {
  char pattern[] = "/tmp/freeform_readme_XXXXXX";
  const std::string scratch = mkdtemp(pattern);
  for (const char* folder : {"examples", "scripts"}) {
    EXPECT_EQ(RunCommand(absl::StrCat("ln -s ", FREEFORM_SOURCE_DIR, "/",
                                      folder, " ", scratch, "/", folder))
                  .exit_code,
              0);
  }
  return scratch;
}

using ReadmeTest = ServerAndCliTest;

TEST_F(ReadmeTest, EveryCliCommandRunsAsWritten) {
  const std::vector<std::string> commands = ReadmeCommands();
  ASSERT_GE(commands.size(), 20u);
  const std::string scratch = MakeScratch();
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

TEST_F(ReadmeTest, OtherLanguageCommandsRunAsWritten) {
  const std::vector<std::string> commands = ReadmeBlock("## Other languages");
  ASSERT_GE(commands.size(), 5u);
  const std::string scratch = MakeScratch();
  for (const std::string& command : commands) {
    const std::string runnable =
        absl::StrReplaceAll(command, {{"127.0.0.1:50051", server_.address()}});
    const CommandResult result =
        RunCommand(absl::StrCat("cd ", scratch, " && ", runnable));
    EXPECT_EQ(result.exit_code, 0) << command << "\n" << result.output;
    if (absl::StrContains(command, "freeform_example")) {
      // Each example prints the worked cubic's row at t = 1/2: the point
      // (2, 1.5) and the derivative (4.5, 0) (Python writes 2 as 2.0).
      EXPECT_THAT(result.output,
                  ::testing::ContainsRegex(R"(1,2(\.0)?,1\.5,4\.5,0(\.0)?)"))
          << command;
    }
  }
  RunCommand("rm -rf " + scratch);
}

TEST(ReadmeHttpTest, CurlCommandsRunAsWritten) {
  std::vector<std::string> commands;
  for (const std::string& line : ReadmeBlock("### HTTP/JSON (Connect)")) {
    if (absl::StartsWith(line, "curl ")) commands.push_back(line);
  }
  ASSERT_GE(commands.size(), 1u);
  ServerProcess server({"--http_listen=127.0.0.1:0"});
  ASSERT_GT(server.http_port(), 0);
  const std::string scratch = MakeScratch();
  for (const std::string& command : commands) {
    const std::string runnable = absl::StrReplaceAll(
        command,
        {{"127.0.0.1:8080", absl::StrCat("127.0.0.1:", server.http_port())}});
    const CommandResult result =
        RunCommand(absl::StrCat("cd ", scratch, " && ", runnable));
    EXPECT_EQ(result.exit_code, 0) << command << "\n" << result.output;
    // The worked cubic's points and first derivatives.
    EXPECT_THAT(result.output, ::testing::HasSubstr("[0,0,2,1.5,4,0]"))
        << command;
    EXPECT_THAT(result.output, ::testing::HasSubstr("[3,6,4.5,0,3,-6]"))
        << command;
  }
  RunCommand("rm -rf " + scratch);
}

}  // namespace
}  // namespace freeform
