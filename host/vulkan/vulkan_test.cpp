// Runs on whatever Vulkan device is here (lavapipe in CI); the limits checked
// against exact numbers are lavapipe's.
#include <algorithm>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "embedded_vulkan_test_shaders.h"
#include "vulkan/buffer.h"
#include "vulkan/compute_pipeline.h"
#include "vulkan/context.h"
#include "vulkan/timestamps.h"

namespace spectrace::vk_util {

// Forces the staging path, which lavapipe's all-host-visible memory never takes.
struct BufferTestAccess {
  static void uploadStaged(Buffer& b, const void* src, vk::DeviceSize bytes, vk::DeviceSize offset) {
    b.uploadStaged(static_cast<const std::byte*>(src), bytes, offset);
  }
  static void downloadStaged(const Buffer& b, void* dst, vk::DeviceSize bytes, vk::DeviceSize offset) {
    b.downloadStaged(static_cast<std::byte*>(dst), bytes, offset);
  }
};

namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// Runs `f`, which must throw VulkanError, and returns the message.
template <typename F>
std::string vulkanErrorOf(F&& f) {
  try {
    f();
  } catch (const VulkanError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a VulkanError";
  return {};
}

std::vector<unsigned char> pattern(size_t n, unsigned seed) {
  std::vector<unsigned char> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = static_cast<unsigned char>((i * 131 + seed * 7 + (i >> 8)) & 0xff);
  return v;
}

DeviceInfo usableInfo(vk::PhysicalDeviceType type, uint32_t index) {
  DeviceInfo d;
  d.index = index;
  d.name = "fake " + std::to_string(index);
  d.type = type;
  d.apiVersion = VK_API_VERSION_1_3;
  d.shaderInt64 = d.int64Atomics = d.scalarBlockLayout = true;
  d.computeQueueFamily = 0;
  return d;
}

const DeviceInfo* findLavapipe(const std::vector<DeviceInfo>& devices) {
  for (const auto& d : devices)
    if (d.name.find("llvmpipe") != std::string::npos || d.driverName == "llvmpipe") return &d;
  return nullptr;
}

// --- devices ---------------------------------------------------------------

TEST(VulkanDevices, EnumerateFindsUsableLavapipeWithItsLimits) {
  const auto devices = enumerateDevices();
  const DeviceInfo* lvp = findLavapipe(devices);
  ASSERT_NE(lvp, nullptr) << describeDevices(devices);
  EXPECT_EQ(lvp->maxStorageBufferRange, 134217728u);
  EXPECT_EQ(lvp->maxMemoryAllocationSize, 2147483648u);
  EXPECT_EQ(lvp->type, vk::PhysicalDeviceType::eCpu);
  EXPECT_FALSE(lvp->isHardware());
  EXPECT_EQ(lvp->maxComputeWorkGroupCount[0], 65535u);
  EXPECT_TRUE(lvp->shaderInt64);
  EXPECT_TRUE(lvp->int64Atomics);
  EXPECT_TRUE(lvp->scalarBlockLayout);
  EXPECT_TRUE(lvp->timestampsSupported);
  EXPECT_TRUE(lvp->computeQueueFamily.has_value());
  EXPECT_GE(lvp->apiVersion, VK_API_VERSION_1_2);
  EXPECT_EQ(lvp->missingFeatures(), "");
  EXPECT_EQ(devices[lvp->index].index, lvp->index);

  const std::string table = describeDevices(devices);
  EXPECT_THAT(table, HasSubstr(lvp->name));
  EXPECT_THAT(table, HasSubstr("maxStorageBufferRange 128 MiB (134217728 B)"));
  EXPECT_THAT(table, HasSubstr("usable"));
  EXPECT_THAT(table, Not(HasSubstr("NOT usable")));
  EXPECT_THAT(table, HasSubstr("(default)"));
}

TEST(VulkanDevices, MissingFeaturesNamesEachRequirement) {
  DeviceInfo d = usableInfo(vk::PhysicalDeviceType::eDiscreteGpu, 0);
  EXPECT_TRUE(d.isHardware());
  EXPECT_EQ(d.missingFeatures(), "");
  d.int64Atomics = false;
  EXPECT_THAT(d.missingFeatures(), HasSubstr("shaderBufferInt64Atomics (64-bit atomic adds on storage buffers)"));
  d.scalarBlockLayout = false;
  d.shaderInt64 = false;
  d.computeQueueFamily.reset();
  d.apiVersion = VK_API_VERSION_1_1;
  const std::string m = d.missingFeatures();
  EXPECT_THAT(m, HasSubstr("scalarBlockLayout"));
  EXPECT_THAT(m, HasSubstr("shaderInt64"));
  EXPECT_THAT(m, HasSubstr("compute queue"));
  EXPECT_THAT(m, HasSubstr("Vulkan 1.2.0"));
  EXPECT_THAT(describeDevices({d}), HasSubstr("NOT usable: lacks"));
}

TEST(VulkanDevices, PreferredDeviceIsHardwareFirstThenCpu) {
  std::vector<DeviceInfo> devs = {usableInfo(vk::PhysicalDeviceType::eCpu, 0),
                                  usableInfo(vk::PhysicalDeviceType::eDiscreteGpu, 1),
                                  usableInfo(vk::PhysicalDeviceType::eVirtualGpu, 2),
                                  usableInfo(vk::PhysicalDeviceType::eIntegratedGpu, 3),
                                  usableInfo(vk::PhysicalDeviceType::eDiscreteGpu, 4)};
  devs[1].int64Atomics = false;  // unusable discrete GPUs are skipped
  EXPECT_EQ(preferredDevice(devs), std::optional<size_t>(4));
  devs[4].scalarBlockLayout = false;
  EXPECT_EQ(preferredDevice(devs), std::optional<size_t>(3));
  devs[3].shaderInt64 = false;
  EXPECT_EQ(preferredDevice(devs), std::optional<size_t>(2));
  devs[2].computeQueueFamily.reset();
  EXPECT_EQ(preferredDevice(devs), std::optional<size_t>(0));
  devs[0].apiVersion = VK_API_VERSION_1_0;
  EXPECT_EQ(preferredDevice(devs), std::nullopt);
  EXPECT_EQ(preferredDevice({}), std::nullopt);
}

TEST(VulkanContext, CreatesOnTheUsableDevice) {
  const auto devices = enumerateDevices();
  auto ctx = Context::create();
  ASSERT_TRUE(ctx);
  EXPECT_EQ(ctx->info().missingFeatures(), "");
  const auto best = preferredDevice(devices);
  ASSERT_TRUE(best);
  EXPECT_EQ(ctx->info().index, devices[*best].index);
  EXPECT_EQ(ctx->info().name, devices[*best].name);
  EXPECT_TRUE(*ctx->device());

  auto byIndex = Context::create(ctx->info().index);
  EXPECT_EQ(byIndex->info().name, ctx->info().name);
}

TEST(VulkanContext, RejectsAnUnknownDeviceIndex) {
  const std::string msg = vulkanErrorOf([] { Context::create(1000); });
  EXPECT_THAT(msg, HasSubstr("index 1000"));
  EXPECT_THAT(msg, HasSubstr("llvmpipe"));
}

TEST(VulkanContext, SubmitAndWaitRefusesReentryAndStaysUsable) {
  auto ctx = Context::create();
  const std::string msg = vulkanErrorOf([&] {
    ctx->submitAndWait([&](const vk::raii::CommandBuffer&) { ctx->submitAndWait([](const auto&) {}); });
  });
  EXPECT_THAT(msg, HasSubstr("inside its own recording callback"));
  bool ran = false;
  ctx->submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
    computeBarrier(cmd);
    ran = true;
  });
  EXPECT_TRUE(ran);
}

