// `freeform health`: asks the server's grpc.health.v1 service; prints
// SERVING, or the status (exit kExitUnavailable when NOT_SERVING or
// unreachable).
#ifndef FREEFORM_CLIENT_CLI_HEALTH_H_
#define FREEFORM_CLIENT_CLI_HEALTH_H_

#include <string>

#include "CLI/CLI.hpp"
#include "common.h"

namespace freeform::cli {

struct HealthOptions {
  std::string service;
};

void AddHealthFlags(CLI::App& command, HealthOptions& options);
int RunHealth(const CommonFlags& flags, const HealthOptions& options);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_HEALTH_H_
