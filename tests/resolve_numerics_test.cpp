// The resolve pass over very many bins. llvmpipe ends a shader loop after
// 65535 iterations, which once cut the sum of a pixel's bins short on the
// GPU (irradiance.E 0.957x the CPU's at 70,000 bins, 0.728x at 100,000,
// while RGB and XYZ, taken from the exact-colour sums, agreed). At 65,535,
// 65,536 and 100,000 bins (the largest a scene may have), the GPU's
// irradiance must equal the CPU reference's to float rounding, and both
// must hold every counted beam.
#include <gtest/gtest.h>

#include <cmath>

#include "backend/cpu_tracer.h"
#include "backend/vulkan_tracer.h"
#include "compile/compile_scene.h"
#include "render/renderer.h"
#include "scene/scene_limits.h"
#include "spectrum/cie_data.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

class ResolveManyBins : public ::testing::TestWithParam<int> {};

TEST_P(ResolveManyBins, GpuIrradianceSumsEveryBin) {
  const int bins = GetParam();
  Scene scene = testing::bareSensorScene(0.01, 0.01, 2, 2, bins);
  scene.lights = {testing::pointLight({0.0, 0.0, 0.1}, 1.0, *cieIlluminant("D65"), "D65")};
  const CompiledScene plan = compileScene(scene, 1);
  constexpr uint64_t kBeams = 200'000;
  VulkanTracer gpu(testing::sharedVulkan(), plan);
  CpuTracer cpu(plan, 2);
  gpu.trace(0, kBeams);
  cpu.trace(0, kBeams);
  const SpectralHistogram gpuFilm = gpu.download(), cpuFilm = cpu.download();
  ASSERT_EQ(gpuFilm.counts(), cpuFilm.counts()) << "the same beams land in the same bins";
  ASSERT_GT(gpuFilm.total(), 0u);
  // Beams in bins past 65535 exist here (D65 has power up to 830 nm), so a
  // cut-short sum would lose them.
  const ResolveParameters parameters = resolveParametersFor(scene, plan, kBeams);
  const RenderImage fromGpu = gpu.develop(parameters), fromCpu = cpu.develop(parameters);
  for (size_t p = 0; p < fromGpu.irradiance.size(); ++p) {
    // The GPU converts the exact uint64 total to float once and multiplies
    // by a float scale: two roundings, 1.2e-7 relative; 1e-6 leaves margin.
    EXPECT_NEAR(fromGpu.irradiance[p], fromCpu.irradiance[p], 1e-6 * std::abs(fromCpu.irradiance[p]))
        << bins << " bins, pixel " << p;
  }
}

INSTANTIATE_TEST_SUITE_P(Bins, ResolveManyBins, ::testing::Values(65535, 65536, kMaxBins));

}  // namespace
}  // namespace spectrace
