// freeformd's log formats: the spdlog formatters of its stderr log and of
// the lines it announces on stdout ("freeformd listening on HOST:PORT").
//
// kText writes "TIME LEVEL message" on stderr and the bare message on
// stdout. kJson writes one JSON object per line on both,
// {"time":"...","level":"...","message":"..."}, with the message escaped
// (quotes, backslashes, control characters), so that every line parses
// whatever the message holds.
#ifndef FREEFORM_SERVER_LOG_FORMAT_H_
#define FREEFORM_SERVER_LOG_FORMAT_H_

#include <memory>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "spdlog/formatter.h"

namespace freeform::server {

enum class LogFormat { kText, kJson };

// ParseLogFormat reads --log_format: "text" or "json".
absl::StatusOr<LogFormat> ParseLogFormat(absl::string_view name);

// LogFormatter formats the log on stderr.
std::unique_ptr<spdlog::formatter> LogFormatter(LogFormat format);

// AnnouncementFormatter formats the lines on stdout that scripts wait for.
std::unique_ptr<spdlog::formatter> AnnouncementFormatter(LogFormat format);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_LOG_FORMAT_H_
