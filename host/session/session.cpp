#include "session/session.h"

#include "compile/compile_scene.h"
#include "film/develop.h"
#include "json/input_file.h"
#include "json/scene_error.h"
#include "session/output_guard.h"

#include <chrono>
#include <cstdio>
#include <utility>
#include <fmt/format.h>
#include <memory>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>

namespace spectrace {

ImageMetadata renderMetadata(const Scene& scene, const std::string& device, bool aimed, uint64_t seed,
                             uint64_t firstBeam, uint64_t beamsDone, double wallSeconds) {
  ImageMetadata meta;
  meta.strings["spectrace:beams"] = std::to_string(beamsDone);
  meta.strings["spectrace:first_beam"] = std::to_string(firstBeam);
  meta.strings["spectrace:seed"] = std::to_string(seed);
  meta.strings["spectrace:device"] = device;
  meta.strings["spectrace:scene_file"] = scene.sourcePath.string();
  meta.strings["spectrace:scene_sha256"] = scene.sourceSha256;
  // The scene rendered is the file changed by these: it is in no file.
  if (!scene.overrides.empty()) meta.strings["spectrace:overrides"] = scene.overrides;
  meta.strings["spectrace:observer"] = scene.observer;
  meta.strings["spectrace:units"] =
      "R,G,B: linear sRGB (Rec. 709, D65) of XYZ; XYZ: CIE XYZ with Y in lux; irradiance.E: W/m^2 over all bins; "
      "error.E: estimated standard error of irradiance.E, W/m^2; S0.<nm>nm (if present): spectral irradiance, "
      "W.m^-2.nm^-1";
  meta.numbers["spectrace:wall_time_s"] = wallSeconds;
  meta.numbers["spectrace:spectrum_min_nm"] = scene.spectrum.minNm;
  meta.numbers["spectrace:spectrum_max_nm"] = scene.spectrum.maxNm;
  meta.numbers["spectrace:spectrum_bins"] = scene.spectrum.bins;
  meta.numbers["spectrace:exposure_s"] = scene.camera.exposureS;
  meta.strings["spectrace:sampling"] = aimed ? "aimed at the camera, weighted" : "analog";
  return meta;
}

bool outputIsComplete(const std::filesystem::path& exr, uint64_t beams) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(exr, ec)) return false;
  try {
    const ExrContents contents = readExr(exr);
    const auto it = contents.meta.strings.find("spectrace:beams");
    if (it == contents.meta.strings.end()) return false;
    size_t used = 0;
    const unsigned long long done = std::stoull(it->second, &used);
    return used == it->second.size() && done == beams;
  } catch (const std::exception&) {
    return false;
  }
}

Session::Session(DeviceChoice device, const std::function<void(const std::string&)>& log,
                 const PipelineCacheOptions& pipelineCache)
    : device_(Device::open(device, log, pipelineCache)) {}

Session::Session(std::unique_ptr<Device> device) : device_(std::move(device)) {}

Session::~Session() { finishWriting(); }

