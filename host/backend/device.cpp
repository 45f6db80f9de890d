#include "backend/device.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "backend/cpu_device.h"
#include "backend/vulkan_device.h"

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

namespace {

// Every Vulkan device the loader reports, usable or not; none without a
// loader.
std::vector<vk_util::DeviceInfo> vulkanDevices() {
  try {
    return vk_util::enumerateDevices();
  } catch (const vk_util::VulkanError&) {
    return {};
  }
}

}  // namespace

std::vector<DeviceSpec> listDevices(const std::string& filter) {
  std::vector<std::string> wanted;
  std::stringstream list(filter);
  for (std::string item; std::getline(list, item, ',');)
    if (!item.empty()) wanted.push_back(item);
  auto accepted = [&](const DeviceSpec& d) {
    if (wanted.empty()) return true;
    for (const auto& w : wanted)
      if (w == deviceKindName(d.kind()) || w == d.name()) return true;
    return false;
  };
  std::vector<DeviceSpec> devices;
  for (const auto& info : vulkanDevices()) {
    DeviceSpec d{vulkanCapabilities(info), int(info.index)};
    if (d.capabilities.unusableBecause.empty() && accepted(d)) devices.push_back(d);
  }
  DeviceSpec cpu{CpuDevice::referenceCapabilities(), -1};
  if (accepted(cpu)) devices.push_back(cpu);
  return devices;
}

std::string describeDevices() {
  std::vector<vk_util::DeviceInfo> devices;
  try {
    devices = vk_util::enumerateDevices();
  } catch (const vk_util::VulkanError& e) {
    return fmt::format("No Vulkan: {}\n\n--device auto uses the CPU reference.\n", e.what());
  }
  std::string text = vk_util::describeDevices(devices);
  if (auto index = vk_util::preferredDevice(devices)) {
    const auto& chosen = devices[*index];
    if (chosen.isHardware())
      text += fmt::format("\n--device auto and --device gpu use: {}\n", chosen.name);
    else
      text += fmt::format("\n--device gpu uses: {} (a CPU implementation of Vulkan).\n--device auto uses the CPU "
                          "reference, faster than it on the same cores.\n",
                          chosen.name);
  } else {
    text += "\nNo usable Vulkan device: --device auto uses the CPU reference.\n";
  }
  return text;
}

std::string describeDevicesJson() {
  nlohmann::json out = nlohmann::json::array();
  const std::vector<vk_util::DeviceInfo> devices = vulkanDevices();
  const auto preferred = vk_util::preferredDevice(devices);
  const bool autoTakesGpu = preferred && devices[*preferred].isHardware();
  for (size_t i = 0; i < devices.size(); ++i) {
    const vk_util::DeviceInfo& d = devices[i];
    const bool chosen = preferred == i;
    out.push_back({
        {"index", d.index},
        {"name", d.name},
        {"kind", "gpu"},
        {"type", vk::to_string(d.type)},
        {"hardware", d.isHardware()},
        {"api_version", fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(d.apiVersion), VK_API_VERSION_MINOR(d.apiVersion),
                                    VK_API_VERSION_PATCH(d.apiVersion))},
        {"driver", d.driverName},
        {"driver_info", d.driverInfo},
        {"usable", d.missingFeatures().empty()},
        {"missing", d.missingFeatures()},
        {"used_by_device_gpu", chosen},
        {"used_by_device_auto", chosen && autoTakesGpu},
        {"limits",
         {{"maxStorageBufferRange", d.maxStorageBufferRange},
          {"maxMemoryAllocationSize", d.maxMemoryAllocationSize},
          {"deviceLocalHeapBytes", d.deviceLocalHeapBytes},
          {"maxComputeWorkGroupCount", d.maxComputeWorkGroupCount},
          {"maxComputeWorkGroupInvocations", d.maxComputeWorkGroupInvocations},
          {"maxPushConstantsSize", d.maxPushConstantsSize},
          {"maxPerStageDescriptorStorageBuffers", d.maxPerStageDescriptorStorageBuffers},
          {"maxUniformBufferRange", d.maxUniformBufferRange},
          {"timestampPeriodNs", d.timestampPeriodNs},
          {"timestamps", d.timestampsSupported},
          {"shaderInt64", d.shaderInt64},
          {"shaderFloat64", d.shaderFloat64},
          {"shaderBufferInt64Atomics", d.int64Atomics},
          {"scalarBlockLayout", d.scalarBlockLayout}}},
    });
  }
  const DeviceCapabilities cpu = CpuDevice::referenceCapabilities();
  out.push_back({{"name", cpu.name},
                 {"kind", "cpu"},
                 {"type", "CPU reference"},
                 {"hardware", false},
                 {"usable", true},
                 {"missing", ""},
                 {"used_by_device_gpu", false},
                 {"used_by_device_auto", !autoTakesGpu}});
  return out.dump();
}

std::unique_ptr<Device> Device::open(DeviceChoice choice, const std::function<void(const std::string&)>& log,
                                     const PipelineCacheOptions& cache) {
  if (choice == DeviceChoice::Cpu) return std::make_unique<CpuDevice>();
  std::string why;
  try {
    const auto devices = vk_util::enumerateDevices();
    const auto index = vk_util::preferredDevice(devices);
    // A CPU implementation of Vulkan (lavapipe) runs the kernel 1.6 to 4.5
    // times slower than the CPU reference on the same cores, so auto takes
    // it only when asked by name (--device gpu).
    if (index && (choice == DeviceChoice::Gpu || devices[*index].isHardware()))
      return std::make_unique<VulkanDevice>(vk_util::Context::create(devices[*index].index), cache, log);
    if (index)
      why = fmt::format("no hardware GPU (the Vulkan device {} runs on the CPU, slower than the reference; "
                        "--device gpu uses it)",
                        devices[*index].name);
    else
      why = devices.empty() ? "no Vulkan device was found"
                            : "no Vulkan device is usable:\n" + vk_util::describeDevices(devices);
  } catch (const vk_util::VulkanError& e) {
    why = e.what();
  }
  if (choice == DeviceChoice::Gpu) throw vk_util::VulkanError("--device gpu: " + why);
  if (log) log("auto: " + why + "; using the CPU reference");
  return std::make_unique<CpuDevice>();
}

std::unique_ptr<Device> Device::open(const DeviceSpec& spec, const PipelineCacheOptions& cache,
                                     const std::function<void(const std::string&)>& log) {
  if (spec.kind() == DeviceKind::Cpu) return std::make_unique<CpuDevice>();
  return std::make_unique<VulkanDevice>(vk_util::Context::create(uint32_t(spec.vulkanIndex)), cache, log);
}

std::unique_ptr<Device> Device::openForLocalRank(DeviceChoice choice, int localRank, const PipelineCacheOptions& cache,
                                                 const std::function<void(const std::string&)>& log) {
  if (choice != DeviceChoice::Cpu) {
    std::vector<DeviceSpec> gpus;
    for (const DeviceSpec& spec : listDevices())
      if (spec.capabilities.hardwareGpu) gpus.push_back(spec);
    if (!gpus.empty()) return open(gpus[size_t(localRank) % gpus.size()], cache, log);
  }
  // No hardware GPU (or no Vulkan loader): open says so (gpu) or falls back (auto).
  return open(choice, log, cache);
}

}  // namespace spectrace
