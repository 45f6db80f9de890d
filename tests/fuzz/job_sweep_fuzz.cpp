// libFuzzer target: sweeps of batch job files. The input is an output
// pattern (its first line) and a "sweep" object (the rest, as JSON text);
// the target writes a job file of three lines, the sweep, a fixed job and
// the same sweep again, and reads it with JobReader (at most 64 jobs).
// job_lines_fuzz must first find a sweep's syntax; this target starts
// there and checks what the reader promises of sweeps: it yields as many
// jobs as it counted, a sweep's jobs in index order and as many as the
// product of its value counts, only .exr outputs, no output or PNG preview
// twice (every job of the repeated line is refused as a copy of the first
// line's), and it refuses a file past the limit only when it is past it.
#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

#include <nlohmann/json.hpp>

#include "fuzz_support.h"
#include "session/job_file.h"

namespace fs = std::filesystem;
using namespace spectrace;

namespace {

constexpr uint64_t kMaxJobs = 64;

fs::path jobFile() {
  static const fs::path file = [] {
    const fs::path dir = fuzz::scratchDir() / "sweep";
    fs::create_directories(dir);
    std::error_code ec;
    fs::create_symlink(fs::path(SPECTRACE_SOURCE_DIR) / "scenes" / "batch" / "lamp.json", dir / "lamp.json", ec);
    return dir / "jobs.jsonl";
  }();
  return file;
}

// The sweep's combinations as the JSON text says (capped at 2^70), or none
// when it is not an object of non-empty arrays.
std::optional<unsigned __int128> combinationsOf(const std::string& sweep) {
  try {
    const auto j = nlohmann::json::parse(sweep, nullptr, true, true);
    if (!j.is_object() || j.empty()) return std::nullopt;
    unsigned __int128 n = 1;
    for (const auto& [key, values] : j.items()) {
      if (!values.is_array() || values.empty()) return std::nullopt;
      n = std::min<unsigned __int128>(n * values.size(), (unsigned __int128)1 << 70);
    }
    return n;
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

std::string lowerCase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  return s;
}

// What every entry promises, and no output (or PNG preview) twice.
void checkEntry(const JobEntry& e, std::unordered_set<std::string>& outputs, std::unordered_set<std::string>& previews) {
  fuzz::require(e.job.has_value() != !e.error.empty(), "a job entry has both or neither of job and error");
  fuzz::require(e.error.empty() || e.error.rfind(e.where + ": ", 0) == 0, "an error does not start with its job's line");
  if (!e.job) return;
  fuzz::require(e.job->output == e.output, "a job's output is not its entry's");
  fuzz::require(lowerCase(e.output.extension().string()) == ".exr", "a job's output does not end in .exr");
  fuzz::require(outputs.insert(e.output.string()).second, "two jobs have one output");
  fuzz::require(previews.insert(fs::path(e.output).replace_extension(".png").string()).second,
                "two jobs have one PNG preview");
}

// Lines 1 and 3 are the same sweep: as many entries, in index order, and
// each job of line 1 makes line 3's a copy.
void checkSweepLines(const std::vector<JobEntry>& first, const std::vector<JobEntry>& third, const std::string& file,
                     const std::optional<unsigned __int128>& combinations) {
  fuzz::require(first.size() == third.size(), "the same line gave another number of jobs");
  const bool swept = first.size() > 1 || (first.size() == 1 && first[0].where != file + ":1");
  if (swept && combinations) fuzz::require(first.size() == *combinations, "a sweep's jobs are not its combinations");
  for (size_t i = 0; i < first.size(); ++i) {
    if (swept) {
      fuzz::require(first[i].where == file + ":1 [" + std::to_string(i) + "]", "a sweep's jobs are out of order");
      fuzz::require(third[i].where == file + ":3 [" + std::to_string(i) + "]", "a sweep's jobs are out of order");
    }
    fuzz::require(!third[i].job, "a job repeating an earlier one was not refused");
    if (first[i].job)
      fuzz::require(third[i].error == third[i].where + ": /output: " + first[i].output.string() +
                                          " is also the output of " + first[i].where,
                    "a copy of " + first[i].where + " was refused for another reason than its output: " + third[i].error);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const size_t newline = input.find('\n');
  const std::string pattern = input.substr(0, newline);
  std::string sweep = newline == std::string::npos ? "" : input.substr(newline + 1);
  std::replace_if(sweep.begin(), sweep.end(), [](char ch) { return ch == '\n' || ch == '\r'; }, ' ');
  const std::string quoted = nlohmann::json(pattern).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  const std::string line = R"({"scene": "lamp.json", "beams": 1, "output": )" + quoted + R"(, "sweep": )" + sweep + "}\n";
  const std::string text = line + R"({"scene": "lamp.json", "beams": 1, "output": "fixed.exr"})" "\n" + line;
  const fs::path file = jobFile();
  fuzz::writeBytes(file, reinterpret_cast<const uint8_t*>(text.data()), text.size());
  const auto combinations = combinationsOf(sweep);
  JobReaderOptions options;
  options.outDir = fuzz::scratchDir() / "sweep_out";
  options.maxJobs = kMaxJobs;
  try {
    JobReader reader(file, options);
    std::vector<JobEntry> lines[3];
    std::unordered_set<std::string> outputs, previews;
    while (auto entry = reader.next()) {
      checkEntry(*entry, outputs, previews);
      const size_t n = entry->where.rfind(file.string() + ":2", 0) == 0 ? 1
                       : entry->where.rfind(file.string() + ":3", 0) == 0 ? 2 : 0;
      lines[n].push_back(std::move(*entry));
    }
    fuzz::require(lines[0].size() + lines[1].size() + lines[2].size() == reader.total(),
                  "the reader yielded another number of jobs than it counted");
    // The fixed job stands unless the sweep before it took its output.
    fuzz::require(lines[1].size() == 1 && (lines[1][0].job || lines[1][0].error.rfind(file.string() + ":2: /output: ", 0) == 0),
                  "the fixed job was not one job, or failed for another reason than its output");
    checkSweepLines(lines[0], lines[2], file.string(), combinations);
  } catch (const JobFileError& e) {
    const std::string message = e.what();
    const bool sweepPast = message.find("/sweep: ") != std::string::npos &&
                           message.find("a job file may hold at most 64 jobs") != std::string::npos;
    const bool fixedPast = message.rfind(file.string() + ":2: the job file holds more than 64 jobs", 0) == 0;
    fuzz::require(sweepPast || fixedPast, "a job file was refused for another reason than its job count: " + message);
    fuzz::require(!combinations || 2 * *combinations + 1 > kMaxJobs, "a sweep within the limit was refused");
  }
  return 0;
}