TEST(VulkanContext, MemoryTypeIndexHonoursWantedAndPreferred) {
  auto ctx = Context::create();
  const auto& mem = ctx->memoryProperties();
  const uint32_t all = (1u << mem.memoryTypeCount) - 1;
  const auto hv = vk::MemoryPropertyFlagBits::eHostVisible;
  const uint32_t t = ctx->memoryTypeIndex(all, hv, vk::MemoryPropertyFlagBits::eHostCached);
  EXPECT_TRUE(mem.memoryTypes[t].propertyFlags & hv);
  const std::string msg = vulkanErrorOf([&] { (void)ctx->memoryTypeIndex(0, hv); });
  EXPECT_THAT(msg, HasSubstr("no memory type"));
  EXPECT_THAT(msg, HasSubstr("HostVisible"));
}

// --- buffers ---------------------------------------------------------------

class VulkanBuffer : public ::testing::Test {
 protected:
  std::unique_ptr<Context> ctx = Context::create();
};

TEST_F(VulkanBuffer, RoundTripsThroughBothPlacementsWithOffsets) {
  for (MemoryPlacement placement : {MemoryPlacement::HostVisible, MemoryPlacement::DeviceLocal}) {
    SCOPED_TRACE(placement == MemoryPlacement::HostVisible ? "host-visible" : "device-local");
    const size_t n = 1001;  // not a whole number of words
    Buffer buf(*ctx, n, {}, placement);
    EXPECT_EQ(buf.size(), n);
    EXPECT_TRUE(buf.handle());
    const auto whole = pattern(n, 1);
    buf.upload(whole.data(), n);
    const auto part = pattern(100, 2);
    buf.upload(part.data(), part.size(), 901);  // ends exactly at the end
    const auto mid = pattern(13, 3);
    buf.upload(mid.data(), mid.size(), 7);

    auto expected = whole;
    std::copy(part.begin(), part.end(), expected.begin() + 901);
    std::copy(mid.begin(), mid.end(), expected.begin() + 7);
    std::vector<unsigned char> got(n);
    buf.download(got.data(), n);
    EXPECT_EQ(got, expected);
    std::vector<unsigned char> slice(50);
    buf.download(slice.data(), slice.size(), 3);
    EXPECT_TRUE(std::equal(slice.begin(), slice.end(), expected.begin() + 3));
  }
}

