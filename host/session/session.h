#pragma once
// Many renders in one process: a Session opens a Device once and renders
// RenderJobs on it, writing each job's EXR (and PNG preview). The CLI's
// `render` and `batch` verbs are thin clients; programs can use it directly.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "backend/device.h"
#include "film/film_state.h"
#include "io/image.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace spectrace {

// One render: a parsed scene, where its image goes and how it is traced
// (the parts of RenderOptions that are the job's; the device is the
// session's).
struct RenderJob {
  Scene scene;
  std::filesystem::path output;           // the EXR; the PNG goes beside it
  // What to trace.
  std::optional<uint64_t> beams;          // default: the scene's render.beams
  std::optional<uint64_t> seed;           // default: the scene's render.seed
  uint64_t firstBeam = 0;
  bool png = true;
  // How (compilation, the device's tuning), what it produces, the loop.
  CompileOptions plan;
  TracerOptions tracer;
  RenderOutputs outputs;
  RenderLoop loop;
  // The exact render state, written at every checkpoint and at the end
  // (film/film_state.h); none when empty.
  std::filesystem::path state;
  // What names the state in messages: the option or job key that gave it.
  std::string stateRole = "--state";
  // A state to go on from: it must be this job's (same fingerprint) and
  // cover beams [firstBeam, firstBeam + k); the render traces the rest.
  std::optional<FilmState> resume;
  std::filesystem::path resumeFile;  // where `resume` was read from, for messages
  // Warnings (a checkpoint that could not be written); default: stderr.
  std::function<void(const std::string&)> warn;

  uint64_t beamCount() const { return beams.value_or(scene.render.beams); }
  uint64_t seedValue() const { return seed.value_or(scene.render.seed); }
  // The job as RenderOptions: its beams and seed resolved.
  RenderOptions renderOptions() const;
};

// Writing a job's output failed (the render itself was fine).
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The output path is unusable (bad input, found before tracing): an input
// file, a device node or folder, not ending in .exr, or not writable.
struct OutputPathError : OutputError {
  OutputPathError(const std::string& message, std::string role) : OutputError(message), role(std::move(role)) {}
  std::string role;  // the refused file's OutputFile::role
};

// One file a run writes: its path, what names it in messages ("output",
// "--state") and the extension it must have ("" for any).
struct OutputFile {
  std::filesystem::path path;
  std::string role;
  std::string extension;
};

// Checks, before any tracing, that every output can be written without
// harm: each is absent or a regular file; none is any of `inputs` (compared
// with std::filesystem::equivalent) nor another of `outputs`; each has its
// extension (the EXR ends in .exr, so the PNG preview beside it never
// replaces it); and each folder can be created and holds a new file (a probe
// file is created and removed). Throws OutputPathError naming the path and
// the reason.
void checkOutputFiles(const std::vector<OutputFile>& outputs, const std::vector<std::filesystem::path>& inputs);
// The files a job writes: its EXR, its PNG preview (when written) and its
// state (when asked for, named `stateRole` in messages).
std::vector<OutputFile> outputFilesOf(const std::filesystem::path& exr, bool png,
                                      const std::filesystem::path& state, const std::string& stateRole = "--state");
// checkOutputFiles for the job's outputs; the scene file, its CSV spectra,
// its OBJ meshes and any of `inputs` are inputs (a state the job resumes
// from may be its own --state, which it replaces). With spectral channels
// (the job's or the scene's), also that no two bins share a channel name
// (SceneError naming /spectrum/bins and the two bins).
void checkOutputPath(const RenderJob& job, const std::vector<std::filesystem::path>& inputs = {});

class Session {
 public:
  // Opens the device once (auto: a GPU if any, else the CPU reference).
  explicit Session(DeviceChoice device, const std::function<void(const std::string&)>& log = {},
                   const PipelineCacheOptions& pipelineCache = {});
  // On a device the caller opened (e.g. an MPI rank's GPU by local rank).
  explicit Session(std::unique_ptr<Device> device);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  const Device& device() const { return *device_; }

  // Renders the job on the session's device, saves the device's pipeline
  // cache if it changed, and writes its outputs (creating the output's
  // folder). checkOutputPath runs first. Throws OutputError when they cannot be
  // written; the result is returned either way only on success.
  RenderResult render(const RenderJob& job) const;

