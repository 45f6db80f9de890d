// Text outputs (JSON, CSV), written as the images are: to a temporary file
// beside the target, renamed into place when complete.
#include "io/atomic_file.h"
#include "io/image.h"

namespace spectrace {

void writeTextFile(const std::filesystem::path& path, const std::string& text, const char* what) {
  io_detail::AtomicFile file(path, what);
  if (const int err = io_detail::pwriteAll(file.fd(), text.data(), text.size(), 0))
    file.fail(io_detail::errnoText(err));
  file.commit();
}

}  // namespace spectrace
