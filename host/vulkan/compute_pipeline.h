#pragma once
// A compute shader with its descriptor set (storage and uniform buffers), push
// constants and specialisation constants. Borrows its Context, which must
// outlive it.
#include <cstdint>
#include <memory>
#include <string>
#include <span>
#include <vector>

#include <vulkan/vulkan_raii.hpp>

#include "vulkan/buffer.h"
#include "vulkan/context.h"

namespace spectrace::vk_util {

struct BindingSpec {
  uint32_t binding;
  // > 1: an array of storage buffers, e.g. a histogram split under
  // maxStorageBufferRange. Shaders must index such arrays with dynamically
  // uniform values: lavapipe has no non-uniform descriptor indexing.
  uint32_t count = 1;
  // A uniform buffer instead of a storage buffer: small read-only tables
  // (lavapipe reads them as constants instead of checked per-lane loads).
  bool uniform = false;
};

// A specialisation constant: `value` for the shader's constant_id `id`.
struct SpecConstant {
  uint32_t id;
  uint32_t value;
};

// A 1D range of `invocations` laid out as a 2D grid of workgroups (one
// dimension stops at maxComputeWorkGroupCount[0] = `maxGroupsX`):
// invocation (x, y) is number y * invocationsPerRow + x. As few rows as the
// limit allows, each as short as it can be, so fewer than `groupsY`
// workgroups find nothing to do. (Rows filled to the limit left up to a
// whole row idle: 2^22 invocations in groups of 64 gave 2 x 65535 groups,
// and lavapipe took 0.15 s over the 65534 empty ones.)
struct DispatchGrid {
  uint32_t groupsX, groupsY, invocationsPerRow;
};
DispatchGrid dispatchGridFor(uint64_t invocations, uint32_t workgroupSize, uint32_t maxGroupsX);

class ComputePipeline {
 public:
  // spirv: SPIR-V bytes (a whole number of 4-byte words, entry point "main").
  // specConstants: uint32 values by constant_id. Creates its own descriptor
  // pool and set. VulkanError on malformed SPIR-V, bindings the device cannot
  // hold, push constants over maxPushConstantsSize, or pipeline creation
  // failure.
  ComputePipeline(const Context&, std::span<const unsigned char> spirv, std::vector<BindingSpec> bindings,
                  uint32_t pushConstantBytes, std::vector<SpecConstant> specConstants = {});

  // Points element `arrayElement` of `binding` at [offset, offset + range) of
  // `buffer` (VK_WHOLE_SIZE: to the end). Refuses ranges larger than the
  // device's maxStorageBufferRange (callers split big buffers) or, for a
  // uniform buffer, maxUniformBufferRange; offsets not aligned to
  // min{Storage,Uniform}BufferOffsetAlignment; and unknown bindings.
  // The update is immediate: do not rebind while a command buffer that
  // dispatches this pipeline is being recorded or executed.
  void bindBuffer(uint32_t binding, uint32_t arrayElement, const Buffer& buffer, vk::DeviceSize offset = 0,
                  vk::DeviceSize range = VK_WHOLE_SIZE);

  // Binds pipeline + set, pushes `pushConstants` (pushConstantBytes of them,
  // if any) and dispatches. VulkanError if a group count exceeds the device's
  // maxComputeWorkGroupCount or a descriptor was never bound.
  void recordDispatch(const vk::raii::CommandBuffer&, const void* pushConstants, uint32_t groupsX,
                      uint32_t groupsY = 1, uint32_t groupsZ = 1) const;

  uint32_t pushConstantBytes() const { return pushConstantBytes_; }

 private:
  const Context* context_;
  std::vector<BindingSpec> bindings_;
  std::vector<std::vector<bool>> bound_;  // per binding spec, per array element
  uint32_t pushConstantBytes_;
  // Shared with every ComputePipeline of the same key on the context
  // (Context::sharedPipeline), which keeps it for its life. Destroyed in
  // reverse: set before pool, both before the layouts they use.
  struct Compiled {
    vk::raii::DescriptorSetLayout setLayout{nullptr};
    vk::raii::PipelineLayout pipelineLayout{nullptr};  // declared after: destroyed before the set layout
    vk::raii::Pipeline pipeline{nullptr};
  };
  std::shared_ptr<Compiled> compiled_;
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet set_{nullptr};
};

}  // namespace spectrace::vk_util