namespace {

// A finished image: the PNG preview beside it when asked for, then the EXR.
// The EXR comes last: its header marks the job complete (--skip-existing),
// so a job whose writing failed is never taken for finished.
void writeImage(const std::filesystem::path& output, const RenderImage& image, const ImageMetadata& metadata,
                bool png) {
  if (png) {
    auto preview = output;
    preview.replace_extension(".png");
    writePngPreview(preview, image);
  }
  writeExr(output, image, metadata);
}

void prepareFolder(const std::filesystem::path& output) {
  const auto folder = output.parent_path();
  if (folder.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw OutputError(fmt::format("cannot create the folder {} for {}: {}", folder.string(), output.string(), ec.message()));
}

}  // namespace

void writeRenderImage(const std::filesystem::path& output, const RenderImage& image, const ImageMetadata& metadata,
                      bool png) {
  prepareFolder(output);
  try {
    writeImage(output, image, metadata, png);
  } catch (const ImageIoError& e) {
    throw OutputError(e.what());
  }
}

FilmFingerprint jobFingerprint(const RenderJob& job, const CompiledScene& plan) {
  FilmFingerprint f = fingerprintOf(plan.film, job.scene.sourcePath.string(), job.scene.sourceSha256,
                                    job.scene.observer, job.seedValue(), job.tracer.specialisedFeatures,
                                    namedCompileOptions(job.plan));
  f.wavelengthsPerBeam = plan.device.constants.wavelengthsPerPath;
  f.referencedFilesSha256 = job.scene.referencedFilesSha256;
  return f;
}

std::optional<SceneBundle> sceneBundleOf(const Scene& scene) {
  if (scene.sourceText.empty()) return std::nullopt;  // built in code: no text to carry
  const std::string sceneName = scene.sourcePath.empty() ? std::string("<scene>") : scene.sourcePath.string();
  if (sceneSha256Hex(scene.sourceText) != scene.sourceSha256)
    throw FilmStateError(fmt::format("{}: the scene's text does not hash to its SHA-256 {}; cannot bundle it",
                                     sceneName, scene.sourceSha256));
  SceneBundle bundle{scene.sourceText, {}};
  try {
    for (const std::filesystem::path& file : referencedFiles(scene))
      if (!bundle.files.count(file.string()))
        bundle.files.emplace(file.string(), readInputFile(file, "file named by the scene", uint64_t(1) << 30));
    // The digest of the bytes just read, by the loader's own rule.
    const BundledInputFiles served(bundle.files, "the bundle");
    if (referencedFilesSha256(scene) != scene.referencedFilesSha256)
      throw FilmStateError(fmt::format("{}: a file the scene names (an OBJ mesh or CSV) has changed since the scene "
                                       "was read; cannot bundle it",
                                       sceneName));
  } catch (const InputFileError& e) {
    throw FilmStateError(fmt::format("{}: cannot bundle a file the scene names: {}", sceneName, e.what()));
  } catch (const SceneError& e) {
    throw FilmStateError(fmt::format("cannot bundle a file the scene names: {}", e.what()));
  }
  return bundle;
}

double stateIrradiancePerCount(const IrradianceScale& scale, uint64_t beams) {
  return beams == 0 ? 0.0 : scale.perCount(beams);
}

RenderOptions RenderJob::renderOptions() const {
  RenderOptions options;
  options.beams = beamCount();
  options.firstBeam = firstBeam;
  options.seed = seedValue();
  options.plan = plan;
  options.tracer = tracer;
  options.outputs = outputs;
  options.loop = loop;
  return options;
}

FilmFingerprint jobFingerprint(const RenderJob& job) {
  return jobFingerprint(job, compileScene(job.scene, job.seedValue(), job.plan));
}

namespace {

// The state a resume starts from, checked against the job: throws
// FilmStateError naming what differs.
void checkResume(const RenderJob& job, const FilmState& state, const FilmFingerprint& fingerprint) {
  const std::string from = job.resumeFile.empty() ? "the state" : job.resumeFile.string();
  const auto refuse = [&](const std::string& why) {
    throw FilmStateError(fmt::format("cannot resume from {}: {}", from, why));
  };
  if (std::string field = fingerprintDifference(state.fingerprint, fingerprint); !field.empty())
    refuse("it belongs to another render: it differs in " + field);
  const uint64_t first = job.firstBeam;
  if (state.ranges.size() != 1)
    refuse(fmt::format("it holds {} beam ranges (a merged state); a render goes on only from a state of its own "
                       "first beams",
                       state.ranges.size()));
  if (state.ranges[0].first != first)
    refuse(fmt::format("its beams start at beam {}, this render's at beam {}", state.ranges[0].first, first));
  if (state.ranges[0].count > job.beamCount())
    refuse(fmt::format("it holds {} beams, more than this render's {}", state.ranges[0].count, job.beamCount()));
}

}  // namespace

namespace {

// Spectral channel names keep 6 decimals of the bin centre, so bins about
// 1e-6 nm apart would share a name the EXR cannot hold twice: refused here,
// before tracing, not when the finished image is written.
void checkSpectralChannels(const Scene& scene) {
  const SpectrumRange& s = scene.spectrum;
  const std::vector<double> centres = binCentresNm(s.minNm, s.maxNm, uint32_t(s.bins));
  const auto clash = spectralChannelClash(centres);
  if (!clash) return;
  throw SceneError(fmt::format(
      "{}: /spectrum/bins: bins {} and {} (centres {} and {} nm) would both be the spectral EXR channel {}, whose "
      "name keeps 6 decimals of nm; use fewer bins or a wider range, or write no spectral channels",
      scene.sourcePath.empty() ? std::string("<scene>") : scene.sourcePath.string(), clash->first, clash->second,
      centres[clash->first], centres[clash->second], clash->name));
}

}  // namespace

void checkOutputPath(const RenderJob& job, const std::vector<std::filesystem::path>& inputs) {
  if (job.outputs.spectral || job.scene.outputSpectral) checkSpectralChannels(job.scene);
  std::vector<std::filesystem::path> all;
  for (const auto& input : inputs) {
    std::error_code ec;
    const bool ownState = job.resume && !job.state.empty() && std::filesystem::equivalent(input, job.state, ec) && !ec;
    if (!ownState) all.push_back(input);  // resuming replaces its own state
  }
  all.push_back(job.scene.sourcePath);
  // The files the scene names: CSV spectra, luminaire files, OBJ meshes.
  for (const std::filesystem::path& file : referencedFiles(job.scene)) all.push_back(file);
  checkOutputFiles(outputFilesOf(job.output, job.png, job.state, job.stateRole), all);
}

std::vector<OutputFile> outputFilesOf(const std::filesystem::path& exr, bool png, const std::filesystem::path& state,
                                      const std::string& stateRole) {
  std::vector<OutputFile> files{{exr, "output", ".exr"}};
  if (png) files.push_back({std::filesystem::path(exr).replace_extension(".png"), "PNG preview", ".png"});
  if (!state.empty()) files.push_back({state, stateRole, ""});
  return files;
}

namespace {

std::string lowerCaseExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// The one file's checks of checkOutputFiles, all but the clash with the
// other outputs.
void checkOutputFile(const OutputFile& output, const std::vector<std::filesystem::path>& inputs) {
  namespace fs = std::filesystem;
  const std::string name = output.role + " " + output.path.string();
  std::error_code ec;
  // Outputs are written by replacing the file (atomic rename), which would
  // replace a link rather than write through it (a link to /dev/stdout
  // would become a regular file).
  if (fs::is_symlink(fs::symlink_status(output.path, ec)) && !ec) {
    std::error_code er;
    const fs::path target = fs::read_symlink(output.path, er);
    throw OutputPathError(fmt::format("{} is a symbolic link (to {}); outputs replace their file, so name the file "
                                      "itself",
                                      name, er ? std::string("an unreadable target") : target.string()),
                          output.role);
  }
  const fs::file_status st = fs::status(output.path, ec);
  if (!ec && fs::exists(st)) {
    for (const auto& input : inputs) {
      if (input.empty()) continue;
      std::error_code eq;
      if (fs::equivalent(output.path, input, eq) && !eq)
        throw OutputPathError(fmt::format("{} is the input file {}; an input is never overwritten", name,
                                          input.string()),
                              output.role);
    }
    if (!fs::is_regular_file(st))
      throw OutputPathError(fmt::format("{} exists and is not a regular file ({}); refusing to replace it", name,
                                        fs::is_directory(st) ? "a folder" : "a device, pipe or socket"),
                            output.role);
  }
  if (!output.extension.empty() && lowerCaseExtension(output.path) != output.extension)
    throw OutputPathError(fmt::format("{} must end in {} (the PNG preview is written beside it as .png)", name,
                                      output.extension),
                          output.role);
  const fs::path folder = output.path.parent_path().empty() ? fs::path(".") : output.path.parent_path();
  fs::create_directories(folder, ec);
  if (ec)
    throw OutputPathError(fmt::format("cannot create the folder {} for {}: {}", folder.string(), name, ec.message()),
                          output.role);
  // A probe file proves the folder takes a new file (permissions, read-only
  // file systems) before any beam is traced; the real write is atomic later.
  const fs::path probe = folder / fmt::format(".{}.probe-{}", output.path.filename().string(), ::getpid());
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    throw OutputPathError(fmt::format("cannot write {}: cannot create a file in {}: {}", name, folder.string(),
                                      std::error_code(err, std::generic_category()).message()),
                          output.role);
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

}  // namespace

void checkOutputFiles(const std::vector<OutputFile>& outputs, const std::vector<std::filesystem::path>& inputs) {
  namespace fs = std::filesystem;
  for (const OutputFile& output : outputs) checkOutputFile(output, inputs);
  for (size_t i = 0; i < outputs.size(); ++i) {
    const fs::path mine = fs::weakly_canonical(fs::absolute(outputs[i].path));
    for (size_t j = 0; j < i; ++j)
      if (fs::weakly_canonical(fs::absolute(outputs[j].path)) == mine)
        throw OutputPathError(fmt::format("{} {} is also this run's {}; each output needs a file of its own",
                                          outputs[i].role, outputs[i].path.string(), outputs[j].role),
                              outputs[i].role);
  }
}

namespace {

// Checkpoint writes that fail (a full disk, a quota) do not stop the render:
// the last good file stays (writes are atomic), the render goes on, and the
// next checkpoint tries again. One warning per streak of failures.
class CheckpointWriter {
 public:
  explicit CheckpointWriter(std::function<void(const std::string&)> warn) : warn_(std::move(warn)) {}

