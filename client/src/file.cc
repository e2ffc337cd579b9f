#include "freeform/client/file.h"

#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"

namespace freeform {

absl::StatusOr<std::string> ReadFileToString(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::NotFoundError(absl::StrCat("cannot read ", path));
  std::ostringstream contents;
  contents << in.rdbuf();
  return contents.str();
}

}  // namespace freeform
