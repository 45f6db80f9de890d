// Context's persistent VkPipelineCache: where it lives, how a file is
// checked before Vulkan sees it, and the atomic save.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

#include "vulkan/context.h"

namespace spectrace::vk_util {
namespace {

// VkPipelineCacheHeaderVersionOne: 4 uint32 fields then the 16-byte UUID.
constexpr size_t kHeaderBytes = 16 + VK_UUID_SIZE;

uint32_t readU32(const std::vector<uint8_t>& data, size_t offset) {
  uint32_t v;
  std::memcpy(&v, data.data() + offset, 4);
  return v;
}

std::string hex(const uint8_t* bytes, size_t n) {
  std::string out;
  for (size_t i = 0; i < n; ++i) out += fmt::format("{:02x}", bytes[i]);
  return out;
}

// "" when `data` starts with a version-one header for `props`, else why not.
std::string headerMismatch(const std::vector<uint8_t>& data, const vk::PhysicalDeviceProperties& props) {
  if (data.size() < kHeaderBytes)
    return fmt::format("{} bytes is too short for a pipeline cache header ({} bytes)", data.size(), kHeaderBytes);
  const uint32_t headerSize = readU32(data, 0), version = readU32(data, 4), vendor = readU32(data, 8),
                 deviceID = readU32(data, 12);
  if (headerSize < kHeaderBytes || headerSize > data.size())
    return fmt::format("header length {} is not between {} and the file size {}", headerSize, kHeaderBytes,
                       data.size());
  if (version != uint32_t(VK_PIPELINE_CACHE_HEADER_VERSION_ONE))
    return fmt::format("header version {} is not {}", version, uint32_t(VK_PIPELINE_CACHE_HEADER_VERSION_ONE));
  if (vendor != props.vendorID || deviceID != props.deviceID)
    return fmt::format("it is for vendor 0x{:x} device 0x{:x}, not vendor 0x{:x} device 0x{:x}", vendor, deviceID,
                       props.vendorID, props.deviceID);
  if (std::memcmp(data.data() + 16, props.pipelineCacheUUID.data(), VK_UUID_SIZE) != 0)
    return fmt::format("its pipelineCacheUUID {} is not the driver's {}", hex(data.data() + 16, VK_UUID_SIZE),
                       hex(props.pipelineCacheUUID.data(), VK_UUID_SIZE));
  return "";
}

}  // namespace

std::string Context::defaultPipelineCachePath() const {
  std::filesystem::path dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    dir = xdg;
  } else if (const char* home = std::getenv("HOME"); home && *home) {
    dir = std::filesystem::path(home) / ".cache";
  } else {
    return "";
  }
  const auto chain = physicalDevice_.getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceIDProperties>();
  const auto& id = chain.get<vk::PhysicalDeviceIDProperties>();
  const uint32_t driverVersion = chain.get<vk::PhysicalDeviceProperties2>().properties.driverVersion;
  return (dir / "spectrace" /
          fmt::format("pipelines-{}-{}.bin", hex(id.deviceUUID.data(), VK_UUID_SIZE), driverVersion))
      .string();
}

void Context::openPipelineCache(const std::string& path, std::function<void(const std::string&)> log) {
  pipelineCachePath_ = path;
  pipelineCacheLog_ = std::move(log);
  std::vector<uint8_t> data;
  if (!path.empty()) {
    std::error_code ec;
    if (std::filesystem::exists(path, ec)) {
      std::ifstream in(path, std::ios::binary);
      data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      std::string why = in.bad() ? std::string("it could not be read") : headerMismatch(data, physicalDevice_.getProperties());
      if (!why.empty()) {
        if (pipelineCacheLog_) pipelineCacheLog_(fmt::format("pipeline cache {} ignored: {}", path, why));
        data.clear();
      }
    }
  }
  try {
    pipelineCache_ = vk::raii::PipelineCache(
        device_, vk::PipelineCacheCreateInfo{.initialDataSize = data.size(), .pInitialData = data.data()});
    pipelineCacheSaved_ = std::move(data);
  } catch (const vk::SystemError& e) {
    if (data.empty()) throw VulkanError(fmt::format("creating the pipeline cache failed: {}", e.what()));
    if (pipelineCacheLog_) pipelineCacheLog_(fmt::format("pipeline cache {} ignored: the driver refused it ({})", path, e.what()));
    pipelineCache_ = vk::raii::PipelineCache(device_, vk::PipelineCacheCreateInfo{});
    pipelineCacheSaved_.clear();
  }
}

std::shared_ptr<void> Context::sharedPipeline(const std::string& key,
                                              const std::function<std::shared_ptr<void>()>& make) const {
  const std::lock_guard lock(pipelinesMutex_);
  auto& slot = pipelines_[key];
  if (!slot) slot = make();
  return slot;
}

void Context::savePipelineCache() const {
  if (!*pipelineCache_ || pipelineCachePath_.empty()) return;
  const auto fail = [&](const std::string& why) {
    if (pipelineCacheLog_) pipelineCacheLog_(fmt::format("pipeline cache {} not saved: {}", pipelineCachePath_, why));
  };
  std::vector<uint8_t> data;
  try {
    data = pipelineCache_.getData();
  } catch (const vk::SystemError& e) {
    return fail(e.what());
  }
  if (data.empty() || data == pipelineCacheSaved_) return;
  const std::filesystem::path target(pipelineCachePath_);
  std::error_code ec;
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path(), ec);
  if (ec) return fail(fmt::format("cannot create {}: {}", target.parent_path().string(), ec.message()));
  const std::string tmp = fmt::format("{}.tmp.{}", pipelineCachePath_, ::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return fail(fmt::format("cannot create {}: {}", tmp, std::strerror(errno)));
  size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += size_t(n);
  }
  const bool ok = done == data.size() && ::fsync(fd) == 0;
  const int err = errno;
  ::close(fd);
  if (!ok || ::rename(tmp.c_str(), pipelineCachePath_.c_str()) != 0) {
    const std::string why = std::strerror(ok ? errno : err);
    ::unlink(tmp.c_str());
    return fail(why);
  }
  pipelineCacheSaved_ = std::move(data);
}

}  // namespace spectrace::vk_util
