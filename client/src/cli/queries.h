// The freeform CLI's query subcommands whose flags add to the request or
// choose the output: closest (query points from --points and --csv),
// sample-length (--count), curvature and section (--svg), each answered as
// JSON, CSV or a picture. The other queries (intersect, arc-length,
// at-length, frames, bbox) are plain JSON subcommands (json_commands.h).
#ifndef FREEFORM_CLIENT_CLI_QUERIES_H_
#define FREEFORM_CLIENT_CLI_QUERIES_H_

#include <cstdint>
#include <string>

#include "CLI/CLI.hpp"
#include "common.h"

namespace freeform::cli {

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

void AddClosestFlags(CLI::App& command, QueryOptions& options);
int RunClosest(const CommonFlags& flags, const QueryOptions& options);

void AddSampleLengthFlags(CLI::App& command, QueryOptions& options);
int RunSampleByLength(const CommonFlags& flags, const QueryOptions& options);

void AddCurvatureFlags(CLI::App& command, QueryOptions& options);
int RunCurvature(const CommonFlags& flags, const QueryOptions& options);

void AddSectionFlags(CLI::App& command, QueryOptions& options);
int RunSection(const CommonFlags& flags, const QueryOptions& options);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_QUERIES_H_
