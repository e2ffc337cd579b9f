// The Utah teapot of examples/teapot.json (32 bicubic Bezier patches) as
// owned nets, for the core tests that mesh it or query it.
#ifndef FREEFORM_TESTS_CORE_TEAPOT_H_
#define FREEFORM_TESTS_CORE_TEAPOT_H_

#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "freeform/core/tensor_surface.h"

namespace freeform::testing_util {

// Owned patch nets.
struct Patches {
  std::vector<std::vector<double>> nets;
  std::vector<std::array<int, 2>> counts;
  std::vector<BezierSurfaceView> Views() const {
    std::vector<BezierSurfaceView> views;
    for (size_t i = 0; i < nets.size(); ++i) {
      views.push_back({.control_net = {.dimension = 3,
                                       .count_u = counts[i][0],
                                       .count_v = counts[i][1],
                                       .coordinates = nets[i]},
                       .weights = {}});
    }
    return views;
  }
};

// ReadTeapot reads the 32 bicubic patches of examples/teapot.json with a
// minimal number scanner: the numbers between "patches" and "vertices".
// FREEFORM_SOURCE_DIR is the repository (a definition of the test target).
inline Patches ReadTeapot() {
  const std::string path = FREEFORM_SOURCE_DIR "/examples/teapot.json";
  std::ifstream file(path);
  EXPECT_TRUE(file.good()) << path;
  std::stringstream buffer;
  buffer << file.rdbuf();
  const std::string text = buffer.str();
  const size_t begin = text.find("\"patches\"");
  size_t end = text.find("\"vertices\"", begin);
  if (end == std::string::npos) end = text.size();
  std::vector<double> numbers;
  for (size_t k = begin; k < end;) {
    const char c = text[k];
    if (c == '-' || c == '.' || (c >= '0' && c <= '9')) {
      size_t used = 0;
      numbers.push_back(std::stod(text.substr(k, 40), &used));
      k += used;
    } else {
      ++k;
    }
  }
  EXPECT_EQ(numbers.size(), 32u * 48u);
  Patches patches;
  for (size_t i = 0; i + 48 <= numbers.size(); i += 48) {
    patches.nets.emplace_back(numbers.begin() + i, numbers.begin() + i + 48);
    patches.counts.push_back({4, 4});
  }
  return patches;
}

}  // namespace freeform::testing_util

#endif  // FREEFORM_TESTS_CORE_TEAPOT_H_
