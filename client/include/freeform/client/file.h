// Reading small files (TLS certificates and keys, request files) into
// memory, with errors as absl::Status: the file I/O of the client library,
// the CLI and the server (the core does none). Thread-safe.
#ifndef FREEFORM_CLIENT_FILE_H_
#define FREEFORM_CLIENT_FILE_H_

#include <string>

#include "absl/status/statusor.h"

namespace freeform {

// ReadFileToString returns the whole contents of `path`, or an error that
// names the path and the reason ("cannot read PATH: No such file or
// directory"): NOT_FOUND when it does not exist, FAILED_PRECONDITION when it
// cannot be opened or read (a directory, no permission).
absl::StatusOr<std::string> ReadFileToString(const std::string& path);

}  // namespace freeform

#endif  // FREEFORM_CLIENT_FILE_H_
