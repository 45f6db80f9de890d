#include "vulkan/buffer.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include <fmt/format.h>

namespace spectrace::vk_util {
namespace {

// Staging copies go in chunks of at most this many bytes so a huge transfer
// does not need a second huge allocation.
constexpr vk::DeviceSize kStagingChunk = 64ull << 20;

const auto kShaderOrTransferWrite = vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eTransferWrite;
const auto kComputeOrTransfer = vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eTransfer;

void barrier(const vk::raii::CommandBuffer& cmd, vk::PipelineStageFlags srcStages, vk::AccessFlags srcAccess,
             vk::PipelineStageFlags dstStages, vk::AccessFlags dstAccess) {
  cmd.pipelineBarrier(srcStages, dstStages, {},
                      vk::MemoryBarrier{.srcAccessMask = srcAccess, .dstAccessMask = dstAccess}, nullptr, nullptr);
}

// Everything a later pass (or a host read after the fence) may do with data
// written by a transfer.
void afterTransferWrite(const vk::raii::CommandBuffer& cmd) {
  barrier(cmd, vk::PipelineStageFlagBits::eTransfer, vk::AccessFlagBits::eTransferWrite,
          kComputeOrTransfer | vk::PipelineStageFlagBits::eHost,
          vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eTransferRead |
              vk::AccessFlagBits::eTransferWrite | vk::AccessFlagBits::eHostRead);
}

std::string placementName(MemoryPlacement p) {
  return p == MemoryPlacement::DeviceLocal ? "device-local" : "host-visible";
}

}  // namespace

Buffer::Buffer(const Context& context, vk::DeviceSize bytes, vk::BufferUsageFlags usage, MemoryPlacement placement)
    : context_(&context), size_(bytes), placement_(placement), usage_(usage) {
  const DeviceInfo& info = context.info();
  if (bytes == 0) throw VulkanError("A Buffer of 0 bytes was requested; Vulkan buffers must not be empty");
  // Rounded up to whole words so vkCmdFillBuffer(VK_WHOLE_SIZE) covers every requested byte.
  const vk::DeviceSize allocBytes = (bytes + 3) / 4 * 4;
  if (info.maxMemoryAllocationSize != 0 && allocBytes > info.maxMemoryAllocationSize)
    throw VulkanError(fmt::format(
        "A Buffer of {} bytes exceeds the maxMemoryAllocationSize ({} bytes) of Vulkan device '{}'; split it", bytes,
        info.maxMemoryAllocationSize, info.name));
  try {
    buffer_ = vk::raii::Buffer(
        context.device(),
        vk::BufferCreateInfo{.size = allocBytes,
                             .usage = usage | vk::BufferUsageFlagBits::eStorageBuffer |
                                      vk::BufferUsageFlagBits::eTransferSrc | vk::BufferUsageFlagBits::eTransferDst,
                             .sharingMode = vk::SharingMode::eExclusive});
  } catch (const vk::SystemError& e) {
    throw VulkanError(fmt::format("Creating a {}-byte buffer on '{}' failed: {}", bytes, info.name, e.what()));
  }

  const vk::MemoryRequirements req = buffer_.getMemoryRequirements();
  // Coherent host memory needs no flush/invalidate; cached makes downloads fast.
  const uint32_t type =
      placement == MemoryPlacement::DeviceLocal
          ? context.memoryTypeIndex(req.memoryTypeBits, vk::MemoryPropertyFlagBits::eDeviceLocal)
          : context.memoryTypeIndex(req.memoryTypeBits,
                                    vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent,
                                    vk::MemoryPropertyFlagBits::eHostCached);
  const auto& memProps = context.memoryProperties();
  const vk::MemoryPropertyFlags typeFlags = memProps.memoryTypes[type].propertyFlags;
  try {
    memory_ = vk::raii::DeviceMemory(context.device(),
                                     vk::MemoryAllocateInfo{.allocationSize = req.size, .memoryTypeIndex = type});
  } catch (const vk::SystemError& e) {
    const uint32_t heap = memProps.memoryTypes[type].heapIndex;
    throw VulkanError(fmt::format("Allocating {} bytes of {} memory (type {}, heap {} of {} bytes) on '{}' failed: {}",
                                  req.size, placementName(placement), type, heap, memProps.memoryHeaps[heap].size,
                                  info.name, e.what()));
  }
  buffer_.bindMemory(*memory_, 0);
  const auto mappable = vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent;
  if ((typeFlags & mappable) == mappable) {
    try {
      mapped_ = static_cast<std::byte*>(memory_.mapMemory(0, VK_WHOLE_SIZE));
    } catch (const vk::SystemError& e) {
      throw VulkanError(fmt::format("Mapping a {}-byte buffer on '{}' failed: {}", bytes, info.name, e.what()));
    }
  }
}

Buffer::Buffer(Buffer&& o) noexcept
    : context_(o.context_),
      size_(std::exchange(o.size_, 0)),
      placement_(o.placement_),
      usage_(o.usage_),
      memory_(std::move(o.memory_)),
      buffer_(std::move(o.buffer_)),
      mapped_(std::exchange(o.mapped_, nullptr)) {}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
  if (this != &o) {
    buffer_ = std::move(o.buffer_);  // the old buffer goes before its memory
    memory_ = std::move(o.memory_);
    context_ = o.context_;
    size_ = std::exchange(o.size_, 0);
    placement_ = o.placement_;
    usage_ = o.usage_;
    mapped_ = std::exchange(o.mapped_, nullptr);
  }
  return *this;
}

