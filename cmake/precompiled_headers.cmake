# freeform_precompile_headers(target header...): precompiles the heavy
# third-party headers that most of a target's files include. Parsing the
# gRPC, protobuf, GoogleTest and CLI11 headers again in every file was the
# larger half of the build's time; a precompiled header halves the time of
# such a file. -DFREEFORM_PRECOMPILE_HEADERS=OFF builds without them, e.g.
# to check that every file includes what it uses.
option(FREEFORM_PRECOMPILE_HEADERS
  "Precompile the gRPC, protobuf, GoogleTest and CLI11 headers" ON)

function(freeform_precompile_headers target)
  if(FREEFORM_PRECOMPILE_HEADERS)
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()

# The headers of every file that speaks gRPC: the generated services and
# the gRPC C++ API.
set(FREEFORM_GRPC_HEADERS
  <grpcpp/grpcpp.h>
  [["freeform/v1/curve_service.grpc.pb.h"]]
  [["freeform/v1/surface_service.grpc.pb.h"]]
  [["absl/status/statusor.h"]]
  [["absl/strings/str_cat.h"]]
  <algorithm> <cmath> <cstdint> <memory> <optional> <string> <vector>)

# The test framework's headers.
set(FREEFORM_TEST_HEADERS <gmock/gmock.h> <gtest/gtest.h>)
