// `spectrace bench`: run time against error. Throughput on a fixed scene,
// an error-vs-time sweep over the reference scenes (exact answers), and the
// colour error of binning, on every device, with ratios taken in one run.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fmt/format.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <algorithm>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "backend/cpu_code.h"
#include "bench/optics_bench.h"
#include "bench/ray_ceiling.h"
#include "bench/throughput_ceiling.h"
#include "bench/error_bench.h"
#include "bench/report.h"
#include "cli/cli_numbers.h"
#include "cli/commands.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "scene/scene_builders.h"
#include "session/session.h"

namespace spectrace::cli {
namespace {

// The fixed throughput scene: one D65 disk light 0.1 m in front of a bare
// 512x512 sensor, 64 bins over 360-830 nm.
Scene throughputScene() {
  Scene scene = bareSensorScene(0.1, 0.1, 512, 512, 64);
  Light disk = surfaceLight(LightType::Disk, {0.0, 0.0, 0.1}, {0.0, 0.0, -1.0}, 1.0, *cieIlluminant("D65"), "D65");
  disk.radiusM = 0.05;
  scene.lights = {disk};
  return scene;
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
  return buffer;
}

std::string machineDescription() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpuinfo, line))
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  return fmt::format("{}, {} hardware threads", model, std::thread::hardware_concurrency());
}

// Renders `scene` for timing: a small render with the same options first, so
// pipeline compilation at the first dispatch stays out of every measured
// variant alike.
RenderResult timedRender(const Scene& scene, const Device& device, uint64_t beams, const std::atomic<bool>& cancel,
                         const std::function<void(RenderOptions&)>& configure = {}) {
  RenderOptions options;
  options.beams = beams;
  options.loop.cancel = &cancel;
  if (configure) configure(options);
  RenderOptions warm = options;
  warm.beams = uint64_t(1) << 16;
  render(scene, warm, device);
  return render(scene, options, device);
}

std::vector<ThroughputRow> runThroughput(const BenchCommand& command, const std::vector<DeviceSpec>& devices,
                                         const std::atomic<bool>& cancel) {
  const Scene scene = throughputScene();
  std::vector<ThroughputRow> rows;
  fmt::print("Throughput: D65 disk light, bare 512x512 sensor, 64 bins, {} beams per device\n", command.beams);
  fmt::print("{:<44} {:<6} {:>9} {:>10} {:>15} {:>9}\n", "device", "colour", "wall s", "Mbeam/s", "Mbeam/s device", "hit rate");
  for (const auto& device : devices) {
    const auto opened = Device::open(device);
    for (bool exactColour : {true, false}) {
      const RenderResult result =
          timedRender(scene, *opened, command.beams, cancel,
                      [&](RenderOptions& o) {
                        o.tracer.cpuThreads = command.threads;
                        o.plan.exactColour = exactColour;
                      });
      ThroughputRow row{device.kind(), device.capabilities.reference, result.deviceName, exactColour,
                        result.beamsTraced, result.summary.countedBeams, result.traceWallSeconds,
                        result.traceDeviceSeconds};
      fmt::print("{:<44} {:<6} {:>9.3f} {:>10.2f} {:>15} {:>8.1f}%\n", row.deviceName, exactColour ? "exact" : "bins",
                 row.wallSeconds, double(row.beams) / row.wallSeconds * 1e-6,
                 row.traceDeviceSeconds > 0 ? fmt::format("{:.2f}", double(row.beams) / row.traceDeviceSeconds * 1e-6) : "-",
                 100.0 * double(row.hits) / double(row.beams));
      rows.push_back(row);
    }
  }
  for (const auto& a : rows)
    for (const auto& b : rows)
      if (!a.reference && b.reference && a.exactColour == b.exactColour)
        fmt::print("ratio {} : {} ({} colour) = {:.2f}\n", a.deviceName, b.deviceName, a.exactColour ? "exact" : "binned",
                   (double(a.beams) / a.wallSeconds) / (double(b.beams) / b.wallSeconds));
  return rows;
}

// Device times of several variants of a render, each the least over
// `rounds` runs taken in turn (variant 0, 1, ..., then again), so that the
// machine's speed drifting during the run (it varies by up to 2x on a
// shared machine) does not favour the variants measured first.
struct BestTimes {
  double traceSeconds = INFINITY, resolveSeconds = INFINITY;
  double traceWallSeconds = INFINITY;
  // Device time where the device has timestamps, else wall time of the trace.
  double traceSecondsOn(const DeviceCapabilities& device) const {
    return device.deviceTimestamps ? traceSeconds : traceWallSeconds;
  }
};
std::vector<BestTimes> interleavedBest(size_t variants, int rounds, const std::function<RenderResult(size_t)>& run) {
  std::vector<BestTimes> best(variants);
  for (int round = 0; round < rounds; ++round)
    for (size_t v = 0; v < variants; ++v) {
      const RenderResult result = run(v);
      best[v].traceSeconds = std::min(best[v].traceSeconds, result.traceDeviceSeconds);
      best[v].resolveSeconds = std::min(best[v].resolveSeconds, result.resolveDeviceSeconds);
      best[v].traceWallSeconds = std::min(best[v].traceWallSeconds, result.traceWallSeconds);
    }
  return best;
}
constexpr int kTimingRounds = 3;

