#include "log_format.h"

#include <cstdio>
#include <string>

#include "absl/strings/str_cat.h"
#include "spdlog/pattern_formatter.h"

namespace freeform::server {
namespace {

constexpr char kJsonPattern[] =
    R"({"time":"%Y-%m-%dT%H:%M:%S.%fZ","level":"%l","message":"%*"})";

// The %* flag: the message as the contents of a JSON string (RFC 8259).
class JsonEscapedMessage : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& message, const std::tm& /*time*/,
              spdlog::memory_buf_t& out) override {
    for (const char c :
         absl::string_view(message.payload.data(), message.payload.size())) {
      switch (c) {
        case '"':
          Append(out, "\\\"");
          break;
        case '\\':
          Append(out, "\\\\");
          break;
        case '\n':
          Append(out, "\\n");
          break;
        case '\r':
          Append(out, "\\r");
          break;
        case '\t':
          Append(out, "\\t");
          break;
        default:
          if (static_cast<unsigned char>(c) < 0x20) {
            char escaped[8];
            std::snprintf(escaped, sizeof(escaped), "\\u%04x",
                          static_cast<unsigned>(c));
            Append(out, escaped);
          } else {
            out.push_back(c);
          }
      }
    }
  }

  std::unique_ptr<custom_flag_formatter> clone() const override {
    return std::make_unique<JsonEscapedMessage>();
  }

 private:
  static void Append(spdlog::memory_buf_t& out, absl::string_view text) {
    out.append(text.data(), text.data() + text.size());
  }
};

std::unique_ptr<spdlog::formatter> JsonFormatter() {
  auto formatter = std::make_unique<spdlog::pattern_formatter>(
      spdlog::pattern_time_type::utc);
  formatter->add_flag<JsonEscapedMessage>('*').set_pattern(kJsonPattern);
  return formatter;
}

}  // namespace

absl::StatusOr<LogFormat> ParseLogFormat(absl::string_view name) {
  if (name == "text") return LogFormat::kText;
  if (name == "json") return LogFormat::kJson;
  return absl::InvalidArgumentError(
      absl::StrCat("--log_format must be text or json, got \"", name, "\""));
}

std::unique_ptr<spdlog::formatter> LogFormatter(LogFormat format) {
  if (format == LogFormat::kJson) return JsonFormatter();
  return std::make_unique<spdlog::pattern_formatter>(
      "%Y-%m-%dT%H:%M:%S.%f %^%l%$ %v");
}

std::unique_ptr<spdlog::formatter> AnnouncementFormatter(LogFormat format) {
  if (format == LogFormat::kJson) return JsonFormatter();
  return std::make_unique<spdlog::pattern_formatter>("%v");
}

}  // namespace freeform::server
