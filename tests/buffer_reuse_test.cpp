// Device buffers are kept between the renders of one device and reused when
// the next scene's shapes fit: a big, then a small, then the big scene again
// allocate only for the first, and every render is bit-identical to the same
// scene rendered on a fresh device (reused histograms start from zero).
#include <gtest/gtest.h>

#include "backend/vulkan_tracer.h"
#include "render/renderer.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

Scene bigScene() {
  Scene scene = testing::bareSensorScene(0.02, 0.02, 96, 72, 40);
  scene.lights = {testing::pointLight({-0.005, 0.003, 0.004}, 0.5, makeBlackbodySpd(3000, 360, 830)),
                  testing::pointLight({0.004, -0.002, 0.005}, 0.3, makeBlackbodySpd(5000, 360, 830))};
  return scene;
}

Scene smallScene() {
  Scene scene = testing::bareSensorScene(0.02, 0.02, 40, 30, 24);
  scene.lights = {testing::pointLight({0.002, 0.001, 0.003}, 0.5, makeBlackbodySpd(2700, 360, 830))};
  return scene;
}

std::unique_ptr<Device> openGpu() {
  return Device::open(DeviceChoice::Gpu, {}, PipelineCacheOptions{false, ""});
}

RenderResult renderOn(const Device& device, const Scene& scene) {
  RenderOptions options;
  options.beams = 300000;
  options.seed = 11;
  return render(scene, options, device);
}

void expectIdentical(const RenderResult& a, const RenderResult& b, const char* what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(a.histogram.counts(), b.histogram.counts());
  EXPECT_EQ(a.histogram.colourSums(), b.histogram.colourSums());
  EXPECT_EQ(a.histogram.squaredWeightSums(), b.histogram.squaredWeightSums());
  EXPECT_EQ(a.histogram.countedBeams, b.histogram.countedBeams);
  EXPECT_EQ(a.image.rgb, b.image.rgb);
  EXPECT_EQ(a.image.xyz, b.image.xyz);
  EXPECT_EQ(a.image.irradiance, b.image.irradiance);
}

TEST(BufferReuse, BigSmallBigAllocatesOnceAndMatchesFreshDevices) {
  const auto shared = openGpu();
  ASSERT_EQ(shared->bufferAllocations(), 0u);
  const RenderResult big1 = renderOn(*shared, bigScene());
  const uint64_t afterBig = shared->bufferAllocations();
  EXPECT_GT(afterBig, 0u);
  ASSERT_GT(big1.histogram.countedBeams, 0u);
  const RenderResult small = renderOn(*shared, smallScene());
  EXPECT_EQ(shared->bufferAllocations(), afterBig) << "the small scene's buffers fit in the big one's";
  const RenderResult big2 = renderOn(*shared, bigScene());
  EXPECT_EQ(shared->bufferAllocations(), afterBig) << "the big scene's buffers were kept";

  const RenderResult bigAlone = renderOn(*openGpu(), bigScene());
  const RenderResult smallAlone = renderOn(*openGpu(), smallScene());
  expectIdentical(big1, bigAlone, "first big render");
  expectIdentical(small, smallAlone, "small render in reused buffers");
  expectIdentical(big2, bigAlone, "big render after the small one");
}

TEST(BufferReuse, BuffersThatDoNotFitAreAllocated) {
  const auto device = openGpu();
  renderOn(*device, smallScene());
  const uint64_t afterSmall = device->bufferAllocations();
  renderOn(*device, bigScene());
  EXPECT_GT(device->bufferAllocations(), afterSmall) << "the big histogram cannot fit in the small one's buffers";
}

// A buffer is reused only for a role whose usage it has: one made without
// the uniform-buffer bit is never handed out to be bound as a uniform buffer.
TEST(BufferReuse, ReusedBuffersHaveTheUsageAsked) {
  const vk_util::Context& context = testing::sharedVulkan();
  TracerBufferPool pool;
  pool.giveBack("table", pool.take(context, "table", 256, vk_util::MemoryPlacement::DeviceLocal));
  EXPECT_EQ(pool.allocations(), 1u);
  const vk_util::Buffer uniform = pool.take(context, "table", 64, vk_util::MemoryPlacement::DeviceLocal,
                                            vk::BufferUsageFlagBits::eUniformBuffer);
  EXPECT_EQ(pool.allocations(), 2u) << "the storage-only buffer must not be reused as a uniform buffer";
  EXPECT_TRUE(uniform.usage() & vk::BufferUsageFlagBits::eUniformBuffer);
  pool.giveBack("constants", pool.take(context, "constants", 64, vk_util::MemoryPlacement::DeviceLocal,
                                       vk::BufferUsageFlagBits::eUniformBuffer));
  const vk_util::Buffer again = pool.take(context, "constants", 64, vk_util::MemoryPlacement::DeviceLocal,
                                          vk::BufferUsageFlagBits::eUniformBuffer);
  EXPECT_EQ(pool.allocations(), 3u) << "a buffer with the usage asked is reused";
}

}  // namespace
}  // namespace spectrace