// A profile row's table: each stage's ns per beam, its increment over the
// stage before, and that increment's share of stage `full`.
template <class Row, class Names>
void printStageTable(const Row& row, const Names& names, size_t full, int nameWidth) {
  fmt::print("{}\n{:<{}} {:>10} {:>18} {:>14}\n", row.deviceName, "stage", nameWidth, "ns/beam", "increment ns/beam",
             "share of full");
  for (size_t s = 0; s < row.stageSeconds.size(); ++s) {
    const double increment = row.nsPerBeam(s) - (s ? row.nsPerBeam(s - 1) : 0.0);
    fmt::print("{:<{}} {:>10.2f} {:>+18.2f} {:>13.1f}%\n", names[s], nameWidth, row.nsPerBeam(s), increment,
               100.0 * increment / row.nsPerBeam(full));
  }
}

// The kernel's cost by stage on the throughput scene (shaders/profile.h),
// on every device: each stage's time, its increment and share of the full
// kernel's.
std::vector<ProfileRow> runProfile(const BenchCommand& command, const std::vector<DeviceSpec>& devices,
                                   const std::atomic<bool>& cancel) {
  const Scene scene = throughputScene();
  std::vector<ProfileRow> rows;
  fmt::print("\nProfile: the kernel cut after each stage, throughput scene, {} beams per stage "
             "(device time on Vulkan, wall time on the CPU; least of {})\n",
             command.profileBeams, kTimingRounds);
  for (const auto& device : devices) {
    const auto opened = Device::open(device);
    ProfileRow row{device.kind(), device.name(), command.profileBeams, {}};
    // The stages with per-beam colour (the reference path, so the exact
    // colour stage has work), then the default: the full kernel with colour
    // from the bins (compile/shortcuts.h).
    const auto best = interleavedBest(device::kProfileStageFull + 2, kTimingRounds, [&](size_t stage) {
      return timedRender(scene, *opened, row.beams, cancel, [&](RenderOptions& o) {
        o.tracer.cpuThreads = command.threads;
        o.plan.exactColour = true;
        o.plan.colourFromBins = stage > device::kProfileStageFull;
        o.tracer.profileStage = uint32_t(std::min<size_t>(stage, device::kProfileStageFull));
      });
    });
    for (const auto& b : best) row.stageSeconds.push_back(b.traceSecondsOn(device.capabilities));
    printStageTable(row, kProfileStageNames, device::kProfileStageFull, 36);
    rows.push_back(row);
  }
  return rows;
}

// The profile's objects stages (kObjectsProfileStages) on the optics
// bench's mesh scene, light paths only, on every device. The scene is
// compiled once: a render of the scene would rebuild its BVH each time.
// Fewer beams than the throughput profile (a beam among objects costs more).
std::vector<ObjectsProfileRow> runObjectsProfile(const BenchCommand& command, const std::vector<DeviceSpec>& devices,
                                                 const std::atomic<bool>& cancel) {
  constexpr uint64_t kTriangles = 100'000;
  const Scene scene = opticsMeshScene(kTriangles);
  RenderOptions base;
  base.beams = std::max<uint64_t>(command.profileBeams / 16, 1);
  base.loop.cancel = &cancel;
  base.plan.cameraPaths = false;
  base.tracer.cpuThreads = command.threads;
  const CompiledScene plan = compileScene(scene, base.seed, base.plan);
  std::vector<ObjectsProfileRow> rows;
  fmt::print("\nObjects profile: the kernel cut after each stage, mesh scene ({} triangles, light paths), {} beams "
             "per stage (device time on Vulkan, wall time on the CPU; least of {})\n",
             plan.device.primitives.size(), base.beams, kTimingRounds);
  for (const auto& device : devices) {
    const auto opened = Device::open(device);
    ObjectsProfileRow row{device.kind(), device.name(), base.beams, plan.device.primitives.size(), {}};
    const auto best = interleavedBest(std::size(kObjectsProfileStages), kTimingRounds, [&](size_t stage) {
      RenderOptions options = base;
      options.tracer.profileStage = kObjectsProfileStages[stage];
      RenderOptions warm = options;  // pipeline compilation out of the measured render (timedRender)
      warm.beams = std::min<uint64_t>(options.beams, uint64_t(1) << 12);
      render(scene, plan, warm, *opened);
      return render(scene, plan, options, *opened);
    });
    for (const auto& b : best) row.stageSeconds.push_back(b.traceSecondsOn(device.capabilities));
    printStageTable(row, kObjectsProfileStageNames, row.stageSeconds.size() - 1, 66);
    rows.push_back(row);
  }
  return rows;
}

