#include "fuzz_support.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include <unistd.h>

namespace spectrace::fuzz {

// Removed, with what it holds, when the process exits normally (a finding's
// abort leaves it; libFuzzer saves the input itself).
const std::filesystem::path& scratchDir() {
  static const struct Scratch {
    std::filesystem::path dir;
    ~Scratch() {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  } scratch{[] {
    auto d = std::filesystem::temp_directory_path() / ("spectrace-fuzz-" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    return d;
  }()};
  return scratch.dir;
}

void writeBytes(const std::filesystem::path& file, const uint8_t* data, size_t size) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  require(bool(out), "cannot write the fuzz input to " + file.string());
}

void requireFinite(double x, const std::string& what) { require(std::isfinite(x), what + " is not finite"); }

void require(bool ok, const std::string& what) {
  if (ok) return;
  std::fprintf(stderr, "spectrace fuzz finding: %s\n", what.c_str());
  std::abort();
}

}  // namespace spectrace::fuzz
