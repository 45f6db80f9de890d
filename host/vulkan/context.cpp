#include "vulkan/context.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <fmt/format.h>

namespace spectrace::vk_util {
namespace {

// spectrace's shaders are compiled for Vulkan 1.2 and rely on its core
// features (scalar layout, 64-bit atomics, host query reset).
constexpr uint32_t kRequiredApiVersion = VK_API_VERSION_1_2;
constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string versionString(uint32_t v) {
  return fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(v), VK_API_VERSION_MINOR(v), VK_API_VERSION_PATCH(v));
}

std::string typeName(vk::PhysicalDeviceType t) {
  switch (t) {
    case vk::PhysicalDeviceType::eDiscreteGpu: return "discrete GPU";
    case vk::PhysicalDeviceType::eIntegratedGpu: return "integrated GPU";
    case vk::PhysicalDeviceType::eVirtualGpu: return "virtual GPU";
    case vk::PhysicalDeviceType::eCpu: return "CPU";
    default: return "other";
  }
}

std::string bytesString(uint64_t b) {
  constexpr uint64_t kMiB = 1ull << 20, kGiB = 1ull << 30;
  if (b >= kGiB && b % (kGiB / 4) == 0) return fmt::format("{:g} GiB", double(b) / double(kGiB));
  if (b >= kMiB && b % (kMiB / 4) == 0) return fmt::format("{:g} MiB", double(b) / double(kMiB));
  return fmt::format("{} B", b);
}

bool hasExtension(const std::vector<vk::ExtensionProperties>& exts, const char* name) {
  return std::any_of(exts.begin(), exts.end(),
                     [&](const vk::ExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// Prints every validation message and records it in the Context's
// ValidationLog (pUserData), which the next sync point turns into a
// VulkanError. A message while the Context is being destroyed has no sync
// point left to fail: it aborts the process, after printing.
VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  const char* level = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT     ? "error"
                      : severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT ? "warning"
                                                                                    : "info";
  std::fprintf(stderr, "spectrace: Vulkan validation %s: %s\n", level, data->pMessage);
  auto* log = static_cast<ValidationLog*>(user);
  std::lock_guard lock(log->mutex);
  log->messages.push_back(fmt::format("{}: {}", level, data->pMessage));
  if (log->tearingDown) {
    std::fprintf(stderr, "spectrace: a Vulkan validation message while the device was destroyed; aborting\n");
    std::abort();
  }
  return VK_FALSE;
}

// Creates an instance for Vulkan 1.2. With `validation`, enables the Khronos
// layer + debug utils if installed and reports on stderr if not; returns
// whether they were enabled in *validationOn.
vk::raii::Instance makeInstance(const vk::raii::Context& loader, bool validation, bool* validationOn) {
  uint32_t loaderVersion = loader.enumerateInstanceVersion();
  if (loaderVersion < kRequiredApiVersion)
    throw VulkanError(fmt::format("The Vulkan loader only supports instance version {}; spectrace needs Vulkan {}",
                                  versionString(loaderVersion), versionString(kRequiredApiVersion)));

  std::vector<const char*> layers, extensions;
  vk::InstanceCreateFlags flags;
  auto instanceExts = loader.enumerateInstanceExtensionProperties();
  // Lets the loader list portability implementations (MoltenVK) too.
  if (hasExtension(instanceExts, VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME)) {
    extensions.push_back(VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME);
    flags |= vk::InstanceCreateFlagBits::eEnumeratePortabilityKHR;
  }
  *validationOn = false;
  if (validation) {
    auto layerProps = loader.enumerateInstanceLayerProperties();
    bool haveLayer = std::any_of(layerProps.begin(), layerProps.end(), [](const vk::LayerProperties& l) {
      return std::strcmp(l.layerName, kValidationLayer) == 0;
    });
    if (!haveLayer) {
      std::fprintf(stderr,
                   "spectrace: SPECTRACE_VALIDATION=1, but the Vulkan validation layer (%s) is not installed; "
                   "continuing without validation\n",
                   kValidationLayer);
    } else if (!hasExtension(instanceExts, VK_EXT_DEBUG_UTILS_EXTENSION_NAME)) {
      std::fprintf(stderr,
                   "spectrace: SPECTRACE_VALIDATION=1, but the loader lacks %s to report messages; "
                   "continuing without validation\n",
                   VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    } else {
      layers.push_back(kValidationLayer);
      extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
      *validationOn = true;
    }
  }

  vk::ApplicationInfo app{.pApplicationName = "spectrace",
                          .applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0),
                          .pEngineName = "spectrace",
                          .engineVersion = VK_MAKE_API_VERSION(0, 0, 1, 0),
                          .apiVersion = kRequiredApiVersion};
  vk::InstanceCreateInfo info{.flags = flags,
                              .pApplicationInfo = &app,
                              .enabledLayerCount = uint32_t(layers.size()),
                              .ppEnabledLayerNames = layers.data(),
                              .enabledExtensionCount = uint32_t(extensions.size()),
                              .ppEnabledExtensionNames = extensions.data()};
  try {
    return vk::raii::Instance(loader, info);
  } catch (const vk::SystemError& e) {
    throw VulkanError(fmt::format("Creating a Vulkan {} instance failed: {}", versionString(kRequiredApiVersion),
                                  e.what()));
  }
}

// Runs `f`, turning Vulkan-Hpp's exceptions into VulkanError that says what
// was being done.
template <typename F>
auto withVulkanErrors(const char* what, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const vk::SystemError& e) {
    throw VulkanError(fmt::format("{} failed: {}", what, e.what()));
  }
}

// vk::raii::Context dlopens the loader and reports its absence as a bare
// std::runtime_error.
vk::raii::Context makeLoader() {
  try {
    return vk::raii::Context();
  } catch (const vk::SystemError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw VulkanError(fmt::format("The Vulkan loader (libvulkan.so.1) could not be loaded: {}", e.what()));
  }
}

DeviceInfo describe(const vk::raii::PhysicalDevice& pd, uint32_t index) {
  DeviceInfo d;
  d.index = index;
  const vk::PhysicalDeviceProperties props = pd.getProperties();
  d.name = props.deviceName.data();
  d.type = props.deviceType;
  d.apiVersion = props.apiVersion;
  const vk::PhysicalDeviceLimits& lim = props.limits;
  d.maxStorageBufferRange = lim.maxStorageBufferRange;
  d.maxComputeWorkGroupCount = {lim.maxComputeWorkGroupCount[0], lim.maxComputeWorkGroupCount[1],
                                lim.maxComputeWorkGroupCount[2]};
  d.maxComputeWorkGroupInvocations = lim.maxComputeWorkGroupInvocations;
  d.maxPushConstantsSize = lim.maxPushConstantsSize;
  d.maxPerStageDescriptorStorageBuffers = lim.maxPerStageDescriptorStorageBuffers;
  d.minStorageBufferOffsetAlignment = lim.minStorageBufferOffsetAlignment;
  d.maxUniformBufferRange = lim.maxUniformBufferRange;
  d.maxPerStageDescriptorUniformBuffers = lim.maxPerStageDescriptorUniformBuffers;
  d.minUniformBufferOffsetAlignment = lim.minUniformBufferOffsetAlignment;
  d.timestampPeriodNs = lim.timestampPeriod;

  // The 1.1/1.2 property and feature structs may only be chained on devices
  // that support those versions; older devices are reported as lacking 1.2.
  if (d.apiVersion >= kRequiredApiVersion) {
    auto props2 = pd.getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceVulkan11Properties,
                                    vk::PhysicalDeviceVulkan12Properties>();
    d.maxMemoryAllocationSize = props2.get<vk::PhysicalDeviceVulkan11Properties>().maxMemoryAllocationSize;
    const auto& p12 = props2.get<vk::PhysicalDeviceVulkan12Properties>();
    d.driverName = p12.driverName.data();
    d.driverInfo = p12.driverInfo.data();
    auto feats = pd.getFeatures2<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan12Features>();
    const auto& f10 = feats.get<vk::PhysicalDeviceFeatures2>().features;
    const auto& f12 = feats.get<vk::PhysicalDeviceVulkan12Features>();
    d.shaderInt64 = f10.shaderInt64;
    d.shaderFloat64 = f10.shaderFloat64;
    d.storageBufferArrayDynamicIndexing = f10.shaderStorageBufferArrayDynamicIndexing;
    d.int64Atomics = f12.shaderBufferInt64Atomics;
    d.scalarBlockLayout = f12.scalarBlockLayout;
    d.hostQueryReset = f12.hostQueryReset;
  } else {
    const vk::PhysicalDeviceFeatures f10 = pd.getFeatures();
    d.shaderInt64 = f10.shaderInt64;
    d.shaderFloat64 = f10.shaderFloat64;
  }

  const vk::PhysicalDeviceMemoryProperties mem = pd.getMemoryProperties();
  for (uint32_t h = 0; h < mem.memoryHeapCount; ++h)
    if (mem.memoryHeaps[h].flags & vk::MemoryHeapFlagBits::eDeviceLocal) d.deviceLocalHeapBytes += mem.memoryHeaps[h].size;

  // Any compute family will do; prefer one that can also write timestamps.
  const auto families = pd.getQueueFamilyProperties();
  for (uint32_t i = 0; i < families.size(); ++i) {
    if (!(families[i].queueFlags & vk::QueueFlagBits::eCompute) || families[i].queueCount == 0) continue;
    if (!d.computeQueueFamily) d.computeQueueFamily = i;
    if (families[i].timestampValidBits > 0) {
      d.computeQueueFamily = i;
      break;
    }
  }
  if (d.computeQueueFamily) d.timestampValidBits = families[*d.computeQueueFamily].timestampValidBits;
  d.timestampsSupported = d.timestampValidBits > 0 && d.timestampPeriodNs > 0.0f;
  return d;
}

int typeRank(vk::PhysicalDeviceType t) {
  switch (t) {
    case vk::PhysicalDeviceType::eDiscreteGpu: return 0;
    case vk::PhysicalDeviceType::eIntegratedGpu: return 1;
    case vk::PhysicalDeviceType::eVirtualGpu: return 2;
    case vk::PhysicalDeviceType::eCpu: return 3;
    default: return 4;
  }
}

std::string deviceLabel(const DeviceInfo& d) {
  return fmt::format("Vulkan device {} '{}' ({})", d.index, d.name, typeName(d.type));
}

}  // namespace

bool DeviceInfo::isHardware() const {
  return type == vk::PhysicalDeviceType::eDiscreteGpu || type == vk::PhysicalDeviceType::eIntegratedGpu ||
         type == vk::PhysicalDeviceType::eVirtualGpu;
}

std::string DeviceInfo::missingFeatures() const {
  std::vector<std::string> missing;
  if (apiVersion < kRequiredApiVersion)
    missing.push_back(fmt::format("Vulkan {} (the device reports {}; the shaders are built for 1.2)",
                                  versionString(kRequiredApiVersion), versionString(apiVersion)));
  if (!computeQueueFamily) missing.push_back("a compute queue (no queue family supports compute)");
  if (!shaderInt64) missing.push_back("shaderInt64 (64-bit integers in shaders, for beam indices and counts)");
  if (!int64Atomics)
    missing.push_back("shaderBufferInt64Atomics (64-bit atomic adds on storage buffers), which the histogram needs");
  if (!scalarBlockLayout)
    missing.push_back("scalarBlockLayout (tightly packed buffer structs shared with the host)");
  std::string out;
  for (const auto& m : missing) out += (out.empty() ? "" : "; ") + m;
  return out;
}

std::vector<DeviceInfo> enumerateDevices() {
  return withVulkanErrors("Listing Vulkan devices", [] {
    vk::raii::Context loader = makeLoader();
    bool validationOn = false;
    vk::raii::Instance instance = makeInstance(loader, false, &validationOn);
    std::vector<DeviceInfo> out;
    vk::raii::PhysicalDevices devices(instance);
    for (uint32_t i = 0; i < devices.size(); ++i) out.push_back(describe(devices[i], i));
    return out;
  });
}

std::optional<size_t> preferredDevice(const std::vector<DeviceInfo>& devices, DeviceRequest request) {
  std::optional<size_t> best;
  for (size_t i = 0; i < devices.size(); ++i) {
    if (!devices[i].missingFeatures().empty()) continue;
    switch (request) {
      case DeviceRequest::PreferHardware:
        if (!best || typeRank(devices[i].type) < typeRank(devices[*best].type)) best = i;
        break;
    }
  }
  return best;
}

std::string describeDevices(const std::vector<DeviceInfo>& devices) {
  if (devices.empty())
    return "No Vulkan devices found (is a Vulkan driver installed? VK_DRIVER_FILES can point the loader at one).\n";
  const auto chosen = preferredDevice(devices);
  std::string out = fmt::format("{} Vulkan device{}:\n", devices.size(), devices.size() == 1 ? "" : "s");
  for (size_t i = 0; i < devices.size(); ++i) {
    const DeviceInfo& d = devices[i];
    const auto yes = [](bool b) { return b ? "yes" : "no"; };
    out += fmt::format("[{}] {}{}\n", d.index, d.name, chosen == i ? "  (default)" : "");
    out += fmt::format("    type {}, Vulkan {}, driver {}{}\n", typeName(d.type), versionString(d.apiVersion),
                       d.driverName.empty() ? "unknown" : d.driverName,
                       d.driverInfo.empty() ? "" : " (" + d.driverInfo + ")");
    out += fmt::format("    maxStorageBufferRange {} ({} B), maxMemoryAllocationSize {}, device-local heaps {}\n",
                       bytesString(d.maxStorageBufferRange), d.maxStorageBufferRange,
                       bytesString(d.maxMemoryAllocationSize), bytesString(d.deviceLocalHeapBytes));
    out += fmt::format(
        "    maxComputeWorkGroupCount {} x {} x {}, maxComputeWorkGroupInvocations {}, maxPushConstantsSize {} B, "
        "maxPerStageDescriptorStorageBuffers {}, maxUniformBufferRange {} B\n",
        d.maxComputeWorkGroupCount[0], d.maxComputeWorkGroupCount[1], d.maxComputeWorkGroupCount[2],
        d.maxComputeWorkGroupInvocations, d.maxPushConstantsSize, d.maxPerStageDescriptorStorageBuffers,
        d.maxUniformBufferRange);
    out += fmt::format("    shaderInt64 {}, shaderFloat64 {}, shaderBufferInt64Atomics {}, scalarBlockLayout {}, ",
                       yes(d.shaderInt64), yes(d.shaderFloat64), yes(d.int64Atomics), yes(d.scalarBlockLayout));
    out += d.timestampsSupported
               ? fmt::format("timestamps yes ({} ns/tick, {} bits)\n", d.timestampPeriodNs, d.timestampValidBits)
               : std::string("timestamps no\n");
    const std::string missing = d.missingFeatures();
    out += missing.empty() ? "    usable\n" : "    NOT usable: lacks " + missing + "\n";
  }
  return out;
}

std::unique_ptr<Context> Context::create(std::optional<uint32_t> deviceIndex) {
  return withVulkanErrors("Creating the Vulkan context", [&] {
    std::unique_ptr<Context> ctx(new Context());
    ctx->init(deviceIndex);
    return ctx;
  });
}

Context::Context() : loader_(makeLoader()) {}

Context::~Context() {
  savePipelineCache();
  if (validationLog_) {
    std::lock_guard lock(validationLog_->mutex);
    if (validationLog_->messages.size() > validationLog_->reported) {
      std::fprintf(stderr, "spectrace: %zu Vulkan validation message(s) were never reported by a sync point; aborting\n",
                   validationLog_->messages.size() - validationLog_->reported);
      std::abort();
    }
    validationLog_->tearingDown = true;
  }
  // Outstanding work would be destroyed under the GPU's feet otherwise.
  try {
    if (*device_) device_.waitIdle();
  } catch (const vk::SystemError&) {
    // A lost device has nothing left to wait for; destruction goes on.
  }
}

void Context::init(std::optional<uint32_t> deviceIndex) {
  const char* env = std::getenv("SPECTRACE_VALIDATION");
  const bool wantValidation = env && std::strcmp(env, "1") == 0;
  bool validationOn = false;
  instance_ = makeInstance(loader_, wantValidation, &validationOn);
  if (validationOn) {
    validationLog_ = std::make_unique<ValidationLog>();
    using Sev = vk::DebugUtilsMessageSeverityFlagBitsEXT;
    using Type = vk::DebugUtilsMessageTypeFlagBitsEXT;
    messenger_ = vk::raii::DebugUtilsMessengerEXT(
        instance_, vk::DebugUtilsMessengerCreateInfoEXT{
                       .messageSeverity = Sev::eWarning | Sev::eError,
                       .messageType = Type::eGeneral | Type::eValidation | Type::ePerformance,
                       .pfnUserCallback = debugCallback,
                       .pUserData = validationLog_.get()});
  }

  vk::raii::PhysicalDevices physical(instance_);
  std::vector<DeviceInfo> infos;
  for (uint32_t i = 0; i < physical.size(); ++i) infos.push_back(describe(physical[i], i));
  if (infos.empty())
    throw VulkanError(
        "No Vulkan devices found: the loader found no driver (is a Vulkan ICD installed? VK_DRIVER_FILES can point "
        "the loader at one)");

  size_t chosen = 0;
  if (deviceIndex) {
    if (*deviceIndex >= infos.size()) {
      std::string list;
      for (const auto& d : infos) list += fmt::format("{}{} '{}'", list.empty() ? "" : ", ", d.index, d.name);
      throw VulkanError(fmt::format("Vulkan device index {} requested, but there {} only {} device{} ({})",
                                    *deviceIndex, infos.size() == 1 ? "is" : "are", infos.size(),
                                    infos.size() == 1 ? "" : "s", list));
    }
    chosen = *deviceIndex;
    const std::string missing = infos[chosen].missingFeatures();
    if (!missing.empty()) throw VulkanError(fmt::format("{} lacks {}", deviceLabel(infos[chosen]), missing));
  } else {
    const auto best = preferredDevice(infos);
    if (!best) {
      std::string why;
      for (const auto& d : infos) why += fmt::format("{}{} lacks {}", why.empty() ? "" : "; and ", deviceLabel(d), d.missingFeatures());
      throw VulkanError("No usable Vulkan device: " + why);
    }
    chosen = *best;
  }
  info_ = infos[chosen];
  physicalDevice_ = std::move(physical[chosen]);
  queueFamily_ = *info_.computeQueueFamily;
  memoryProperties_ = physicalDevice_.getMemoryProperties();

  const float priority = 1.0f;
  vk::DeviceQueueCreateInfo queueInfo{.queueFamilyIndex = queueFamily_, .queueCount = 1, .pQueuePriorities = &priority};
  vk::StructureChain<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan12Features> features{
      vk::PhysicalDeviceFeatures2{.features = {.shaderStorageBufferArrayDynamicIndexing = info_.storageBufferArrayDynamicIndexing,
                                                    .shaderFloat64 = info_.shaderFloat64,
                                                    .shaderInt64 = VK_TRUE}},
      vk::PhysicalDeviceVulkan12Features{.shaderBufferInt64Atomics = VK_TRUE,
                                         .scalarBlockLayout = VK_TRUE,
                                         .hostQueryReset = info_.hostQueryReset}};
  std::vector<const char*> extensions;
  // The spec requires enabling it wherever it is offered (MoltenVK).
  if (hasExtension(physicalDevice_.enumerateDeviceExtensionProperties(), "VK_KHR_portability_subset"))
    extensions.push_back("VK_KHR_portability_subset");
  vk::DeviceCreateInfo deviceInfo{.pNext = &features.get<vk::PhysicalDeviceFeatures2>(),
                                  .queueCreateInfoCount = 1,
                                  .pQueueCreateInfos = &queueInfo,
                                  .enabledExtensionCount = uint32_t(extensions.size()),
                                  .ppEnabledExtensionNames = extensions.data()};
  try {
    device_ = vk::raii::Device(physicalDevice_, deviceInfo);
  } catch (const vk::SystemError& e) {
    throw VulkanError(fmt::format("Creating a logical device on {} failed: {}", deviceLabel(info_), e.what()));
  }
  queue_ = vk::raii::Queue(device_, queueFamily_, 0);
  commandPool_ = vk::raii::CommandPool(
      device_, vk::CommandPoolCreateInfo{.flags = vk::CommandPoolCreateFlagBits::eTransient,
                                         .queueFamilyIndex = queueFamily_});
}

void Context::submitAndWait(const std::function<void(const vk::raii::CommandBuffer&)>& record) const {
  if (submittingThread_.load() == std::this_thread::get_id())
    throw VulkanError(
        "Context::submitAndWait was called from inside its own recording callback (e.g. Buffer::upload while "
        "recording); record into the command buffer you were given instead");
  std::lock_guard lock(submitMutex_);
  submittingThread_ = std::this_thread::get_id();
  struct ClearOwner {
    std::atomic<std::thread::id>& owner;
    ~ClearOwner() { owner = std::thread::id(); }
  } clearOwner{submittingThread_};

  vk::raii::CommandBuffer cmd = withVulkanErrors("Allocating a command buffer", [&] {
    vk::raii::CommandBuffers cmds(device_, vk::CommandBufferAllocateInfo{.commandPool = *commandPool_,
                                                                         .level = vk::CommandBufferLevel::ePrimary,
                                                                         .commandBufferCount = 1});
    return std::move(cmds.front());
  });
  withVulkanErrors("Beginning a command buffer", [&] {
    cmd.begin(vk::CommandBufferBeginInfo{.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  });
  record(cmd);  // its exceptions are the caller's, passed on unchanged
  withVulkanErrors("Submitting compute work", [&] {
    cmd.end();
    vk::raii::Fence fence(device_, vk::FenceCreateInfo{});
    const vk::CommandBuffer raw = *cmd;
    queue_.submit(vk::SubmitInfo{.commandBufferCount = 1, .pCommandBuffers = &raw}, *fence);
    // No timeout: long passes are legitimate, and a hung device surfaces as
    // VK_ERROR_DEVICE_LOST here.
    if (device_.waitForFences(*fence, VK_TRUE, UINT64_MAX) != vk::Result::eSuccess)
      throw VulkanError("waiting for the compute queue's fence did not succeed");
  });
  throwOnValidationMessages();
}

void Context::throwOnValidationMessages() const {
  if (!validationLog_) return;
  std::lock_guard lock(validationLog_->mutex);
  const auto& messages = validationLog_->messages;
  if (messages.size() == validationLog_->reported) return;
  const size_t first = validationLog_->reported, count = messages.size() - first;
  validationLog_->reported = messages.size();
  throw VulkanError(fmt::format("Vulkan validation (SPECTRACE_VALIDATION=1) reported {} message{}; the first: {}", count,
                                count == 1 ? "" : "s", messages[first]));
}

uint32_t Context::memoryTypeIndex(uint32_t typeBits, vk::MemoryPropertyFlags wanted,
                                  vk::MemoryPropertyFlags preferred) const {
  std::optional<uint32_t> fallback;
  for (uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i) {
    if (!(typeBits & (1u << i))) continue;
    const auto flags = memoryProperties_.memoryTypes[i].propertyFlags;
    if ((flags & wanted) != wanted) continue;
    if ((flags & preferred) == preferred) return i;
    if (!fallback) fallback = i;
  }
  if (fallback) return *fallback;
  std::string types;
  for (uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i)
    if (typeBits & (1u << i))
      types += fmt::format("{}{}: {}", types.empty() ? "" : ", ", i,
                           vk::to_string(memoryProperties_.memoryTypes[i].propertyFlags));
  throw VulkanError(fmt::format("{} has no memory type with {} among those allowed ({})", deviceLabel(info_),
                                vk::to_string(wanted), types.empty() ? "none" : types));
}

void computeBarrier(const vk::raii::CommandBuffer& cmd) {
  const vk::MemoryBarrier barrier{
      .srcAccessMask = vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eTransferWrite,
      .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite |
                       vk::AccessFlagBits::eTransferRead | vk::AccessFlagBits::eTransferWrite};
  const auto stages = vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eTransfer;
  cmd.pipelineBarrier(stages, stages, {}, barrier, nullptr, nullptr);
}

}  // namespace spectrace::vk_util
