#pragma once
// Vulkan instance + device for spectrace's compute work. One Context per
// process is the norm; everything else (Buffer, ComputePipeline,
// TimestampQueries) borrows it and must not outlive it.
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <vulkan/vulkan_raii.hpp>

namespace spectrace::vk_util {

// Every failure in this module is reported as a VulkanError whose message
// names what failed and why.
struct VulkanError : std::runtime_error {
  using runtime_error::runtime_error;
};

// What spectrace needs to know about one physical device, gathered without
// creating a logical device.
struct DeviceInfo {
  uint32_t index = 0;  // position in vkEnumeratePhysicalDevices
  std::string name, driverName, driverInfo;
  vk::PhysicalDeviceType type = vk::PhysicalDeviceType::eOther;
  uint32_t apiVersion = 0;
  uint64_t maxStorageBufferRange = 0, maxMemoryAllocationSize = 0, deviceLocalHeapBytes = 0;
  std::array<uint32_t, 3> maxComputeWorkGroupCount{};
  uint32_t maxComputeWorkGroupInvocations = 0, maxPushConstantsSize = 0,
           maxPerStageDescriptorStorageBuffers = 0, maxPerStageDescriptorUniformBuffers = 0;
  uint64_t maxUniformBufferRange = 0;
  float timestampPeriodNs = 0.0f;
  bool timestampsSupported = false;  // on the chosen compute queue family
  bool shaderInt64 = false, shaderFloat64 = false, int64Atomics = false, scalarBlockLayout = false;
  // Beyond the essentials: what Context and friends need to use the device.
  bool hostQueryReset = false;
  bool storageBufferArrayDynamicIndexing = false;  // uniform-but-not-constant indices into binding arrays
  uint64_t minStorageBufferOffsetAlignment = 1, minUniformBufferOffsetAlignment = 1;
  uint32_t timestampValidBits = 0;
  std::optional<uint32_t> computeQueueFamily;  // first family with compute (and timestamps if any has them)

  bool isHardware() const;  // discrete/integrated/virtual GPU (not CPU/other)
  // "" if spectrace can run on this device, otherwise each missing
  // requirement with what it is needed for, separated by "; ".
  std::string missingFeatures() const;
};

// Lists devices with a temporary instance. Throws VulkanError if there is no
// Vulkan loader or instance creation fails. An empty list is not an error.
std::vector<DeviceInfo> enumerateDevices();
// Human-readable table for `spectrace devices`: name, type, driver, API,
// limits, and either "usable" or what is missing. Marks the default choice.
std::string describeDevices(const std::vector<DeviceInfo>&);

// How to pick a device when none is named. (Extensible.)
enum class DeviceRequest {
  PreferHardware,  // hardware GPU (discrete > integrated > virtual), then CPU implementations such as lavapipe
};
// Position in `devices` of the best usable device for `request`, or nullopt
// if none is usable. Ties go to the lower index.
std::optional<size_t> preferredDevice(const std::vector<DeviceInfo>& devices,
                                      DeviceRequest request = DeviceRequest::PreferHardware);

// Validation messages received by the debug messenger (SPECTRACE_VALIDATION=1):
// `reported` of them have been thrown as VulkanError already.
struct ValidationLog {
  std::mutex mutex;
  std::vector<std::string> messages;
  size_t reported = 0;
  bool tearingDown = false;  // set by ~Context: a later message aborts
};

class Context {
 public:
  // Creates instance + device on `deviceIndex` (a DeviceInfo::index) or, if
  // not given, on preferredDevice(). Enables shaderInt64,
  // shaderBufferInt64Atomics, scalarBlockLayout, and shaderFloat64 /
  // hostQueryReset / shaderStorageBufferArrayDynamicIndexing where present.
  // Throws VulkanError with a precise reason (no loader, no devices, index
  // out of range, or why each device is not usable). SPECTRACE_VALIDATION=1
  // turns on the Khronos validation layer if it is installed (if it is
  // missing, stderr says so and validation stays off). Every validation
  // warning or error is printed to stderr and makes the next
  // submitAndWait (or throwOnValidationMessages) throw VulkanError; one still
  // unreported when the Context is destroyed, or arriving during its
  // destruction, aborts the process.
  static std::unique_ptr<Context> create(std::optional<uint32_t> deviceIndex = std::nullopt);

  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  ~Context();

  const DeviceInfo& info() const { return info_; }
  const vk::raii::Instance& instance() const { return instance_; }
  const vk::raii::PhysicalDevice& physicalDevice() const { return physicalDevice_; }
  const vk::raii::Device& device() const { return device_; }
  uint32_t computeQueueFamily() const { return queueFamily_; }
  bool hostQueryResetEnabled() const { return info_.hostQueryReset; }
  const vk::PhysicalDeviceMemoryProperties& memoryProperties() const { return memoryProperties_; }

