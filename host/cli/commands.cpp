#include "cli/commands.h"

#include "cli/cli_numbers.h"
#include "cli/progress_line.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <fmt/format.h>
#include <functional>
#include <vector>

#include "backend/device.h"
#include "compile/estimators.h"
#include "io/image.h"
#include "json/json_fields.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "scene/scene_override.h"
#include "session/session.h"

namespace spectrace::cli {
namespace {

std::filesystem::path defaultOutput(const std::filesystem::path& scene) {
  return std::filesystem::path("out") / (scene.stem().string() + ".exr");
}

// -o names a folder when it ends with '/' or is an existing directory.
bool namesFolder(const std::filesystem::path& output) {
  const std::string text = output.string();
  std::error_code ec;
  return (!text.empty() && text.back() == '/') || std::filesystem::is_directory(output, ec);
}

// --cpu-code: none for "auto"; a code this processor cannot run is a usage
// error, not a crash on an illegal instruction.
std::optional<CpuCode> cpuCodeOption(const std::string& text) {
  if (text == "auto") return std::nullopt;
  const std::optional<CpuCode> code = cpuCodeNamed(text);
  if (!code) throw UsageError(fmt::format("--cpu-code {}: must be auto, baseline or x86-64-v3", text));
  if (!cpuRuns(*code)) throw UsageError(fmt::format("--cpu-code {}: this processor cannot run that code", text));
  return code;
}

// --state, --resume and --shard on a job (throws UsageError).
void applyStateOptions(const RenderCommand& command, RenderJob& job) {
  if (command.shard) {
    // from_chars, not sscanf: sscanf saturates a number past 2^64 - 1
    // instead of failing, which made a huge K an empty shard.
    const std::string& text = *command.shard;
    uint64_t index = 0, count = 0;
    const char* end = text.data() + text.size();
    const auto first = std::from_chars(text.data(), end, index);
    bool parsed = first.ec == std::errc() && first.ptr != end && *first.ptr == '/';
    if (parsed) {
      const auto second = std::from_chars(first.ptr + 1, end, count);
      parsed = second.ec == std::errc() && second.ptr == end;
    }
    if (!parsed || count == 0 || index >= count)
      throw UsageError(fmt::format("--shard {}: give I/K with 0 <= I < K < 2^64, e.g. 0/4", text));
    if (count > job.beamCount())
      throw UsageError(fmt::format("--shard {}: {} shards of {} beams would leave shards with no beams", text, count,
                                   job.beamCount()));
    const BeamRange range = shardRange(job.firstBeam, job.beamCount(), index, count);
    job.firstBeam = range.first;
    job.beams = range.count;
    // A shard is finished by `merge`: keep its exact state.
    if (!command.state) job.state = std::filesystem::path(job.output).replace_extension(".state");
  }
  if (command.state) job.state = *command.state;
  if (command.resume) {
    job.resume = readFilmState(*command.resume);
    job.resumeFile = *command.resume;
    if (!command.state) job.state = *command.resume;
  }
}

// One --set POINTER=JSON. Throws UsageError naming the option.
SceneOverride parseSetOption(const std::string& text) {
  const size_t equals = text.find('=');
  if (equals == std::string::npos)
    throw UsageError(fmt::format("--set {}: no '=' (give POINTER=JSON, e.g. --set /lights/0/power_w=2)", text));
  SceneOverride override{text.substr(0, equals), {}};
  try {
    sceneOverridePointer(override.pointer);
  } catch (const SceneOverrideError& e) {
    throw UsageError(fmt::format("--set {}: {}", text, e.what()));
  }
  // The scene's own JSON reader: a key repeated in an object is refused,
  // and so is nesting past its depth limit.
  json_fields::Source source;
  source.file = fmt::format("--set {}: the value", text);
  source.note = " (the value after '=' is JSON: a string needs its quotes, e.g. --set '/observer=\"CIE1964_10\"')";
  source.raise = [](const std::string& message) { throw UsageError(message); };
  override.value = json_fields::parseJson(source, text.substr(equals + 1));
  return override;
}

// Every --set, in order; a pointer given twice is refused, as a job's "set"
// refuses a repeated key.
std::vector<SceneOverride> overridesOf(const RenderCommand& command) {
  std::vector<SceneOverride> overrides;
  for (size_t i = 0; i < command.overrides.size(); ++i) {
    overrides.push_back(parseSetOption(command.overrides[i]));
    for (size_t j = 0; j < i; ++j)
      if (overrides[j].pointer == overrides[i].pointer)
        throw UsageError(fmt::format("--set {}: {} is already set by --set {} (give each pointer once)",
                                     command.overrides[i], overrides[i].pointer, command.overrides[j]));
  }
  return overrides;
}

// "--set A --set B", for messages.
std::string setOptionsText(const RenderCommand& command) {
  std::string text;
  for (const std::string& given : command.overrides) text += (text.empty() ? "--set " : " --set ") + given;
  return text;
}

// The scene file at `path` with the --set overrides applied to its JSON,
// then parsed and validated like any scene (loadScene without overrides).
Scene sceneOf(const std::filesystem::path& path, const RenderCommand& command,
              const std::vector<SceneOverride>& overrides) {
  if (overrides.empty()) return loadScene(path);
  nlohmann::json json = readSceneJson(path);
  for (size_t i = 0; i < overrides.size(); ++i) {
    try {
      applySceneOverride(json, overrides[i], path);
    } catch (const SceneOverrideError& e) {
      throw UsageError(fmt::format("--set {}: {}", command.overrides[i], e.what()));
    }
  }
  try {
    Scene scene = parseSceneJson(json, path);
    scene.overrides = overridesText(overrides);
    return scene;
  } catch (const SceneError& e) {
    throw UsageError(fmt::format("{}: the scene with {} is invalid: {}", setOptionsText(command),
                                 overrides.size() == 1 ? "this override" : "these overrides", e.what()));
  }
}

}  // namespace

int runMerge(const MergeCommand& command) {
  try {
    // Every state read and checked, and every sum, before any output is touched.
    FilmState merged = mergeStateFiles(command.states);
    // The same output checks as render, before the film is developed: the
    // states and the scene they name are inputs, never overwritten (a scene
    // that is gone, as a bundled state allows, is simply not among them).
    std::vector<std::filesystem::path> inputs(command.states.begin(), command.states.end());
    inputs.emplace_back(merged.fingerprint.sceneFile);
    checkOutputFiles(outputFilesOf(command.output, command.png, command.state.value_or(std::filesystem::path())),
                     inputs);
    std::function<void(const std::string&)> log;
    if (!command.quiet) log = [](const std::string& line) { std::fprintf(stderr, "spectrace: %s\n", line.c_str()); };
    const Session session(parseDeviceChoice(command.device), log);
    const RenderResult result = session.develop(merged, command.output, command.spectral, command.png);
    // The merged beams' scale, from the scene as develop compiled it.
    merged.irradiancePerCount = stateIrradiancePerCount(result.plan.irradianceScale(), merged.beams());
    if (command.state) writeFilmState(*command.state, merged);
    if (!command.quiet)
      std::fprintf(stderr, "spectrace: merged %zu state%s, %llu beam%s -> %s\n", command.states.size(),
                   command.states.size() == 1 ? "" : "s", (unsigned long long)result.beamsTraced,
                   result.beamsTraced == 1 ? "" : "s", command.output.c_str());
    return 0;
  } catch (const FilmStateError& e) {
    std::fprintf(stderr, "spectrace: error: %s\n", e.what());
    return 2;
  }
}

std::vector<RenderJob> renderJobsOf(const RenderCommand& command, const std::atomic<bool>& cancel, bool checkOutputs) {
  const bool several = command.scenes.size() > 1;
  if (several && command.output && !namesFolder(*command.output))
    throw UsageError(fmt::format("-o {} names one file but there are {} scenes; give a folder (ending in '/') "
                                 "or leave -o out",
                                 command.output->string(), command.scenes.size()));
  if (several && (command.state || command.resume || command.shard))
    throw UsageError(fmt::format("--state, --resume and --shard take one scene (got {})", command.scenes.size()));
  const std::vector<SceneOverride> overrides = overridesOf(command);
  std::vector<RenderJob> jobs;
  for (const auto& path : command.scenes) {
    RenderJob job;
    job.scene = sceneOf(path, command, overrides);
    if (command.wavelengthsPerBeam) job.scene.render.wavelengthsPerBeam = *command.wavelengthsPerBeam;
    if (!command.output) job.output = defaultOutput(path);
    else if (several || namesFolder(*command.output)) job.output = *command.output / (path.stem().string() + ".exr");
    else job.output = *command.output;
    job.beams = command.beams;
    job.seed = command.seed;
    job.png = command.png;
    job.firstBeam = command.firstBeam;
    job.tracer.cpuThreads = command.threads;
    job.tracer.cpuCode = cpuCodeOption(command.cpuCode);
    job.loop.cancel = &cancel;
    job.loop.checkpointSeconds = command.checkpointSeconds;
    job.plan.trimSpectrum = !command.fullSpectrum;
    job.outputs.spectral = command.spectral;
    job.outputs.downloadFilm = false;  // Session downloads it when the state or the spectral block needs it
    job.plan.trimPixels = !command.fullSensor;
    job.tracer.specialisedFeatures = command.general ? kSpecialiseNone : kSpecialiseAll;
    job.plan.aim = !command.noAim;
    job.plan.connect = !command.noConnect;
    job.plan.lightPaths = command.estimator != "camera";
    job.plan.cameraPaths = command.estimator != "light";
    job.plan.colourFromBins = !command.perBeamColour;
    if (!command.quiet) job.loop.log = [](const std::string& line) { std::fprintf(stderr, "spectrace: %s\n", line.c_str()); };
    checkBeamRange(command.firstBeam, job.beamCount());
    applyStateOptions(command, job);
    std::vector<std::filesystem::path> inputs(command.scenes.begin(), command.scenes.end());
    if (command.resume) inputs.push_back(*command.resume);
    if (checkOutputs) checkOutputPath(job, inputs);  // before any tracing; exit 2
    for (const RenderJob& other : jobs)
      if (other.output == job.output)
        throw UsageError(fmt::format("{} and {} would both be written to {}", other.scene.sourcePath.string(),
                                     path.string(), job.output.string()));
    jobs.push_back(std::move(job));
  }
  return jobs;
}

int runRender(const RenderCommand& command, const std::atomic<bool>& cancel) {
  if (command.mpi) return runMpiRender(command, cancel);
  const bool several = command.scenes.size() > 1;
  std::vector<RenderJob> jobs = renderJobsOf(command, cancel, true);

  ProgressLine progress = ProgressLine::forStderr();
  std::function<void(const std::string&)> log;
  if (!command.quiet) log = [&progress](const std::string& line) { progress.notice(line); };
  const Session session(parseDeviceChoice(command.device), log, command.pipelineCache);
  for (RenderJob& job : jobs) {
    const auto& output = job.output;
    const uint64_t beams = job.beamCount();
    if (!command.quiet) {
      job.loop.log = log;
      job.loop.onCheckpoint = [&](const RenderImage&, uint64_t done, const std::string&) {
        progress.notice(fmt::format("checkpoint: {} beams -> {}", done, output.string()));
      };
      job.loop.onStart = [&progress](uint64_t done, uint64_t total) { progress.start(total, done); };
      job.loop.onProgress = [&progress](uint64_t done, uint64_t) { progress.update(done); };
      if (several) progress.notice(fmt::format("rendering {}", job.scene.sourcePath.string()));
    }
    const RenderResult result = session.render(job);
    if (!command.quiet) {
      progress.finish();
      // The rate of this run's beams: a resumed film's were traced before.
      const uint64_t thisRun = result.beamsTraced - result.beamsResumed;
      std::fprintf(stderr, "spectrace: %llu beams in %.2f s (%.1f Mbeam/s) on %s%s\n", (unsigned long long)thisRun,
                   result.wallSeconds, double(thisRun) / result.wallSeconds * 1e-6, result.deviceName.c_str(),
                   result.beamsResumed
                       ? fmt::format(", after {} resumed from the state", result.beamsResumed).c_str()
                       : "");
      const uint64_t counted = result.summary.countedBeams;
      const double countsBound = double(counted) * double(countsPerPathBound(result.plan.device.constants));
      std::fprintf(stderr,
                   "spectrace: %llu beams counted (%.3g%% of those traced); the largest pixel-bin holds %.4g beams; "
                   "rounding adds at most %.2g of the variance\n",
                   (unsigned long long)counted,
                   result.beamsTraced ? 100.0 * double(counted) / double(result.beamsTraced) : 0.0,
                   result.summary.largestBeams,
                   roundingVarianceShare(result.summary, uint64_t(std::min(countsBound, 1.8e19)),
                                         result.plan.film.weighted()));
      auto png = output;
      png.replace_extension(".png");
      std::fprintf(stderr, "spectrace: wrote %s%s\n", output.c_str(), command.png ? (" and " + png.string()).c_str() : "");
    }
    if (result.beamsTraced < beams) {
      std::fprintf(stderr, "spectrace: interrupted after %llu of %llu beams; the image holds the finished beams\n",
                   (unsigned long long)result.beamsTraced, (unsigned long long)beams);
      return 130;
    }
  }
  return 0;
}

int runDevices() {
  std::printf("%s", describeDevices().c_str());
  return 0;
}

}  // namespace spectrace::cli
