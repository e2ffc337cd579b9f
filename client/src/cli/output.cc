// Writing the freeform CLI's answers (output.h).
#include "output.h"

#include <google/protobuf/util/json_util.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <iostream>

#include "absl/strings/str_cat.h"

namespace freeform::cli {

std::string ToJson(const google::protobuf::Message& message,
                   bool proto_field_names) {
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = proto_field_names;
  std::string json;
  (void)google::protobuf::util::MessageToJsonString(message, &json, options);
  return json + "\n";
}

int PrintJson(const CommonFlags& flags,
              const google::protobuf::Message& message) {
  std::cout << ToJson(message, flags.proto_field_names);
  return kExitOk;
}

int WriteOutput(const std::string& path,
                absl::FunctionRef<void(std::ostream&)> write,
                const std::string& summary) {
  if (path == "-") {
    write(std::cout);
    return kExitOk;
  }
  std::ofstream out(path);
  if (!out) {
    std::cerr << "error: cannot write " << path << ": " << std::strerror(errno)
              << "\n";
    return kExitUsage;
  }
  write(out);
  out.close();
  if (!out) {
    std::cerr << "error: cannot write " << path << "\n";
    return kExitUsage;
  }
  std::cerr << "wrote " << path << summary << "\n";
  return kExitOk;
}

int WriteSvg(const SvgDrawing& drawing, const std::string& path) {
  return WriteOutput(path, [&](std::ostream& out) { drawing.Write(out); });
}

int WriteObj(const ObjMesh& mesh, const std::string& path) {
  return WriteOutput(
      path, [&](std::ostream& out) { mesh.Write(out); },
      absl::StrCat(": ", mesh.vertex_count(), " vertices, ",
                   mesh.triangle_count(), " triangles"));
}

int FinishRows(RowWriter& writer) {
  const absl::Status status = writer.Finish();
  return status.ok() ? kExitOk : InputError(status);
}

std::string FormatNumber(double value) {
  char buffer[32];
  const std::to_chars_result result =
      std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

}  // namespace freeform::cli