TEST_F(VulkanBuffer, StagingPathRoundTripsAcrossChunks) {
  // Beyond one 64 MiB staging chunk, at odd offsets.
  const size_t n = (64u << 20) + 4096;
  Buffer buf(*ctx, n, {}, MemoryPlacement::DeviceLocal);
  const auto data = pattern(n - 12, 4);
  BufferTestAccess::uploadStaged(buf, data.data(), data.size(), 12);
  std::vector<unsigned char> got(data.size() - 5);
  BufferTestAccess::downloadStaged(buf, got.data(), got.size(), 17);
  EXPECT_TRUE(std::equal(got.begin(), got.end(), data.begin() + 5));
  std::vector<unsigned char> viaMap(100);
  buf.download(viaMap.data(), viaMap.size(), 12);
  EXPECT_TRUE(std::equal(viaMap.begin(), viaMap.end(), data.begin()));
}

TEST_F(VulkanBuffer, FillZeroClearsEveryByte) {
  for (MemoryPlacement placement : {MemoryPlacement::HostVisible, MemoryPlacement::DeviceLocal}) {
    const size_t n = 4099;  // the last word is partial
    Buffer buf(*ctx, n, {}, placement);
    const auto data = pattern(n, 5);
    buf.upload(data.data(), n);
    buf.fillZero();
    std::vector<unsigned char> got(n, 0xff);
    buf.download(got.data(), n);
    EXPECT_EQ(std::count(got.begin(), got.end(), 0), ptrdiff_t(n));
  }
}

TEST_F(VulkanBuffer, RefusesOutOfBoundsCopiesAndEmptyBuffers) {
  Buffer buf(*ctx, 64, {}, MemoryPlacement::HostVisible);
  std::vector<unsigned char> host(128);
  EXPECT_THAT(vulkanErrorOf([&] { buf.upload(host.data(), 65); }), HasSubstr("overflows the 64-byte buffer"));
  EXPECT_THAT(vulkanErrorOf([&] { buf.upload(host.data(), 8, 60); }), HasSubstr("8 bytes at offset 60"));
  EXPECT_THAT(vulkanErrorOf([&] { buf.download(host.data(), 1, 64); }), HasSubstr("overflows"));
  EXPECT_THAT(vulkanErrorOf([&] { buf.download(host.data(), 2, ~vk::DeviceSize(0)); }), HasSubstr("overflows"));
  buf.upload(host.data(), 0, 64);  // empty copies at the end are fine
  EXPECT_THAT(vulkanErrorOf([&] { Buffer(*ctx, 0, {}, MemoryPlacement::DeviceLocal); }), HasSubstr("0 bytes"));

  Buffer moved = std::move(buf);
  EXPECT_EQ(moved.size(), 64u);
  EXPECT_EQ(buf.size(), 0u);  // NOLINT(bugprone-use-after-move): moved-from is documented empty
  EXPECT_FALSE(buf.handle());
}

