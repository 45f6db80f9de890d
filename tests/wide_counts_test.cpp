// A weighted film's two-word counters (device_shared.h,
// kWeightUnitsFractional):
//  - wideFixedPoint gives x * 2^63 exactly for x >= 2^-39 and rounds
//    below without bias;
//  - the low word's carry reaches the high word on the device and in the
//    CPU reference, whatever the order of the adds: films preset with low
//    words just below 2^64 come back as preset + hits, exactly, on both;
//  - merge, and the two devices' films, agree word for word.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "backend/vulkan_tracer.h"
#include "camera/pinhole_camera.h"
#include "compile/compile_scene.h"
#include "film/spectral_histogram.h"
#include "kernel/beam_kernel.h"
#include "scene/scene_builders.h"
#include "support/cpu_trace.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

using u128 = unsigned __int128;

// An aimed disk light in front of a pinhole: every counted beam has its own
// fractional weight, so the film is weighted.
CompiledScene weightedPlan(bool perBeamColour) {
  Scene scene = bareSensorScene(0.036, 0.024, 12, 8, 6);
  scene.camera.model = pinholeModel({0.05, 0.0005});
  Light disk = surfaceLight(LightType::Disk, {0.0, 0.0, 0.3}, {0, 0, -1}, 1.0, *cieIlluminant("D65"));
  disk.radiusM = 0.2;
  scene.lights = {disk};
  CompileOptions options;
  options.colourFromBins = !perBeamColour;
  return compileScene(scene, 4242, options);
}

// x * 2^63 for a float x, exactly (x's 24-bit significand, shifted).
u128 exactScaled(float x) {
  int exponent = 0;
  const double significand = std::frexp(double(x), &exponent);  // x = s 2^e, s in [0.5, 1)
  const u128 m = u128(uint64_t(std::ldexp(significand, 24)));  // 24 bits, exact
  const int shift = exponent - 24 + 63;
  return shift >= 0 ? m << shift : m >> -shift;
}

TEST(WideCounts, FixedPointIsExactAboveTwoToTheMinus39) {
  device::BeamKernel k(device::TraceConstants{}, {}, {}, {});
  const float values[] = {1.0f,      0.5f,    0x1p-39f, 0x1.8p-39f, 1e-10f, 3.7f, 0.2f, 1.7e19f, 123456.78f,
                          2.5e-12f, 1.0e-5f, 0.999999f};
  for (const float x : values) {
    for (const float u : {0.0f, 0.5f, 0.999f}) {
      const device::WideCount w = k.wideFixedPoint(x, u);
      EXPECT_TRUE(wideValue(w) == exactScaled(x)) << "x = " << x << ", u = " << u;
    }
  }
}

TEST(WideCounts, FixedPointRoundsWithoutBiasBelowTwoToTheMinus39) {
  device::BeamKernel k(device::TraceConstants{}, {}, {}, {});
  // x * 2^63 = 3.3 and 0.0043 (a 25 um pinhole's connection at 1 m, in the
  // old 2^-24 units): rounded to floor or floor + 1, with the mean over a
  // grid of N uniforms within 1 / N of the fraction.
  for (const double scaled : {3.3, 0.0043, 1e6 + 0.25}) {
    const float x = float(scaled * 0x1p-63);
    const double exact = double(x) * 0x1p63;
    constexpr int kN = 100'000;
    double sum = 0.0;
    for (int i = 0; i < kN; ++i) {
      const device::WideCount w = k.wideFixedPoint(x, (float(i) + 0.5f) / float(kN));
      ASSERT_EQ(w.high, 0u);
      ASSERT_TRUE(double(w.low) == std::floor(exact) || double(w.low) == std::floor(exact) + 1.0) << scaled;
      sum += double(w.low);
    }
    EXPECT_NEAR(sum / kN, exact, 2.0 / kN + 1e-9 * exact) << scaled;
  }
}

// Low words within the hits' reach of 2^64, so most counters carry; high
// words at varied values.
SpectralHistogram presetNearCarry(const SpectralHistogram& hits) {
  SpectralHistogram preset = hits;
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c) {
    std::vector<uint64_t>& words = preset.channel(c);
    const std::vector<uint64_t>& added = hits.channel(c);
    for (size_t i = 0; i + 1 < words.size(); i += 2) {
      // Half the counters just wrap (the hits pass 2^64), the others stop short.
      const uint64_t reach = added[i] == 0 ? 1 : added[i] / 2 + 1;
      words[i] = (i / 2) % 2 == 0 ? UINT64_MAX - reach + 1 : UINT64_MAX - added[i];
      words[i + 1] = (i / 2) % 7 == 0 ? 0 : uint64_t(i) * 977;
    }
  }
  return preset;
}

// result == preset + hits as 128-bit numbers, counter by counter.
void expectWideSum(const SpectralHistogram& result, const SpectralHistogram& preset, const SpectralHistogram& hits,
                   const char* name) {
  ASSERT_TRUE(result.sameShape(preset)) << name;
  size_t wrong = 0, carried = 0;
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c)
    for (size_t i = 0; i < result.channel(c).size() / 2; ++i) {
      const u128 expected = wideValue(preset.counter(c, i)) + wideValue(hits.counter(c, i));
      carried += preset.counter(c, i).low + hits.counter(c, i).low < preset.counter(c, i).low;
      if (wideValue(result.counter(c, i)) != expected && ++wrong <= 5)
        ADD_FAILURE() << name << ": " << filmChannelName(c) << " counter " << i << " is off";
    }
  EXPECT_EQ(wrong, 0u) << name;
  EXPECT_GT(carried, 20u) << name << ": the presets must make counters carry";
}

TEST(WideCounts, CarriesAreExactOnBothDevices) {
  for (const bool perBeamColour : {false, true}) {
    const CompiledScene plan = weightedPlan(perBeamColour);
    ASSERT_TRUE(plan.film.weighted());
    constexpr uint64_t kFirst = 17, kBeams = 200'000;
    SpectralHistogram hits;
    CpuTraceOptions options;
    options.threads = 2;
    traceOnCpu(plan, kFirst, kBeams, hits, options);
    ASSERT_GT(hits.countedBeams, 1000u);

    VulkanTracer zeroed(testing::sharedVulkan(), plan);
    zeroed.trace(kFirst, kBeams);
    const SpectralHistogram gpuHits = zeroed.download();
    for (uint32_t c = 0; c < device::kFilmChannelCount; ++c)
      EXPECT_EQ(gpuHits.channel(c), hits.channel(c)) << filmChannelName(c) << ": device and CPU reference differ";

    const SpectralHistogram preset = presetNearCarry(hits);
    SpectralHistogram onCpu = preset;
    traceOnCpu(plan, kFirst, kBeams, onCpu, options);
    expectWideSum(onCpu, preset, hits, "CPU reference");

    VulkanTracer gpu(testing::sharedVulkan(), plan);
    gpu.upload(preset);
    gpu.trace(kFirst, kBeams / 2);  // two dispatches: carries within and between them
    gpu.trace(kFirst + kBeams / 2, kBeams - kBeams / 2);
    expectWideSum(gpu.download(), preset, hits, "device");

    SpectralHistogram merged = preset;
    merged.merge(hits);
    expectWideSum(merged, preset, hits, "merge");
  }
}

}  // namespace
}  // namespace spectrace
