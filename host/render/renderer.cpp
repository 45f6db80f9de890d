#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <fmt/format.h>
#include <sys/resource.h>

#include "colour/colour.h"
#include "compile/estimators.h"
#include "json/scene_error.h"

namespace spectrace {

ResolveParameters resolveParametersFor(const Scene& scene, const CompiledScene& plan, uint64_t beams) {
  ResolveParameters parameters;
  const Observer& observer = observerByName(scene.observer);
  parameters.binWeights = plan.film.colourFromBins
                              ? plan.colourBinMeans
                              : binAveragedCmf(observer, plan.film.lambdaMinNm, plan.film.lambdaMaxNm, int(plan.film.bins));
  for (auto& w : parameters.binWeights)
    for (double& v : w) v *= kLumensPerWatt;
  parameters.xyzToRgb = xyzToLinearSrgb();
  parameters.irradiancePerCount = beams > 0 ? plan.irradiancePerCount(beams) : 0.0;
  parameters.beams = beams;
  return parameters;
}

void addSpectralChannels(RenderImage& image, const SpectralHistogram& histogram, const CompiledScene& plan,
                         const ResolveParameters& parameters) {
  const FilmLayout& film = plan.film;
  image.spectralBinCentresNm = binCentresNm(film.lambdaMinNm, film.lambdaMaxNm, film.bins);
  image.spectralIrradiance =
      developSpectrum(histogram, parameters, (film.lambdaMaxNm - film.lambdaMinNm) / double(film.bins));
}

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Beams per batch: about half a second of work at the rate measured so far,
// so progress and cancellation answer within about a second whatever a
// beam costs (a mesh scene's beams can be 100 times a bare one's). The
// first batch is small for the same reason; the image does not depend on
// the batches (each beam's random numbers are keyed on its index).
constexpr double kBatchSeconds = 0.5;
constexpr uint64_t kFirstBatch = uint64_t(1) << 16;
constexpr uint64_t kSmallestBatch = uint64_t(1) << 10, kLargestBatch = uint64_t(1) << 30;
uint64_t nextBatch(uint64_t done, double seconds, uint64_t remaining, const RenderOptions& options) {
  if (options.loop.batchBeams) return std::min(options.loop.batchBeams, remaining);
  uint64_t batch = kFirstBatch;
  if (done > 0 && seconds > 0.0) batch = uint64_t(std::min(double(kLargestBatch), double(done) / seconds * kBatchSeconds));
  batch = std::clamp(batch, kSmallestBatch, kLargestBatch);
  return std::min(batch, remaining);
}

// A number from a one-line file such as /sys/fs/cgroup/memory.max ("max" or
// absent: none).
std::optional<uint64_t> readCount(const char* path) {
  std::optional<uint64_t> value;
  if (std::FILE* f = std::fopen(path, "r")) {
    unsigned long long v = 0;
    if (std::fscanf(f, "%llu", &v) == 1) value = v;
    std::fclose(f);
  }
  return value;
}

// Bytes of memory this process can still get: MemAvailable, and less when
// a container's memory limit (cgroup v2) or an address-space or data limit
// (ulimit -v, -d) is lower.
uint64_t availableHostBytes() {
  uint64_t available = UINT64_MAX;
  if (std::FILE* f = std::fopen("/proc/meminfo", "r")) {
    char line[256];
    unsigned long long kib = 0;
    while (std::fgets(line, sizeof line, f))
      if (std::sscanf(line, "MemAvailable: %llu kB", &kib) == 1) available = uint64_t(kib) * 1024;
    std::fclose(f);
  }
  const auto cgroupMax = readCount("/sys/fs/cgroup/memory.max");
  const auto cgroupUsed = readCount("/sys/fs/cgroup/memory.current");
  if (cgroupMax && cgroupUsed) available = std::min(available, *cgroupMax > *cgroupUsed ? *cgroupMax - *cgroupUsed : 0);
  for (int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit limit{};
    if (::getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
      available = std::min<uint64_t>(available, limit.rlim_cur);
  }
  return available;
}

std::string scenePrefix(const Scene& scene) {
  return scene.sourcePath.empty() ? std::string("<scene>: ") : scene.sourcePath.string() + ": ";
}

}  // namespace

uint64_t filmHostBytes(const CompiledScene& plan, const DeviceCapabilities& device, bool spectral, bool downloadsFilm) {
  const FilmLayout& film = plan.film;
  const uint64_t pixels = film.pixelCount();
  // The full-film histogram: counts, colour sums, squared weight sums.
  const uint64_t histogram =
      pixels * (uint64_t(film.bins) + (film.exactColour ? 3 : 0) + (film.weighted() ? 1 : 0)) * sizeof(uint64_t);
  // Held at once at the end: the result's histogram and a downloaded copy
  // when the film is downloaded, and either the device's counters, where
  // they live in host memory, or the resolve's per-pixel results.
  uint64_t bytes = (downloadsFilm || spectral ? 2 * histogram : 0) +
                   (device.filmInHostMemory ? film.storedCounterCount() * sizeof(uint64_t)
                                            : film.storedPixelCount() * sizeof(device::ResolvedPixel));
  // The image: RGB, XYZ, E, error.E as floats, and the spectral block.
  bytes += pixels * 8 * sizeof(float) + (spectral ? pixels * film.bins * sizeof(float) : 0);
  return bytes;
}

void checkFilmFitsMemory(const Scene& scene, const CompiledScene& plan, const DeviceCapabilities& device, bool spectral,
                         bool downloadsFilm) {
  const uint64_t needed = filmHostBytes(plan, device, spectral, downloadsFilm);
  const uint64_t available = availableHostBytes();
  if (needed > available)
    throw SceneError(fmt::format(
        "{}/camera/sensor/pixels: a film of {}x{} pixels x {} bins needs about {} bytes ({:.1f} GiB) of memory; "
        "{} bytes ({:.1f} GiB) are available; use fewer pixels or bins",
        scenePrefix(scene), plan.film.pixelsX, plan.film.pixelsY, plan.film.bins, needed,
        double(needed) / double(1ull << 30), available, double(available) / double(1ull << 30)));
}

std::vector<std::string> planNotes(const Scene& scene, const CompiledScene& plan) {
  std::vector<std::string> notes{fmt::format(
      "estimator: {}{}", estimatorsDescription(plan.device.constants.estimators),
      plan.cameraPathsOffBecause.empty() ? "" : fmt::format(" (no camera paths: {})", plan.cameraPathsOffBecause))};
  std::vector<const LightSummary*> cannotShine;
  size_t traced = 0;
  for (const LightSummary& light : plan.summaries) {
    if (!light.traced) {
      notes.push_back(fmt::format("note: {} is never sampled: {}", light.label, light.notTracedBecause));
      continue;
    }
    ++traced;
    if (light.powerLm > 0.0)
      notes.push_back(fmt::format("{}: {:g} lm is {:.5g} W ({:.5g} lm/W for its spectrum)", light.label, light.powerLm,
                                  light.powerW, light.powerLm / light.powerW));
    if (light.aimed)
      notes.push_back(fmt::format("{}: beams aimed at the camera (largest weight {:.3g})", light.label,
                                  light.largestWeight));
    if (!light.cannotShineOnCameraBecause.empty()) cannotShine.push_back(&light);
  }
  // With objects no light is refused for missing the camera: what it lights
  // may be seen. Whether anything is cannot be proved before tracing (the
  // render warns after it when nothing was counted), so this is a note.
  if (!scene.objects.empty() && traced > 0 && cannotShine.size() == traced)
    notes.push_back(fmt::format(
        "note: no light can shine on the camera directly ({}: {}{}); only what the objects scatter can reach it",
        cannotShine[0]->label, cannotShine[0]->cannotShineOnCameraBecause,
        traced > 1 ? fmt::format("; and {} more", traced - 1) : std::string()));
  return notes;
}

RenderResult render(const Scene& scene, const RenderOptions& options) {
  const auto device = Device::open(options.device, options.loop.log, options.pipelineCache);
  return render(scene, options, *device);
}

RenderResult render(const Scene& scene, const RenderOptions& options, const Device& device) {
  return render(scene, compileScene(scene, options.seed, options.plan), options, device);
}

RenderResult render(const Scene& scene, CompiledScene compiled, const RenderOptions& options, const Device& device) {
  const auto start = Clock::now();
  if (compiled.device.constants.seed != options.seed)
    throw std::logic_error("render: the plan was compiled with another seed than options.seed");
  RenderResult result;
  result.plan = std::move(compiled);
  const CompiledScene& plan = result.plan;
  checkBeamScale(scene, plan, options.beams);
  // Before any film is allocated: a clear refusal, not a bad_alloc mid-render.
  checkFilmFitsMemory(scene, plan, device.capabilities(), options.outputs.spectral, options.outputs.downloadFilm);
  std::unique_ptr<Tracer> tracer;
  try {
    tracer = device.makeTracer(plan, options.tracer);
  } catch (const SceneError& e) {  // the device's limits, named by field; add the file
    throw SceneError(scenePrefix(scene) + e.what());
  }
  result.deviceKind = tracer->kind();
  result.deviceName = tracer->deviceName();
  if (options.loop.log) {
    options.loop.log(fmt::format("device: {}", result.deviceLabel()));
    for (const std::string& note : planNotes(scene, plan)) options.loop.log(note);
  }

  uint64_t done = 0;
  if (options.loop.resumeFilm) {
    tracer->upload(*options.loop.resumeFilm);
    done = std::min(options.loop.resumedBeams, options.beams);
  }
  const uint64_t resumed = done;
  auto lastCheckpoint = Clock::now();
  const auto traceStart = Clock::now();
  if (options.loop.onStart) options.loop.onStart(done, options.beams);
  while (done < options.beams) {
    if (options.loop.cancel && options.loop.cancel->load()) break;
    const uint64_t batch = nextBatch(done - resumed, secondsSince(traceStart), options.beams - done, options);
    done += tracer->trace(options.firstBeam + done, batch, options.loop.cancel);
    if (options.loop.onProgress) options.loop.onProgress(done, options.beams);
    if (options.loop.onCheckpoint && options.loop.checkpointSeconds > 0.0 && done < options.beams &&
        secondsSince(lastCheckpoint) >= options.loop.checkpointSeconds) {
      const ResolveParameters parameters = resolveParametersFor(scene, plan, done);
      RenderImage image = tracer->develop(parameters);
      const bool needsFilm = options.outputs.spectral || options.loop.onCheckpointFilm;
      const SpectralHistogram film = needsFilm ? tracer->download() : SpectralHistogram();
      if (options.outputs.spectral) addSpectralChannels(image, film, plan, parameters);
      options.loop.onCheckpoint(image, done, result.deviceLabel());
      if (options.loop.onCheckpointFilm) options.loop.onCheckpointFilm(film, done);
      lastCheckpoint = Clock::now();
    }
  }
  result.beamsTraced = done;
  result.beamsResumed = resumed;
  result.traceWallSeconds = secondsSince(traceStart);
  const ResolveParameters parameters = resolveParametersFor(scene, plan, done);
  result.image = tracer->develop(parameters, &result.summary);
  if (options.loop.log && done > resumed && !(result.summary.largestBeams > 0.0))
    options.loop.log(fmt::format("warning: no light reached the camera in {} beams: the image is black", done));
  if (options.outputs.downloadFilm || options.outputs.spectral) result.histogram = tracer->download();
  if (options.outputs.spectral && !options.outputs.spectralByCaller) addSpectralChannels(result.image, result.histogram, plan, parameters);
  result.traceDeviceSeconds = tracer->traceDeviceSeconds();
  result.resolveDeviceSeconds = tracer->developDeviceSeconds();
  result.wallSeconds = secondsSince(start);
  return result;
}

}  // namespace spectrace
