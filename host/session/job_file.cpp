#include "session/job_file.h"

#include <algorithm>
#include <cctype>
#include <unordered_map>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "json/input_file.h"
#include "json/json_fields.h"
#include "scene/scene_override.h"

namespace spectrace {
namespace {

namespace fs = std::filesystem;
namespace jf = json_fields;
using jf::Json;

struct JobError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
[[noreturn]] void raiseJobError(const std::string& message) { throw JobError(message); }

// The value at `pointer` as it appears in an output name: numbers as fmt
// "{}" writes them, strings bare, anything else as compact JSON.
std::string nameOf(const Json& v) {
  if (v.is_number_unsigned()) return fmt::format("{}", v.get<uint64_t>());
  if (v.is_number_integer()) return fmt::format("{}", v.get<int64_t>());
  if (v.is_number_float()) return fmt::format("{}", v.get<double>());
  if (v.is_string()) return v.get<std::string>();
  return v.dump();
}

Json::json_pointer pointerOf(const jf::Source& c, const std::string& field, const std::string& text) {
  try {
    return Json::json_pointer(text);
  } catch (const nlohmann::json::exception&) {
    c.fail(field, fmt::format("{} is not a JSON pointer (it must be empty or start with '/')", jf::jsonQuoted(text)));
  }
}

// Sets `pointer` in the scene (applySceneOverride), failing at `field`.
void applyOverride(const jf::Source& c, const std::string& field, Json& scene, const std::string& text,
                   const Json& value, const fs::path& scenePath) {
  try {
    applySceneOverride(scene, SceneOverride{text, value}, scenePath);
  } catch (const SceneOverrideError& e) {
    c.fail(field, e.what());
  }
}

// Output or state pattern (`field`: "/output", "/state"): {index} and
// {<pointer>} replaced; "{{" and "}}" are braces.
std::string expandPattern(const jf::Source& c, const std::string& field, const std::string& pattern, uint64_t index,
                          const Json& scene) {
  std::string out;
  for (size_t i = 0; i < pattern.size(); ++i) {
    const char ch = pattern[i];
    if ((ch == '{' || ch == '}') && i + 1 < pattern.size() && pattern[i + 1] == ch) {
      out.push_back(ch);
      ++i;
      continue;
    }
    if (ch != '{') {
      out.push_back(ch);
      continue;
    }
    const size_t end = pattern.find('}', i);
    if (end == std::string::npos) c.fail(field, fmt::format("unclosed '{{' in {}", jf::jsonQuoted(pattern)));
    const std::string name = pattern.substr(i + 1, end - i - 1);
    if (name == "index") {
      out += std::to_string(index);
    } else {
      const auto pointer = pointerOf(c, field, name);
      if (name.empty() || !scene.contains(pointer))
        c.fail(field, fmt::format("{{{}}} names no field of the scene (use {{index}} or {{/json/pointer}})", name));
      out += nameOf(scene[pointer]);
    }
    i = end;
  }
  return out;
}

using Sweep = std::vector<std::pair<std::string, std::vector<Json>>>;

// What a line says, before its scene is read.
struct LineSpec {
  jf::Source c;  // names the line ("jobs.jsonl:3") in messages
  Json job;
  fs::path scenePath;
  std::optional<uint64_t> beams, seed;
  std::optional<std::string> outputPattern, statePattern;
  Sweep sweep;
  std::optional<uint64_t> count;  // the sweep's combinations; none when they pass 2^64 - 1
};

// The sweep's keys in the order written (nlohmann::json sorts them).
Sweep readSweep(const jf::Source& c, const Json& sweep, const std::string& text) {
  if (!sweep.is_object() || sweep.empty())
    c.fail("/sweep", fmt::format("must be an object of JSON pointer: [values...] (got {})", jf::describe(sweep)));
  Sweep out;
  const auto ordered = nlohmann::ordered_json::parse(text, nullptr, true, true);
  for (const auto& [key, values] : ordered.at("sweep").items()) {
    const std::string field = jf::child("/sweep", key);
    if (!values.is_array() || values.empty())
      c.fail(field, fmt::format("must be a non-empty array of values (got {})", jf::describe(Json::parse(values.dump()))));
    std::vector<Json> list;
    list.reserve(values.size());
    for (const auto& v : values) list.push_back(Json::parse(v.dump()));
    out.emplace_back(key, std::move(list));
  }
  return out;
}

// The number of combinations, or none when it passes 2^64 - 1.
std::optional<uint64_t> combinationsOf(const Sweep& sweep) {
  uint64_t count = 1;
  for (const auto& [key, values] : sweep)
    if (__builtin_mul_overflow(count, uint64_t(values.size()), &count)) return std::nullopt;
  return count;
}

// "1001 x 1000" (the first few factors of a long product).
std::string factorsOf(const Sweep& sweep) {
  std::string out;
  for (size_t k = 0; k < sweep.size() && k < 8; ++k) out += fmt::format("{}{}", k ? " x " : "", sweep[k].second.size());
  if (sweep.size() > 8) out += fmt::format(" x ... ({} keys)", sweep.size());
  return out;
}

// Parses and checks one line up to (not including) its scene.
LineSpec parseLine(const fs::path& file, size_t number, const std::string& text) {
  LineSpec spec;
  jf::Source& c = spec.c;
  c.file = fmt::format("{}:{}", file.string(), number);
  c.dir = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  c.raise = raiseJobError;
  spec.job = jf::parseJson(c, text);
  const Json& job = spec.job;
  if (!job.is_object()) c.fail("", fmt::format("a job must be a JSON object (got {})", jf::describe(job)));
  jf::checkObject(c, job, "", {"scene", "output", "state", "beams", "seed", "set", "sweep"}, "a job");
  const std::string sceneName = jf::getString(c, jf::require(c, job, "", "scene", " (the scene file)"), "/scene");
  const bool relative = !fs::path(sceneName).is_absolute();
  spec.scenePath = (relative ? c.dir / sceneName : fs::path(sceneName)).lexically_normal();
  // The path as the line gives it, and where it was looked for: relative
  // to the job file's folder, not to the working folder.
  std::error_code missing;
  if (fs::status(spec.scenePath, missing).type() == fs::file_type::not_found)
    c.fail("/scene", fmt::format("{}: scene file not found (looked for {}{})", sceneName,
                                 fs::absolute(spec.scenePath, missing).lexically_normal().string(),
                                 relative ? ", relative to the job file's folder" : ""));
  if (auto* x = jf::find(job, "beams")) spec.beams = jf::getU64(c, *x, "/beams", 1);
  if (auto* x = jf::find(job, "seed")) spec.seed = jf::getU64(c, *x, "/seed", 0);
  if (auto* x = jf::find(job, "output")) spec.outputPattern = jf::getString(c, *x, "/output");
  // A state carries the scene it was rendered from (overrides applied), so
  // a job with "set" or "sweep" may write one too.
  if (auto* x = jf::find(job, "state")) spec.statePattern = jf::getString(c, *x, "/state");
  if (auto* x = jf::find(job, "sweep")) {
    spec.sweep = readSweep(c, *x, text);
    const auto& pattern = spec.outputPattern;
    bool named = pattern && pattern->find("{index}") != std::string::npos;
    for (const auto& [key, values] : spec.sweep)
      if (pattern && pattern->find("{" + key + "}") != std::string::npos) named = true;
    if (!named)
      c.fail("/output", "a sweep needs an output pattern with {index} or a swept {/pointer} (or the outputs would collide)");
  }
  spec.count = combinationsOf(spec.sweep);
  return spec;
}

JobFileError tooManyJobs(const std::string& where, uint64_t maxJobs) {
  return JobFileError(fmt::format("{}: the job file holds more than {} jobs, the most a job file may hold; split it "
                                  "over several job files", where, maxJobs));
}

// Refuses the line when its jobs would bring the file past `maxJobs`
// (`before`: the jobs of the lines above, at most maxJobs).
void checkJobCount(const LineSpec& spec, uint64_t before, uint64_t maxJobs) {
  if (spec.count && *spec.count <= maxJobs - before) return;
  if (spec.sweep.empty()) throw tooManyJobs(spec.c.file, maxJobs);
  const std::string count = spec.count ? fmt::format("{} combinations", *spec.count) : "2^64 or more combinations";
  const std::string earlier = before ? fmt::format(" after {} job{} on the lines above", before, before == 1 ? "" : "s") : "";
  throw JobFileError(fmt::format("{}: /sweep: {} ({}){}; a job file may hold at most {} jobs; split the sweep over "
                                 "several job files", spec.c.file, count, factorsOf(spec.sweep), earlier, maxJobs));
}

// Scene files by path, each read once and held (up to kSceneCacheBytes).
class SceneCache {
 public:
  // The file's JSON, and with `sha256` and `text` the digest of its bytes
  // and the bytes.
  std::shared_ptr<const Json> get(const jf::Source& c, const fs::path& path, std::string* sha256 = nullptr,
                                  std::shared_ptr<const std::string>* text = nullptr) {
    auto it = held_.find(path.string());
    if (it == held_.end()) it = read(path);
    if (!it->second.json) c.fail("/scene", it->second.error);
    if (sha256) *sha256 = it->second.sha256;
    if (text) *text = it->second.text;
    return it->second.json;
  }
  uint64_t reads() const { return reads_; }

