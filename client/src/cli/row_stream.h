// StreamRows: a streaming evaluation's answer written as rows chunk by chunk
// as the chunks arrive, in constant memory, with a progress bar (`eval
// --stream`, `surface --stream`), and the flags that ask for it.
#ifndef FREEFORM_CLIENT_CLI_ROW_STREAM_H_
#define FREEFORM_CLIENT_CLI_ROW_STREAM_H_

#include <cstdint>
#include <cstdio>
#include <string>

#include "CLI/CLI.hpp"
#include "absl/functional/function_ref.h"
#include "absl/status/status.h"
#include "common.h"
#include "freeform/client.h"
#include "output.h"
#include "progress.h"
#include "rows.h"
#include "subcommand.h"

namespace freeform::cli {

// AddStreamFlags adds --stream (the Stream RPC, written as it arrives;
// `use` says for what) and --format (json, csv or jsonl).
inline void AddStreamFlags(CLI::App& command, bool& stream, std::string& format,
                           const std::string& use) {
  command.add_flag(
      "--stream", stream,
      "Use EvaluateStream and write the points as they arrive, in constant "
      "memory (" +
          use +
          "); --format json then writes one document "
          "{\"dimension\": D, \"points\": [{\"index\": I, \"point\": "
          "[...], ...}, ...], \"count\": N}");
  AddFormatFlag(command, format, {"json", "csv", "jsonl"});
}

// StreamRows runs `stream` (a Client method such as EvaluateCurveStream)
// on `request`, writes each chunk with `write_chunk` in `format` to stdout,
// shows progress towards `total` points, and returns the exit status.
template <typename Request, typename Response>
int StreamRows(const CommonFlags& flags, Client& client,
               absl::Status (Client::*stream)(
                   const Request&,
                   absl::FunctionRef<absl::Status(const Response&)>),
               const Request& request, uint64_t total, RowFormat format,
               absl::Status (*write_chunk)(const Response&, RowWriter&)) {
  RowWriter writer(format, stdout);
  Progress progress(!flags.no_progress, total, "points");
  uint64_t done = 0;
  const absl::Status status =
      (client.*stream)(request, [&](const Response& chunk) {
        if (absl::Status written = write_chunk(chunk, writer); !written.ok()) {
          return written;
        }
        progress.Update(done += chunk.count());
        return absl::OkStatus();
      });
  if (!status.ok()) return ReportError(status);
  return FinishRows(writer);
}

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_ROW_STREAM_H_