  // Records via `record` into a fresh one-time command buffer, submits it on
  // the compute queue and waits on a fence. Serialised across threads (the
  // queue needs external synchronisation); calling it from inside `record`
  // throws VulkanError instead of deadlocking. Exceptions from `record`
  // propagate unchanged and nothing is submitted.
  void submitAndWait(const std::function<void(const vk::raii::CommandBuffer&)>& record) const;

  // Whether the validation layer is on (SPECTRACE_VALIDATION=1 and installed).
  bool validationEnabled() const { return bool(validationLog_); }
  // Throws VulkanError with the first validation message not yet reported
  // (a no-op without validation). submitAndWait calls it after each wait.
  void throwOnValidationMessages() const;

  // A memory type allowed by `typeBits` with all `wanted` flags, preferring
  // one that also has all `preferred` flags. VulkanError if none.
  uint32_t memoryTypeIndex(uint32_t typeBits, vk::MemoryPropertyFlags wanted,
                           vk::MemoryPropertyFlags preferred = {}) const;

  // Persistent pipeline cache (pipeline_cache.cpp). Creates this device's
  // VkPipelineCache, seeded from `path` when that file holds a cache whose
  // header matches this device (header length, version, vendorID, deviceID,
  // pipelineCacheUUID); a missing file is silently empty, a corrupt,
  // truncated or foreign one is ignored with "pipeline cache PATH ignored:
  // WHY" through `log`. An empty `path` gives an in-memory cache that is
  // never saved. Every ComputePipeline made afterwards uses the cache. Call
  // at most once, before making pipelines.
  void openPipelineCache(const std::string& path, std::function<void(const std::string&)> log = {});
  // Writes the cache to its file atomically (temporary file in the same
  // folder, fsync, rename) if it has a file and changed since the last load
  // or save. Failures are reported through the log, never thrown. Also done
  // by the destructor.
  void savePipelineCache() const;
  // Null (no cache) until openPipelineCache.
  const vk::raii::PipelineCache& pipelineCache() const { return pipelineCache_; }
  const std::string& pipelineCachePath() const { return pipelineCachePath_; }
  // $XDG_CACHE_HOME/spectrace/pipelines-<device UUID hex>-<driverVersion>.bin
  // ($HOME/.cache/... without XDG_CACHE_HOME; "" with neither).
  std::string defaultPipelineCachePath() const;

  // Compiled pipelines kept for the Context's life, by a key of their code,
  // bindings, push constants and specialisation constants: `make` runs only
  // for a key not seen before (ComputePipeline's business; the objects are
  // type-erased to keep this header small). Thread-safe.
  std::shared_ptr<void> sharedPipeline(const std::string& key, const std::function<std::shared_ptr<void>()>& make) const;

 private:
  Context();
  void init(std::optional<uint32_t> deviceIndex);

  // Members are destroyed in reverse declaration order: the device and its
  // children before the instance, the instance before the loader.
  vk::raii::Context loader_;
  vk::raii::Instance instance_{nullptr};
  std::unique_ptr<ValidationLog> validationLog_;  // outlives the messenger that writes to it
  vk::raii::DebugUtilsMessengerEXT messenger_{nullptr};
  vk::raii::PhysicalDevice physicalDevice_{nullptr};
  vk::raii::Device device_{nullptr};
  vk::raii::Queue queue_{nullptr};
  vk::raii::CommandPool commandPool_{nullptr};
  vk::raii::PipelineCache pipelineCache_{nullptr};
  std::string pipelineCachePath_;
  std::function<void(const std::string&)> pipelineCacheLog_;
  mutable std::vector<uint8_t> pipelineCacheSaved_;  // the file's contents as last loaded or saved
  mutable std::mutex pipelinesMutex_;
  mutable std::map<std::string, std::shared_ptr<void>> pipelines_;  // after device_: destroyed before it
  DeviceInfo info_;
  uint32_t queueFamily_ = 0;
  vk::PhysicalDeviceMemoryProperties memoryProperties_;
  mutable std::mutex submitMutex_;
  mutable std::atomic<std::thread::id> submittingThread_{};  // detects re-entry from `record`
};

// Pipeline barrier for passes on the compute queue: makes compute-shader and
// transfer writes visible to later compute-shader and transfer reads/writes
// (covers compute->compute, transfer->compute and compute->transfer).
void computeBarrier(const vk::raii::CommandBuffer&);

}  // namespace spectrace::vk_util
