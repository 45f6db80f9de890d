#pragma once
// A Vulkan device (a GPU, or lavapipe) as a Device: one Context with its
// pipeline cache, and a pool of device buffers its tracers share.
#include <memory>

#include "backend/device.h"
#include "vulkan/context.h"

namespace spectrace {

class TracerBufferPool;

// What a Vulkan device can do, from what it reports (limits, type, features).
DeviceCapabilities vulkanCapabilities(const vk_util::DeviceInfo& info);

class VulkanDevice final : public Device {
 public:
  VulkanDevice(std::unique_ptr<vk_util::Context> context, const PipelineCacheOptions& cache,
               const std::function<void(const std::string&)>& log);
  ~VulkanDevice() override;

  const DeviceCapabilities& capabilities() const override { return capabilities_; }
  std::unique_ptr<Tracer> makeTracer(const CompiledScene& plan, const TracerOptions& options = {}) const override;
  CeilingResult traceCeiling(const CeilingScene& scene, uint64_t beams, unsigned threads = 0) const override;
  void savePipelineCache() const override;
  std::string pipelineCachePath() const override;
  uint64_t bufferAllocations() const override;

 private:
  std::unique_ptr<vk_util::Context> context_;
  std::shared_ptr<TracerBufferPool> buffers_;  // shared by its tracers
  DeviceCapabilities capabilities_;
};

}  // namespace spectrace