 private:
  struct Held {
    std::shared_ptr<const Json> json;
    std::string sha256;  // of the file's bytes
    std::shared_ptr<const std::string> text;  // the bytes: a job's state carries them
    std::string error;   // when json is null
  };
  std::unordered_map<std::string, Held>::iterator read(const fs::path& path) {
    std::error_code ec;
    const uint64_t size = fs::file_size(path, ec);
    // Held twice: as JSON (about its size) and as the file's bytes.
    if (ec == std::error_code() && bytes_ + 2 * size > kSceneCacheBytes) {
      held_.clear();
      bytes_ = 0;
    }
    Held held;
    try {
      std::string text;
      held.json = std::make_shared<const Json>(readSceneJson(path, &held.sha256, &text));
      held.text = std::make_shared<const std::string>(std::move(text));
      if (ec == std::error_code()) bytes_ += 2 * size;
    } catch (const SceneError& e) {
      held.error = e.what();
    }
    ++reads_;
    return held_.emplace(path.string(), std::move(held)).first;
  }
  std::unordered_map<std::string, Held> held_;
  uint64_t bytes_ = 0, reads_ = 0;
};

// The line's "set" overrides, in the order applied (a JSON object's: by key).
std::vector<SceneOverride> setOverridesOf(const LineSpec& spec) {
  std::vector<SceneOverride> overrides;
  if (const Json* set = jf::find(spec.job, "set"))
    for (const auto& [key, value] : set->items()) overrides.push_back({key, value});
  return overrides;
}

// The line's scene with its "set" overrides applied; `fileSha256` and
// `fileText`: the scene file's digest and bytes.
std::shared_ptr<const Json> baseOf(const LineSpec& spec, SceneCache& scenes, std::string* fileSha256 = nullptr,
                                   std::shared_ptr<const std::string>* fileText = nullptr) {
  const jf::Source& c = spec.c;
  std::shared_ptr<const Json> scene = scenes.get(c, spec.scenePath, fileSha256, fileText);
  const Json* set = jf::find(spec.job, "set");
  if (!set) return scene;
  if (!set->is_object()) c.fail("/set", fmt::format("must be an object of JSON pointer: value (got {})", jf::describe(*set)));
  auto copy = std::make_shared<Json>(*scene);
  for (const SceneOverride& o : setOverridesOf(spec))
    applyOverride(c, jf::child("/set", o.pointer), *copy, o.pointer, o.value, spec.scenePath);
  return copy;
}

std::string lowerCase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  return s;
}

}  // namespace

