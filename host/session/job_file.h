#pragma once
// Batch job files (JSON Lines): each non-empty line not starting with '#'
// is one job, e.g.
//   {"scene": "lamp.json", "output": "lamp_2700.exr", "beams": 1e8, "seed": 3,
//    "set": {"/lights/0/spd/blackbody_k": 2700}}
// "set" overrides scene fields by JSON pointer before the scene is parsed
// and validated; "sweep" ({pointer: [values...]}) expands a line into the
// Cartesian product of its values (first key outermost), named by an output
// pattern with {index} and {<pointer>} placeholders. "state" names the
// job's render state (as render --state), with the same placeholders, on a
// line without "set" or "sweep" (merge and resume develop a state from its
// scene file). Relative scene paths resolve against the job file's folder,
// relative outputs and states against the output folder (default: the job
// file's folder).
//
// A JobReader reads a job file in two passes. The first, in the
// constructor, checks every line and counts its jobs without building any
// (a sweep's count is the product of its value counts), so a file past
// the job limit is refused before anything renders. The second, next(),
// builds one job at a time. Memory is the file's bytes, a few words per
// line and one entry per distinct output, never a scene per job.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "session/session.h"

namespace spectrace {

// At most this many jobs per job file (all lines and sweeps together).
// The batch keeps a table row and an output name per job (a few hundred
// bytes each, some hundreds of MB at the limit), and even at a second per
// job 10^6 jobs take 11 days; a larger study is split over several files.
inline constexpr uint64_t kMaxJobsPerFile = 1'000'000;

// A job file's scenes are read once each and held while it is read, up to
// this many bytes of scene files; past it the held ones are dropped (and
// read again when named again), so a file naming many big scenes cannot
// hold them all.
inline constexpr uint64_t kSceneCacheBytes = uint64_t(256) << 20;

// The job file cannot be read, or holds more jobs than the limit. Bad
// input: exit code 2.
struct JobFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The cancel flag was set while the job file was being read.
struct JobFileCancelled : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One job of a job file: a RenderJob ready to render, or why there is none.
struct JobEntry {
  std::string where;                 // "jobs.jsonl:3", "jobs.jsonl:3 [2]" within a sweep
  std::optional<RenderJob> job;      // empty when the line or its scene is bad
  std::string error;                 // "jobs.jsonl:3: <field>: <what>" when job is empty
  std::filesystem::path output;      // when known
  std::optional<uint64_t> beams;     // when known
};

struct JobReaderOptions {
  std::optional<std::filesystem::path> outDir;  // relative outputs resolve here
  uint64_t maxJobs = kMaxJobsPerFile;
  const std::atomic<bool>* cancel = nullptr;    // checked between lines of the first pass
};

class JobReader {
 public:
  // Reads and checks `file`, counting its jobs. Throws JobFileError when
  // the file cannot be read or holds more than options.maxJobs jobs (a
  // sweep whose count passes 2^64 included), JobFileCancelled when the
  // cancel flag is set. A bad line is not an error here: it becomes one
  // entry with an error, and the other jobs stand.
  explicit JobReader(const std::filesystem::path& file, JobReaderOptions options = {});
  ~JobReader();
  JobReader(const JobReader&) = delete;
  JobReader& operator=(const JobReader&) = delete;

  // The number of entries next() yields in all.
  uint64_t total() const;
  // The next job in file order (a sweep's in index order), built now, or
  // none after the last. An output that is not an .exr, or that an earlier
  // job of the file already has, makes the entry an error; so does a state
  // that an earlier job writes (as its state, output or PNG preview).
  std::optional<JobEntry> next();
  // Scene files read from disk so far: each once, however many lines and
  // jobs name it (unless the scenes held pass kSceneCacheBytes).
  uint64_t sceneFilesRead() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace spectrace
