// Writing the freeform CLI's answers: messages as proto3 JSON, files such as
// pictures and meshes ('-' for stdout), and numbers in their shortest form.
#ifndef FREEFORM_CLIENT_CLI_OUTPUT_H_
#define FREEFORM_CLIENT_CLI_OUTPUT_H_

#include <google/protobuf/message.h>

#include <ostream>
#include <string>

#include "absl/functional/function_ref.h"
#include "common.h"
#include "obj_mesh.h"
#include "rows.h"
#include "svg_drawing.h"

namespace freeform::cli {

// ToJson prints a message as one line of canonical proto3 JSON
// (lowerCamelCase names), or with the .proto field names when
// `proto_field_names`.
std::string ToJson(const google::protobuf::Message& message,
                   bool proto_field_names);

// PrintJson writes the message's JSON (as `flags` asks) to stdout and
// returns kExitOk.
int PrintJson(const CommonFlags& flags,
              const google::protobuf::Message& message);

// WriteOutput writes with `write` to `path` ('-': stdout), tells on stderr
// what it wrote (the path, then `summary`) and returns the exit status.
int WriteOutput(const std::string& path,
                absl::FunctionRef<void(std::ostream&)> write,
                const std::string& summary = "");

// WriteSvg writes the drawing to `path` ('-': stdout) and returns the exit
// status.
int WriteSvg(const SvgDrawing& drawing, const std::string& path);

// WriteObj writes the mesh as OBJ to `path` ('-': stdout), telling its
// size on stderr, and returns the exit status.
int WriteObj(const ObjMesh& mesh, const std::string& path);

// FinishRows ends the rows' output and returns the exit status
// (kExitUsage when stdout could not be written).
int FinishRows(RowWriter& writer);

// FormatNumber prints a double with the fewest digits that read back to
// it.
std::string FormatNumber(double value);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_OUTPUT_H_
