#include "cli/commands.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fmt/format.h>

#include "io/image.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "vulkan/context.h"

namespace spectrace::cli {
namespace {

std::filesystem::path defaultOutput(const std::filesystem::path& scene) {
  return std::filesystem::path("out") / (scene.stem().string() + ".exr");
}

ImageMetadata metadataFor(const Scene& scene, const std::string& device, bool aimed, uint64_t seed,
                          uint64_t firstBeam, uint64_t beamsDone, double wallSeconds) {
  ImageMetadata meta;
  meta.strings["spectrace:beams"] = std::to_string(beamsDone);
  meta.strings["spectrace:first_beam"] = std::to_string(firstBeam);
  meta.strings["spectrace:seed"] = std::to_string(seed);
  meta.strings["spectrace:device"] = device;
  meta.strings["spectrace:scene_file"] = scene.sourcePath.string();
  meta.strings["spectrace:scene_sha256"] = scene.sourceSha256;
  meta.strings["spectrace:observer"] = scene.observer;
  meta.strings["spectrace:units"] =
      "R,G,B: linear sRGB (Rec. 709, D65) of XYZ; XYZ: CIE XYZ with Y in lux; irradiance.E: W/m^2 over all bins";
  meta.numbers["spectrace:wall_time_s"] = wallSeconds;
  meta.numbers["spectrace:spectrum_min_nm"] = scene.spectrum.minNm;
  meta.numbers["spectrace:spectrum_max_nm"] = scene.spectrum.maxNm;
  meta.numbers["spectrace:spectrum_bins"] = scene.spectrum.bins;
  meta.numbers["spectrace:exposure_s"] = scene.camera.exposureS;
  meta.strings["spectrace:sampling"] = aimed ? "aimed at the camera, weighted" : "analog";
  return meta;
}

}  // namespace

int runRender(const RenderCommand& command, const std::atomic<bool>& cancel) {
  const Scene scene = loadScene(command.scene);
  const auto output = command.output.value_or(defaultOutput(command.scene));
  auto png = output;
  png.replace_extension(".png");

  RenderOptions options;
  options.beams = command.beams.value_or(scene.render.beams);
  options.seed = command.seed.value_or(scene.render.seed);
  options.firstBeam = command.firstBeam;
  options.device = parseDeviceChoice(command.device);
  options.cpuThreads = command.threads;
  options.cancel = &cancel;
  options.checkpointSeconds = command.checkpointSeconds;
  options.plan.trimSpectrum = !command.fullSpectrum;
  options.plan.trimPixels = !command.fullSensor;
  options.specialisedFeatures = command.general ? kSpecialiseNone : kSpecialiseAll;
  options.plan.aim = !command.noAim;
  if (!command.quiet) options.log = [](const std::string& line) { std::fprintf(stderr, "spectrace: %s\n", line.c_str()); };

  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  // A checkpoint is a complete, valid image of the beams finished so far.
  options.onCheckpoint = [&](const RenderImage& image, uint64_t done, const std::string& device) {
    writeExr(output, image, metadataFor(scene, device, options.plan.aim, options.seed, options.firstBeam, done, elapsed()));
    if (!command.quiet) std::fprintf(stderr, "spectrace: checkpoint: %llu beams -> %s\n", (unsigned long long)done, output.c_str());
  };
  if (!command.quiet) {
    options.onProgress = [&](uint64_t done, uint64_t total) {
      std::fprintf(stderr, "\rspectrace: %5.1f%% (%llu of %llu beams)", 100.0 * double(done) / double(total),
                   (unsigned long long)done, (unsigned long long)total);
      if (done == total) std::fprintf(stderr, "\n");
    };
  }

  RenderResult result = render(scene, options);
  if (!command.quiet) {
    for (const auto& light : result.plan.summaries) {
      if (!light.traced)
        std::fprintf(stderr, "spectrace: note: %s is never sampled: %s\n", light.label.c_str(),
                     light.notTracedBecause.c_str());
      else if (light.aimed)
        std::fprintf(stderr, "spectrace: %s: beams aimed at the camera (largest weight %.3g)\n", light.label.c_str(),
                     light.largestWeight);
    }
  }
  writeExr(output, result.image, metadataFor(scene, result.deviceLabel(), options.plan.aim, options.seed, options.firstBeam,
                                             result.beamsTraced, result.wallSeconds));
  if (command.png) writePngPreview(png, result.image);
  if (!command.quiet) {
    std::fprintf(stderr, "\nspectrace: %llu beams in %.2f s (%.1f Mbeam/s) on %s\n", (unsigned long long)result.beamsTraced,
                 result.wallSeconds, double(result.beamsTraced) / result.wallSeconds * 1e-6, result.deviceName.c_str());
    const auto& counts = result.histogram.counts;
    const uint64_t largest = counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end());
    const uint64_t counted = result.histogram.countedBeams;
    std::fprintf(stderr, "spectrace: %llu beams counted (%.3g%% of those traced); the largest pixel-bin holds %llu %s\n",
                 (unsigned long long)counted,
                 result.beamsTraced ? 100.0 * double(counted) / double(result.beamsTraced) : 0.0,
                 (unsigned long long)largest,
                 result.histogram.isWeighted() ? "units of 2^-24 beam" : "beams");
    std::fprintf(stderr, "spectrace: wrote %s%s\n", output.c_str(), command.png ? (" and " + png.string()).c_str() : "");
  }
  if (result.beamsTraced < options.beams) {
    std::fprintf(stderr, "spectrace: interrupted after %llu of %llu beams; the image holds the finished beams\n",
                 (unsigned long long)result.beamsTraced, (unsigned long long)options.beams);
    return 130;
  }
  return 0;
}

int runDevices() {
  const auto devices = vk_util::enumerateDevices();
  std::printf("%s", vk_util::describeDevices(devices).c_str());
  if (auto index = vk_util::preferredDevice(devices))
    std::printf("\n--device auto and --device gpu use: %s\n", devices[*index].name.c_str());
  else
    std::printf("\nNo usable Vulkan device: --device auto uses the CPU reference.\n");
  return 0;
}

}  // namespace spectrace::cli
