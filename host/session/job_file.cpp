#include "session/job_file.h"

#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "json/input_file.h"
#include "json/json_fields.h"

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

// Sets `pointer` in the scene: its parent must exist (an object, or an
// array holding that index), so a typo cannot add a stray branch.
void applyOverride(const jf::Source& c, const std::string& field, Json& scene, const std::string& text,
                   const Json& value, const fs::path& scenePath) {
  const auto pointer = pointerOf(c, field, text);
  if (pointer.empty()) c.fail(field, "cannot replace the whole scene (the pointer is empty)");
  const auto parent = pointer.parent_pointer();
  if (!scene.contains(parent))
    c.fail(field, fmt::format("unknown pointer {}: {} has no {}", text, scenePath.string(),
                              parent.empty() ? std::string("top level") : parent.to_string()));
  Json& holder = scene[parent];
  if (holder.is_array()) {
    if (!scene.contains(pointer))
      c.fail(field, fmt::format("unknown pointer {}: {} has no {} (the array has {} elements)", text,
                                scenePath.string(), text, holder.size()));
  } else if (!holder.is_object()) {
    c.fail(field, fmt::format("unknown pointer {}: {} is {}, not an object or array", text, parent.to_string(),
                              jf::describe(holder)));
  }
  scene[pointer] = value;
}

// Output pattern: {index} and {<pointer>} replaced; "{{" and "}}" are braces.
std::string expandPattern(const jf::Source& c, const std::string& pattern, size_t index, const Json& scene) {
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
    if (end == std::string::npos) c.fail("/output", fmt::format("unclosed '{{' in {}", jf::jsonQuoted(pattern)));
    const std::string name = pattern.substr(i + 1, end - i - 1);
    if (name == "index") {
      out += std::to_string(index);
    } else {
      const auto pointer = pointerOf(c, "/output", name);
      if (name.empty() || !scene.contains(pointer))
        c.fail("/output", fmt::format("{{{}}} names no field of the scene (use {{index}} or {{/json/pointer}})", name));
      out += nameOf(scene[pointer]);
    }
    i = end;
  }
  return out;
}

struct Line {
  std::string text;
  size_t number;
};

