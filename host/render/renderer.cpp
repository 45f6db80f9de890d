#include "render/renderer.h"

#include <chrono>
#include <fmt/format.h>
#include <memory>
#include <stdexcept>
#include <thread>

#include "colour/colour.h"
#include "cpu/reference_tracer.h"
#include "cpu/resolve_cpu.h"
#include "render/gpu_tracer.h"
#include "vulkan/context.h"

namespace spectrace {

DeviceChoice parseDeviceChoice(const std::string& text) {
  if (text == "auto") return DeviceChoice::Auto;
  if (text == "gpu") return DeviceChoice::Gpu;
  if (text == "cpu") return DeviceChoice::Cpu;
  throw std::invalid_argument(fmt::format("unknown device '{}': use auto, gpu or cpu", text));
}

ResolveParameters resolveParametersFor(const Scene& scene, const TracePlan& plan, uint64_t beams) {
  ResolveParameters parameters;
  const Observer& observer = observerByName(scene.observer);
  parameters.binWeights = binAveragedCmf(observer, plan.lambdaMinNm, plan.lambdaMaxNm, int(plan.bins));
  for (auto& w : parameters.binWeights)
    for (double& v : w) v *= kLumensPerWatt;
  parameters.xyzToRgb = xyzToLinearSrgb();
  parameters.irradiancePerCount = beams > 0 ? plan.irradiancePerCount(beams) : 0.0;
  return parameters;
}

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Picks the Vulkan device for --device auto/gpu. Returns nullptr (auto only)
// when there is no usable Vulkan device, so the caller falls back to the CPU.
std::unique_ptr<vk_util::Context> openVulkan(DeviceChoice choice, const RenderOptions& options) {
  std::vector<vk_util::DeviceInfo> devices;
  std::string why;
  try {
    devices = vk_util::enumerateDevices();
    if (auto index = vk_util::preferredDevice(devices)) return vk_util::Context::create(devices[*index].index);
    why = devices.empty() ? "no Vulkan device was found" : "no Vulkan device is usable:\n" + vk_util::describeDevices(devices);
  } catch (const vk_util::VulkanError& e) {
    why = e.what();
  }
  if (choice == DeviceChoice::Gpu) throw vk_util::VulkanError("--device gpu: " + why);
  if (options.log) options.log("auto: " + why + "; using the CPU reference");
  return nullptr;
}

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
  const auto start = Clock::now();
  RenderResult result;
  result.plan = buildTracePlan(scene, options.seed, options.plan);
  const TracePlan& plan = result.plan;

  std::unique_ptr<vk_util::Context> vulkan;
  std::unique_ptr<GpuTracer> gpu;
  if (options.device != DeviceChoice::Cpu) vulkan = openVulkan(options.device, options);
  if (vulkan) {
    gpu = std::make_unique<GpuTracer>(*vulkan, plan, options.workgroupSize, options.specialisedFeatures);
    result.deviceKind = "gpu";
    result.deviceName = vulkan->info().name;
  } else {
    const unsigned threads = options.cpuThreads ? options.cpuThreads : std::max(1u, std::thread::hardware_concurrency());
    result.deviceKind = "cpu";
    result.deviceName = fmt::format("CPU reference, {} threads", threads);
    result.histogram = plan.emptyHistogram();
  }
  if (options.log)
    options.log(fmt::format("device: {} ({})", result.deviceName, result.deviceKind == "gpu" ? "Vulkan" : "C++"));

  auto resolveNow = [&](uint64_t beams) {
    const ResolveParameters parameters = resolveParametersFor(scene, plan, beams);
    if (gpu) return gpu->resolve(parameters, &result.resolveDeviceSeconds);
    return resolveOnCpu(result.histogram, parameters);
  };

  auto lastCheckpoint = Clock::now();
  const auto traceStart = Clock::now();
  uint64_t done = 0;
  while (done < options.beams) {
    if (options.cancel && options.cancel->load()) break;
    const uint64_t batch = nextBatch(done, secondsSince(traceStart), options.beams - done, options);
    if (gpu) {
      result.traceDeviceSeconds += gpu->trace(options.firstBeam + done, batch);
      done += batch;
    } else {
      CpuTraceOptions cpu;
      cpu.threads = options.cpuThreads;
      cpu.cancel = options.cancel;
      done += traceOnCpu(plan, options.firstBeam + done, batch, result.histogram, cpu);
    }
    if (options.onProgress) options.onProgress(done, options.beams);
    if (options.onCheckpoint && options.checkpointSeconds > 0.0 && done < options.beams &&
        secondsSince(lastCheckpoint) >= options.checkpointSeconds) {
      options.onCheckpoint(resolveNow(done), done, result.deviceLabel());
      lastCheckpoint = Clock::now();
    }
  }
  result.beamsTraced = done;
  result.traceWallSeconds = secondsSince(traceStart);
  if (gpu) result.histogram = gpu->downloadHistogram();
  result.image = resolveNow(done);
  result.wallSeconds = secondsSince(start);
  return result;
}

}  // namespace spectrace
