// Reading small files (TLS certificates and keys, request files) into
// memory, with errors as absl::Status: the file I/O of the client library,
// the CLI and the server (the core does none). Thread-safe.
#ifndef FREEFORM_IO_FILE_H_
#define FREEFORM_IO_FILE_H_

#include <cstddef>
#include <limits>
#include <string>

#include "absl/status/statusor.h"

namespace freeform {

// The most bytes read of one TLS certificate chain, private key or CA
// bundle. PEM files are a few KB; 1 MiB holds any real chain, and Debian's
// whole CA bundle (/etc/ssl/certs/ca-certificates.crt) is about 220 KB.
inline constexpr size_t kMaxCredentialFileBytes = size_t{1} << 20;

// ReadFileToString returns the whole contents of `path` (any file that
// reads: a pipe or process substitution too), or an error that names the
// path and the reason ("cannot read PATH: No such file or directory"):
// NOT_FOUND when it does not exist, FAILED_PRECONDITION when it cannot be
// opened or read (a directory, no permission) or holds more than
// `max_bytes` ("... is larger than N bytes", after reading max_bytes + 1).
absl::StatusOr<std::string> ReadFileToString(
    const std::string& path,
    size_t max_bytes = std::numeric_limits<size_t>::max());

// ReadStandardInput returns what stdin holds, refused like
// ReadFileToString past `max_bytes`.
absl::StatusOr<std::string> ReadStandardInput(size_t max_bytes);

// ReadRegularFile returns the contents of `path` when it is a regular file
// (or a symbolic link to one) of at most `max_bytes` bytes. Anything else is
// refused with FAILED_PRECONDITION naming the path, without reading more
// than max_bytes + 1 bytes: a device, FIFO, socket or directory ("cannot
// read /dev/zero: not a regular file (a character device)"; opening a FIFO
// does not wait for a writer), or a longer file ("... is larger than
// 1048576 bytes"). NOT_FOUND when it does not exist.
absl::StatusOr<std::string> ReadRegularFile(const std::string& path,
                                            size_t max_bytes);

}  // namespace freeform

#endif  // FREEFORM_IO_FILE_H_
