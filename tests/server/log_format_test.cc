// freeformd's log formats (log_format.h): JSON lines stay valid JSON
// whatever the message holds, and text lines are the plain message.
#include "log_format.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <sstream>
#include <string>

#include "spdlog/logger.h"
#include "spdlog/sinks/ostream_sink.h"

namespace freeform::server {
namespace {

using ::testing::EndsWith;
using ::testing::MatchesRegex;

// Formatted returns what `formatter` makes of one info line `message`.
std::string Formatted(std::unique_ptr<spdlog::formatter> formatter,
                      const std::string& message) {
  std::ostringstream out;
  auto sink = std::make_shared<spdlog::sinks::ostream_sink_st>(out);
  spdlog::logger logger("test", sink);
  logger.set_formatter(std::move(formatter));
  logger.info("{}", message);
  logger.flush();
  return out.str();
}

TEST(LogFormatTest, JsonEscapesQuotesBackslashesAndControlCharacters) {
  const std::string line =
      Formatted(LogFormatter(LogFormat::kJson),
                "field \"x\" at C:\\tmp\nnext\tcell\x01 end");
  ASSERT_FALSE(line.empty());
  EXPECT_EQ(line.back(), '\n');
  EXPECT_THAT(line.substr(0, line.size() - 1),
              MatchesRegex(R"(\{"time":"[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9:.]+Z",)"
                           R"("level":"info",.*\})"));
  EXPECT_THAT(line, EndsWith(R"("message":"field \"x\" at C:\\tmp\nnext\t)"
                             R"(cell\u0001 end"})"
                             "\n"));
}

TEST(LogFormatTest, AnnouncementsAreThePlainMessageInText) {
  EXPECT_EQ(Formatted(AnnouncementFormatter(LogFormat::kText),
                      "freeformd listening on 127.0.0.1:50051"),
            "freeformd listening on 127.0.0.1:50051\n");
  EXPECT_THAT(Formatted(AnnouncementFormatter(LogFormat::kJson),
                        "freeformd listening on 127.0.0.1:50051"),
              EndsWith(R"("message":"freeformd listening on 127.0.0.1:50051"})"
                       "\n"));
}

TEST(LogFormatTest, OnlyTextAndJsonAreFormats) {
  EXPECT_EQ(*ParseLogFormat("text"), LogFormat::kText);
  EXPECT_EQ(*ParseLogFormat("json"), LogFormat::kJson);
  EXPECT_FALSE(ParseLogFormat("xml").ok());
  EXPECT_FALSE(ParseLogFormat("JSON").ok());
}

}  // namespace
}  // namespace freeform::server
