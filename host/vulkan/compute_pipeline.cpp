#include "vulkan/compute_pipeline.h"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>

namespace spectrace::vk_util {
namespace {

constexpr uint32_t kSpirvMagic = 0x07230203;

vk::DescriptorType descriptorTypeOf(const BindingSpec& b) {
  return b.uniform ? vk::DescriptorType::eUniformBuffer : vk::DescriptorType::eStorageBuffer;
}

std::string declaredBindings(const std::vector<BindingSpec>& bindings) {
  std::string out;
  for (const auto& b : bindings)
    out += fmt::format("{}{}{}", out.empty() ? "" : ", ", b.binding, b.count > 1 ? fmt::format("[{}]", b.count) : "");
  return out.empty() ? "none" : out;
}

}  // namespace

ComputePipeline::ComputePipeline(const Context& context, std::span<const unsigned char> spirv,
                                 std::vector<BindingSpec> bindings, uint32_t pushConstantBytes,
                                 std::vector<SpecConstant> specConstants)
    : context_(&context), bindings_(std::move(bindings)), pushConstantBytes_(pushConstantBytes) {
  const DeviceInfo& info = context.info();
  if (spirv.empty() || spirv.size() % 4 != 0)
    throw VulkanError(fmt::format("ComputePipeline: SPIR-V must be a non-empty whole number of 4-byte words, got {} bytes",
                                  spirv.size()));
  // Copied so that the words are aligned whatever the caller's bytes are.
  std::vector<uint32_t> words(spirv.size() / 4);
  std::memcpy(words.data(), spirv.data(), spirv.size());
  if (words[0] != kSpirvMagic)
    throw VulkanError(fmt::format("ComputePipeline: the code does not start with the SPIR-V magic number 0x{:08x} "
                                  "(found 0x{:08x})",
                                  kSpirvMagic, words[0]));

  uint32_t totalDescriptors = 0, uniformDescriptors = 0;
  std::vector<vk::DescriptorSetLayoutBinding> layoutBindings;
  for (size_t i = 0; i < bindings_.size(); ++i) {
    const BindingSpec& b = bindings_[i];
    if (b.count == 0) throw VulkanError(fmt::format("ComputePipeline: binding {} has a count of 0", b.binding));
    for (size_t j = 0; j < i; ++j)
      if (bindings_[j].binding == b.binding)
        throw VulkanError(fmt::format("ComputePipeline: binding {} is declared twice", b.binding));
    totalDescriptors += b.count;
    if (b.uniform) uniformDescriptors += b.count;
    layoutBindings.push_back(vk::DescriptorSetLayoutBinding{.binding = b.binding,
                                                            .descriptorType = descriptorTypeOf(b),
                                                            .descriptorCount = b.count,
                                                            .stageFlags = vk::ShaderStageFlagBits::eCompute});
    bound_.emplace_back(b.count, false);
  }
  const uint32_t storageDescriptors = totalDescriptors - uniformDescriptors;
  if (storageDescriptors > info.maxPerStageDescriptorStorageBuffers)
    throw VulkanError(fmt::format("ComputePipeline: {} storage buffer descriptors exceed the "
                                  "maxPerStageDescriptorStorageBuffers ({}) of Vulkan device '{}'",
                                  storageDescriptors, info.maxPerStageDescriptorStorageBuffers, info.name));
  if (uniformDescriptors > info.maxPerStageDescriptorUniformBuffers)
    throw VulkanError(fmt::format("ComputePipeline: {} uniform buffer descriptors exceed the "
                                  "maxPerStageDescriptorUniformBuffers ({}) of Vulkan device '{}'",
                                  uniformDescriptors, info.maxPerStageDescriptorUniformBuffers, info.name));
  if (pushConstantBytes % 4 != 0 || pushConstantBytes > info.maxPushConstantsSize)
    throw VulkanError(fmt::format("ComputePipeline: {} bytes of push constants; they must be a multiple of 4 and at "
                                  "most the maxPushConstantsSize ({}) of Vulkan device '{}'",
                                  pushConstantBytes, info.maxPushConstantsSize, info.name));

  const vk::raii::Device& device = context.device();
  // The compiled objects are shared by every ComputePipeline with the same
  // key on this context, for the context's life: a batch that makes many
  // tracers compiles each specialisation once.
  std::string key(reinterpret_cast<const char*>(words.data()), words.size() * 4);
  const auto append = [&](uint32_t v) { key.append(reinterpret_cast<const char*>(&v), 4); };
  append(0xffffffffu);  // separates the code from the rest
  append(pushConstantBytes);
  append(uint32_t(bindings_.size()));
  for (const auto& b : bindings_) append(b.binding), append(b.count), append(b.uniform ? 1u : 0u);
  append(uint32_t(specConstants.size()));
  for (const auto& c : specConstants) append(c.id), append(c.value);
  compiled_ = std::static_pointer_cast<Compiled>(context.sharedPipeline(key, [&]() -> std::shared_ptr<void> {
    auto compiled = std::make_shared<Compiled>();
    try {
      compiled->setLayout = vk::raii::DescriptorSetLayout(
          device, vk::DescriptorSetLayoutCreateInfo{.bindingCount = uint32_t(layoutBindings.size()),
                                                    .pBindings = layoutBindings.data()});
      const vk::PushConstantRange pushRange{
          .stageFlags = vk::ShaderStageFlagBits::eCompute, .offset = 0, .size = pushConstantBytes};
      const vk::DescriptorSetLayout rawSetLayout = *compiled->setLayout;
      compiled->pipelineLayout = vk::raii::PipelineLayout(
          device, vk::PipelineLayoutCreateInfo{.setLayoutCount = 1,
                                               .pSetLayouts = &rawSetLayout,
                                               .pushConstantRangeCount = pushConstantBytes > 0 ? 1u : 0u,
                                               .pPushConstantRanges = &pushRange});
    } catch (const vk::SystemError& e) {
      throw VulkanError(fmt::format("ComputePipeline: creating the pipeline layout failed: {}", e.what()));
    }

    std::vector<vk::SpecializationMapEntry> specEntries;
    std::vector<uint32_t> specValues;
    for (uint32_t i = 0; i < specConstants.size(); ++i) {
      specEntries.push_back(vk::SpecializationMapEntry{.constantID = specConstants[i].id, .offset = 4 * i, .size = 4});
      specValues.push_back(specConstants[i].value);
    }
    const vk::SpecializationInfo specInfo{.mapEntryCount = uint32_t(specEntries.size()),
                                          .pMapEntries = specEntries.data(),
                                          .dataSize = specValues.size() * 4,
                                          .pData = specValues.data()};
    try {
      vk::raii::ShaderModule module(
          device, vk::ShaderModuleCreateInfo{.codeSize = words.size() * 4, .pCode = words.data()});
      // The context's pipeline cache (if any) skips recompiling what an
      // earlier run already compiled.
      compiled->pipeline = vk::raii::Pipeline(
          device, context.pipelineCache(),
          vk::ComputePipelineCreateInfo{
              .stage = {.stage = vk::ShaderStageFlagBits::eCompute,
                        .module = *module,
                        .pName = "main",
                        .pSpecializationInfo = specConstants.empty() ? nullptr : &specInfo},
              .layout = *compiled->pipelineLayout});
    } catch (const vk::SystemError& e) {
      throw VulkanError(fmt::format("ComputePipeline: creating the compute pipeline on '{}' failed: {}", info.name,
                                    e.what()));
    }
    return compiled;
  }));

  if (totalDescriptors > 0) {
    try {
      std::vector<vk::DescriptorPoolSize> poolSizes;
      if (storageDescriptors > 0)
        poolSizes.push_back({.type = vk::DescriptorType::eStorageBuffer, .descriptorCount = storageDescriptors});
      if (uniformDescriptors > 0)
        poolSizes.push_back({.type = vk::DescriptorType::eUniformBuffer, .descriptorCount = uniformDescriptors});
      // FreeDescriptorSet: the RAII set frees itself before the pool goes.
      pool_ = vk::raii::DescriptorPool(
          device, vk::DescriptorPoolCreateInfo{.flags = vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet,
                                               .maxSets = 1,
                                               .poolSizeCount = uint32_t(poolSizes.size()),
                                               .pPoolSizes = poolSizes.data()});
      const vk::DescriptorSetLayout rawSetLayout = *compiled_->setLayout;
      vk::raii::DescriptorSets sets(device, vk::DescriptorSetAllocateInfo{.descriptorPool = *pool_,
                                                                           .descriptorSetCount = 1,
                                                                           .pSetLayouts = &rawSetLayout});
      set_ = std::move(sets.front());
    } catch (const vk::SystemError& e) {
      throw VulkanError(fmt::format("ComputePipeline: allocating the descriptor set failed: {}", e.what()));
    }
  }
}

void ComputePipeline::bindBuffer(uint32_t binding, uint32_t arrayElement, const Buffer& buffer, vk::DeviceSize offset,
                                 vk::DeviceSize range) {
  const auto it = std::find_if(bindings_.begin(), bindings_.end(),
                               [&](const BindingSpec& b) { return b.binding == binding; });
  if (it == bindings_.end())
    throw VulkanError(fmt::format("ComputePipeline::bindBuffer: binding {} is not declared (declared: {})", binding,
                                  declaredBindings(bindings_)));
  const std::string where = fmt::format("ComputePipeline::bindBuffer: binding {} element {}", binding, arrayElement);
  if (arrayElement >= it->count)
    throw VulkanError(fmt::format("{} is out of range: the binding has {} element{}", where, it->count,
                                  it->count == 1 ? "" : "s"));
  if (!buffer.handle()) throw VulkanError(where + ": the buffer is empty (moved from)");
  const DeviceInfo& info = context_->info();
  if (offset >= buffer.size())
    throw VulkanError(fmt::format("{}: offset {} is at or past the end of the {}-byte buffer", where, offset,
                                  buffer.size()));
  const char* kind = it->uniform ? "Uniform" : "Storage";
  const uint64_t alignment = it->uniform ? info.minUniformBufferOffsetAlignment : info.minStorageBufferOffsetAlignment;
  if (offset % alignment != 0)
    throw VulkanError(fmt::format("{}: offset {} is not a multiple of the min{}BufferOffsetAlignment ({}) of "
                                  "Vulkan device '{}'",
                                  where, offset, kind, alignment, info.name));
  if (range != VK_WHOLE_SIZE && (range == 0 || range > buffer.size() - offset))
    throw VulkanError(fmt::format("{}: range {} at offset {} does not fit in the {}-byte buffer", where, range, offset,
                                  buffer.size()));
  const vk::DeviceSize effective = range == VK_WHOLE_SIZE ? buffer.size() - offset : range;
  const uint64_t maxRange = it->uniform ? info.maxUniformBufferRange : info.maxStorageBufferRange;
  if (effective > maxRange)
    throw VulkanError(fmt::format("{}: a range of {} bytes exceeds the max{}BufferRange ({} bytes) of Vulkan "
                                  "device '{}'; split the buffer across array elements or dispatches",
                                  where, effective, kind, maxRange, info.name));

  // The explicit range (never VK_WHOLE_SIZE) keeps the shader's view to the
  // requested bytes, not the buffer's rounded-up allocation.
  const vk::DescriptorBufferInfo bufferInfo{.buffer = buffer.handle(), .offset = offset, .range = effective};
  context_->device().updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *set_,
                                                                 .dstBinding = binding,
                                                                 .dstArrayElement = arrayElement,
                                                                 .descriptorCount = 1,
                                                                 .descriptorType = descriptorTypeOf(*it),
                                                                 .pBufferInfo = &bufferInfo},
                                          nullptr);
  bound_[size_t(it - bindings_.begin())][arrayElement] = true;
}

