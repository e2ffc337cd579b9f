// The freeform CLI's query subcommands: closest, intersect, arc-length,
// at-length, sample-length, curvature, frames, bbox and section, each a
// CurveService (or with --surface a SurfaceService) query RPC with a proto3
// JSON request, answered as JSON or CSV (section: or an SVG picture).
#ifndef FREEFORM_CLIENT_CLI_QUERIES_H_
#define FREEFORM_CLIENT_CLI_QUERIES_H_

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "CLI/CLI.hpp"
#include "cli_common.h"

namespace freeform::cli {

// What the query subcommands' flags set (one subcommand runs per call).
struct QueryOptions {
  std::string file;
  bool surface = false;
  std::string format = "json";
  // closest: query points "x,y[,z];x,y..." and a CSV file of them.
  std::string points;
  std::string csv;
  // sample-length: overrides the request's count when not 0.
  uint32_t count = 0;
  // section: draw the polylines here.
  std::string svg;
};

class QueryCommands {
 public:
  // Adds the subcommands to `app`; their connection flags go to `flags`.
  QueryCommands(CLI::App& app, CommonFlags& flags);
  QueryCommands(const QueryCommands&) = delete;
  QueryCommands& operator=(const QueryCommands&) = delete;

  // Run runs the query subcommand that was parsed and returns its exit
  // status; nullopt when none of them was.
  std::optional<int> Run() const;

 private:
  // Adds a subcommand with the common flags and -f/--file.
  CLI::App* Add(CLI::App& app, const std::string& name,
                const std::string& description, const std::string& request,
                std::function<int()> run);
  void AddSurfaceFlag(CLI::App* command, const std::string& request);
  void AddFormatFlag(CLI::App* command);

  CommonFlags& flags_;
  QueryOptions options_;
  std::vector<std::pair<CLI::App*, std::function<int()>>> commands_;
};

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_QUERIES_H_