// spectrace's full kernel (exact colour on) against the ceiling kernel on
// the throughput scene, on every device, in turn, least of 3 each.
std::vector<CeilingRow> runCeiling(const BenchCommand& command, const std::vector<DeviceSpec>& devices,
                                   const std::atomic<bool>& cancel) {
  const Scene scene = throughputScene();
  const CeilingScene ceilingScene = throughputCeilingScene();
  std::vector<CeilingRow> rows;
  fmt::print("\nCeiling: a kernel with no exactness work against spectrace (exact colour on), {} beams "
             "(device time on Vulkan, wall time on the CPU; least of {})\n",
             command.profileBeams, kTimingRounds);
  fmt::print("{:<44} {:>16} {:>18} {:>20}\n", "device", "ceiling Mbeam/s", "spectrace Mbeam/s", "spectrace : ceiling");
  for (const auto& device : devices) {
    const auto opened = Device::open(device);
    CeilingRow row{device.kind(), device.name(), command.profileBeams, INFINITY, INFINITY, 0};
    for (int round = 0; round < kTimingRounds && !cancel.load(); ++round) {
      const CeilingResult ceiling = opened->traceCeiling(ceilingScene, row.beams, command.threads);
      row.ceilingSeconds = std::min(row.ceilingSeconds, ceiling.seconds);
      row.ceilingHits = ceiling.hits;
      const RenderResult result = timedRender(scene, *opened, row.beams, cancel, [&](RenderOptions& o) {
        o.tracer.cpuThreads = command.threads;
        o.plan.exactColour = true;
      });
      row.spectraceSeconds = std::min(row.spectraceSeconds, device.capabilities.deviceTimestamps
                                                                 ? result.traceDeviceSeconds
                                                                 : result.traceWallSeconds);
    }
    fmt::print("{:<44} {:>16.2f} {:>18.2f} {:>20.3f}\n", row.deviceName, double(row.beams) / row.ceilingSeconds * 1e-6,
               double(row.beams) / row.spectraceSeconds * 1e-6, row.ratio());
    rows.push_back(row);
  }
  return rows;
}

// Closest-hit rays through the optics bench's mesh of `triangles`, by the
// shared kernel's BVH walk and by Embree (bench/ray_ceiling.h), on the CPU.
// 2^20 rays; with --profile-beams under that (quick checks), that many.
RayCeilingRow runRayCeilingSection(const BenchCommand& command, uint64_t triangles, const std::atomic<bool>& cancel) {
  const uint64_t rays = std::min(command.profileBeams, uint64_t(1) << 20);
  const unsigned threads = command.threads ? command.threads : std::max(1u, std::thread::hardware_concurrency());
  fmt::print("\nRay ceiling: {} incoherent closest-hit rays through a mesh of {} triangles, spectrace's BVH "
             "(shared kernel, CPU, {} code as the renderer runs it) against Embree, 1 and {} threads (wall time, "
             "least of 2)\n",
             rays, triangles, cpuCodeName(fastestCpuCode()), threads);
  const RayCeilingRow r = runRayCeiling(triangles, rays, threads, cancel);
  const double m = double(r.rays) * 1e-6;
  fmt::print("{:<10} {:>10} {:>8} {:>14} {:>14} {:>16}\n", "tracer", "triangles", "threads", "Mray/s", "bytes/triangle",
             "spectrace : Embree");
  fmt::print("{:<10} {:>10} {:>8} {:>14.3f} {:>14.1f}\n", "spectrace", r.triangles, 1, m / r.spectrace1, r.bytesPerTriangle);
  fmt::print("{:<10} {:>10} {:>8} {:>14.3f} {:>14.1f}\n", "spectrace", r.triangles, r.threads, m / r.spectraceN,
             r.bytesPerTriangle);
  fmt::print("{:<10} {:>10} {:>8} {:>14.3f} {:>14.1f}{}\n", "spectrace", r.triangles, 1, m / r.interleaved1,
             r.bytesPerTriangle, r.embree ? fmt::format(" {:>16.3f}", r.interleavedRatio1()) : "");
  fmt::print("{:<10} {:>10} {:>8} {:>14.3f} {:>14.1f}{}\n", "spectrace", r.triangles, r.threads, m / r.interleavedN,
             r.bytesPerTriangle, r.embree ? fmt::format(" {:>16.3f}", r.interleavedRatioN()) : "");
  fmt::print("(the last two: {} walks in turn on each thread, as the CPU reference walks a tree larger than the last-level "
             "cache; {} rays hit differently from one walk at a time)\n",
             kCeilingWalksInFlight, r.interleavedDifferences);
  fmt::print("(bytes/triangle: the CPU reference's full nodes; the Vulkan trace's packed nodes take {:.1f})\n",
             r.vulkanBytesPerTriangle);
  if (!r.embree) {
    fmt::print("Embree: unavailable (built without it: install libembree-dev, configure with -DSPECTRACE_EMBREE=ON)\n");
    return r;
  }
  fmt::print("{:<10} {:>10} {:>8} {:>14.3f} {:>14.1f} {:>16.3f}\n", "Embree", r.triangles, 1, m / r.embree1,
             r.embreeBytesPerTriangle, r.ratio1());
  fmt::print("{:<10} {:>10} {:>8} {:>14.3f} {:>14.1f} {:>16.3f}\n", "Embree", r.triangles, r.threads, m / r.embreeN,
             r.embreeBytesPerTriangle, r.ratioN());
  const HitComparison& d = r.disagreements;
  fmt::print("{} of {} rays hit; disagreements: hit/miss {}, other primitive {}, distance beyond 1e-5 relative {}; "
             "largest relative distance difference on the same primitive {:.2g}; Embree build {:.2f} s\n",
             r.hits, r.rays, d.hitMiss, d.otherPrimitive, d.distance, d.largestRelativeDistance, r.embreeBuildSeconds);
  return r;
}