  // Runs `write`; true when it succeeded.
  template <typename Write>
  bool attempt(const std::filesystem::path& file, uint64_t beams, Write&& write) {
    std::string failure;
    try {
      write();
    } catch (const ImageIoError& e) {  // both name the file and the reason
      failure = e.what();
    } catch (const FilmStateError& e) {
      failure = e.what();
    }
    if (!failure.empty()) {
      if (!failing_)
        warn_(fmt::format("checkpoint of {} beams not written, the render goes on and retries at the next "
                          "checkpoint: {}{}",
                          beams, failure,
                          lastGood_ ? fmt::format(" ({} still holds the checkpoint of {} beams)", file.string(), lastGood_)
                                    : std::string()));
      failing_ = true;
      return false;
    }
    if (failing_) warn_(fmt::format("checkpoint of {} beams written to {} again", beams, file.string()));
    failing_ = false;
    lastGood_ = beams;
    return true;
  }

  // The beams of the last checkpoint written (0: none).
  uint64_t lastGood() const { return lastGood_; }

 private:
  std::function<void(const std::string&)> warn_;
  bool failing_ = false;
  uint64_t lastGood_ = 0;
};

void warnOnStderr(const std::string& line) { std::fprintf(stderr, "spectrace: warning: %s\n", line.c_str()); }

bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ea, eb;
  const auto ca = std::filesystem::weakly_canonical(a, ea), cb = std::filesystem::weakly_canonical(b, eb);
  return (!ea && !eb) ? ca == cb : a.lexically_normal() == b.lexically_normal();
}

}  // namespace

RenderResult Session::render(const RenderJob& job) const { return renderOverlapped(job).get(); }

void Session::finishWriting() const {
  if (writing_.valid()) writing_.wait();
}

std::shared_future<RenderResult> Session::renderOverlapped(const RenderJob& job) const {
  checkOutputPath(job);
  // A second render to this output is refused until this one's writing is done.
  auto lock = std::make_shared<const OutputLock>(job.output);
  {
    auto preview = job.output;
    preview.replace_extension(".png");
    for (const auto& target : {job.output, preview, job.state})
      if (!target.empty())
        for (const auto& stale : removeStaleTemporaries(target))
          if (job.loop.log) job.loop.log("removed the stale temporary file " + stale.string());
  }
  RenderOptions options = job.renderOptions();
  options.outputs.spectral = options.outputs.spectral || job.scene.outputSpectral;  // --spectral, or the scene's output.spectral
  options.outputs.spectralByCaller = true;  // on the writer thread
  // The state file and the spectral block need the film on the host.
  options.outputs.downloadFilm = options.outputs.downloadFilm || options.outputs.spectral || !job.state.empty();
  const auto& output = job.output;
  auto preview = output;
  preview.replace_extension(".png");
  // The previous job's writer and this job's checkpoints must never write the same file at once.
  for (const auto& file : writingFiles_)
    for (const auto& mine : {output, preview, job.state})
      if (!mine.empty() && sameFile(file, mine)) finishWriting();
  prepareFolder(output);
  // Compiled once: for the state's fingerprint and the render.
  CompiledScene plan = compileScene(job.scene, options.seed, options.plan);
  FilmFingerprint fingerprint;
  if (!job.state.empty() || job.resume) fingerprint = jobFingerprint(job, plan);
  if (job.resume) {
    checkResume(job, *job.resume, fingerprint);
    options.loop.resumeFilm = &job.resume->histogram;
    options.loop.resumedBeams = job.resume->beams();
  }
  // Bundled once, shared by every checkpoint's state and the last.
  std::shared_ptr<const std::optional<SceneBundle>> bundle;
  if (!job.state.empty()) bundle = std::make_shared<const std::optional<SceneBundle>>(sceneBundleOf(job.scene));
  auto writeState = [state = job.state, fingerprint, bundle, scale = plan.irradianceScale(),
                     first = options.firstBeam](const SpectralHistogram& film, uint64_t done) {
    if (state.empty()) return;
    writeFilmState(state, FilmState{fingerprint, {{first, done}}, film, *bundle,
                                    stateIrradiancePerCount(scale, done)});
  };
  const auto warn = job.warn ? job.warn : std::function<void(const std::string&)>(warnOnStderr);
  CheckpointWriter exrCheckpoints(warn), stateCheckpoints(warn);
  auto onCheckpointFilm = options.loop.onCheckpointFilm;
  options.loop.onCheckpointFilm = [&](const SpectralHistogram& film, uint64_t done) {
    stateCheckpoints.attempt(job.state, done, [&] { writeState(film, done); });
    if (onCheckpointFilm) onCheckpointFilm(film, done);
  };
  const auto start = std::chrono::steady_clock::now();
  auto onCheckpoint = options.loop.onCheckpoint;
  // A checkpoint is a complete, valid image of the beams finished so far.
  options.loop.onCheckpoint = [&](const RenderImage& image, uint64_t done, const std::string& device) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const bool written = exrCheckpoints.attempt(output, done, [&] {
      writeExr(output, image,
               renderMetadata(job.scene, device, options.plan.aim, options.seed, options.firstBeam, done, seconds));
    });
    if (written && onCheckpoint) onCheckpoint(image, done, device);
  };
  RenderResult result = spectrace::render(job.scene, std::move(plan), options, *device_);
  device_->savePipelineCache();
  // The final write failing is a run-time failure; say what survived.
  const std::string survived =
      exrCheckpoints.lastGood()
          ? fmt::format("; {} still holds the last checkpoint ({} beams){}", output.string(), exrCheckpoints.lastGood(),
                        stateCheckpoints.lastGood()
                            ? fmt::format(" and {} its state ({} beams)", job.state.string(), stateCheckpoints.lastGood())
                            : std::string())
          : std::string();
  // Bounded: the previous job is written before this one is handed over.
  finishWriting();
  auto write = [result = std::move(result), scene = job.scene, output, png = job.png, spectral = options.outputs.spectral,
                aim = options.plan.aim, seed = options.seed, firstBeam = options.firstBeam, writeState, survived,
                lock]() mutable -> RenderResult {
    const auto held = std::move(lock);  // released when this write ends, not when the future goes
    try {
      if (spectral)
        addSpectralChannels(result.image, result.histogram, result.plan,
                            resolveParametersFor(scene, result.plan, result.beamsTraced));
      writeState(result.histogram, result.beamsTraced);
      writeImage(output, result.image,
                 renderMetadata(scene, result.deviceLabel(), aim, seed, firstBeam, result.beamsTraced,
                                result.wallSeconds),
                 png);
      return std::move(result);
    } catch (const ImageIoError& e) {
      throw OutputError(e.what() + survived);
    } catch (const FilmStateError& e) {
      throw OutputError(e.what() + survived);
    }
  };
  writingFiles_ = {output, preview, job.state};
  writing_ = std::async(std::launch::async, std::move(write)).share();
  return writing_;
}

