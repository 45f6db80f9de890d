#pragma once
// A whole render: choose a device, trace in batches (checkpointing and
// honouring cancellation between them), resolve to an image.
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "backend/device.h"
#include "film/develop.h"
#include "film/spectral_histogram.h"
#include "io/image.h"
#include "compile/compile_scene.h"
#include "scene/scene.h"

namespace spectrace {

// What a render produces besides its image.
struct RenderOutputs {
  // Add the spectral block (one spectral irradiance per bin of the full
  // spectrum) to the image; error.E is always added.
  bool spectral = false;
  // Leave the final image's spectral block (addSpectralChannels) to the
  // caller, who may compute it on another thread.
  bool spectralByCaller = false;
  // Download the final film into RenderResult::histogram. A render whose
  // image is all it writes needs no download (about a copy of the film
  // and its allocation); the spectral block and the render state do.
  bool downloadFilm = true;
};

// How the render loop runs: batches, checkpoints, progress, cancellation,
// and where it starts from.
struct RenderLoop {
  uint64_t batchBeams = 0;           // 0: adapt to about half a second per batch
  const std::atomic<bool>* cancel = nullptr;
  double checkpointSeconds = 60.0;   // 0 disables checkpoints
  // Called between batches at most every checkpointSeconds with the image
  // of the beams finished so far, their count and the device's label.
  std::function<void(const RenderImage&, uint64_t beamsDone, const std::string& device)> onCheckpoint;
  // With each checkpoint, the exact film of the beams finished so far
  // (for the render state, film/film_state.h).
  std::function<void(const SpectralHistogram& film, uint64_t beamsDone)> onCheckpointFilm;
  // Once, as tracing starts (beamsDone: those resumed), then after each batch.
  std::function<void(uint64_t beamsDone, uint64_t beamsTotal)> onStart;
  std::function<void(uint64_t beamsDone, uint64_t beamsTotal)> onProgress;
  std::function<void(const std::string&)> log;  // device choice and notices
  // Resume: the film of beams [firstBeam, firstBeam + resumedBeams), already
  // traced; the render goes on after them and ends as if never stopped.
  const SpectralHistogram* resumeFilm = nullptr;
  uint64_t resumedBeams = 0;
};

// A render, split by who decides each part.
struct RenderOptions {
  // What to trace.
  uint64_t beams = 0;        // total beams
  uint64_t firstBeam = 0;    // index of the first beam (disjoint ranges merge exactly)
  uint64_t seed = 1;
  // Where: the device render(scene, options) opens (unused when the caller
  // passes one).
  DeviceChoice device = DeviceChoice::Auto;
  PipelineCacheOptions pipelineCache;
  // How: the scene's compilation (shortcuts, estimators), which a render
  // state's fingerprint holds, and the device's tuning (threads, workgroup,
  // specialised pipeline), which changes no film.
  CompileOptions plan;
  TracerOptions tracer;
  // What it produces.
  RenderOutputs outputs;
  // The loop.
  RenderLoop loop;
};

struct RenderResult {
  CompiledScene plan;
  SpectralHistogram histogram;  // empty unless options.downloadFilm
  FilmSummary summary;          // counted beams and largest count, from develop
  RenderImage image;
  uint64_t beamsTraced = 0;     // < options.beams only when cancelled
  uint64_t beamsResumed = 0;    // of beamsTraced, those the resumed film held (not traced in this run)
  DeviceKind deviceKind = DeviceKind::Cpu;
  std::string deviceName;       // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)" or "CPU reference, 2 threads, x86-64-v3"
  double wallSeconds = 0.0;
  double traceWallSeconds = 0.0;      // the batch loop alone (no device setup, no resolve)
  double traceDeviceSeconds = 0.0;    // GPU timestamps (0 on the CPU)
  double resolveDeviceSeconds = 0.0;

  // "name (kind)", as written into EXR headers.
  std::string deviceLabel() const { return deviceName + " (" + deviceKindName(deviceKind) + ")"; }
};

// What a render says before it traces: the estimator, lights never sampled
// or aimed (named by their "name" when they have one), and a warning when,
// with objects, no light can shine on the camera directly.
std::vector<std::string> planNotes(const Scene& scene, const CompiledScene& plan);

RenderResult render(const Scene& scene, const RenderOptions& options);
// The same render on a device opened by the caller (options.device unused).
RenderResult render(const Scene& scene, const RenderOptions& options, const Device& device);
// The same render of `plan`, the scene compiled by the caller with
// options.seed and options.plan (a caller that needs the plan first, for a
// state's fingerprint, compiles the scene once).
RenderResult render(const Scene& scene, CompiledScene plan, const RenderOptions& options, const Device& device);

// The resolve inputs for a scene and beam count: 683 x bin-averaged CMFs of
// the scene's observer, XYZ -> linear sRGB, and the irradiance of one count.
// The spectral block of the image (one spectral irradiance per bin of the
// full spectrum), from the downloaded histogram on the host.
void addSpectralChannels(RenderImage& image, const SpectralHistogram& histogram, const CompiledScene& plan,
                         const ResolveParameters& parameters);

// About the host memory a render of `plan` holds at its peak (histograms,
// counters, image), and the check render() makes with it before tracing:
// SceneError naming /camera/sensor/pixels, the bytes needed and the bytes
// available (MemAvailable, cgroup memory.max, ulimit -v / -d), not a
// bad_alloc mid-render. `downloadsFilm`: the render downloads the film
// (RenderOptions::downloadFilm, or the spectral block), which holds
// histograms of the whole film on the host; without it only the CPU
// reference's counters and the image are held.
uint64_t filmHostBytes(const CompiledScene& plan, const DeviceCapabilities& device, bool spectral,
                       bool downloadsFilm = true);
void checkFilmFitsMemory(const Scene& scene, const CompiledScene& plan, const DeviceCapabilities& device, bool spectral,
                         bool downloadsFilm = true);

ResolveParameters resolveParametersFor(const Scene& scene, const CompiledScene& plan, uint64_t beams);

}  // namespace spectrace