// General against specialised trace pipelines, device time, same run.
std::vector<SpecialisationRow> runSpecialisation(const std::vector<DeviceSpec>& devices,
                                                 const std::filesystem::path& scenesDir, const std::atomic<bool>& cancel) {
  std::vector<std::pair<std::string, Scene>> scenes = {{"throughput scene", throughputScene()}};
  for (const char* name : {"default", "reference/point_on_axis", "reference/disk_on_axis", "reference/uniform_d65",
                           "reference/laser_532", "reference/pinhole_rect"})
    scenes.emplace_back(name, loadScene(scenesDir / (std::string(name) + ".json")));
  std::vector<SpecialisationRow> rows;
  fmt::print("\nSpecialised pipelines (device time of the trace pass)\n");
  fmt::print("{:<26} {:>10} {:>16} {:>20} {:>8}   gain of each alone (light types, choice, camera model, colour, aim, uniform tables, object types)\n",
             "scene", "beams", "general Mbeam/s", "specialised Mbeam/s", "gain");
  for (const auto& device : devices) {
    if (!device.capabilities.specialisedPipelines || !device.capabilities.deviceTimestamps) continue;
    const auto opened = Device::open(device);
    for (const auto& [name, scene] : scenes) {
      SpecialisationRow row{name, device.name(), uint64_t(1) << 23, 0.0, 0.0, {}};
      // Variants: general, each feature alone, all.
      std::vector<uint32_t> variants = {kSpecialiseNone};
      for (uint32_t feature = 1; feature < kSpecialiseAll; feature <<= 1) variants.push_back(feature);
      variants.push_back(kSpecialiseAll);
      const auto best = interleavedBest(variants.size(), kTimingRounds, [&](size_t v) {
        return timedRender(scene, *opened, row.beams, cancel,
                           [&](RenderOptions& o) { o.tracer.specialisedFeatures = variants[v]; });
      });
      row.generalSeconds = best.front().traceSeconds;
      for (size_t v = 1; v + 1 < variants.size(); ++v) row.featureSeconds.push_back(best[v].traceSeconds);
      row.specialisedSeconds = best.back().traceSeconds;
      std::string alone;
      for (double s : row.featureSeconds) alone += fmt::format(" {:.2f}", row.generalSeconds / s);
      fmt::print("{:<26} {:>10} {:>16.2f} {:>20.2f} {:>8.2f}  {}\n", name, row.beams, double(row.beams) / row.generalSeconds * 1e-6,
                 double(row.beams) / row.specialisedSeconds * 1e-6, row.generalSeconds / row.specialisedSeconds, alone);
      rows.push_back(row);
    }
  }
  return rows;
}

