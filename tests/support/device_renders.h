#pragma once
// A scene rendered on one device, or on both with the same beams, for the
// optics tests that check a closed form on the CPU's film after lavapipe's
// film has been shown equal to it.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <memory>

#include "backend/device.h"
#include "render/renderer.h"
#include "support/render_comparison.h"

namespace spectrace::testing {

// One device of each kind (Gpu, else Cpu) per test program, opened at first
// use: a device keeps its compiled pipelines, so a test's second render of
// the same pipeline skips lavapipe's compile, seconds a time.
inline const Device& sharedDevice(DeviceChoice device) {
  if (device == DeviceChoice::Gpu) {
    static const std::unique_ptr<Device> gpu = Device::open(DeviceChoice::Gpu);
    return *gpu;
  }
  static const std::unique_ptr<Device> cpu = Device::open(DeviceChoice::Cpu);
  return *cpu;
}

// On the shared device of its kind, without checkpoints; the general
// pipeline (nothing specialised to the scene) when asked. Prints the device, the time and the counted beams.
inline RenderResult renderOn(DeviceChoice device, const Scene& scene, uint64_t beams, uint64_t seed,
                             const CompileOptions& plan = {}, bool generalPipeline = false) {
  RenderOptions options;
  if (generalPipeline) options.tracer.specialisedFeatures = kSpecialiseNone;
  options.beams = beams;
  options.seed = seed;
  options.plan = plan;
  options.loop.checkpointSeconds = 0.0;
  RenderResult result = render(scene, options, sharedDevice(device));
  EXPECT_EQ(result.deviceKind, device == DeviceChoice::Gpu ? DeviceKind::Vulkan : DeviceKind::Cpu);
  std::printf("  %s: %llu beams in %.2f s, %llu counted\n", result.deviceName.c_str(), (unsigned long long)beams,
              result.traceWallSeconds, (unsigned long long)result.summary.countedBeams);
  return result;
}

// The scene on lavapipe and on the CPU reference with the same beams: the
// films must be equal bit for bit. Returns the CPU's render.
inline RenderResult renderOnBothDevices(const Scene& scene, uint64_t beams, uint64_t seed,
                                        const CompileOptions& plan = {}) {
  const RenderResult gpu = renderOn(DeviceChoice::Gpu, scene, beams, seed, plan);
  RenderResult cpu = renderOn(DeviceChoice::Cpu, scene, beams, seed, plan);
  EXPECT_GT(cpu.summary.countedBeams, 0u);
  EXPECT_TRUE(gpu.histogram.counts() == cpu.histogram.counts()) << "lavapipe and the CPU reference binned differently";
  EXPECT_TRUE(gpu.histogram.colourSums() == cpu.histogram.colourSums()) << "colour sums differ";
  EXPECT_TRUE(gpu.histogram.squaredWeightSums() == cpu.histogram.squaredWeightSums()) << "squared weights differ";
  return cpu;
}

// Light paths alone (with camera connections) against camera paths alone
// on one scene: first small renders of each on both devices, bit for bit
// (seeds seed, seed + 1), then lightBeams and `paths` on the CPU reference
// (seeds seed + 2, seed + 3), which must give the same image within their
// noise (compareRenders). Returns the CPU's light-path estimates.
inline PixelEstimates expectCameraPathsMatchLightPaths(const Scene& scene, uint64_t smallBeams, uint64_t lightBeams,
                                                       uint64_t paths, uint64_t seed) {
  CompileOptions lightOnly;
  lightOnly.cameraPaths = false;
  CompileOptions cameraOnly;
  cameraOnly.lightPaths = false;
  renderOnBothDevices(scene, smallBeams, seed, lightOnly);
  renderOnBothDevices(scene, smallBeams, seed + 1, cameraOnly);
  const RenderResult light = renderOn(DeviceChoice::Cpu, scene, lightBeams, seed + 2, lightOnly);
  const RenderResult camera = renderOn(DeviceChoice::Cpu, scene, paths, seed + 3, cameraOnly);
  PixelEstimates lightEstimates = pixelEstimates(light.histogram, light.plan, lightBeams);
  const RenderComparison result = compareRenders(lightEstimates, pixelEstimates(camera.histogram, camera.plan, paths),
                                                 "light paths vs camera paths");
  const size_t pixels = lightEstimates.irradiance.size();
  EXPECT_EQ(size_t(result.cells), pixels);
  EXPECT_GT(result.pValue, 1e-3);
  return lightEstimates;
}

}  // namespace spectrace::testing
