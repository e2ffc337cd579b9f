// ReadFileToString, ReadStandardInput and ReadRegularFile
// (freeform/io/file.h): the file
// through POSIX read, so that a failure names its reason (errno).
#include "freeform/io/file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>

#include "absl/strings/str_cat.h"

namespace freeform {
namespace {

absl::Status ReadError(const std::string& path, int error) {
  const std::string message =
      absl::StrCat("cannot read ", path, ": ", std::strerror(error));
  return error == ENOENT ? absl::NotFoundError(message)
                         : absl::FailedPreconditionError(message);
}

// OpenedFile closes its descriptor when it goes out of scope.
class OpenedFile {
 public:
  explicit OpenedFile(int fd) : fd_(fd) {}
  ~OpenedFile() {
    if (fd_ >= 0) close(fd_);
  }
  OpenedFile(const OpenedFile&) = delete;
  OpenedFile& operator=(const OpenedFile&) = delete;

  int fd() const { return fd_; }

 private:
  const int fd_;
};

// ReadAtMost appends what `fd` holds to `contents`, up to `limit` bytes in
// all: fewer when the file ends first.
absl::Status ReadAtMost(const std::string& path, int fd, size_t limit,
                        std::string& contents) {
  char buffer[1 << 16];
  while (contents.size() < limit) {
    const size_t wanted = std::min(sizeof(buffer), limit - contents.size());
    const ssize_t got = read(fd, buffer, wanted);
    if (got == 0) break;
    if (got < 0) {
      if (errno == EINTR) continue;
      return ReadError(path, errno);
    }
    contents.append(buffer, static_cast<size_t>(got));
  }
  return absl::OkStatus();
}

// KindOf names what a file that is not a regular file is.
const char* KindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a file";
}

// ReadBounded returns what `fd` (named `path`) holds, refusing more than
// `max_bytes`: one byte past the limit tells.
absl::StatusOr<std::string> ReadBounded(const std::string& path, int fd,
                                        size_t max_bytes) {
  std::string contents;
  const size_t limit = max_bytes == std::numeric_limits<size_t>::max()
                           ? max_bytes
                           : max_bytes + 1;
  absl::Status read = ReadAtMost(path, fd, limit, contents);
  if (!read.ok()) return read;
  if (contents.size() > max_bytes) {
    return absl::FailedPreconditionError(absl::StrCat(
        "cannot read ", path, ": it is larger than ", max_bytes, " bytes"));
  }
  return contents;
}

}  // namespace

absl::StatusOr<std::string> ReadFileToString(const std::string& path,
                                             size_t max_bytes) {
  const OpenedFile file(open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (file.fd() < 0) return ReadError(path, errno);
  return ReadBounded(path, file.fd(), max_bytes);
}

absl::StatusOr<std::string> ReadStandardInput(size_t max_bytes) {
  return ReadBounded("stdin", STDIN_FILENO, max_bytes);
}

absl::StatusOr<std::string> ReadRegularFile(const std::string& path,
                                            size_t max_bytes) {
  // O_NONBLOCK: opening a FIFO returns at once instead of waiting for a
  // writer; it changes nothing for a regular file.
  const OpenedFile file(open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK));
  if (file.fd() < 0) return ReadError(path, errno);
  struct stat status {};
  if (fstat(file.fd(), &status) != 0) return ReadError(path, errno);
  if (!S_ISREG(status.st_mode)) {
    return absl::FailedPreconditionError(
        absl::StrCat("cannot read ", path, ": not a regular file (",
                     KindOf(status.st_mode), ")"));
  }
  const std::string too_long = absl::StrCat(
      "cannot read ", path, ": it is larger than ", max_bytes, " bytes");
  if (static_cast<uint64_t>(status.st_size) > max_bytes) {
    return absl::FailedPreconditionError(too_long);
  }
  // The file may grow between fstat and read.
  return ReadBounded(path, file.fd(), max_bytes);
}

}  // namespace freeform