void ComputePipeline::recordDispatch(const vk::raii::CommandBuffer& cmd, const void* pushConstants, uint32_t groupsX,
                                     uint32_t groupsY, uint32_t groupsZ) const {
  const DeviceInfo& info = context_->info();
  const auto& limit = info.maxComputeWorkGroupCount;
  if (groupsX > limit[0] || groupsY > limit[1] || groupsZ > limit[2])
    throw VulkanError(fmt::format("ComputePipeline::recordDispatch: {} x {} x {} workgroups exceed the "
                                  "maxComputeWorkGroupCount ({} x {} x {}) of Vulkan device '{}'",
                                  groupsX, groupsY, groupsZ, limit[0], limit[1], limit[2], info.name));
  for (size_t i = 0; i < bindings_.size(); ++i)
    for (size_t e = 0; e < bound_[i].size(); ++e)
      if (!bound_[i][e])
        throw VulkanError(fmt::format("ComputePipeline::recordDispatch: binding {} element {} has no buffer bound",
                                      bindings_[i].binding, e));
  if (pushConstantBytes_ > 0 && !pushConstants)
    throw VulkanError(fmt::format("ComputePipeline::recordDispatch: the pipeline takes {} bytes of push constants, "
                                  "but none were given",
                                  pushConstantBytes_));
  if (pushConstantBytes_ == 0 && pushConstants)
    throw VulkanError("ComputePipeline::recordDispatch: push constants were given, but the pipeline declares none");

  cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *compiled_->pipeline);
  if (*set_) cmd.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *compiled_->pipelineLayout, 0, *set_, nullptr);
  if (pushConstantBytes_ > 0)
    cmd.pushConstants<unsigned char>(
        *compiled_->pipelineLayout, vk::ShaderStageFlagBits::eCompute, 0,
        vk::ArrayProxy<const unsigned char>(pushConstantBytes_, static_cast<const unsigned char*>(pushConstants)));
  cmd.dispatch(groupsX, groupsY, groupsZ);
}

DispatchGrid dispatchGridFor(uint64_t invocations, uint32_t workgroupSize, uint32_t maxGroupsX) {
  const uint64_t groups = std::max<uint64_t>(1, (invocations + workgroupSize - 1) / workgroupSize);
  const uint64_t rows = (groups + maxGroupsX - 1) / maxGroupsX;
  const uint32_t groupsX = uint32_t((groups + rows - 1) / rows);
  return {groupsX, uint32_t(rows), groupsX * workgroupSize};
}

}  // namespace spectrace::vk_util
