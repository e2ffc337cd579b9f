// ParseText: a message of the fuzz support tests from protobuf text
// format, failing the test when the text does not parse.
#ifndef FREEFORM_TESTS_FUZZ_PARSE_TEXT_H_
#define FREEFORM_TESTS_FUZZ_PARSE_TEXT_H_

#include <gtest/gtest.h>

#include <string>

#include "google/protobuf/text_format.h"

namespace freeform::fuzz {

template <typename T>
T ParseText(const std::string& text) {
  T message;
  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &message))
      << text;
  return message;
}

}  // namespace freeform::fuzz

#endif  // FREEFORM_TESTS_FUZZ_PARSE_TEXT_H_