  // The same render, overlapped with the next: it traces the job, then hands
  // everything after the histogram's download (error and spectral channels,
  // EXR, PNG, final state) to a writer thread and returns, so the caller can
  // trace the next job meanwhile. At most one job waits to be written: before
  // handing this one over it waits until the previous one is written (and,
  // before tracing, when both would write the same file). Errors found before
  // or while tracing are thrown here; the writing's (OutputError) by the
  // future's get(). The destructor and finishWriting() wait for the last write,
  // so every finished output is complete even after an interrupt.
  std::shared_future<RenderResult> renderOverlapped(const RenderJob& job) const;
  // Waits until the last handed-over job is written (its errors stay in its future).
  void finishWriting() const;

  // The same render held in memory, for programs that read the image
  // rather than a file (the Python module): nothing is written, and no
  // checkpoint is taken. The image is the one render() would write, the
  // spectral block included when asked for; `state` is the exact state
  // render() would write with job.state set (its film moved there: the
  // result's histogram is left empty). Cancelled renders return what was
  // traced (result.beamsTraced < the job's beams).
  struct InMemoryRender {
    RenderResult result;
    FilmState state;
  };
  InMemoryRender renderInMemory(const RenderJob& job) const;

  // A (merged) state developed in memory, as a render of all its beams
  // would resolve it; `scene` gets the state's scene (for the image's
  // metadata). Throws FilmStateError.
  RenderResult developInMemory(const FilmState& state, bool spectral, Scene* scene = nullptr) const;

  // Develops a (merged) state into `output` on the session's device, as a
  // render of all its beams would: the scene is the state's bundle (or, in
  // a state without one, its fingerprint's file), which must hash as the
  // fingerprint says and compile to the same film.
  // `wallSeconds` goes into the header (the time the state took to trace).
  // Throws FilmStateError (bad input) or OutputError.
  RenderResult develop(const FilmState& state, const std::filesystem::path& output, bool spectral, bool png,
                       double wallSeconds = 0.0) const;

 private:
  std::unique_ptr<Device> device_;
  // The job being written on the writer thread, and the files it writes.
  // Mutable: the hand-over to the writer, not the device's state.
  mutable std::shared_future<RenderResult> writing_;
  mutable std::vector<std::filesystem::path> writingFiles_;
};

// The beams of shard `index` (0-based) of `count` equal parts of `beams`
// beams starting at `firstBeam` (throws std::invalid_argument for index >= count).
BeamRange shardRange(uint64_t firstBeam, uint64_t beams, uint64_t index, uint64_t count);

// The fingerprint of `job` rendered as it is set up (its scene compiled
// with its options and seed): what its state files carry.
FilmFingerprint jobFingerprint(const RenderJob& job);
// The same for `plan`, the job's scene as a render compiled it.
FilmFingerprint jobFingerprint(const RenderJob& job, const CompiledScene& plan);
// What a state of `scene` carries so that merge and develop need no other
// file: its sourceText and the files it names (referencedFiles), read now
// and checked against its digests; none for a scene built in code (no
// text). Throws FilmStateError when a file cannot be read or has changed
// since the scene was parsed.
std::optional<SceneBundle> sceneBundleOf(const Scene& scene);
// A state's irradiance_per_count: scale.perCount(beams), or 0 for a state
// of no beams (whose scale is infinite).
double stateIrradiancePerCount(const IrradianceScale& scale, uint64_t beams);

// The EXR header the renders write (spectrace:beams etc.).
ImageMetadata renderMetadata(const Scene& scene, const std::string& device, bool aimed, uint64_t seed,
                             uint64_t firstBeam, uint64_t beamsDone, double wallSeconds);
// A finished image written as render() writes it: the output's folder
// created, the PNG preview beside it when asked for, then the EXR. Throws
// OutputError. (Check the path first with checkOutputPath.)
void writeRenderImage(const std::filesystem::path& output, const RenderImage& image, const ImageMetadata& metadata,
                      bool png);
// Whether `exr` is a complete render of `beams` beams: it reads, and its
// spectrace:beams attribute says so. False for a missing or broken file.
bool outputIsComplete(const std::filesystem::path& exr, uint64_t beams);

}  // namespace spectrace
