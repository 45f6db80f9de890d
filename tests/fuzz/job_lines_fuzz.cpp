// libFuzzer target: batch job files (JobReader): JSON lines with "set"
// overrides and sweeps, each job built and its scene parsed. A bad line must
// become a job entry with an error; the reader itself throws only
// JobFileError, for a file it cannot read or one past its job limit.
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
  JobReaderOptions options;
  options.outDir = fuzz::scratchDir() / "out";
  options.maxJobs = 64;  // each job's scene is parsed: a few per input keep the fuzzer fast
  try {
    JobReader reader(file, options);
    uint64_t entries = 0;
    while (auto entry = reader.next()) {
      ++entries;
      fuzz::require(entry->job.has_value() != !entry->error.empty(), "a job entry has both or neither of job and error");
      fuzz::require(!entry->where.empty(), "a job entry does not say where it is from");
    }
    fuzz::require(entries == reader.total(), "the reader yielded another number of jobs than it counted");
  } catch (const JobFileError&) {
  }
  return 0;
}