BeamRange shardRange(uint64_t firstBeam, uint64_t beams, uint64_t index, uint64_t count) {
  if (count == 0 || index >= count)
    throw std::invalid_argument(fmt::format("shard {} of {}: the index must be below the count", index, count));
  // floor(beams * i / count), in 128 bits: shards tile [0, beams) exactly.
  auto cut = [&](uint64_t i) { return uint64_t((unsigned __int128)beams * i / count); };
  return {firstBeam + cut(index), cut(index + 1) - cut(index)};
}

namespace {

// The scene of a state without a bundle: its file, which must still hash
// the same, as must the files it names.
Scene sceneFileOf(const FilmState& state) {
  const FilmFingerprint& f = state.fingerprint;
  Scene scene;
  try {
    scene = loadScene(f.sceneFile);
  } catch (const std::exception& e) {
    // The scene's path is the one the render was given, relative to the
    // folder it ran in: e.what() names it and, if missing, where it was looked for.
    throw FilmStateError(fmt::format("cannot read the scene the state was rendered from: {}", e.what()));
  }
  if (scene.sourceSha256 != f.sceneSha256)
    throw FilmStateError(fmt::format("the scene file {} has changed since the state was written (SHA-256 {} against {})",
                                     f.sceneFile, scene.sourceSha256, f.sceneSha256));
  if (scene.referencedFilesSha256 != f.referencedFilesSha256)
    throw FilmStateError(fmt::format("a file the scene {} names (an OBJ mesh or CSV) has changed since the state was "
                                     "written (referenced_files_sha256 {} against {})",
                                     f.sceneFile, scene.referencedFilesSha256, f.referencedFilesSha256));
  return scene;
}

// The scene a state carries: its text parsed under the fingerprint's scene
// path, so relative paths resolve to the bundle's keys, with every file it
// names read from the bundle and none from the disk.
Scene bundledSceneOf(const FilmState& state) {
  const FilmFingerprint& f = state.fingerprint;
  Scene scene;
  try {
    const BundledInputFiles served(state.bundle->files, "the state's bundle");
    scene = parseScene(state.bundle->sceneText, f.sceneFile);
  } catch (const std::exception& e) {
    throw FilmStateError(fmt::format("cannot use the scene bundled in the state: {}", e.what()));
  }
  if (scene.sourceSha256 != f.sceneSha256)
    throw FilmStateError(fmt::format("the scene bundled in the state is not the one it was rendered from (SHA-256 {} "
                                     "against /fingerprint/scene_sha256 {})",
                                     scene.sourceSha256, f.sceneSha256));
  if (scene.referencedFilesSha256 != f.referencedFilesSha256)
    throw FilmStateError(fmt::format("the files bundled in the state are not those the scene named when it was "
                                     "rendered (referenced_files_sha256 {} against {})",
                                     scene.referencedFilesSha256, f.referencedFilesSha256));
  return scene;
}

}  // namespace