// --- compute ---------------------------------------------------------------

struct Push {
  uint64_t addend;
  uint32_t invocations;
  uint32_t rowInvocations;
};
static_assert(sizeof(Push) == 16);

class VulkanCompute : public ::testing::Test {
 protected:
  static constexpr uint32_t kLocalSize = 64, kSlots = 7;
  std::unique_ptr<Context> ctx = Context::create();
  ComputePipeline makePipeline() {
    return ComputePipeline(*ctx, embedded::spv_vk_test_atomic_counters(), {{.binding = 0, .count = 2}}, sizeof(Push),
                           {{0, kLocalSize}, {1, kSlots}});
  }
};

TEST_F(VulkanCompute, Int64AtomicCountersAreExact) {
  constexpr uint32_t n = 100003;
  constexpr uint64_t preset2 = 0xffffffffull - 7, preset3 = 5;
  constexpr uint64_t addend = 0x1ffffffffull;  // low word overflows on the second add
  const uint32_t groupsX = (n + 2 * kLocalSize - 1) / (2 * kLocalSize);
  const Push push{.addend = addend, .invocations = n, .rowInvocations = groupsX * kLocalSize};

  Buffer a(*ctx, 5 * sizeof(uint64_t), {}, MemoryPlacement::DeviceLocal);
  const std::vector<uint64_t> presetA = {0, 0, preset2, preset3, 0};
  a.upload(presetA.data(), 40);

  // counters[1] lives at an aligned offset inside b, between sentinels.
  const vk::DeviceSize offset = std::max<vk::DeviceSize>(ctx->info().minStorageBufferOffsetAlignment, 64);
  const vk::DeviceSize slotsBytes = kSlots * sizeof(uint64_t);
  Buffer b(*ctx, offset + slotsBytes + 8, {}, MemoryPlacement::HostVisible);
  b.fillZero();
  const std::vector<unsigned char> front(offset, 0xab), back(8, 0xcd);
  b.upload(front.data(), front.size());
  b.upload(back.data(), back.size(), offset + slotsBytes);

  auto pipeline = makePipeline();
  pipeline.bindBuffer(0, 0, a);
  pipeline.bindBuffer(0, 1, b, offset, slotsBytes);
  ctx->submitAndWait([&](const vk::raii::CommandBuffer& cmd) { pipeline.recordDispatch(cmd, &push, groupsX, 2); });

  std::vector<uint64_t> gotA(5);
  a.download(gotA.data(), 40);
  EXPECT_EQ(gotA[0], n);
  EXPECT_EQ(gotA[1], uint64_t(n) * (n - 1) / 2);
  EXPECT_EQ(gotA[2], preset2 + n);
  EXPECT_GT(gotA[2], 0xffffffffull);  // carried past 2^32
  EXPECT_EQ(gotA[3], preset3 + uint64_t(n) * 0xffffffffull);
  EXPECT_EQ(gotA[4], kLocalSize);  // the specialisation constant took effect

  std::vector<uint64_t> slots(kSlots);
  b.download(slots.data(), slotsBytes, offset);
  for (uint32_t j = 0; j < kSlots; ++j) {
    const uint64_t hits = n / kSlots + (j < n % kSlots ? 1 : 0);
    EXPECT_EQ(slots[j], hits * addend) << "slot " << j;
  }
  std::vector<unsigned char> gotFront(offset), gotBack(8);
  b.download(gotFront.data(), offset);
  b.download(gotBack.data(), 8, offset + slotsBytes);
  EXPECT_EQ(gotFront, front);
  EXPECT_EQ(gotBack, back);

  // A second pass in one command buffer, ordered by the barrier, doubles everything.
  ctx->submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
    a.recordFillZero(cmd);
    pipeline.recordDispatch(cmd, &push, groupsX, 2);
    computeBarrier(cmd);
    pipeline.recordDispatch(cmd, &push, groupsX, 2);
  });
  a.download(gotA.data(), 40);
  EXPECT_EQ(gotA[0], 2 * uint64_t(n));
  EXPECT_EQ(gotA[1], uint64_t(n) * (n - 1));
  b.download(slots.data(), slotsBytes, offset);
  EXPECT_EQ(slots[0], 3 * (n / kSlots + 1) * addend);
}

