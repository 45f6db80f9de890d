// The GPU's Philox (shaders/philox.glsl) against the CPU's (Random123):
// identical integers for the first 10^6 draws of several streams.
#include <gtest/gtest.h>

#include "backend/vulkan_tracer.h"
#include "rng/philox.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

struct Stream {
  uint64_t seed;
  uint64_t firstIndex;
  uint32_t block;
};

TEST(GpuRng, FirstMillionDrawsOfSeveralStreamsMatchTheCpu) {
  const auto& vulkan = testing::sharedVulkan();
  // Seeds with high words set, beam indices past 2^32 and 2^40, all blocks.
  const Stream streams[] = {{1, 0, 0}, {1, 0, 1}, {1, 0, 2}, {0xfedcba9876543210ull, 0, 0},
                            {42, (1ull << 32) - 500000, 0}, {7, 1ull << 40, 1}};
  constexpr uint32_t kCount = 1'000'000;
  for (const Stream& s : streams) {
    const auto gpu = philoxOnGpu(vulkan, s.seed, s.firstIndex, kCount, s.block);
    uint64_t mismatches = 0;
    for (uint32_t i = 0; i < kCount; ++i) {
      const auto cpu = philoxWords(s.seed, s.firstIndex + i, s.block);
      for (int k = 0; k < 4; ++k) mismatches += gpu[i][k] != cpu[k];
    }
    EXPECT_EQ(mismatches, 0u) << "seed " << s.seed << " first " << s.firstIndex << " block " << s.block;
  }
}

}  // namespace
}  // namespace spectrace
