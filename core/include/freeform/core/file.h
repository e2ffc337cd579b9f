// Reading small files (certificates, request files) into memory, with errors
// as absl::Status. Thread-safe.
#ifndef FREEFORM_CORE_FILE_H_
#define FREEFORM_CORE_FILE_H_

#include <string>

#include "absl/status/statusor.h"

namespace freeform {

// ReadFileToString returns the whole contents of `path`, or NOT_FOUND when
// it cannot be opened.
absl::StatusOr<std::string> ReadFileToString(const std::string& path);

}  // namespace freeform

#endif  // FREEFORM_CORE_FILE_H_
