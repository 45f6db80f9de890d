#include "backend/device.h"

#include <fmt/format.h>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "backend/cpu_tracer.h"
#include "backend/vulkan_tracer.h"
#include "vulkan/context.h"

namespace spectrace {

const char* deviceKindName(DeviceKind kind) { return kind == DeviceKind::Vulkan ? "gpu" : "cpu"; }

void Tracer::merge(const SpectralHistogram& other) {
  SpectralHistogram film = download();
  film.merge(other);
  upload(film);
}

DeviceChoice parseDeviceChoice(const std::string& text) {
  if (text == "auto") return DeviceChoice::Auto;
  if (text == "gpu") return DeviceChoice::Gpu;
  if (text == "cpu") return DeviceChoice::Cpu;
  throw std::invalid_argument(fmt::format("unknown device '{}': use auto, gpu or cpu", text));
}

std::vector<DeviceSpec> listDevices(const std::string& filter) {
  std::vector<std::string> wanted;
  std::stringstream list(filter);
  for (std::string item; std::getline(list, item, ',');)
    if (!item.empty()) wanted.push_back(item);
  auto accepted = [&](const DeviceSpec& d) {
    if (wanted.empty()) return true;
    for (const auto& w : wanted)
      if (w == deviceKindName(d.kind) || w == d.name) return true;
    return false;
  };
  std::vector<DeviceSpec> devices;
  try {
    for (const auto& info : vk_util::enumerateDevices()) {
      if (!info.missingFeatures().empty()) continue;
      DeviceSpec d{DeviceKind::Vulkan, info.name, int(info.index)};
      if (accepted(d)) devices.push_back(d);
    }
  } catch (const vk_util::VulkanError&) {
    // No Vulkan: the CPU reference alone.
  }
  DeviceSpec cpu{DeviceKind::Cpu,
                 fmt::format("CPU reference, {} threads, {}", std::max(1u, std::thread::hardware_concurrency()),
                             cpuCodeName(fastestCpuCode())),
                 -1};
  if (accepted(cpu)) devices.push_back(cpu);
  return devices;
}

Device::Device(std::unique_ptr<vk_util::Context> vulkan)
    : vulkan_(std::move(vulkan)), buffers_(std::make_shared<TracerBufferPool>()) {}
// The pooled buffers go before the context they were made on.
Device::~Device() { buffers_.reset(); }

namespace {

std::unique_ptr<vk_util::Context> withPipelineCache(std::unique_ptr<vk_util::Context> context,
                                                    const PipelineCacheOptions& cache,
                                                    const std::function<void(const std::string&)>& log) {
  context->openPipelineCache(cache.enabled ? (cache.path.empty() ? context->defaultPipelineCachePath() : cache.path) : "",
                             log);
  return context;
}

}  // namespace

std::unique_ptr<Device> Device::open(DeviceChoice choice, const std::function<void(const std::string&)>& log,
                                     const PipelineCacheOptions& cache) {
  if (choice == DeviceChoice::Cpu) return std::unique_ptr<Device>(new Device(nullptr));
  std::string why;
  try {
    const auto devices = vk_util::enumerateDevices();
    if (auto index = vk_util::preferredDevice(devices))
      return std::unique_ptr<Device>(
          new Device(withPipelineCache(vk_util::Context::create(devices[*index].index), cache, log)));
    why = devices.empty() ? "no Vulkan device was found" : "no Vulkan device is usable:\n" + vk_util::describeDevices(devices);
  } catch (const vk_util::VulkanError& e) {
    why = e.what();
  }
  if (choice == DeviceChoice::Gpu) throw vk_util::VulkanError("--device gpu: " + why);
  if (log) log("auto: " + why + "; using the CPU reference");
  return std::unique_ptr<Device>(new Device(nullptr));
}

std::unique_ptr<Device> Device::open(const DeviceSpec& spec, const PipelineCacheOptions& cache,
                                     const std::function<void(const std::string&)>& log) {
  if (spec.kind == DeviceKind::Cpu) return std::unique_ptr<Device>(new Device(nullptr));
  return std::unique_ptr<Device>(
      new Device(withPipelineCache(vk_util::Context::create(uint32_t(spec.vulkanIndex)), cache, log)));
}

void Device::savePipelineCache() const {
  if (vulkan_) vulkan_->savePipelineCache();
}

std::string Device::pipelineCachePath() const { return vulkan_ ? vulkan_->pipelineCachePath() : ""; }

uint64_t Device::bufferAllocations() const { return buffers_->allocations(); }

std::unique_ptr<Tracer> Device::makeTracer(const CompiledScene& plan, const TracerOptions& options) const {
  if (vulkan_)
    return std::make_unique<VulkanTracer>(*vulkan_, plan, options.workgroupSize, options.specialisedFeatures, buffers_,
                                          options.profileStage);
  return std::make_unique<CpuTracer>(plan, options.cpuThreads, options.profileStage,
                                     options.cpuCode.value_or(fastestCpuCode()));
}

}  // namespace spectrace