namespace {

// The job that traced `state` (its scene, seed, beams and options), checked
// to compile to the state's film. Throws FilmStateError.
struct StateJob {
  RenderJob job;
  CompiledScene plan;
};

StateJob jobOfState(const FilmState& state, bool spectral) {
  const FilmFingerprint& f = state.fingerprint;
  StateJob s;
  RenderJob& job = s.job;
  job.scene = state.bundle ? bundledSceneOf(state) : sceneFileOf(state);
  job.outputs.spectral = spectral;
  job.seed = f.seed;
  job.beams = state.beams();
  job.firstBeam = state.ranges.empty() ? 0 : state.ranges.front().first;
  job.tracer.specialisedFeatures = f.specialisation;
  try {
    job.plan = compileOptionsNamed(f.compileOptions);
  } catch (const std::invalid_argument& e) {
    throw FilmStateError(fmt::format("the state's compile options cannot be used: {}", e.what()));
  }
  // The wavelengths per camera path the state was rendered with (the
  // command line may have set them over the scene's).
  if (f.compileOptions.count("camera_paths") && f.compileOptions.at("camera_paths"))
    job.scene.render.wavelengthsPerBeam = f.wavelengthsPerBeam;
  s.plan = compileScene(job.scene, f.seed, job.plan);
  if (std::string field = fingerprintDifference(f, jobFingerprint(job, s.plan)); !field.empty())
    throw FilmStateError("the scene no longer compiles to the state's film: it differs in " + field);
  return s;
}

// The state's film resolved on `device` as its job would resolve it.
RenderResult developStateJob(const Device& device, const FilmState& state, const StateJob& s, bool spectral) {
  TracerOptions tracerOptions;
  tracerOptions.specialisedFeatures = state.fingerprint.specialisation;
  const auto tracer = device.makeTracer(s.plan, tracerOptions);
  tracer->upload(state.histogram);
  RenderResult result;
  result.plan = s.plan;
  result.histogram = state.histogram;
  result.beamsTraced = state.beams();
  result.deviceKind = tracer->kind();
  result.deviceName = tracer->deviceName();
  const ResolveParameters parameters = resolveParametersFor(s.job.scene, s.plan, result.beamsTraced);
  result.image = tracer->develop(parameters, &result.summary);
  if (spectral || s.job.scene.outputSpectral) addSpectralChannels(result.image, state.histogram, s.plan, parameters);
  return result;
}

}  // namespace