// Pipelines of one key share their compiled objects on the context (made
// once), yet each keeps its own descriptor set.
TEST_F(VulkanCompute, SameKeySharesCompiledPipelineButNotBindings) {
  int made = 0;
  const auto make = [&]() -> std::shared_ptr<void> { ++made; return std::make_shared<int>(made); };
  const auto first = ctx->sharedPipeline("test key", make);
  const auto second = ctx->sharedPipeline("test key", make);
  const auto other = ctx->sharedPipeline("other key", make);
  EXPECT_EQ(made, 2);
  EXPECT_EQ(first, second);
  EXPECT_NE(first, other);

  constexpr uint32_t n = 1000;
  const uint32_t groupsX = (n + 2 * kLocalSize - 1) / (2 * kLocalSize);
  const Push push{.addend = 1, .invocations = n, .rowInvocations = groupsX * kLocalSize};
  auto p1 = makePipeline();
  auto p2 = makePipeline();
  Buffer a1(*ctx, 5 * sizeof(uint64_t), {}, MemoryPlacement::HostVisible), s1(*ctx, kSlots * 8, {}, MemoryPlacement::HostVisible);
  Buffer a2(*ctx, 5 * sizeof(uint64_t), {}, MemoryPlacement::HostVisible), s2(*ctx, kSlots * 8, {}, MemoryPlacement::HostVisible);
  for (Buffer* b : {&a1, &s1, &a2, &s2}) b->fillZero();
  p1.bindBuffer(0, 0, a1);
  p1.bindBuffer(0, 1, s1);
  p2.bindBuffer(0, 0, a2);
  p2.bindBuffer(0, 1, s2);
  ctx->submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
    p1.recordDispatch(cmd, &push, groupsX, 2);
    computeBarrier(cmd);
    p2.recordDispatch(cmd, &push, groupsX, 2);
    computeBarrier(cmd);
    p2.recordDispatch(cmd, &push, groupsX, 2);
  });
  std::vector<uint64_t> got1(5), got2(5);
  a1.download(got1.data(), 40);
  a2.download(got2.data(), 40);
  EXPECT_EQ(got1[0], n);
  EXPECT_EQ(got2[0], 2 * uint64_t(n));
}

TEST_F(VulkanCompute, DispatchBeyondTheGroupLimitThrows) {
  Buffer a(*ctx, 64, {}, MemoryPlacement::DeviceLocal);
  auto pipeline = makePipeline();
  pipeline.bindBuffer(0, 0, a);
  const Push push{.addend = 1, .invocations = 0, .rowInvocations = 0};
  std::string msg = vulkanErrorOf([&] {
    ctx->submitAndWait([&](const vk::raii::CommandBuffer& cmd) { pipeline.recordDispatch(cmd, &push, 1); });
  });
  EXPECT_THAT(msg, HasSubstr("binding 0 element 1 has no buffer bound"));
  pipeline.bindBuffer(0, 1, a);

  const auto limit = ctx->info().maxComputeWorkGroupCount;
  msg = vulkanErrorOf([&] {
    ctx->submitAndWait(
        [&](const vk::raii::CommandBuffer& cmd) { pipeline.recordDispatch(cmd, &push, limit[0] + 1); });
  });
  EXPECT_THAT(msg, HasSubstr("maxComputeWorkGroupCount"));
  EXPECT_THAT(msg, HasSubstr(std::to_string(limit[0] + 1)));
  EXPECT_THAT(vulkanErrorOf([&] {
                ctx->submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
                  pipeline.recordDispatch(cmd, &push, 1, 1, limit[2] + 1);
                });
              }),
              HasSubstr("maxComputeWorkGroupCount"));
  EXPECT_THAT(vulkanErrorOf([&] {
                ctx->submitAndWait(
                    [&](const vk::raii::CommandBuffer& cmd) { pipeline.recordDispatch(cmd, nullptr, 1); });
              }),
              HasSubstr("push constants"));
  // The limit itself is allowed, and the context survives the failures.
  ctx->submitAndWait([&](const vk::raii::CommandBuffer& cmd) { pipeline.recordDispatch(cmd, &push, limit[0]); });
}