struct JobReader::State {
  // A job line of the file, as the first pass found it.
  struct Planned {
    size_t begin, size;  // its text within `bytes`
    size_t number;       // its line number
    uint64_t count;      // its jobs (1 for a bad line)
  };
  // The job that first claimed an output (its where, rebuilt for messages).
  struct Owner {
    size_t number;
    uint64_t index;
    bool swept;
    std::string extension;  // ".exr" as written (".EXR" is another EXR, but the same PNG preview)
  };
  // The line whose jobs next() is yielding.
  struct Current {
    size_t number;
    std::string where;
    std::optional<LineSpec> spec;        // none for a bad line
    std::shared_ptr<const Json> base;    // the scene with "set" applied
    std::string fileSha256;              // the scene file's digest
    std::shared_ptr<const std::string> fileText;  // and its bytes
    std::string error;                   // for a bad line
    uint64_t count = 1, index = 0;
    bool swept = false;
  };

  fs::path file;
  JobReaderOptions options;
  std::string bytes;
  std::vector<Planned> lines;
  std::unordered_map<size_t, std::string> errors;  // the bad lines' messages, by index in `lines`
  uint64_t total = 0;
  SceneCache scenes;
  size_t nextLine = 0;
  std::optional<Current> current;
  std::unordered_map<std::string, Owner> outputs;  // by the output without its extension
  std::unordered_map<std::string, Owner> states;   // by the state file

