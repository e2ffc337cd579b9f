// Evaluates the cubic Bezier (0,0) (1,2) (3,2) (4,0) at t = 0, 0.5, 1 on the
// freeformd given as the first argument and prints points and derivatives.
#include <cstdio>
#include <string>

#include "freeform/client.h"

int main(int argc, char** argv) {
  freeform::ClientOptions options;
  options.target = argc > 1 ? argv[1] : "localhost:50051";
  auto client = freeform::Client::Create(options);
  if (!client.ok()) return 1;
  auto samples = (*client)->EvaluateBezier(2, {0, 0, 1, 2, 3, 2, 4, 0},
                                           {0.0, 0.5, 1.0}, 1);
  if (!samples.ok()) {
    std::fprintf(stderr, "%s\n", samples.status().ToString().c_str());
    return 1;
  }
  for (size_t r = 0; r < samples->count; ++r) {
    auto point = samples->Point(0, r);
    auto tangent = samples->Point(1, r);
    std::printf("C = (%g, %g)  C' = (%g, %g)\n", point[0], point[1], tangent[0],
                tangent[1]);
  }
  return 0;
}
