#pragma once
// Batch job files (JSON Lines): each non-empty line not starting with '#'
// is one job, e.g.
//   {"scene": "lamp.json", "output": "lamp_2700.exr", "beams": 1e8, "seed": 3,
//    "set": {"/lights/0/spd/blackbody_k": 2700}}
// "set" overrides scene fields by JSON pointer before the scene is parsed
// and validated; "sweep" ({pointer: [values...]}) expands a line into the
// Cartesian product of its values (first key outermost), named by an output
// pattern with {index} and {<pointer>} placeholders. Relative scene paths
// resolve against the job file's folder, relative outputs against the
// output folder (default: the job file's folder).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "session/session.h"

namespace spectrace {

// The job file itself cannot be read.
struct JobFileError : std::runtime_error {
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

// Reads every job of `file`. A bad line or scene becomes an entry with an
// error (the other jobs are unaffected); only an unreadable file throws.
std::vector<JobEntry> readJobFile(const std::filesystem::path& file,
                                  const std::optional<std::filesystem::path>& outDir = std::nullopt);

}  // namespace spectrace