  std::string whereOf(size_t number) const { return fmt::format("{}:{}", file.string(), number); }
  std::string whereOf(const Owner& owner) const {
    return owner.swept ? fmt::format("{} [{}]", whereOf(owner.number), owner.index) : whereOf(owner.number);
  }
  void plan(size_t begin, size_t size, size_t number);
  Current open(size_t line);
  JobEntry entryOf(const Current& line, uint64_t index);
  void buildJob(const Current& line, uint64_t index, JobEntry& entry);
  fs::path outputFile(const jf::Source& jc, const std::string& field, const std::string& what, const LineSpec& spec,
                      const std::string& name) const;
  fs::path claimOutput(const jf::Source& jc, const Current& line, uint64_t index, const Json& scene);
  fs::path claimState(const jf::Source& jc, const Current& line, uint64_t index, const Json& scene);
};

// The first pass over one job line: checked, its scene read (once per
// file), its jobs counted but none built.
void JobReader::State::plan(size_t begin, size_t size, size_t number) {
  Planned line{begin, size, number, 1};
  const std::string text = bytes.substr(begin, size);
  std::string error;
  try {
    const LineSpec spec = parseLine(file, number, text);
    checkJobCount(spec, total, options.maxJobs);
    baseOf(spec, scenes);
    line.count = *spec.count;
  } catch (const JobError& e) {
    error = e.what();
  } catch (const nlohmann::json::exception& e) {
    error = fmt::format("{}: {}", whereOf(number), e.what());
  }
  if (!error.empty()) {
    if (total == options.maxJobs) throw tooManyJobs(whereOf(number), options.maxJobs);  // a bad line is an entry too
    errors.emplace(lines.size(), std::move(error));
  }
  total += line.count;
  lines.push_back(line);
}

JobReader::JobReader(const fs::path& file, JobReaderOptions options) : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.file = file;
  s.options = std::move(options);
  try {
    s.bytes = readInputFile(file, "job file");
  } catch (const InputFileError& e) {
    throw JobFileError(e.what());
  }
  size_t number = 0;
  for (size_t pos = 0; pos < s.bytes.size();) {
    const size_t end = std::min(s.bytes.find('\n', pos), s.bytes.size());
    const size_t begin = pos;
    pos = end + 1;
    ++number;
    if (s.options.cancel && s.options.cancel->load())
      throw JobFileCancelled(fmt::format("interrupted while reading {} (at line {})", file.string(), number));
    size_t size = end - begin;
    if (size && s.bytes[begin + size - 1] == '\r') --size;
    const size_t first = s.bytes.find_first_not_of(" \t", begin);
    if (first >= begin + size || s.bytes[first] == '#') continue;
    s.plan(begin, size, number);
  }
}

JobReader::~JobReader() = default;

