#pragma once
// Device timestamps for measuring how long passes take on the device.
// Borrows its Context, which must outlive it.
#include <cstdint>
#include <vector>

#include <vulkan/vulkan_raii.hpp>

#include "vulkan/context.h"

namespace spectrace::vk_util {

// Device timestamps around passes, for measuring device time.
class TimestampQueries {
 public:
  // VulkanError if the compute queue cannot write timestamps. With
  // hostQueryReset the queries start out reset; otherwise call reset() in the
  // first command buffer.
  TimestampQueries(const Context&, uint32_t count);
  void reset(const vk::raii::CommandBuffer&);  // all queries, recorded
  void resetFromHost();                          // all queries, now (needs hostQueryReset)
  // Records a timestamp taken once all earlier commands finished their compute
  // shader stage.
  void write(const vk::raii::CommandBuffer&, uint32_t query);
  // All `count` timestamps in nanoseconds (ticks scaled by timestampPeriod;
  // the origin is arbitrary, so only differences mean anything). Does not
  // wait: VulkanError if a query was not written or its work has not finished.
  std::vector<double> readNanoseconds() const;
  // The same as raw ticks (masked to timestampValidBits), exact.
  std::vector<uint64_t> readTicks() const;
  uint32_t count() const { return count_; }

 private:
  const Context* context_;
  uint32_t count_;
  vk::raii::QueryPool pool_{nullptr};
};

}  // namespace spectrace::vk_util
