#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>

#include "colour/colour.h"

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
  return parameters;
}

void addHostChannels(RenderImage& image, const SpectralHistogram& histogram, const CompiledScene& plan,
                     const ResolveParameters& parameters, uint64_t beams, bool spectral) {
  image.irradianceError = developIrradianceError(histogram, parameters, beams);
  if (spectral) {
    const FilmLayout& film = plan.film;
    image.spectralBinCentresNm = binCentresNm(film.lambdaMinNm, film.lambdaMaxNm, film.bins);
    image.spectralIrradiance =
        developSpectrum(histogram, parameters, (film.lambdaMaxNm - film.lambdaMinNm) / double(film.bins));
  }
}

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Beams per batch: about a second of work, between 2^20 and 2^30.
uint64_t nextBatch(uint64_t done, double seconds, uint64_t remaining, const RenderOptions& options) {
  if (options.batchBeams) return std::min(options.batchBeams, remaining);
  uint64_t batch = uint64_t(1) << 22;
  if (done > 0 && seconds > 0.0) batch = uint64_t(double(done) / seconds);
  batch = std::clamp<uint64_t>(batch, uint64_t(1) << 20, uint64_t(1) << 30);
  return std::min(batch, remaining);
}

}  // namespace

RenderResult render(const Scene& scene, const RenderOptions& options) {
  const auto device = Device::open(options.device, options.log, options.pipelineCache);
  return render(scene, options, *device);
}

RenderResult render(const Scene& scene, const RenderOptions& options, const Device& device) {
  const auto start = Clock::now();
  RenderResult result;
  result.plan = compileScene(scene, options.seed, options.plan);
  const CompiledScene& plan = result.plan;
  checkBeamScale(scene, plan, options.beams);
  const auto tracer = device.makeTracer(
      plan, TracerOptions{options.workgroupSize, options.specialisedFeatures, options.cpuThreads});
  result.deviceKind = tracer->kind();
  result.deviceName = tracer->deviceName();
  if (options.log)
    options.log(fmt::format("device: {} ({})", result.deviceName, result.deviceKind == DeviceKind::Vulkan ? "Vulkan" : "C++"));

  uint64_t done = 0;
  if (options.resumeFilm) {
    tracer->upload(*options.resumeFilm);
    done = std::min(options.resumedBeams, options.beams);
  }
  const uint64_t resumed = done;
  auto lastCheckpoint = Clock::now();
  const auto traceStart = Clock::now();
  while (done < options.beams) {
    if (options.cancel && options.cancel->load()) break;
    const uint64_t batch = nextBatch(done - resumed, secondsSince(traceStart), options.beams - done, options);
    done += tracer->trace(options.firstBeam + done, batch, options.cancel);
    if (options.onProgress) options.onProgress(done, options.beams);
    if (options.onCheckpoint && options.checkpointSeconds > 0.0 && done < options.beams &&
        secondsSince(lastCheckpoint) >= options.checkpointSeconds) {
      const ResolveParameters parameters = resolveParametersFor(scene, plan, done);
      RenderImage image = tracer->develop(parameters);
      const SpectralHistogram film = tracer->download();
      addHostChannels(image, film, plan, parameters, done, options.spectral);
      options.onCheckpoint(image, done, result.deviceLabel());
      if (options.onCheckpointFilm) options.onCheckpointFilm(film, done);
      lastCheckpoint = Clock::now();
    }
  }
  result.beamsTraced = done;
  result.traceWallSeconds = secondsSince(traceStart);
  result.histogram = tracer->download();
  const ResolveParameters parameters = resolveParametersFor(scene, plan, done);
  result.image = tracer->develop(parameters);
  addHostChannels(result.image, result.histogram, plan, parameters, done, options.spectral);
  result.traceDeviceSeconds = tracer->traceDeviceSeconds();
  result.resolveDeviceSeconds = tracer->developDeviceSeconds();
  result.wallSeconds = secondsSince(start);
  return result;
}

}  // namespace spectrace
