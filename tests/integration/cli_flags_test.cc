// The freeform CLI as a tool: --version, --help with the exit statuses and
// the kebab-case flags, file and JSON errors that say where and why, the
// default port, canonical proto3 JSON names, the old flag spellings and
// the exit status of an unreachable server.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "absl/strings/str_cat.h"
#include "cli_test_util.h"

namespace freeform {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

CommandResult RunCli(const std::string& arguments) {
  return RunCommand(absl::StrCat(FREEFORM_CLI_PATH, " ", arguments));
}

TEST(CliFlags, VersionPrintsTheProjectVersion) {
  const CommandResult version = RunCli("--version");
  EXPECT_EQ(version.exit_code, 0) << version.output;
  EXPECT_THAT(version.output,
              ::testing::MatchesRegex("freeform [0-9]+\\.[0-9]+\\.[0-9]+\n"));
}

TEST(CliFlags, HelpListsExitStatusesAndKebabCaseFlags) {
  const CommandResult help = RunCli("--help");
  EXPECT_EQ(help.exit_code, 0) << help.output;
  EXPECT_THAT(help.output, HasSubstr("Exit status: 0 success; 1 the server"));
  EXPECT_THAT(help.output, HasSubstr("3 the server could not be reached"));
  const CommandResult eval = RunCli("eval --help");
  EXPECT_EQ(eval.exit_code, 0) << eval.output;
  EXPECT_THAT(eval.output, HasSubstr("--tls-root-ca"));
  EXPECT_THAT(eval.output, HasSubstr("--proto-field-names"));
  EXPECT_THAT(eval.output, HasSubstr("--no-progress"));
  // The old spelling works (below) but is not advertised.
  EXPECT_THAT(eval.output, Not(HasSubstr("--tls_root_ca")));
  const CommandResult unknown = RunCli("eval --no-such-flag");
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
}

TEST(CliFlags, AMissingFileNamesItsReason) {
  const CommandResult result = RunCli("eval --file /nonexistent/nope.json");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_THAT(result.output,
              HasSubstr("cannot read /nonexistent/nope.json: No such file or "
                        "directory"));
}

// An endless input ends with an error after kMaxInputBytes (256 MiB), from
// a file or from stdin; it was read until the memory ran out.
TEST(CliFlags, AnEndlessInputIsRefusedAtItsLimit) {
  const CommandResult file = RunCli("eval --file /dev/zero");
  EXPECT_EQ(file.exit_code, 2) << file.output;
  EXPECT_THAT(file.output, HasSubstr("cannot read /dev/zero: it is larger "
                                     "than 268435456 bytes"));
  const CommandResult piped = RunCommand(absl::StrCat(
      "head -c 300000000 /dev/zero | ", FREEFORM_CLI_PATH, " eval 2>&1"));
  EXPECT_EQ(piped.exit_code, 2) << piped.output;
  EXPECT_THAT(piped.output,
              HasSubstr("cannot read stdin: it is larger than 268435456"));
}

TEST(CliFlags, MalformedJsonNamesLineAndColumn) {
  const std::string file = WriteTempFile("{\n  \"curve\": {,\n}\n");
  const CommandResult result = RunCli("eval --file " + file);
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_THAT(result.output, HasSubstr(file + ":2:13: malformed JSON"));
  // From stdin the source is "stdin".
  const CommandResult piped = RunCommand(
      absl::StrCat("printf '[1, 2' | ", FREEFORM_CLI_PATH, " eval 2>&1"));
  EXPECT_EQ(piped.exit_code, 2) << piped.output;
  EXPECT_THAT(piped.output, HasSubstr("stdin:1:6: malformed JSON"));
}

// Nothing listens on port 1: UNAVAILABLE, exit status 3.
TEST(CliFlags, AnUnreachableServerExitsThree) {
  const CommandResult result =
      RunCli("health --address 127.0.0.1:1 --timeout 5");
  EXPECT_EQ(result.exit_code, 3) << result.output;
  EXPECT_THAT(result.output, HasSubstr("UNAVAILABLE"));
}

// --address without a port means 50051: run a freeformd there when the
// port is free.
TEST(CliFlags, AnAddressWithoutAPortUses50051) {
  ServerProcess server({"--listen=127.0.0.1:50051"});
  if (server.port() != 50051) GTEST_SKIP() << "port 50051 is taken";
  for (const char* address : {"127.0.0.1", "localhost"}) {
    const CommandResult result =
        RunCli(absl::StrCat("health --address ", address));
    EXPECT_EQ(result.exit_code, 0) << address << "\n" << result.output;
    EXPECT_EQ(result.output, "SERVING\n");
  }
}

using CliOutputTest = ServerAndCliTest;

// Answers are canonical proto3 JSON (lowerCamelCase) unless
// --proto-field-names asks for the .proto names; requests may use either.
TEST_F(CliOutputTest, CamelCaseByDefaultSnakeCaseOnRequest) {
  const std::string csv = WriteTempFile("0,0\n3,4\n-1,4\n-4,0\n-4,-3\n");
  const CommandResult camel =
      RunCommand(Cli("interpolate --degree 3 --csv " + csv));
  EXPECT_EQ(camel.exit_code, 0) << camel.output;
  EXPECT_THAT(camel.output, HasSubstr(R"("controlPoints":{"dimension":2)"));
  EXPECT_THAT(camel.output, Not(HasSubstr("control_points")));
  const CommandResult snake = RunCommand(
      Cli("interpolate --proto-field-names --degree 3 --csv " + csv));
  EXPECT_EQ(snake.exit_code, 0) << snake.output;
  EXPECT_THAT(snake.output, HasSubstr(R"("control_points":{"dimension":2)"));
  EXPECT_THAT(snake.output, Not(HasSubstr("controlPoints")));

  const std::string request = WriteTempFile(R"({"curve": {"bezier": {
      "control_points": {"dimension": 1, "coordinates": [0, 2]}}},
      "parameters": {"list": {"values": [0.25]}}, "derivative_order": 1})");
  const CommandResult snake_request =
      RunCommand(Cli("eval --format csv --file " + request));
  EXPECT_EQ(snake_request.exit_code, 0) << snake_request.output;
  EXPECT_EQ(snake_request.output, "index,x0,d1x0\n0,0.5,2\n");
}

// The snake_case spellings of the last release still work.
TEST_F(CliOutputTest, OldFlagSpellingsStillWork) {
  // Without --tls the root CA is not read: the flag only has to parse.
  const CommandResult tls =
      RunCommand(Cli("health --tls_root_ca /nonexistent/ca.pem"));
  EXPECT_EQ(tls.exit_code, 0) << tls.output;
  const std::string csv = WriteTempFile("0,0\n1,1\n2,0\n3,1\n");
  for (const char* value : {"chord_length", "chord-length"}) {
    const CommandResult result = RunCommand(Cli(absl::StrCat(
        "interpolate --parameterization ", value, " --degree 2 --csv ", csv)));
    EXPECT_EQ(result.exit_code, 0) << value << "\n" << result.output;
  }
}

}  // namespace
}  // namespace freeform
