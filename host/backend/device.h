#pragma once
// Devices a tracer can run on: Vulkan devices (a GPU, or lavapipe) and the
// CPU reference. A Device is opened once and makes tracers for scenes.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "backend/cpu_code.h"
#include "backend/specialisation.h"
#include "backend/tracer.h"
#include "compile/compile_scene.h"

namespace spectrace {
namespace vk_util {
class Context;
}
class TracerBufferPool;

enum class DeviceChoice { Auto, Gpu, Cpu };
DeviceChoice parseDeviceChoice(const std::string& text);  // throws std::invalid_argument

// How a tracer is built; each backend reads its part.
struct TracerOptions {
  uint32_t workgroupSize = 64;                     // Vulkan
  uint32_t specialisedFeatures = kSpecialiseAll;   // Vulkan: SpecialisedFeature bits
  unsigned cpuThreads = 0;                         // CPU: 0 = all hardware threads
  std::optional<CpuCode> cpuCode;                  // CPU: none = the fastest this processor runs
  uint32_t profileStage = device::kProfileStageFull;  // bench only: the kernel cut after a stage (shaders/profile.h)
};

// A device to open: a Vulkan device by index, or the CPU reference.
struct DeviceSpec {
  DeviceKind kind = DeviceKind::Cpu;
  std::string name;
  int vulkanIndex = -1;
};

// The persistent Vulkan pipeline cache of an opened device.
struct PipelineCacheOptions {
  bool enabled = true;
  // "" : $XDG_CACHE_HOME/spectrace/pipelines-<device UUID>-<driverVersion>.bin
  // (or $HOME/.cache/...; no file if neither is set).
  std::string path;
};

// Every usable Vulkan device, then the CPU reference, filtered by a
// comma-separated list of "gpu", "cpu" or device names (empty: all).
std::vector<DeviceSpec> listDevices(const std::string& filter = "");

class Device {
 public:
  // auto: a hardware GPU if any, else lavapipe, else the CPU reference
  // (saying why through `log`); gpu: a Vulkan device or VulkanError.
  // Vulkan devices load their pipeline cache as `cache` says; notices about
  // it (an ignored file, a failed save) go to `log`.
  static std::unique_ptr<Device> open(DeviceChoice choice, const std::function<void(const std::string&)>& log = {},
                                      const PipelineCacheOptions& cache = {});
  static std::unique_ptr<Device> open(const DeviceSpec& spec, const PipelineCacheOptions& cache = {},
                                      const std::function<void(const std::string&)>& log = {});
  ~Device();

  DeviceKind kind() const { return vulkan_ ? DeviceKind::Vulkan : DeviceKind::Cpu; }
  std::unique_ptr<Tracer> makeTracer(const CompiledScene& plan, const TracerOptions& options = {}) const;
  // Writes the pipeline cache to its file if it changed (also done on close).
  void savePipelineCache() const;
  // The pipeline cache file in use ("" : none, or the CPU reference).
  std::string pipelineCachePath() const;
  // Device buffers allocated so far for tracers: they are kept and reused by
  // the next tracer when its shapes fit (0 on the CPU reference).
  uint64_t bufferAllocations() const;

 private:
  explicit Device(std::unique_ptr<vk_util::Context> vulkan);
  std::unique_ptr<vk_util::Context> vulkan_;  // null for the CPU reference
  std::shared_ptr<TracerBufferPool> buffers_;  // shared by its Vulkan tracers
};

}  // namespace spectrace
