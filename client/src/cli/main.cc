// freeform: the command-line client of freeformd. Every subcommand comes
// from the table in subcommands.cc; `freeform --help` lists them and
// `freeform SUBCOMMAND --help` their flags.
//
// Requests are the proto3 JSON of the request message (from --file or
// stdin); answers are printed as canonical proto3 JSON (lowerCamelCase;
// --proto-field-names for the .proto names), CSV, JSON lines, or written as
// SVG, OBJ or STL files. Exit statuses: common.h (kExit*).
#include <exception>
#include <functional>
#include <iostream>
#include <utility>
#include <vector>

#include "CLI/CLI.hpp"
#include "absl/strings/str_cat.h"
#include "common.h"
#include "subcommand.h"

// The version of freeform, set by the build (client/CMakeLists.txt).
#ifndef FREEFORM_VERSION
#define FREEFORM_VERSION "unknown"
#endif

namespace freeform::cli {
namespace {

std::string Footer() {
  return absl::StrCat("Exit status: ", kExitOk, " success; ", kExitServerError,
                      " the server answered with an error; ", kExitUsage,
                      " bad flags or input (unreadable file, malformed JSON); ",
                      kExitUnavailable, " the server could not be reached.\n");
}

// Runs the subcommand that was parsed; exceptions end here (the
// subcommands report errors as statuses).
int RunParsed(const std::vector<std::pair<CLI::App*, Runner>>& subcommands) {
  for (const auto& [command, run] : subcommands) {
    if (!command->parsed()) continue;
    try {
      return run();
    } catch (const std::exception& error) {
      std::cerr << "error: " << error.what() << "\n";
      return kExitUsage;
    }
  }
  return kExitUsage;
}

int Main(int argc, char** argv) {
  CLI::App app{"freeform: command-line client of the freeform gRPC service"};
  app.set_version_flag("--version", "freeform " FREEFORM_VERSION);
  app.footer(Footer());
  app.require_subcommand(1);
  CommonFlags flags;
  std::vector<std::pair<CLI::App*, Runner>> subcommands;
  for (const Subcommand& subcommand : Subcommands()) {
    CLI::App* command =
        app.add_subcommand(subcommand.name, subcommand.description);
    AddCommonFlags(*command, flags);
    subcommands.emplace_back(command, subcommand.add_flags(*command, flags));
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // --help and --version are "errors" with exit code 0.
    return app.exit(error) == 0 ? kExitOk : kExitUsage;
  }
  return RunParsed(subcommands);
}

}  // namespace
}  // namespace freeform::cli

int main(int argc, char** argv) { return freeform::cli::Main(argc, argv); }
