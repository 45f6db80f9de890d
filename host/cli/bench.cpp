// `spectrace bench`: throughput of each device on one fixed reference scene,
// with ratios taken in the same run (machines are noisy; only ratios in one
// run compare).
#include <fmt/format.h>

#include <sstream>
#include <vector>

#include "cli/commands.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace spectrace::cli {
namespace {

// The fixed reference scene: one D65 disk light 0.1 m in front of a bare
// 512x512 sensor, 64 bins over 360-830 nm.
Scene benchScene() {
  Scene scene;
  scene.spectrum = {360.0, 830.0, 64};
  scene.camera.position = {0.0, 0.0, 0.0};
  scene.camera.lookAt = {0.0, 0.0, 1.0};
  scene.camera.up = {0.0, 1.0, 0.0};
  scene.camera.sensorWidthM = 0.1;
  scene.camera.sensorHeightM = 0.1;
  scene.camera.pixelsX = 512;
  scene.camera.pixelsY = 512;
  Light disk;
  disk.type = LightType::Disk;
  disk.label = "/lights/0";
  disk.position = {0.0, 0.0, 0.1};
  disk.direction = {0.0, 0.0, -1.0};
  disk.radiusM = 0.05;
  disk.powerW = 1.0;
  disk.spdLabel = "D65";
  disk.spd = *cieIlluminant("D65");
  scene.lights.push_back(disk);
  return scene;
}

}  // namespace

int runBench(const BenchCommand& command, const std::atomic<bool>& cancel) {
  const Scene scene = benchScene();
  std::vector<std::string> devices;
  std::stringstream list(command.devices);
  for (std::string item; std::getline(list, item, ',');) devices.push_back(item);

  fmt::print("spectrace bench: D65 disk light, bare 512x512 sensor, 64 bins, {} beams per device\n", command.beams);
  fmt::print("{:<8} {:<44} {:>10} {:>12} {:>10}\n", "device", "name", "wall s", "Mbeam/s", "hit rate");
  std::vector<std::pair<std::string, double>> rates;
  for (const auto& name : devices) {
    RenderOptions options;
    options.device = parseDeviceChoice(name);
    options.beams = command.beams;
    options.seed = 1;
    options.cpuThreads = command.threads;
    options.cancel = &cancel;
    // Warm-up: pipeline compilation happens at the first dispatch.
    RenderOptions warm = options;
    warm.beams = uint64_t(1) << 16;
    render(scene, warm);
    const RenderResult result = render(scene, options);
    const double seconds = result.traceDeviceSeconds > 0.0 ? result.traceDeviceSeconds : result.wallSeconds;
    const double rate = double(result.beamsTraced) / result.wallSeconds;
    fmt::print("{:<8} {:<44} {:>10.3f} {:>12.2f} {:>9.1f}%\n", result.deviceKind, result.deviceName, result.wallSeconds,
               rate * 1e-6, 100.0 * double(result.histogram.total()) / double(result.beamsTraced));
    if (result.traceDeviceSeconds > 0.0)
      fmt::print("{:<8} {:<44} {:>10.3f} {:>12.2f}   (device time of the trace pass)\n", "", "", seconds,
                 double(result.beamsTraced) / seconds * 1e-6);
    rates.emplace_back(fmt::format("{} ({})", result.deviceKind, result.deviceName), rate);
  }
  for (size_t i = 1; i < rates.size(); ++i)
    fmt::print("ratio {} : {} = {:.2f}\n", rates[0].first, rates[i].first, rates[0].second / rates[i].second);
  return 0;
}

}  // namespace spectrace::cli
