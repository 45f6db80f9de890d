#pragma once
// Devices a tracer can run on, behind one interface: the CPU reference
// (cpu_device.cpp) and Vulkan devices, a GPU or lavapipe
// (vulkan_device.cpp). Everything outside host/backend reaches a device
// through Device and what it says of itself (DeviceCapabilities); devices
// are listed in one place (listDevices) and opened once.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "backend/ceiling.h"
#include "backend/cpu_code.h"
#include "backend/specialisation.h"
#include "backend/tracer.h"
#include "compile/compile_scene.h"

namespace spectrace {

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

// What a device is and can do, as its callers need to know it; queried
// from the device (Vulkan's limits) when devices are listed.
struct DeviceCapabilities {
  DeviceKind kind = DeviceKind::Cpu;
  std::string name;             // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)", "CPU reference, 2 threads, x86-64-v3"
  bool reference = false;       // the exact CPU reference every device is checked against
  bool hardwareGpu = false;     // a GPU, not a CPU implementation of Vulkan (lavapipe) nor the reference
  bool deviceTimestamps = false;      // tracers report device time of their passes
  bool specialisedPipelines = false;  // trace pipelines can be specialised to a scene (TracerOptions)
  bool pipelineCache = false;         // compiled pipelines are kept in a file between runs
  bool filmInHostMemory = false;      // the film's counters are held in host memory while tracing
  std::string unusableBecause;  // "": spectrace can run on it; otherwise what it lacks
};

// A device to open: one of listDevices().
struct DeviceSpec {
  DeviceCapabilities capabilities;
  int vulkanIndex = -1;  // position among the Vulkan devices (backend use only)
  DeviceKind kind() const { return capabilities.kind; }
  const std::string& name() const { return capabilities.name; }
};

// The persistent Vulkan pipeline cache of an opened device.
struct PipelineCacheOptions {
  bool enabled = true;
  // "" : $XDG_CACHE_HOME/spectrace/pipelines-<device UUID>-<driverVersion>.bin
  // (or $HOME/.cache/...; no file if neither is set).
  std::string path;
};

// Every usable device, Vulkan devices first, then the CPU reference,
// filtered by a comma-separated list of "gpu", "cpu" or device names
// (empty: all). The one enumeration of devices.
std::vector<DeviceSpec> listDevices(const std::string& filter = "");
// `spectrace devices`: every Vulkan device with its limits and whether it
// is usable, and what --device auto and gpu pick.
std::string describeDevices();
// The same as JSON, for programs (the Python module's devices()): an array
// with one object for each Vulkan device (index, name, type, kind "gpu",
// api_version, driver, usable, missing, limits, and which of --device auto
// and gpu pick it) and one for the CPU reference (kind "cpu").
std::string describeDevicesJson();

class Device {
 public:
  // auto: a hardware GPU if any, else lavapipe, else the CPU reference
  // (saying why through `log`); gpu: a Vulkan device or an error.
  // Vulkan devices load their pipeline cache as `cache` says; notices about
  // it (an ignored file, a failed save) go to `log`.
  static std::unique_ptr<Device> open(DeviceChoice choice, const std::function<void(const std::string&)>& log = {},
                                      const PipelineCacheOptions& cache = {});
  static std::unique_ptr<Device> open(const DeviceSpec& spec, const PipelineCacheOptions& cache = {},
                                      const std::function<void(const std::string&)>& log = {});
  // The device of one of several processes on a node (MPI ranks): the
  // hardware GPUs in turn by `localRank`, else what open(choice) picks.
  static std::unique_ptr<Device> openForLocalRank(DeviceChoice choice, int localRank, const PipelineCacheOptions& cache,
                                                  const std::function<void(const std::string&)>& log = {});
  virtual ~Device() = default;

  virtual const DeviceCapabilities& capabilities() const = 0;
  DeviceKind kind() const { return capabilities().kind; }
  const std::string& name() const { return capabilities().name; }

  virtual std::unique_ptr<Tracer> makeTracer(const CompiledScene& plan, const TracerOptions& options = {}) const = 0;
  // The bench's ceiling kernel (backend/ceiling.h) on this device; `threads`
  // for the CPU reference (0: all).
  virtual CeilingResult traceCeiling(const CeilingScene& scene, uint64_t beams, unsigned threads = 0) const = 0;

  // Writes the pipeline cache to its file if it changed (also done on close).
  virtual void savePipelineCache() const {}
  // The pipeline cache file in use ("": none).
  virtual std::string pipelineCachePath() const { return ""; }
  // Device buffers allocated so far for tracers: they are kept and reused by
  // the next tracer when its shapes fit (0 without a buffer pool).
  virtual uint64_t bufferAllocations() const { return 0; }
};

}  // namespace spectrace