// The jobs of one line (several with a sweep).
void readLine(const fs::path& file, const Line& line, const std::optional<fs::path>& outDir,
              std::vector<JobEntry>& entries) {
  const std::string where = fmt::format("{}:{}", file.string(), line.number);
  jf::Source c;
  c.file = where;
  c.dir = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  c.raise = raiseJobError;
  const size_t firstEntry = entries.size();
  try {
    const Json job = jf::parseJson(c, line.text);
    if (!job.is_object()) c.fail("", fmt::format("a job must be a JSON object (got {})", jf::describe(job)));
    jf::checkObject(c, job, "", {"scene", "output", "beams", "seed", "set", "sweep"}, "a job");
    const std::string sceneName = jf::getString(c, jf::require(c, job, "", "scene", " (the scene file)"), "/scene");
    const bool relative = !fs::path(sceneName).is_absolute();
    const fs::path scenePath = (relative ? c.dir / sceneName : fs::path(sceneName)).lexically_normal();
    // The path as the line gives it, and where it was looked for: relative
    // to the job file's folder, not to the working folder.
    std::error_code missing;
    if (fs::status(scenePath, missing).type() == fs::file_type::not_found)
      c.fail("/scene", fmt::format("{}: scene file not found (looked for {}{})", sceneName,
                                   fs::absolute(scenePath, missing).lexically_normal().string(),
                                   relative ? ", relative to the job file's folder" : ""));
    std::optional<uint64_t> beams, seed;
    if (auto* x = jf::find(job, "beams")) beams = jf::getU64(c, *x, "/beams", 1);
    if (auto* x = jf::find(job, "seed")) seed = jf::getU64(c, *x, "/seed", 0);
    std::optional<std::string> outputPattern;
    if (auto* x = jf::find(job, "output")) outputPattern = jf::getString(c, *x, "/output");

    // The sweep's keys in the order written (nlohmann::json sorts them).
    std::vector<std::pair<std::string, std::vector<Json>>> sweep;
    if (auto* x = jf::find(job, "sweep")) {
      if (!x->is_object() || x->empty())
        c.fail("/sweep", fmt::format("must be an object of JSON pointer: [values...] (got {})", jf::describe(*x)));
      const auto ordered = nlohmann::ordered_json::parse(line.text, nullptr, true, true);
      for (const auto& [key, values] : ordered.at("sweep").items()) {
        const std::string field = jf::child("/sweep", key);
        if (!values.is_array() || values.empty())
          c.fail(field, fmt::format("must be a non-empty array of values (got {})", jf::describe(Json::parse(values.dump()))));
        std::vector<Json> list;
        for (const auto& v : values) list.push_back(Json::parse(v.dump()));
        sweep.emplace_back(key, std::move(list));
      }
      bool named = outputPattern && outputPattern->find("{index}") != std::string::npos;
      for (const auto& [key, values] : sweep)
        if (outputPattern && outputPattern->find("{" + key + "}") != std::string::npos) named = true;
      if (!named)
        c.fail("/output", "a sweep needs an output pattern with {index} or a swept {/pointer} (or the outputs would collide)");
    }

    // The scene, read once; each job overrides a copy.
    Json base;
    try {
      base = readSceneJson(scenePath);
    } catch (const SceneError& e) {
      c.fail("/scene", e.what());
    }
    if (auto* x = jf::find(job, "set")) {
      if (!x->is_object()) c.fail("/set", fmt::format("must be an object of JSON pointer: value (got {})", jf::describe(*x)));
      for (const auto& [key, value] : x->items()) applyOverride(c, jf::child("/set", key), base, key, value, scenePath);
    }

    size_t count = 1;
    for (const auto& [key, values] : sweep) count *= values.size();
    for (size_t index = 0; index < count; ++index) {
      JobEntry entry;
      entry.where = sweep.empty() ? where : fmt::format("{} [{}]", where, index);
      entry.beams = beams;
      jf::Source jc = c;
      jc.file = entry.where;
      try {
        Json scene = base;
        size_t rest = index;
        std::vector<size_t> digits(sweep.size());
        for (size_t k = sweep.size(); k-- > 0;) {
          digits[k] = rest % sweep[k].second.size();
          rest /= sweep[k].second.size();
        }
        for (size_t k = 0; k < sweep.size(); ++k)
          applyOverride(jc, jf::child("/sweep", sweep[k].first), scene, sweep[k].first, sweep[k].second[digits[k]],
                        scenePath);
        const std::string outputName =
            outputPattern ? expandPattern(jc, *outputPattern, index, scene) : scenePath.stem().string() + ".exr";
        fs::path output = outputName;
        if (output.is_relative()) output = outDir ? *outDir / output : c.dir / output;
        entry.output = output.lexically_normal();
        for (size_t e = 0; e < entries.size(); ++e)
          if (entries[e].output == entry.output)
            jc.fail("/output", fmt::format("{} is also the output of {}", entry.output.string(), entries[e].where));
        RenderJob renderJob;
        try {
          renderJob.scene = parseSceneJson(scene, scenePath);
        } catch (const SceneError& e) {
          jc.fail(sweep.empty() && !jf::find(job, "set") ? "/scene" : "/scene (with the job's overrides)", e.what());
        }
        renderJob.output = entry.output;
        renderJob.beams = beams;
        renderJob.seed = seed;
        entry.beams = renderJob.beamCount();
        entry.job = std::move(renderJob);
      } catch (const JobError& e) {
        entry.error = e.what();
      }
      entries.push_back(std::move(entry));
    }
  } catch (const JobError& e) {
    entries.resize(firstEntry);
    JobEntry entry;
    entry.where = where;
    entry.error = e.what();
    entries.push_back(std::move(entry));
  } catch (const nlohmann::json::exception& e) {
    entries.resize(firstEntry);
    JobEntry entry;
    entry.where = where;
    entry.error = fmt::format("{}: {}", where, e.what());
    entries.push_back(std::move(entry));
  }
}

}  // namespace

std::vector<JobEntry> readJobFile(const fs::path& file, const std::optional<fs::path>& outDir) {
  std::string bytes;
  try {
    bytes = readInputFile(file, "job file");
  } catch (const InputFileError& e) {
    throw JobFileError(e.what());
  }
  std::istringstream in(bytes);
  std::vector<JobEntry> entries;
  std::string text;
  for (size_t number = 1; std::getline(in, text); ++number) {
    if (!text.empty() && text.back() == '\r') text.pop_back();
    const size_t first = text.find_first_not_of(" \t");
    if (first == std::string::npos || text[first] == '#') continue;
    readLine(file, Line{text, number}, outDir, entries);
  }
  return entries;
}

}  // namespace spectrace