// Full against trimmed spectra: memory, trace and resolve time, same run.
std::vector<TrimRow> runTrim(const std::vector<DeviceSpec>& devices, const std::filesystem::path& scenesDir,
                             const std::atomic<bool>& cancel) {
  std::vector<TrimRow> rows;
  fmt::print("\nTrimmed spectra and sensor (device histogram, device times)\n");
  fmt::print("{:<28} {:>10} {:>16} {:>16} {:>18} {:>18}\n", "scene", "bins", "pixels", "histogram MiB", "trace s",
             "resolve ms");
  for (const auto& device : devices) {
    if (device.capabilities.filmInHostMemory || !device.capabilities.deviceTimestamps) continue;  // device film and times
    const auto opened = Device::open(device);
    for (const char* name : {"reference/laser_532", "reference/uniform_f11", "reference/uniform_led_b3",
                             "reference/pinhole_rect", "stress/laser_one_pixel", "default"}) {
      const Scene scene = loadScene(scenesDir / (std::string(name) + ".json"));
      TrimRow row;
      row.scene = name;
      row.deviceName = device.name();
      row.beams = uint64_t(1) << 23;
      const auto best = interleavedBest(2, kTimingRounds, [&](size_t v) {
        const bool trim = v == 1;
        RenderResult result = timedRender(scene, *opened, row.beams, cancel, [&](RenderOptions& o) {
          o.plan.trimSpectrum = trim;
          o.plan.trimPixels = trim;
        });
        const double mib = double(result.plan.film.storedPixelCount() * result.plan.film.countersPerPixel() * 8) / (1 << 20);
        (trim ? row.storedBins : row.fullBins) = result.plan.film.storedBins;
        (trim ? row.storedPixels : row.fullPixels) = result.plan.film.storedPixelCount();
        (trim ? row.trimmedMiB : row.fullMiB) = mib;
        return result;
      });
      row.fullTraceSeconds = best[0].traceSeconds;
      row.trimmedTraceSeconds = best[1].traceSeconds;
      row.fullResolveSeconds = best[0].resolveSeconds;
      row.trimmedResolveSeconds = best[1].resolveSeconds;
      fmt::print("{:<28} {:>4} -> {:<4} {:>7} -> {:<7} {:>7.2f} -> {:<6.2f} {:>8.3f} -> {:<6.3f} {:>8.2f} -> {:<6.2f}\n",
                 name, row.fullBins, row.storedBins, row.fullPixels, row.storedPixels, row.fullMiB, row.trimmedMiB, row.fullTraceSeconds, row.trimmedTraceSeconds,
                 row.fullResolveSeconds * 1e3, row.trimmedResolveSeconds * 1e3);
      rows.push_back(row);
    }
  }
  return rows;
}