TEST_F(VulkanCompute, BindBufferRefusesRangesOverMaxStorageBufferRange) {
  const uint64_t maxRange = ctx->info().maxStorageBufferRange;
  const vk::DeviceSize align = std::max<vk::DeviceSize>(ctx->info().minStorageBufferOffsetAlignment, 4);
  Buffer big(*ctx, maxRange + align, {}, MemoryPlacement::DeviceLocal);
  auto pipeline = makePipeline();

  std::string msg = vulkanErrorOf([&] { pipeline.bindBuffer(0, 0, big); });
  EXPECT_THAT(msg, HasSubstr("maxStorageBufferRange"));
  EXPECT_THAT(msg, HasSubstr(std::to_string(maxRange)));
  EXPECT_THAT(vulkanErrorOf([&] { pipeline.bindBuffer(0, 1, big, 0, maxRange + 4); }),
              HasSubstr("maxStorageBufferRange"));
  // Exactly the limit is fine, as is the whole rest after an offset.
  pipeline.bindBuffer(0, 0, big, 0, maxRange);
  pipeline.bindBuffer(0, 1, big, align);

  EXPECT_THAT(vulkanErrorOf([&] { pipeline.bindBuffer(3, 0, big, 0, 64); }), HasSubstr("binding 3 is not declared"));
  EXPECT_THAT(vulkanErrorOf([&] { pipeline.bindBuffer(0, 2, big, 0, 64); }), HasSubstr("out of range"));
  EXPECT_THAT(vulkanErrorOf([&] { pipeline.bindBuffer(0, 0, big, big.size(), 4); }), HasSubstr("past the end"));
  EXPECT_THAT(vulkanErrorOf([&] { pipeline.bindBuffer(0, 0, big, 0, big.size() + 4); }),
              HasSubstr("does not fit"));
  if (align > 4) {
    EXPECT_THAT(vulkanErrorOf([&] { pipeline.bindBuffer(0, 0, big, 4, 64); }),
                HasSubstr("minStorageBufferOffsetAlignment"));
  }
}

TEST_F(VulkanCompute, RejectsMalformedPipelines) {
  const auto spv = embedded::spv_vk_test_atomic_counters();
  EXPECT_THAT(vulkanErrorOf([&] { ComputePipeline(*ctx, spv.first(spv.size() - 1), {{.binding = 0}}, 0); }),
              HasSubstr("4-byte words"));
  const std::vector<unsigned char> zeros(64, 0);
  EXPECT_THAT(vulkanErrorOf([&] { ComputePipeline(*ctx, zeros, {{.binding = 0}}, 0); }), HasSubstr("magic"));
  EXPECT_THAT(vulkanErrorOf([&] { ComputePipeline(*ctx, spv, {{.binding = 0, .count = 2}}, 4096); }),
              HasSubstr("maxPushConstantsSize"));
  EXPECT_THAT(vulkanErrorOf([&] { ComputePipeline(*ctx, spv, {{.binding = 0}, {.binding = 0}}, 16); }),
              HasSubstr("declared twice"));
  EXPECT_THAT(
      vulkanErrorOf([&] { ComputePipeline(*ctx, spv, {{.binding = 0, .count = 100000}}, 16); }),
      HasSubstr("maxPerStageDescriptorStorageBuffers"));
}

// --- timestamps ------------------------------------------------------------

