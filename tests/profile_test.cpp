// The bench's cost profile (shaders/profile.h) and ceiling (backend/ceiling.h):
// the full stage is the normal kernel, every stage runs on both devices and
// draws the same beams on both, and the ceiling traces the throughput
// scene's geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numeric>

#include "backend/cpu_tracer.h"
#include "backend/vulkan_tracer.h"
#include "bench/optics_bench.h"
#include "bench/throughput_ceiling.h"
#include "compile/compile_scene.h"
#include "render/renderer.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

// A small throughput scene: a D65 disk before a bare sensor, unaimed so the
// profile's unaimed stages trace the same beams as the full kernel.
Scene profileScene() {
  Scene scene = testing::bareSensorScene(0.02, 0.02, 32, 32, 16);
  Light disk = testing::surfaceLight(LightType::Disk, {0.0, 0.0, 0.02}, {0, 0, -1}, 1.0, *cieIlluminant("D65"));
  disk.radiusM = 0.01;
  scene.lights = {disk};
  return scene;
}

CompiledScene profilePlan(bool aim) {
  CompileOptions options;
  options.aim = aim;
  options.colourFromBins = false;  // per-beam colour, so the exact-colour stage has work to do
  return compileScene(profileScene(), 7, options);
}

constexpr uint64_t kBeams = 300'000;

SpectralHistogram cpuProfile(const CompiledScene& plan, uint32_t stage) {
  CpuTracer tracer(plan, 2, stage);
  tracer.trace(0, kBeams);
  return tracer.download();
}
SpectralHistogram gpuProfile(const CompiledScene& plan, uint32_t stage) {
  VulkanTracer tracer(testing::sharedVulkan(), plan, 64, kSpecialiseAll, nullptr, stage);
  tracer.trace(0, kBeams);
  return tracer.download();
}

void expectSameHistogram(const SpectralHistogram& a, const SpectralHistogram& b, const std::string& what) {
  EXPECT_EQ(a.counts(), b.counts()) << what;
  EXPECT_EQ(a.colourSums(), b.colourSums()) << what;
  EXPECT_EQ(a.squaredWeightSums(), b.squaredWeightSums()) << what;
  EXPECT_EQ(a.countedBeams, b.countedBeams) << what;
}

// The specialisation constant's default is the whole kernel: a render with
// the full stage asked for explicitly is bit-identical to a plain one, on
// both devices, and the CPU's profileBeam at the full stage is traceAndCountBeam.
TEST(Profile, FullStageIsTheNormalKernel) {
  for (bool aim : {true, false}) {
    const CompiledScene plan = profilePlan(aim);
    VulkanTracer plain(testing::sharedVulkan(), plan);
    plain.trace(0, kBeams);
    const SpectralHistogram reference = plain.download();
    EXPECT_GT(reference.countedBeams, 1000u);
    expectSameHistogram(gpuProfile(plan, device::kProfileStageFull), reference, "gpu full stage");
    expectSameHistogram(cpuProfile(plan, device::kProfileStageFull), reference, "cpu full stage");
  }
  RenderOptions options;
  options.beams = kBeams;
  options.device = DeviceChoice::Gpu;
  const RenderResult plain = render(profileScene(), options);
  options.tracer.profileStage = device::kProfileStageFull;
  const RenderResult full = render(profileScene(), options);
  EXPECT_EQ(plain.image.rgb, full.image.rgb);
  EXPECT_EQ(plain.image.irradiance, full.image.irradiance);
}

// Every stage runs on both devices and draws the same beams on both; the
// stages before counting count nothing, and unaimed, the last two stages
// before the full kernel count what it counts.
TEST(Profile, EveryStageRunsOnBothDevicesAlike) {
  const CompiledScene plan = profilePlan(false);
  ASSERT_FALSE(plan.film.weighted());
  const SpectralHistogram full = cpuProfile(plan, device::kProfileStageFull);
  for (uint32_t stage = device::kProfileStagePhilox; stage <= device::kProfileStageFull; ++stage) {
    const std::string what = "stage " + std::to_string(stage);
    const SpectralHistogram cpu = cpuProfile(plan, stage);
    expectSameHistogram(gpuProfile(plan, stage), cpu, what + ", gpu vs cpu");
    const uint64_t total = std::accumulate(cpu.counts().begin(), cpu.counts().end(), uint64_t(0));
    if (stage < device::kProfileStageCounting) {
      // Only the dead-code guard writes, when a beam's 32-bit hash equals a
      // constant: with this fixed seed, for none of these beams.
      EXPECT_EQ(total, 0u) << what;
      EXPECT_EQ(cpu.countedBeams, 0u) << what;
    } else {
      EXPECT_EQ(cpu.counts(), full.counts()) << what << ": unaimed, the bins are the full kernel's";
      EXPECT_EQ(cpu.countedBeams, full.countedBeams) << what;
      EXPECT_GT(cpu.countedBeams, 1000u) << what;
    }
    if (stage == device::kProfileStageCounting) {
      const uint64_t colour = std::accumulate(cpu.colourSums().begin(), cpu.colourSums().end(), uint64_t(0));
      EXPECT_EQ(colour, 0u) << what << ": exact colour is off";
    }
    if (stage >= device::kProfileStageColour) {
      EXPECT_EQ(cpu.colourSums(), full.colourSums()) << what;
    }
  }
}