// Aimed against analog sampling on reference scenes (exact answers), each
// at a beam count where its error is well inside the N^-1/2 regime.
// Batch warm-up: open the device and render a little, once with an empty
// pipeline cache file and once with the one that run saved.
std::vector<PipelineCacheRow> runPipelineCacheStudy(const std::vector<DeviceSpec>& devices,
                                                    const std::atomic<bool>& cancel) {
  std::vector<PipelineCacheRow> rows;
  const Scene scene = throughputScene();
  const auto folder = std::filesystem::temp_directory_path() / fmt::format("spectrace-bench-{}", ::getpid());
  const auto file = folder / "pipelines.bin";
  const auto firstRender = [&](const DeviceSpec& spec) {
    const auto start = std::chrono::steady_clock::now();
    {
      const auto device = Device::open(spec, PipelineCacheOptions{true, file.string()});
      RenderOptions options;
      options.beams = 4096;
      options.loop.cancel = &cancel;
      render(scene, options, *device);
    }  // closing the device saves the cache
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  bool printed = false;
  for (const auto& spec : devices) {
    if (!spec.capabilities.pipelineCache) continue;
    if (!printed) {
      fmt::print("\nBatch: time to first beam (open + 4096 beams), cold vs warm pipeline cache\n");
      fmt::print("{:<44} {:>9} {:>9} {:>11} {:>12}\n", "device", "cold s", "warm s", "cold : warm", "cache bytes");
      printed = true;
    }
    std::error_code ec;
    std::filesystem::remove_all(folder, ec);
    PipelineCacheRow row{spec.name()};
    row.coldSeconds = firstRender(spec);
    row.cacheBytes = std::filesystem::exists(file) ? std::filesystem::file_size(file) : 0;
    row.warmSeconds = firstRender(spec);
    fmt::print("{:<44} {:>9.3f} {:>9.3f} {:>11.2f} {:>12}\n", row.deviceName, row.coldSeconds, row.warmSeconds,
               row.ratio(), row.cacheBytes);
    rows.push_back(row);
  }
  std::error_code ec;
  std::filesystem::remove_all(folder, ec);
  return rows;
}

// Runs this program (/proc/self/exe) with `args`, its output discarded;
// returns its exit code (-1 if it could not start or died of a signal).
int runSelf(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  std::string self = "spectrace";
  argv.push_back(self.data());
  std::vector<std::string> copies = args;
  for (auto& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int failed = posix_spawn(&pid, "/proc/self/exe", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (failed) return -1;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

double secondsOf(const std::function<void()>& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The blackbody temperatures of the batch section's sweeps.
std::vector<int> sweepKelvins(size_t count) {
  std::vector<int> kelvins;
  for (size_t i = 0; i < count; ++i) kelvins.push_back(2000 + int(i) * 100);
  return kelvins;
}

// 64 small jobs: one `batch` process against 64 `render` processes.
std::vector<BatchProcessRow> runBatchProcesses(const std::vector<DeviceSpec>& devices,
                                               const std::filesystem::path& lampScene, const std::atomic<bool>& cancel) {
  constexpr size_t kJobs = 64;
  constexpr uint64_t kBeams = 100'000;
  const auto folder = std::filesystem::temp_directory_path() / fmt::format("spectrace-bench-batch-{}", ::getpid());
  std::filesystem::create_directories(folder);
  std::ifstream in(lampScene);
  const nlohmann::json lamp = nlohmann::json::parse(in);
  const auto kelvins = sweepKelvins(kJobs);
  {
    std::ofstream jobs(folder / "jobs.jsonl");
    jobs << nlohmann::json{{"scene", std::filesystem::absolute(lampScene).string()},
                           {"output", "batch_{index}.exr"},
                           {"beams", kBeams},
                           {"seed", 1},
                           {"sweep", {{"/lights/0/spd/blackbody_k", kelvins}}}}
                .dump()
         << "\n";
  }
  for (size_t i = 0; i < kJobs; ++i) {
    nlohmann::json scene = lamp;
    scene["lights"][0]["spd"]["blackbody_k"] = kelvins[i];
    std::ofstream(folder / fmt::format("scene_{}.json", i)) << scene.dump(2);
  }
  std::vector<BatchProcessRow> rows;
  fmt::print("\nBatch: {} jobs of {} beams, one batch process against one render process per job\n", kJobs, kBeams);
  fmt::print("{:<44} {:>11} {:>14} {:>17}\n", "device", "batch s", "separate s", "separate : batch");
  std::set<DeviceKind> done;
  for (const auto& spec : devices) {
    if (!done.insert(spec.kind()).second || cancel.load()) continue;  // the CLI picks devices by kind
    const std::string device = deviceKindName(spec.kind());
    BatchProcessRow row{spec.name(), spec.kind(), kJobs, kBeams};
    // A warm-up render, so both sides find the same pipeline and shader caches.
    runSelf({"render", (folder / "scene_0.json").string(), "-o", (folder / "warm.exr").string(), "--beams", "1000",
             "--device", device, "-q", "--no-png"});
    int failures = 0;
    row.batchSeconds = secondsOf([&] {
      failures += runSelf({"batch", (folder / "jobs.jsonl").string(), "--out-dir", (folder / "batch").string(),
                           "--device", device, "-q", "--no-png"}) != 0;
    });
    row.separateSeconds = secondsOf([&] {
      for (size_t i = 0; i < kJobs && !cancel.load(); ++i)
        failures += runSelf({"render", (folder / fmt::format("scene_{}.json", i)).string(), "-o",
                             (folder / fmt::format("separate_{}.exr", i)).string(), "--beams", std::to_string(kBeams),
                             "--seed", "1", "--device", device, "-q", "--no-png"}) != 0;
    });
    if (failures) throw std::runtime_error(fmt::format("bench: {} of the batch section's processes failed", failures));
    fmt::print("{:<44} {:>11.2f} {:>14.2f} {:>17.1f}\n", row.deviceName, row.batchSeconds, row.separateSeconds,
               row.ratio());
    rows.push_back(row);
  }
  std::error_code ec;
  std::filesystem::remove_all(folder, ec);
  return rows;
}

// 8 large jobs in one session: wall time against the traces' device time.
std::vector<BatchOverheadRow> runBatchOverhead(const std::vector<DeviceSpec>& devices,
                                               const std::filesystem::path& lampScene, const std::atomic<bool>& cancel) {
  constexpr size_t kJobs = 8;
  constexpr uint64_t kBeams = 10'000'000;
  const auto folder = std::filesystem::temp_directory_path() / fmt::format("spectrace-bench-large-{}", ::getpid());
  std::vector<BatchOverheadRow> rows;
  const Scene lamp = loadScene(lampScene);
  for (const auto& spec : devices) {
    if (!spec.capabilities.deviceTimestamps || cancel.load()) continue;  // against the traces' device time
    if (rows.empty()) {
      fmt::print("\nBatch: {} jobs of {} beams in one session, wall time against the traces' device time\n", kJobs,
                 kBeams);
      fmt::print("{:<44} {:>13} {:>15} {:>9} {:>12}\n", "device", "batch wall s", "trace device s", "overhead",
                 "allocations");
    }
    Session session(Device::open(spec));
    std::vector<RenderJob> jobs;
    for (size_t i = 0; i < kJobs; ++i) {
      RenderJob job;
      job.scene = lamp;
      job.scene.lights[0].spd = makeBlackbodySpd(sweepKelvins(kJobs)[i], 360, 830);
      job.output = folder / fmt::format("large_{}.exr", i);
      job.beams = kBeams;
      job.loop.cancel = &cancel;
      jobs.push_back(std::move(job));
    }
    // A warm-up job, so pipeline compilation stays out of the timing.
    RenderJob warm = jobs.front();
    warm.beams = 1000;
    warm.output = folder / "warm.exr";
    session.render(warm);
    BatchOverheadRow row{spec.name(), kJobs, kBeams};
    std::vector<std::shared_future<RenderResult>> results;
    row.batchWallSeconds = secondsOf([&] {
      for (const RenderJob& job : jobs) results.push_back(session.renderOverlapped(job));
      session.finishWriting();
    });
    for (const auto& r : results) row.traceDeviceSeconds += r.get().traceDeviceSeconds;
    row.bufferAllocations = session.device().bufferAllocations();
    fmt::print("{:<44} {:>13.2f} {:>15.2f} {:>+8.1f}% {:>12}\n", row.deviceName, row.batchWallSeconds,
               row.traceDeviceSeconds, 100.0 * row.overhead(), row.bufferAllocations);
    rows.push_back(row);
  }
  std::error_code ec;
  std::filesystem::remove_all(folder, ec);
  return rows;
}

std::vector<AimRow> runAimStudy(const std::vector<DeviceSpec>& devices, const std::filesystem::path& dir) {
  struct Case {
    const char* scene;
    uint64_t aimedBeams, analogBeams;
  };
  const Case cases[] = {{"pinhole_small", 2'000'000, 100'000'000}, {"pinhole_rect", 2'000'000, 20'000'000},
                        {"point_off_axis", 4'000'000, 4'000'000},    {"disk_off_axis", 4'000'000, 4'000'000},
                        {"laser_532", 4'000'000, 4'000'000}};
  std::vector<AimRow> rows;
  fmt::print("\nAimed against analog sampling (error against the exact answer)\n");
  fmt::print("{:<15} {:<6} {:<7} {:>11} {:>9} {:>12} {:>16} {:>10} {:>10} {:>8}\n", "scene", "device", "sampling",
             "beams", "counted", "Mbeam/s all", "Mbeam/s counted", "relRMSE", "FOM", "gain");
  for (const auto& device : devices) {
    for (const Case& c : cases) {
      AimRow row;
      for (bool aim : {true, false}) {
        SweepOptions options;
        options.scenes = {(dir / (std::string(c.scene) + ".json")).string()};
        options.beamCounts = {aim ? c.aimedBeams : c.analogBeams};
        options.plan.aim = aim;
        (aim ? row.aimed : row.analog) = runErrorSweep({device}, options).front();
      }
      for (const SweepRow* r : {&row.aimed, &row.analog})
        fmt::print("{:<15} {:<6} {:<7} {:>11} {:>8.3g}% {:>12.2f} {:>16.3g} {:>10.3g} {:>10.4g} {:>8}\n", r->scene,
                   deviceKindName(r->device), r->aimed ? "aimed" : "analog", r->beams, 100.0 * double(r->hits) / double(r->beams),
                   double(r->beams) / r->wallSeconds * 1e-6, double(r->hits) / r->wallSeconds * 1e-6,
                   r->metrics.relRmse, r->fom, r->aimed ? fmt::format("{:.3g}", row.fomGain()) : "");
      rows.push_back(row);
    }
  }
  return rows;
}

std::vector<OpticsRow> runOptics(const std::vector<DeviceSpec>& devices, const std::filesystem::path& scenesDir,
                                 bool objects, bool matched, const std::atomic<bool>& cancel) {
  fmt::print("\nOptics: scenes with objects{} (relMSE from two seeds)\n",
             matched ? ", and the scenes matched with pbrt-v4 (fom_*: Y over the square's interior)" : "");
  fmt::print("{:<18} {:<12} {:<6} {:>10} {:>10} {:>9} {:>9} {:>10} {:>10}\n", "scene", "variant", "device", "primitives",
             "beams", "trace s", "Mbeam/s", "relMSE", "FOM");
  OpticsBenchOptions options;
  options.scenesDir = scenesDir;
  options.cancel = &cancel;
  options.objects = objects;
  options.matched = matched;
  options.onRow = [](const OpticsRow& r) {
    fmt::print("{:<18} {:<12} {:<6} {:>10} {:>10} {:>9.3f} {:>9.2f} {:>10.3g} {:>10.4g}\n", r.scene, r.variant,
               deviceKindName(r.device), r.primitives, r.beams, r.traceSeconds, r.beamsPerSecond() * 1e-6, r.relMse, r.fom);
  };
  return runOpticsBench(devices, options);
}

std::vector<std::string> referenceScenes(const std::filesystem::path& dir) {
  // A fixed list, so the benchmark's rows are comparable between runs.
  std::vector<std::string> scenes;
  for (const char* name : {"point_on_axis", "point_off_axis", "disk_on_axis", "disk_off_axis", "furnace", "uniform_d65",
                           "uniform_a", "uniform_f2", "uniform_f11", "uniform_led_b3", "laser_532", "pinhole_rect",
                           "pinhole_small"})
    scenes.push_back((dir / (std::string(name) + ".json")).string());
  return scenes;
}

}  // namespace

std::string benchSectionNames() {
  std::string names;
  for (const BenchSection& s : kBenchSections) names += (names.empty() ? "" : ", ") + std::string(s.name);
  return names;
}

void selectBenchSections(BenchCommand& command, const std::string& list) {
  for (const BenchSection& s : kBenchSections) command.*s.run = false;
  std::stringstream items(list);
  for (std::string item; std::getline(items, item, ',');) {
    const auto it = std::find_if(std::begin(kBenchSections), std::end(kBenchSections),
                                 [&](const BenchSection& s) { return s.name == item; });
    if (it == std::end(kBenchSections))
      throw UsageError(fmt::format("--only {}: unknown section '{}' ({})", list, item, benchSectionNames()));
    command.*it->run = true;
  }
}

int runBench(const BenchCommand& command, const std::atomic<bool>& cancel) {
  BenchReport report;
  report.date = utcNow();
  report.machine = machineDescription();
  report.devices = listDevices(command.devices);
  if (report.devices.empty()) throw std::runtime_error("bench: no device matches --device " + command.devices);
  if (command.throughput) report.throughput = runThroughput(command, report.devices, cancel);

  std::filesystem::path dir = command.scenesDir;
  if (dir.empty()) {
    dir = "scenes/reference";
    if (!std::filesystem::exists(dir)) dir = std::filesystem::path(SPECTRACE_SOURCE_DIR) / "scenes/reference";
  }
  if (command.specialisation) {
    report.specialisation = runSpecialisation(report.devices, dir.parent_path(), cancel);
    report.trim = runTrim(report.devices, dir.parent_path(), cancel);
  }
  if (command.aim) report.aim = runAimStudy(report.devices, dir);
  if (command.optics || command.fom)
    report.optics = runOptics(report.devices, dir.parent_path(), command.optics, command.fom, cancel);
  if (command.batch) {
    const auto lampScene = dir.parent_path() / "batch" / "lamp.json";
    report.batchProcesses = runBatchProcesses(report.devices, lampScene, cancel);
    report.batchOverhead = runBatchOverhead(report.devices, lampScene, cancel);
  }
  if (command.batch && command.pipelineCache) report.pipelineCache = runPipelineCacheStudy(report.devices, cancel);
  if (command.profile) report.profile = runProfile(command, report.devices, cancel);
  if (command.profile && !cancel.load()) report.objectsProfile = runObjectsProfile(command, report.devices, cancel);
  if (command.ceiling) report.ceiling = runCeiling(command, report.devices, cancel);
  if (command.ceiling) {
    // The million-triangle mesh, and smaller ones that fit in the caches,
    // which tell the walk's own instructions from its waits on memory; a
    // quick check (--profile-beams under 2^20) the smallest alone.
    const bool full = command.profileBeams >= (uint64_t(1) << 20);
    for (uint64_t triangles : {uint64_t(1'000), uint64_t(10'000), uint64_t(100'000), uint64_t(1'000'000)}) {
      if (cancel.load() || (!full && triangles > 1'000)) break;
      report.rayCeiling.push_back(runRayCeilingSection(command, triangles, cancel));
    }
  }
  if (command.sweep) {
    SweepOptions options;
    options.scenes = referenceScenes(dir);
    for (double d = command.minDecade; d <= command.maxDecade + 1e-9; d += 1.0)
      options.beamCounts.push_back(uint64_t(std::llround(std::pow(10.0, d))));
    fmt::print("\nError sweep: {} reference scenes, {} to {} beams\n", options.scenes.size(), options.beamCounts.front(),
               options.beamCounts.back());
    fmt::print("{:<16} {:<6} {:>11} {:>9} {:>10} {:>10} {:>10} {:>8} {:>10}\n", "scene", "device", "beams", "wall s",
               "relRMSE", "estimated", "bias", "ΔE mean", "FOM");
    options.onRow = [](const SweepRow& r) {
      fmt::print("{:<16} {:<6} {:>11} {:>9.4f} {:>10.3g} {:>10.3g} {:>+10.2e} {:>8.3f} {:>10.4g}\n", r.scene, deviceKindName(r.device),
                 r.beams, r.wallSeconds, r.metrics.relRmse, r.metrics.estimatedRelRmse, r.metrics.bias,
                 r.metrics.deltaE2000Mean, r.fom);
    };
    report.sweep = runErrorSweep(report.devices, options);
  }

  if (command.colour) {
    fmt::print("\nColour error from binning ({} beams per render, on {})\n", command.colourBeams, report.devices[0].name());
    fmt::print("{:<12} {:>5} {:>14} {:>14} {:>14} {:>10} {:>10} {:>10}\n", "SPD", "bins", "Δxy bins", "(expected)",
               "Δxy per beam", "noise σ", "ΔE bins", "ΔE beam");
    report.colour = runColourBinStudy(report.devices[0], command.colourBeams, [](const ColourBinRow& r) {
      fmt::print("{:<12} {:>5} {:>14.3e} {:>14.3e} {:>14.3e} {:>10.1e} {:>10.4f} {:>10.4f}\n", r.spd, r.bins,
                 r.binnedChromaticityError, r.expectedBinnedChromaticityError, r.exactChromaticityError,
                 r.chromaticitySigma, r.binnedDeltaE, r.exactDeltaE);
    });
  }

  if (command.out) {
    writeBenchReport(*command.out, report);
    fmt::print("\nwrote {}/benchmarks.md and {}/bench/\n", command.out->string(), command.out->string());
  }
  return 0;
}

}  // namespace spectrace::cli