TEST_F(VulkanCompute, TimestampsIncreaseAcrossPasses) {
  constexpr uint32_t n = 200000;
  const uint32_t groupsX = (n + kLocalSize - 1) / kLocalSize;
  const Push push{.addend = 1, .invocations = n, .rowInvocations = groupsX * kLocalSize};
  Buffer a(*ctx, 64, {}, MemoryPlacement::DeviceLocal);
  Buffer b(*ctx, kSlots * 8, {}, MemoryPlacement::DeviceLocal);
  a.fillZero();
  b.fillZero();
  auto pipeline = makePipeline();
  pipeline.bindBuffer(0, 0, a);
  pipeline.bindBuffer(0, 1, b);

  TimestampQueries queries(*ctx, 3);
  EXPECT_EQ(queries.count(), 3u);
  ctx->submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
    queries.reset(cmd);
    queries.write(cmd, 0);
    pipeline.recordDispatch(cmd, &push, groupsX);
    computeBarrier(cmd);
    queries.write(cmd, 1);
    pipeline.recordDispatch(cmd, &push, groupsX);
    computeBarrier(cmd);
    queries.write(cmd, 2);
  });
  const auto ns = queries.readNanoseconds();
  ASSERT_EQ(ns.size(), 3u);
  EXPECT_LT(ns[0], ns[1]);
  EXPECT_LT(ns[1], ns[2]);
  const auto ticks = queries.readTicks();
  EXPECT_LT(ticks[0], ticks[1]);
  EXPECT_LT(ticks[1], ticks[2]);

  uint64_t count = 0;
  a.download(&count, 8);
  EXPECT_EQ(count, 2 * uint64_t(n));
}

TEST_F(VulkanCompute, UnwrittenTimestampIsAnErrorNotAHang) {
  TimestampQueries queries(*ctx, 2);
  EXPECT_THAT(vulkanErrorOf([&] {
                ctx->submitAndWait([&](const vk::raii::CommandBuffer& cmd) { queries.write(cmd, 2); });
              }),
              HasSubstr("out of range"));
  ctx->submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
    queries.reset(cmd);
    queries.write(cmd, 0);
  });
  EXPECT_THAT(vulkanErrorOf([&] { (void)queries.readNanoseconds(); }), HasSubstr("query 1 has no result"));
  if (ctx->hostQueryResetEnabled()) {
    queries.resetFromHost();
    EXPECT_THAT(vulkanErrorOf([&] { (void)queries.readTicks(); }), HasSubstr("query 0 has no result"));
  }
  EXPECT_THAT(vulkanErrorOf([&] { TimestampQueries(*ctx, 0); }), HasSubstr("0 queries"));
}

// The grid covers every invocation, stays within the limit, and leaves
// fewer than one workgroup per row idle (never a whole row), including at
// the sizes that once left a row of 65534 empty groups.
TEST(DispatchGrid, CoversTheRangeWithFewerIdleGroupsThanRows) {
  constexpr uint32_t kMaxX = 65535;
  for (uint32_t workgroup : {1u, 64u, 256u}) {
    for (uint64_t invocations :
         {uint64_t(1), uint64_t(63), uint64_t(65535) * 64, uint64_t(65536) * 64, uint64_t(1) << 22,
          uint64_t(1) << 23, uint64_t(11'007'525), uint64_t(1) << 31}) {
      const DispatchGrid grid = dispatchGridFor(invocations, workgroup, kMaxX);
      const uint64_t groups = (invocations + workgroup - 1) / workgroup;
      const uint64_t launched = uint64_t(grid.groupsX) * grid.groupsY;
      SCOPED_TRACE(::testing::Message() << invocations << " invocations in groups of " << workgroup);
      EXPECT_LE(grid.groupsX, kMaxX);
      EXPECT_EQ(grid.invocationsPerRow, grid.groupsX * workgroup);
      EXPECT_GE(launched, groups);                   // every invocation has a slot
      EXPECT_LT(launched - groups, grid.groupsY);    // fewer idle groups than rows
      EXPECT_EQ(grid.groupsY, (groups + kMaxX - 1) / kMaxX);  // no more rows than needed
    }
  }
}

}  // namespace
}  // namespace spectrace::vk_util