uint64_t JobReader::total() const { return state_->total; }

uint64_t JobReader::sceneFilesRead() const { return state_->scenes.reads(); }

// The second pass over one job line: parsed again and its scene taken
// from the cache (the first pass's verdict stands for a bad line).
JobReader::State::Current JobReader::State::open(size_t index) {
  const Planned& planned = lines[index];
  Current line;
  line.number = planned.number;
  line.where = whereOf(planned.number);
  line.count = planned.count;
  if (auto bad = errors.find(index); bad != errors.end()) {
    line.error = std::move(bad->second);
    errors.erase(bad);
    return line;
  }
  try {
    line.spec = parseLine(file, planned.number, bytes.substr(planned.begin, planned.size));
    line.swept = !line.spec->sweep.empty();
    line.base = baseOf(*line.spec, scenes, &line.fileSha256, &line.fileText);
  } catch (const JobError& e) {  // a scene that changed since the first pass
    line.error = e.what();
  } catch (const nlohmann::json::exception& e) {
    line.error = fmt::format("{}: {}", line.where, e.what());
  }
  if (!line.error.empty()) line.spec.reset();
  return line;
}

std::optional<JobEntry> JobReader::next() {
  State& s = *state_;
  while (!s.current || s.current->index == s.current->count) {
    if (s.nextLine == s.lines.size()) return std::nullopt;
    s.current = s.open(s.nextLine++);
  }
  return s.entryOf(*s.current, s.current->index++);
}

JobEntry JobReader::State::entryOf(const Current& line, uint64_t index) {
  JobEntry entry;
  entry.where = line.swept || line.count > 1 ? fmt::format("{} [{}]", line.where, index) : line.where;
  if (!line.spec) {
    entry.error = line.error;
    return entry;
  }
  entry.beams = line.spec->beams;
  try {
    buildJob(line, index, entry);
  } catch (const JobError& e) {
    entry.job.reset();
    entry.error = e.what();
  } catch (const nlohmann::json::exception& e) {
    entry.job.reset();
    entry.error = fmt::format("{}: {}", entry.where, e.what());
  }
  return entry;
}

// Job `index` of a line: its sweep values applied to the line's scene, its
// output named and claimed, its scene parsed and validated.
void JobReader::State::buildJob(const Current& line, uint64_t index, JobEntry& entry) {
  const LineSpec& spec = *line.spec;
  jf::Source jc = spec.c;
  jc.file = entry.where;
  Json scene = *line.base;
  const Sweep& sweep = spec.sweep;
  std::vector<size_t> digits(sweep.size());
  uint64_t rest = index;
  for (size_t k = sweep.size(); k-- > 0;) {
    digits[k] = rest % sweep[k].second.size();
    rest /= sweep[k].second.size();
  }
  std::vector<SceneOverride> applied = setOverridesOf(spec);  // line.base has them
  for (size_t k = 0; k < sweep.size(); ++k) {
    applied.push_back({sweep[k].first, sweep[k].second[digits[k]]});
    applyOverride(jc, jf::child("/sweep", sweep[k].first), scene, sweep[k].first, applied.back().value,
                  spec.scenePath);
  }
  entry.output = claimOutput(jc, line, index, scene);
  const fs::path state = spec.statePattern ? claimState(jc, line, index, scene) : fs::path();
  RenderJob job;
  try {
    job.scene = parseSceneJson(scene, spec.scenePath);
  } catch (const SceneError& e) {
    jc.fail(applied.empty() ? "/scene" : "/scene (with the job's overrides)", e.what());
  }
  // The scene file's digest and bytes, as render's: a state carries them.
  if (applied.empty()) {
    job.scene.sourceSha256 = line.fileSha256;
    job.scene.sourceText = *line.fileText;
  } else {
    job.scene.overrides = overridesText(applied);
  }
  job.output = entry.output;
  job.state = state;
  job.stateRole = "state";
  job.beams = spec.beams;
  job.seed = spec.seed;
  entry.beams = job.beamCount();
  entry.job = std::move(job);
}

