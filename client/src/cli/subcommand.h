// The freeform CLI's subcommands as one table (Subcommands()): each entry
// names a subcommand, adds its own flags and returns what runs it. A
// subcommand is an options struct, a function that adds its flags and a
// run function, tied together by Register.
#ifndef FREEFORM_CLIENT_CLI_SUBCOMMAND_H_
#define FREEFORM_CLIENT_CLI_SUBCOMMAND_H_

#include <functional>
#include <memory>

#include "CLI/CLI.hpp"
#include "absl/types/span.h"
#include "common.h"

namespace freeform::cli {

// Runs a parsed subcommand and returns the exit status.
using Runner = std::function<int()>;

struct Subcommand {
  const char* name;
  const char* description;
  // Adds the subcommand's flags to `command` (the common flags are added
  // for every subcommand; `flags` holds them once parsed) and returns what
  // runs it.
  Runner (*add_flags)(CLI::App& command, const CommonFlags& flags);
};

// Register makes a Subcommand::add_flags of an options struct, the
// function that adds its flags and the one that runs it.
template <typename Options, void (*AddFlags)(CLI::App&, Options&),
          int (*Run)(const CommonFlags&, const Options&)>
Runner Register(CLI::App& command, const CommonFlags& flags) {
  auto options = std::make_shared<Options>();
  AddFlags(command, *options);
  return [&flags, options] { return Run(flags, *options); };
}

// Subcommands returns the table of every subcommand, in --help's order.
absl::Span<const Subcommand> Subcommands();

// AddFileFlag adds -f/--file (the request as proto3 JSON; stdin without
// it).
void AddFileFlag(CLI::App& command, std::string& file);

// AddFormatFlag adds --format with `formats` ("json", "csv", "jsonl").
void AddFormatFlag(CLI::App& command, std::string& format,
                   const std::vector<std::string>& formats);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_SUBCOMMAND_H_
