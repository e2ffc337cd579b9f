#include "static_files.h"

namespace freeform::server {

const StaticFile* FindStaticFile(absl::string_view path) {
  for (const StaticFile& file : StaticFiles()) {
    if (file.path == path) return &file;
  }
  return nullptr;
}

}  // namespace freeform::server