// The objects stages, on a small mesh scene (light paths), on both devices:
// the first-hit stage counts nothing, and the no-connection stage is the
// whole kernel with the plan's connections switched off (the film's layout
// kept: compiled without connections, the film would count in other units)
// and counts fewer beams than the full kernel.
TEST(Profile, ObjectsStagesCutTheKernelAmongObjects) {
  CompileOptions options;
  options.cameraPaths = false;
  const CompiledScene plan = compileScene(opticsMeshScene(1'000), 7, options);
  ASSERT_EQ(plan.device.constants.connect, 1u);
  CompiledScene unconnected = plan;
  unconnected.device.constants.connect = 0;
  auto cpuTrace = [](const CompiledScene& p, uint32_t stage) {
    CpuTracer tracer(p, 2, stage);
    tracer.trace(0, kBeams);
    return tracer.download();
  };
  auto gpuTrace = [](const CompiledScene& p, uint32_t stage) {
    VulkanTracer tracer(testing::sharedVulkan(), p, 64, kSpecialiseAll, nullptr, stage);
    tracer.trace(0, kBeams);
    return tracer.download();
  };
  for (bool gpu : {false, true}) {
    const auto trace = gpu ? std::function(gpuTrace) : std::function(cpuTrace);
    const std::string what = gpu ? "gpu" : "cpu";
    const SpectralHistogram full = trace(plan, device::kProfileStageFull);
    EXPECT_GT(full.countedBeams, 1000u) << what;
    const SpectralHistogram firstHit = trace(plan, device::kProfileStageObjectsFirstHit);
    EXPECT_EQ(std::accumulate(firstHit.counts().begin(), firstHit.counts().end(), uint64_t(0)), 0u) << what;
    EXPECT_EQ(firstHit.countedBeams, 0u) << what;
    const SpectralHistogram noConnection = trace(plan, device::kProfileStageObjectsNoConnection);
    expectSameHistogram(noConnection, trace(unconnected, device::kProfileStageFull), what + " no-connection stage");
    EXPECT_LT(noConnection.countedBeams, full.countedBeams) << what;
  }
}

// The ceiling kernel traces the throughput scene's geometry: its hit rate
// is the analog (unaimed) full kernel's, within 5 sigma of the difference of
// two binomial fractions; the GPU and the CPU ceiling count the same beams.
TEST(Ceiling, HitsAsOftenAsTheFullKernelOnBothDevices) {
  const CeilingScene scene = throughputCeilingScene();
  constexpr uint64_t kCeilingBeams = 2'000'000;
  const CeilingResult cpu = Device::open(DeviceChoice::Cpu)->traceCeiling(scene, kCeilingBeams, 2);
  const CeilingResult gpu = Device::open(DeviceChoice::Gpu)->traceCeiling(scene, kCeilingBeams);
  EXPECT_GT(cpu.seconds, 0.0);
  EXPECT_GT(gpu.seconds, 0.0);
  // The same hashes and float operations; sin/cos and sqrt may round
  // differently on the device, moving a rare beam across a pixel edge.
  EXPECT_NEAR(double(gpu.hits), double(cpu.hits), 1e-4 * double(kCeilingBeams));

  Scene throughput = bareSensorScene(0.1, 0.1, 512, 512, 64);
  Light disk = surfaceLight(LightType::Disk, {0.0, 0.0, 0.1}, {0.0, 0.0, -1.0}, 1.0, *cieIlluminant("D65"), "D65");
  disk.radiusM = 0.05;
  throughput.lights = {disk};
  RenderOptions options;
  options.beams = kCeilingBeams;
  options.device = DeviceChoice::Cpu;
  options.tracer.cpuThreads = 2;
  options.plan.aim = false;
  const RenderResult spectrace = render(throughput, options);
  const double p1 = double(cpu.hits) / double(kCeilingBeams);
  const double p2 = double(spectrace.histogram.countedBeams) / double(kCeilingBeams);
  const double sigma = std::sqrt(p1 * (1 - p1) / double(kCeilingBeams) + p2 * (1 - p2) / double(kCeilingBeams));
  EXPECT_GT(p1, 0.1);
  EXPECT_NEAR(p1, p2, 5.0 * sigma);  // 5 sigma: the two estimators are independent
}

}  // namespace
}  // namespace spectrace