// The job's output, refused unless it ends in .exr (its PNG preview would
// be the same file or unrelated to it) and no earlier job of the file has
// it or its PNG preview. One hash lookup per job.
// An output or state file named by the job: resolved against the output
// folder (default: the job file's), refused if it holds a NUL character.
fs::path JobReader::State::outputFile(const jf::Source& jc, const std::string& field, const std::string& what,
                                      const LineSpec& spec, const std::string& name) const {
  fs::path path = name;
  if (path.is_relative()) path = options.outDir ? *options.outDir / path : spec.c.dir / path;
  // The system reads a file name up to its first NUL: "a\u0000b.exr" would
  // write the EXR, and then its PNG preview, to "a".
  if (const size_t nul = name.find('\0'); nul != std::string::npos)
    jc.fail(field, fmt::format("{} {} holds a NUL character, which no file name can (it would be cut to {})", what,
                               jf::jsonQuoted(name), jf::jsonQuoted(name.substr(0, nul))));
  return path.lexically_normal();
}

fs::path JobReader::State::claimOutput(const jf::Source& jc, const Current& line, uint64_t index, const Json& scene) {
  const LineSpec& spec = *line.spec;
  const std::string name = spec.outputPattern ? expandPattern(jc, "/output", *spec.outputPattern, index, scene)
                                              : spec.scenePath.stem().string() + ".exr";
  const fs::path output = outputFile(jc, "/output", "output", spec, name);
  const std::string extension = output.extension().string();
  if (lowerCase(extension) != ".exr") {
    const std::string from = spec.outputPattern && *spec.outputPattern != name
                                 ? fmt::format(" (from the pattern {})", jf::jsonQuoted(*spec.outputPattern))
                                 : "";
    jc.fail("/output", fmt::format("output {}{} must end in .exr (the PNG preview is written beside it as .png)",
                                   output.string(), from));
  }
  const fs::path preview = fs::path(output).replace_extension(".png");
  if (auto state = states.find(output.string()); state != states.end())
    jc.fail("/output", fmt::format("{} is also the state of {}", output.string(), whereOf(state->second)));
  if (auto state = states.find(preview.string()); state != states.end())
    jc.fail("/output", fmt::format("its PNG preview {} is also the state of {}", preview.string(), whereOf(state->second)));
  const auto [it, mine] = outputs.try_emplace(fs::path(output).replace_extension().string(),
                                              Owner{line.number, index, line.swept, extension});
  if (mine) return output;
  const Owner& owner = it->second;
  const std::string other = whereOf(owner);
  if (owner.extension == extension) jc.fail("/output", fmt::format("{} is also the output of {}", output.string(), other));
  jc.fail("/output", fmt::format("its PNG preview {} is also that of {}", preview.string(), other));
}

// The job's state, refused when an earlier job of the file writes that file
// (its state, output or PNG preview); the job's own output and PNG preview
// are refused by checkOutputPath before it renders. One hash lookup or two.
fs::path JobReader::State::claimState(const jf::Source& jc, const Current& line, uint64_t index, const Json& scene) {
  const LineSpec& spec = *line.spec;
  const fs::path state = outputFile(jc, "/state", "state", spec,
                                    expandPattern(jc, "/state", *spec.statePattern, index, scene));
  const std::string extension = state.extension().string();
  if (auto it = outputs.find(fs::path(state).replace_extension().string()); it != outputs.end()) {
    const Owner& owner = it->second;
    if (owner.number != line.number || owner.index != index) {
      if (extension == owner.extension)
        jc.fail("/state", fmt::format("{} is also the output of {}", state.string(), whereOf(owner)));
      if (extension == ".png")
        jc.fail("/state", fmt::format("{} is also the PNG preview of {}", state.string(), whereOf(owner)));
    }
  }
  const auto [it, mine] = states.try_emplace(state.string(), Owner{line.number, index, line.swept, extension});
  if (!mine) jc.fail("/state", fmt::format("{} is also the state of {}", state.string(), whereOf(it->second)));
  return state;
}

}  // namespace spectrace
