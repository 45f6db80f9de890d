#include "backend/vulkan_device.h"

#include <algorithm>
#include <numeric>

#include "backend/vulkan_tracer.h"
#include "embedded_shaders.h"
#include "vulkan/buffer.h"
#include "vulkan/compute_pipeline.h"
#include "vulkan/timestamps.h"

namespace spectrace {

DeviceCapabilities vulkanCapabilities(const vk_util::DeviceInfo& info) {
  DeviceCapabilities c;
  c.kind = DeviceKind::Vulkan;
  c.name = info.name;
  c.hardwareGpu = info.isHardware();
  c.deviceTimestamps = info.timestampsSupported;
  c.specialisedPipelines = true;
  c.pipelineCache = true;
  c.unusableBecause = info.missingFeatures();
  return c;
}

VulkanDevice::VulkanDevice(std::unique_ptr<vk_util::Context> context, const PipelineCacheOptions& cache,
                           const std::function<void(const std::string&)>& log)
    : context_(std::move(context)),
      buffers_(std::make_shared<TracerBufferPool>()),
      capabilities_(vulkanCapabilities(context_->info())) {
  context_->openPipelineCache(
      cache.enabled ? (cache.path.empty() ? context_->defaultPipelineCachePath() : cache.path) : "", log);
}

// The pooled buffers go before the context they were made on.
VulkanDevice::~VulkanDevice() { buffers_.reset(); }

std::unique_ptr<Tracer> VulkanDevice::makeTracer(const CompiledScene& plan, const TracerOptions& options) const {
  return std::make_unique<VulkanTracer>(*context_, plan, options.workgroupSize, options.specialisedFeatures, buffers_,
                                        options.profileStage);
}

void VulkanDevice::savePipelineCache() const { context_->savePipelineCache(); }
std::string VulkanDevice::pipelineCachePath() const { return context_->pipelineCachePath(); }
uint64_t VulkanDevice::bufferAllocations() const { return buffers_->allocations(); }

CeilingResult VulkanDevice::traceCeiling(const CeilingScene& scene, uint64_t beams, unsigned) const {
  const vk_util::Context& context = *context_;
  constexpr uint32_t kWorkgroup = 64;
  vk_util::ComputePipeline pipeline(context, embedded::spv_ceiling(), bindingSpecs(device::kCeilingBindings),
                                    sizeof(device::CeilingPush),
                                    {{device::kSpecWorkgroupSize, kWorkgroup}});
  vk_util::Buffer cdf(context, scene.cdf.size() * sizeof(float), {}, vk_util::MemoryPlacement::DeviceLocal);
  cdf.upload(scene.cdf.data(), scene.cdf.size() * sizeof(float));
  vk_util::Buffer counts(context, ceilingCountersOf(scene) * sizeof(uint32_t), {}, vk_util::MemoryPlacement::DeviceLocal);
  counts.fillZero();
  pipeline.bindBuffer(device::kBindingCeilingCdf, 0, cdf);
  pipeline.bindBuffer(device::kBindingCeilingHistogram, 0, counts);
  vk_util::TimestampQueries timestamps(context, 2);
  CeilingResult result;
  result.beams = beams;
  const uint32_t maxGroupsX = context.info().maxComputeWorkGroupCount[0];
  for (uint64_t done = 0; done < beams;) {
    const uint64_t count = std::min<uint64_t>(beams - done, uint64_t(1) << 30);
    const vk_util::DispatchGrid grid = vk_util::dispatchGridFor(count, kWorkgroup, maxGroupsX);
    device::CeilingPush push = scene.geometry;
    push.beamBase = uint32_t(done);
    push.beamCount = uint32_t(count);
    push.beamsPerRow = grid.invocationsPerRow;
    context.submitAndWait([&](const vk::raii::CommandBuffer& cb) {
      timestamps.reset(cb);
      timestamps.write(cb, 0);
      pipeline.recordDispatch(cb, &push, grid.groupsX, grid.groupsY);
      timestamps.write(cb, 1);
    });
    const auto ns = timestamps.readNanoseconds();
    result.seconds += (ns[1] - ns[0]) * 1e-9;
    done += count;
  }
  result.counts.resize(ceilingCountersOf(scene));
  counts.download(result.counts.data(), result.counts.size() * sizeof(uint32_t));
  result.hits = std::accumulate(result.counts.begin(), result.counts.end(), uint64_t(0));
  return result;
}

}  // namespace spectrace