RenderResult Session::developInMemory(const FilmState& state, bool spectral, Scene* scene) const {
  const StateJob s = jobOfState(state, spectral);
  if (scene) *scene = s.job.scene;
  return developStateJob(*device_, state, s, spectral);
}

RenderResult Session::develop(const FilmState& state, const std::filesystem::path& output, bool spectral, bool png,
                              double wallSeconds) const {
  StateJob s = jobOfState(state, spectral);
  s.job.output = output;
  checkOutputPath(s.job);  // the scene and its CSV spectra are inputs too
  RenderResult result = developStateJob(*device_, state, s, spectral);
  result.wallSeconds = wallSeconds;
  const FilmFingerprint& f = state.fingerprint;
  prepareFolder(output);
  const OutputLock lock(output);
  removeStaleTemporaries(output);
  try {
    writeImage(output, result.image,
               renderMetadata(s.job.scene, result.deviceLabel(), s.job.plan.aim, f.seed, s.job.firstBeam,
                              result.beamsTraced, wallSeconds),
               png);
  } catch (const ImageIoError& e) {
    throw OutputError(e.what());
  }
  return result;
}

Session::InMemoryRender Session::renderInMemory(const RenderJob& job) const {
  if (job.resume) throw std::invalid_argument("renderInMemory: resuming is not supported");
  RenderOptions options = job.renderOptions();
  options.outputs.spectral = options.outputs.spectral || job.scene.outputSpectral;
  options.outputs.spectralByCaller = true;
  options.outputs.downloadFilm = true;  // the state holds the film
  options.loop.checkpointSeconds = 0.0;
  options.loop.onCheckpoint = nullptr;
  options.loop.onCheckpointFilm = nullptr;
  if (options.outputs.spectral) checkSpectralChannels(job.scene);
  CompiledScene plan = compileScene(job.scene, options.seed, options.plan);
  const FilmFingerprint fingerprint = jobFingerprint(job, plan);
  std::optional<SceneBundle> bundle = sceneBundleOf(job.scene);
  InMemoryRender out;
  out.result = spectrace::render(job.scene, std::move(plan), options, *device_);
  device_->savePipelineCache();
  RenderResult& result = out.result;
  if (options.outputs.spectral)
    addSpectralChannels(result.image, result.histogram, result.plan,
                        resolveParametersFor(job.scene, result.plan, result.beamsTraced));
  // The film moves into the state: the result's copy would be a second one.
  out.state = FilmState{fingerprint, {{options.firstBeam, result.beamsTraced}}, std::move(result.histogram),
                        std::move(bundle), stateIrradiancePerCount(result.plan.irradianceScale(), result.beamsTraced)};
  return out;
}

}  // namespace spectrace
