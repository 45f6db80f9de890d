#pragma once
// Storage buffers: one VkBuffer with its own VkDeviceMemory, since spectrace
// allocates few, large buffers (histograms, scene data) and lives long with
// them. A Buffer borrows its Context, which must outlive it.
#include <cstddef>

#include <vulkan/vulkan_raii.hpp>

#include "vulkan/context.h"

namespace spectrace::vk_util {

enum class MemoryPlacement {
  DeviceLocal,  // fastest for shaders; host copies go through staging unless the memory is also host-visible
  HostVisible,  // host-coherent (cached where available), mapped for the buffer's lifetime
};

class Buffer {
 public:
  // `bytes` > 0 and at most the device's maxMemoryAllocationSize. The usage
  // always gets eStorageBuffer | eTransferSrc | eTransferDst on top; add
  // eUniformBuffer for a buffer bound as a uniform buffer.
  Buffer(const Context&, vk::DeviceSize bytes, vk::BufferUsageFlags usage, MemoryPlacement);
  Buffer(Buffer&&) noexcept;
  Buffer& operator=(Buffer&&) noexcept;  // a moved-from Buffer is empty (size 0, null handle)

  // Host<->device copies of [offset, offset + bytes). They run synchronously
  // on the Context's queue (ordered after all earlier submitted work), going
  // through a temporary staging buffer when the memory is not host-visible.
  // VulkanError if the range overflows the buffer.
  void upload(const void* src, vk::DeviceSize bytes, vk::DeviceSize offset = 0);
  void download(void* dst, vk::DeviceSize bytes, vk::DeviceSize offset = 0) const;
  // Zeroes the whole buffer with vkCmdFillBuffer and waits.
  void fillZero();
  // The same, recorded into a command buffer, followed by a barrier that
  // makes the zeros visible to later compute and transfer commands.
  void recordFillZero(const vk::raii::CommandBuffer&) const;

  vk::Buffer handle() const { return *buffer_; }
  vk::DeviceSize size() const { return size_; }  // as requested
  MemoryPlacement placement() const { return placement_; }
  vk::BufferUsageFlags usage() const { return usage_; }  // as requested, without the flags always added
  bool hostMapped() const { return mapped_ != nullptr; }  // host copies are plain memcpy

 private:
  friend struct BufferTestAccess;  // lets the tests force the staging path on unified-memory devices
  void checkRange(const char* what, vk::DeviceSize bytes, vk::DeviceSize offset) const;
  void uploadStaged(const std::byte* src, vk::DeviceSize bytes, vk::DeviceSize offset);
  void downloadStaged(std::byte* dst, vk::DeviceSize bytes, vk::DeviceSize offset) const;

  const Context* context_;
  vk::DeviceSize size_;
  MemoryPlacement placement_;
  vk::BufferUsageFlags usage_;
  // Declared before the buffer so the buffer is destroyed first.
  vk::raii::DeviceMemory memory_{nullptr};
  vk::raii::Buffer buffer_{nullptr};
  std::byte* mapped_ = nullptr;  // unmapped implicitly when memory_ is freed
};

}  // namespace spectrace::vk_util
