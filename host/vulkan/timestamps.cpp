#include "vulkan/timestamps.h"

#include <fmt/format.h>

namespace spectrace::vk_util {

TimestampQueries::TimestampQueries(const Context& context, uint32_t count) : context_(&context), count_(count) {
  const DeviceInfo& info = context.info();
  if (count == 0) throw VulkanError("TimestampQueries: a pool of 0 queries was requested");
  if (!info.timestampsSupported)
    throw VulkanError(fmt::format("TimestampQueries: the compute queue (family {}) of Vulkan device '{}' cannot "
                                  "write timestamps (timestampValidBits {}, timestampPeriod {})",
                                  context.computeQueueFamily(), info.name, info.timestampValidBits,
                                  info.timestampPeriodNs));
  try {
    pool_ = vk::raii::QueryPool(context.device(),
                                vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = count});
  } catch (const vk::SystemError& e) {
    throw VulkanError(fmt::format("TimestampQueries: creating a pool of {} queries failed: {}", count, e.what()));
  }
  // Queries must be reset before first use.
  if (context.hostQueryResetEnabled()) pool_.reset(0, count_);
}

void TimestampQueries::reset(const vk::raii::CommandBuffer& cmd) { cmd.resetQueryPool(*pool_, 0, count_); }

void TimestampQueries::resetFromHost() {
  if (!context_->hostQueryResetEnabled())
    throw VulkanError(fmt::format("TimestampQueries::resetFromHost: Vulkan device '{}' lacks hostQueryReset; record "
                                  "reset() into a command buffer instead",
                                  context_->info().name));
  pool_.reset(0, count_);
}

void TimestampQueries::write(const vk::raii::CommandBuffer& cmd, uint32_t query) {
  if (query >= count_)
    throw VulkanError(fmt::format("TimestampQueries::write: query {} is out of range (the pool has {})", query, count_));
  cmd.writeTimestamp(vk::PipelineStageFlagBits::eComputeShader, *pool_, query);
}

std::vector<uint64_t> TimestampQueries::readTicks() const {
  // Availability instead of WAIT: waiting on a query that was never written
  // would hang forever.
  std::vector<uint64_t> raw;
  try {
    raw = pool_.getResults<uint64_t>(0, count_, size_t(count_) * 16, 16,
                                     vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWithAvailability)
              .second;
  } catch (const vk::SystemError& e) {
    throw VulkanError(fmt::format("TimestampQueries: reading {} queries failed: {}", count_, e.what()));
  }
  const uint32_t bits = context_->info().timestampValidBits;
  const uint64_t mask = bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1;
  std::vector<uint64_t> ticks(count_);
  for (uint32_t i = 0; i < count_; ++i) {
    if (raw[2 * i + 1] == 0)
      throw VulkanError(fmt::format("TimestampQueries: query {} has no result: it was not written since the last "
                                    "reset, or the work that writes it has not completed",
                                    i));
    ticks[i] = raw[2 * i] & mask;
  }
  return ticks;
}

std::vector<double> TimestampQueries::readNanoseconds() const {
  const auto ticks = readTicks();
  const double period = context_->info().timestampPeriodNs;
  std::vector<double> ns(ticks.size());
  for (size_t i = 0; i < ticks.size(); ++i) ns[i] = double(ticks[i]) * period;
  return ns;
}

}  // namespace spectrace::vk_util