void Buffer::checkRange(const char* what, vk::DeviceSize bytes, vk::DeviceSize offset) const {
  if (offset > size_ || bytes > size_ - offset)
    throw VulkanError(fmt::format("Buffer::{} of {} bytes at offset {} overflows the {}-byte buffer", what, bytes,
                                  offset, size_));
}

void Buffer::upload(const void* src, vk::DeviceSize bytes, vk::DeviceSize offset) {
  checkRange("upload", bytes, offset);
  if (bytes == 0) return;
  if (!src) throw VulkanError("Buffer::upload was given a null source pointer");
  // Host writes to coherent memory become visible to the device at the next
  // queue submission, so no barrier is needed.
  if (mapped_) std::memcpy(mapped_ + offset, src, bytes);
  else uploadStaged(static_cast<const std::byte*>(src), bytes, offset);
}

void Buffer::download(void* dst, vk::DeviceSize bytes, vk::DeviceSize offset) const {
  checkRange("download", bytes, offset);
  if (bytes == 0) return;
  if (!dst) throw VulkanError("Buffer::download was given a null destination pointer");
  if (!mapped_) return downloadStaged(static_cast<std::byte*>(dst), bytes, offset);
  // Device writes only reach host reads through a barrier to the host stage.
  context_->submitAndWait([](const vk::raii::CommandBuffer& cmd) {
    barrier(cmd, kComputeOrTransfer, kShaderOrTransferWrite, vk::PipelineStageFlagBits::eHost,
            vk::AccessFlagBits::eHostRead);
  });
  std::memcpy(dst, mapped_ + offset, bytes);
}

void Buffer::uploadStaged(const std::byte* src, vk::DeviceSize bytes, vk::DeviceSize offset) {
  Buffer staging(*context_, std::min(bytes, kStagingChunk), {}, MemoryPlacement::HostVisible);
  for (vk::DeviceSize done = 0; done < bytes;) {
    const vk::DeviceSize n = std::min(bytes - done, kStagingChunk);
    std::memcpy(staging.mapped_, src + done, n);
    context_->submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
      // Earlier passes' accesses to this range finish before it is overwritten.
      barrier(cmd, kComputeOrTransfer, kShaderOrTransferWrite, vk::PipelineStageFlagBits::eTransfer,
              vk::AccessFlagBits::eTransferWrite);
      cmd.copyBuffer(staging.handle(), *buffer_, vk::BufferCopy{.srcOffset = 0, .dstOffset = offset + done, .size = n});
      afterTransferWrite(cmd);
    });
    done += n;
  }
}

void Buffer::downloadStaged(std::byte* dst, vk::DeviceSize bytes, vk::DeviceSize offset) const {
  Buffer staging(*context_, std::min(bytes, kStagingChunk), {}, MemoryPlacement::HostVisible);
  for (vk::DeviceSize done = 0; done < bytes;) {
    const vk::DeviceSize n = std::min(bytes - done, kStagingChunk);
    context_->submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
      barrier(cmd, kComputeOrTransfer, kShaderOrTransferWrite, vk::PipelineStageFlagBits::eTransfer,
              vk::AccessFlagBits::eTransferRead);
      cmd.copyBuffer(*buffer_, staging.handle(), vk::BufferCopy{.srcOffset = offset + done, .dstOffset = 0, .size = n});
      afterTransferWrite(cmd);
    });
    std::memcpy(dst + done, staging.mapped_, n);
    done += n;
  }
}

void Buffer::recordFillZero(const vk::raii::CommandBuffer& cmd) const {
  barrier(cmd, kComputeOrTransfer, kShaderOrTransferWrite, vk::PipelineStageFlagBits::eTransfer,
          vk::AccessFlagBits::eTransferWrite);
  cmd.fillBuffer(*buffer_, 0, VK_WHOLE_SIZE, 0u);
  afterTransferWrite(cmd);
}

void Buffer::fillZero() {
  context_->submitAndWait([this](const vk::raii::CommandBuffer& cmd) { recordFillZero(cmd); });
}

}  // namespace spectrace::vk_util
