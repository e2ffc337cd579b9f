// `freeform health` (health.h).
#include "health.h"

#include <iostream>
#include <memory>

namespace freeform::cli {

void AddHealthFlags(CLI::App& command, HealthOptions& options) {
  command.add_option("--service", options.service,
                     "Service name (empty: the whole server)");
}

int RunHealth(const CommonFlags& flags, const HealthOptions& options) {
  std::unique_ptr<Client> client = Connect(flags);
  if (client == nullptr) return kExitUsage;
  const absl::Status status = client->CheckHealth(options.service);
  if (!status.ok()) return ReportError(status);
  std::cout << "SERVING\n";
  return kExitOk;
}

}  // namespace freeform::cli
