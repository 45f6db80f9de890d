// libFuzzer target: batch job files (readJobFile): JSON lines with "set"
// overrides and sweeps, each expanded and its scene parsed. A bad line must
// become a job entry with an error; readJobFile itself throws only
// JobFileError, for a file it cannot read.
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "fuzz_support.h"
#include "session/job_file.h"

namespace fs = std::filesystem;
using namespace spectrace;

namespace {

// The job file sits three folders below a link to scenes/, as the seeds
// from tests/data/batch/ expect ("../../../scenes/batch/lamp.json"), beside
// a link to lamp.json for the seeds from scenes/batch/.
fs::path jobFile() {
  static const fs::path file = [] {
    const fs::path root = fuzz::scratchDir(), dir = root / "a" / "b" / "c";
    const fs::path scenes = fs::path(SPECTRACE_SOURCE_DIR) / "scenes";
    fs::create_directories(dir);
    std::error_code ec;
    fs::create_directory_symlink(scenes, root / "scenes", ec);
    fs::create_symlink(scenes / "batch" / "lamp.json", dir / "lamp.json", ec);
    return dir / "jobs.jsonl";
  }();
  return file;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fs::path file = jobFile();
  fuzz::writeBytes(file, data, size);
  for (const JobEntry& entry : readJobFile(file, fuzz::scratchDir() / "out")) {
    fuzz::require(entry.job.has_value() != !entry.error.empty(), "a job entry has both or neither of job and error");
    fuzz::require(!entry.where.empty(), "a job entry does not say where it is from");
  }
  return 0;
}
