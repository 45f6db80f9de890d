// Integer numerics of the trace:
//  - huge counts: a pixel-bin counter stays exact past 2^32 (and up to
//    2^64 - 2^40) on the device, whose trace shader adds with 64-bit
//    atomics, and in the CPU reference: both tracers' films are preset near
//    those limits (Tracer::upload); the resolve shader then turns such
//    counts into irradiance.
//  - beam indices past 2^32: beam i and beam i + 2^32 (or 2^40, 2^63, or
//    the seed + 2^32) are independent, and renders whose beam indices start
//    near 2^32, 2^40 and 2^64 match the exact irradiance of a point light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "kernel/beam_kernel.h"
#include "support/cpu_trace.h"
#include "film/develop.h"
#include "camera/camera_frame.h"
#include "compile/compile_scene.h"
#include "backend/vulkan_tracer.h"
#include "render/renderer.h"
#include "rng/philox.h"
#include "support/p_values.h"
#include "support/statistics.h"
#include "support/beam_agreement.h"
#include "support/test_scenes.h"
#include "support/test_scale.h"

namespace spectrace {
namespace {

using testing::pointLight;
using testing::surfaceLight;

using testing::propertyKey;

constexpr double kSigmas = 5.0;
constexpr uint64_t k2To32 = uint64_t(1) << 32;
constexpr uint64_t k2To40 = uint64_t(1) << 40;

// ---------------------------------------------------------------------------
// The Vulkan tracer on a film preset near the counters' limits.

class PresetTrace {
 public:
  PresetTrace(const CompiledScene& plan, const SpectralHistogram& preset) : tracer_(testing::sharedVulkan(), plan) {
    tracer_.upload(preset);
  }
  void trace(uint64_t firstBeam, uint32_t count) { tracer_.trace(firstBeam, count); }
  SpectralHistogram download() const { return tracer_.download(); }
  // The resolve shader over the (preset and traced) counters.
  RenderImage resolve(const ResolveParameters& parameters) { return tracer_.develop(parameters); }

 private:
  VulkanTracer tracer_;
};

// ---------------------------------------------------------------------------
// Huge counts

// Four thin lasers straight down into the centres of the diagonal pixels of
// a 4 x 4 sensor, each a Dirac line in its own bin: every beam hits, and
// lands in one of four known cells.
Scene fourLaserScene() {
  Scene scene = testing::bareSensorScene(0.008, 0.008, 4, 4, 4);
  const CameraFrame frame = CameraFrame::fromCamera(scene.camera);
  const double lines[] = {400.0, 520.0, 640.0, 760.0};  // bins of 117.5 nm from 360 nm
  for (int k = 0; k < 4; ++k) {
    // Centre of pixel (k, k) in the camera frame, 1 cm above the sensor.
    const glm::dvec3 local(-0.003 + 0.002 * k, 0.003 - 0.002 * k, 0.01);
    const glm::dvec3 world = frame.origin + frame.right * local.x + frame.up * local.y + frame.forward * local.z;
    Light laser = surfaceLight(LightType::Laser, world, -frame.forward, 1.0 + k, makeLineSpd(lines[k]));
    laser.label = "/lights/" + std::to_string(k);
    laser.radiusM = 1e-4;
    scene.lights.push_back(laser);
  }
  return scene;
}

// The plan's shape, all zero.
SpectralHistogram emptyHistogram(const CompiledScene& plan) {
  return SpectralHistogram(plan.film.pixelsX, plan.film.pixelsY, plan.film.bins, plan.film.exactColour);
}

// Presets: the four lit cells just below 2^31, 2^32 and 2^40 and at
// 2^64 - 2^40; their pixels' colour sums (if any) just below 2^32 and
// 2^63 and at 2^64 - 2^46 (each hit adds < 2^22 there); and cells no beam
// reaches at awkward values, which must come back unchanged.
SpectralHistogram presetHistogram(const CompiledScene& plan, const SpectralHistogram& hits) {
  SpectralHistogram preset = emptyHistogram(plan);
  const uint64_t countPresets[] = {(uint64_t(1) << 31) - 700, k2To32 - 1000, k2To40 - 1000, UINT64_MAX - k2To40 + 1};
  const uint64_t colourPresets[] = {k2To32 - 12345, (uint64_t(1) << 63) - 999, UINT64_MAX - (uint64_t(1) << 46) + 1};
  size_t lit = 0;
  for (uint32_t pixel = 0; pixel < plan.film.pixelCount(); ++pixel)
    for (uint32_t bin = 0; bin < plan.film.bins; ++bin)
      if (hits.at(pixel, bin) > 0) {
        if (lit >= std::size(countPresets)) throw std::logic_error("the four lasers should light exactly four cells");
        preset.at(pixel, bin) = countPresets[lit];
        if (preset.hasExactColour())
          for (int k = 0; k < 3; ++k) preset.colourSums()[pixel * 3 + k] = colourPresets[(lit + k) % 3];
        ++lit;
      }
  if (lit != std::size(countPresets)) throw std::logic_error("the four lasers should light exactly four cells");
  const uint64_t idle[] = {0xFFFFFFFFull, k2To32, uint64_t(1) << 63, UINT64_MAX, 0x0123456789ABCDEFull};
  size_t next = 0;
  for (uint32_t pixel = 1; pixel < plan.film.pixelCount() && next < std::size(idle); pixel += 2) {
    uint64_t pixelHits = 0;
    for (uint32_t bin = 0; bin < plan.film.bins; ++bin) pixelHits += hits.at(pixel, bin);
    if (pixelHits != 0) continue;
    preset.at(pixel, next % plan.film.bins) = idle[next];
    if (preset.hasExactColour()) preset.colourSums()[pixel * 3 + next % 3] = idle[next];
    ++next;
  }
  return preset;
}

// `result` == `preset` + `hits`, counter by counter (modulo 2^64, though no
// counter here passes 2^64).
void expectExactSum(const SpectralHistogram& result, const SpectralHistogram& preset, const SpectralHistogram& hits,
                    const char* name) {
  ASSERT_TRUE(result.sameShape(preset) && result.sameShape(hits)) << name;
  size_t wrong = 0;
  auto check = [&](const std::vector<uint64_t>& r, const std::vector<uint64_t>& p, const std::vector<uint64_t>& h,
                   const char* what, uint32_t perPixel) {
    for (size_t i = 0; i < r.size(); ++i) {
      const uint64_t expected = p[i] + h[i];
      if (r[i] != expected && ++wrong <= 10)
        ADD_FAILURE() << name << ": " << what << " of pixel " << i / perPixel << " [" << i % perPixel << "] holds "
                      << r[i] << ", expected " << p[i] << " + " << h[i] << " = " << expected << " (off by "
                      << int64_t(r[i] - expected) << ")";
    }
  };
  check(result.counts(), preset.counts(), hits.counts(), "bin count", result.bins);
  check(result.colourSums(), preset.colourSums(), hits.colourSums(), "colour sum", 3);
  EXPECT_EQ(wrong, 0u) << name;
}

// Crossing 2^32 must not be special, so each target also needs more than
// 2^32 - preset added, which the presets just below 2^32 guarantee.
TEST(CountsNumerics, DeviceCountersStayExactPast2To32) {
  const Scene scene = fourLaserScene();
  const CompiledScene plan = compileScene(scene, 31);
  // Two dispatches, so each counter crosses its limit partly within one
  // dispatch and partly between them.
  constexpr uint64_t kFirst = 1000;
  constexpr uint32_t kBeams = 400'000;

  // The same beams on zeroed counters, and the CPU reference's hits.
  PresetTrace zeroed(plan, emptyHistogram(plan));
  zeroed.trace(kFirst, kBeams);
  zeroed.trace(kFirst + kBeams, kBeams);
  const SpectralHistogram hits = zeroed.download();
  ASSERT_EQ(hits.total(), 2 * uint64_t(kBeams)) << "every beam should hit";
  SpectralHistogram cpuHits;
  CpuTraceOptions options;
  options.threads = 2;
  traceOnCpu(plan, kFirst, 2 * uint64_t(kBeams), cpuHits, options);
  EXPECT_EQ(hits.counts(), cpuHits.counts()) << "device and CPU reference disagree on where the beams land";
  EXPECT_EQ(hits.colourSums(), cpuHits.colourSums()) << "device and CPU reference disagree on the colour sums";

  const SpectralHistogram preset = presetHistogram(plan, hits);
  PresetTrace device(plan, preset);
  device.trace(kFirst, kBeams);
  device.trace(kFirst + kBeams, kBeams);
  const SpectralHistogram result = device.download();
  expectExactSum(result, preset, hits, "device");
  for (uint32_t p = 0; p < plan.film.pixelCount(); ++p)
    for (uint32_t b = 0; b < plan.film.bins; ++b)
      if (hits.at(p, b))
        std::printf("device: pixel %u bin %u: %llu + %llu hits = %llu\n", p, b, (unsigned long long)preset.at(p, b),
                    (unsigned long long)hits.at(p, b), (unsigned long long)result.at(p, b));

  // The resolve shader: irradiance = float(total) * irradiancePerCount, and
  // XYZ from float(count), both within float rounding of the exact values.
  ResolveParameters parameters = resolveParametersFor(scene, plan, uint64_t(1) << 50);
  // The preset counts are more than 2^50 beams could carry: no error
  // estimate (develop would refuse them), only the resolve under test.
  parameters.beams = 0;
  const auto pixels = device.resolve(parameters);
  const RenderImage exact = resolveOnCpu(result, parameters);
  for (uint32_t p = 0; p < plan.film.pixelCount(); ++p) {
    uint64_t total = 0;
    for (uint32_t b = 0; b < plan.film.bins; ++b) total += result.at(p, b);  // no pixel's total passes 2^64
    const double expected = double(total) * double(float(parameters.irradiancePerCount));
    EXPECT_NEAR(pixels.irradiance[p], expected, 4e-7 * std::abs(expected)) << "resolve, pixel " << p;
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(pixels.xyz[p * 3 + k], exact.xyz[p * 3 + k], 4e-7 * std::abs(exact.xyz[p * 3 + k]))
          << "resolve, pixel " << p << " XYZ[" << k << "]";
  }
}

TEST(CountsNumerics, CpuReferenceCountersStayExactPast2To32) {
  const Scene scene = fourLaserScene();
  const CompiledScene plan = compileScene(scene, 32);
  constexpr uint64_t kFirst = 77, kBeams = 400'000;
  CpuTraceOptions options;
  options.threads = 4;  // contended atomics even on a small machine
  SpectralHistogram hits;
  ASSERT_EQ(traceOnCpu(plan, kFirst, kBeams, hits, options), kBeams);
  ASSERT_EQ(hits.total(), kBeams);
  const SpectralHistogram preset = presetHistogram(plan, hits);
  SpectralHistogram histogram = preset;
  ASSERT_EQ(traceOnCpu(plan, kFirst, kBeams, histogram, options), kBeams);
  expectExactSum(histogram, preset, hits, "CPU reference");
  // Merging partial renders is exact too.
  SpectralHistogram merged = preset;
  merged.merge(hits);
  EXPECT_EQ(merged.counts(), histogram.counts());
  EXPECT_EQ(merged.colourSums(), histogram.colourSums());
}

// Presetting through Tracer::upload, then tracing on the Vulkan tracer.
TEST(CountsNumerics, GpuTracerCountersStayExactPast2To32) {
  const Scene scene = fourLaserScene();
  const CompiledScene plan = compileScene(scene, 33);
  constexpr uint64_t kFirst = 5, kBeams = 200'000;
  SpectralHistogram hits;
  traceOnCpu(plan, kFirst, kBeams, hits);
  const SpectralHistogram preset = presetHistogram(plan, hits);
  VulkanTracer gpu(testing::sharedVulkan(), plan);
  gpu.upload(preset);
  gpu.trace(kFirst, kBeams);
  expectExactSum(gpu.download(), preset, hits, "VulkanTracer");
}

// ---------------------------------------------------------------------------
// Beam indices past 2^32

// A Lambertian disk 1 mm above a 360 x 240 sensor, white light over 94 bins:
// nearly every beam hits, spread over ~8 million (pixel, bin) cells.
Scene diskOverSensorScene() {
  Scene scene = testing::bareSensorScene(0.036, 0.024, 360, 240, 94);
  Light disk = surfaceLight(LightType::Disk, {0.0, 0.0, 0.001}, {0.0, 0.0, -1.0}, 1.0, makeTabulatedSpd({360.0, 830.0}, {1.0, 1.0}));
  disk.radiusM = 0.008;
  scene.lights = {disk};
  return scene;
}

TEST(CountsNumerics, PhiloxWordsDoNotRepeatPast2To32) {
  constexpr uint64_t kSeed = 0x5EEDull;
  constexpr uint32_t kCount = 65'536;
  const auto& vulkan = testing::sharedVulkan();
  for (const uint32_t block : {0u, 1u, 2u}) {  // the trace's Philox blocks
    const auto base = philoxOnGpu(vulkan, kSeed, 0, kCount, block);
    for (const uint64_t offset : {k2To32, k2To40, uint64_t(1) << 63, k2To32 - 1}) {
      const auto shifted = philoxOnGpu(vulkan, kSeed, offset, kCount, block);
      uint64_t equalWords = 0, cpuMismatch = 0;
      for (uint32_t i = 0; i < kCount; ++i) {
        for (int k = 0; k < 4; ++k) equalWords += base[i][k] == shifted[i][k];
        const auto cpu = philoxWords(kSeed, offset + i, block);
        for (int k = 0; k < 4; ++k) cpuMismatch += cpu[k] != shifted[i][k];
      }
      // Independent words agree with probability 2^-32 each.
      EXPECT_LE(equalWords, 2u) << "block " << block << ", offset " << offset;
      EXPECT_EQ(cpuMismatch, 0u) << "block " << block << ", offset " << offset;
    }
  }
}

TEST(CountsNumerics, BeamStreamsDoNotRepeatPast2To32) {
  const Scene scene = diskOverSensorScene();
  constexpr uint32_t kCount = 1'000'000;
  constexpr uint64_t kSeed = 41;
  const CompiledScene plan = compileScene(scene, kSeed);
  VulkanTracer gpu(testing::sharedVulkan(), plan);
  const auto base = gpu.traceRecorded(0, kCount);

  // Chance agreement of two independent beams: sum over cells of p^2,
  // estimated from the base records (unbiased: n (n - 1) / (N (N - 1))).
  std::vector<uint32_t> perCell(size_t(plan.film.pixelCount() * plan.film.bins), 0);
  uint64_t hits = 0;
  for (const auto& r : base)
    if (r.pixel != device::kBeamMissed) {
      ++perCell[size_t(r.pixel) * plan.film.bins + r.bin];
      ++hits;
    }
  double sumP2 = 0.0;
  for (uint32_t n : perCell) sumP2 += double(n) * (double(n) - 1.0);
  sumP2 /= double(kCount) * (double(kCount) - 1.0);
  const double expectedSame = sumP2 * kCount;
  const double allowed = expectedSame + kSigmas * std::sqrt(expectedSame) + 3.0;
  ASSERT_GT(hits, kCount * 9 / 10) << "most beams should hit";

  struct Shift {
    const char* name;
    uint64_t firstBeam, seed;
  };
  const Shift shifts[] = {{"index + 2^32", k2To32, kSeed},
                          {"index + 2^40", k2To40, kSeed},
                          {"index + 2^63", uint64_t(1) << 63, kSeed},
                          {"index + 2^32 - 1", k2To32 - 1, kSeed},
                          {"seed + 2^32", 0, kSeed + k2To32}};
  for (const Shift& s : shifts) {
    const CompiledScene shiftedPlan = compileScene(scene, s.seed);
    VulkanTracer shiftedGpu(testing::sharedVulkan(), shiftedPlan);
    const auto shifted = shiftedGpu.traceRecorded(s.firstBeam, kCount);
    device::BeamKernel cpu(shiftedPlan.device.constants, shiftedPlan.device.lights, shiftedPlan.device.intervals, shiftedPlan.device.aliasColumns);
    uint64_t same = 0, cpuDiffers = 0;
    for (uint32_t i = 0; i < kCount; ++i) {
      if (base[i].pixel != device::kBeamMissed && testing::sameRecord(base[i], shifted[i])) ++same;
      cpuDiffers += !testing::sameRecord(testing::cpuRecord(cpu, s.firstBeam + i), shifted[i]);
    }
    std::printf("%s: %llu of %u beams land in the same (pixel, bin) as beam i (chance: %.2f); CPU/GPU differ on "
                "%llu\n",
                s.name, (unsigned long long)same, kCount, expectedSame, (unsigned long long)cpuDiffers);
    EXPECT_LE(double(same), allowed) << s.name << ": the beam stream repeats";
    EXPECT_LE(cpuDiffers, kCount / 10'000) << s.name;
  }
}

// ---------------------------------------------------------------------------
// Renders at large beam indices against the exact point-light irradiance.

double cornerTerm(double a, double b, double d) { return std::atan(a * b / (d * std::sqrt(a * a + b * b + d * d))); }
double rectangleSolidAngle(double x1, double x2, double y1, double y2, double x0, double y0, double d) {
  return cornerTerm(x2 - x0, y2 - y0, d) - cornerTerm(x1 - x0, y2 - y0, d) - cornerTerm(x2 - x0, y1 - y0, d) +
         cornerTerm(x1 - x0, y1 - y0, d);
}

// Per-pixel counts (over bins) against beams * Omega(pixel) / 4 pi, 5 sigma
// each; returns the worst |z|.
double expectPointLightCounts(const SpectralHistogram& histogram, const Scene& scene, uint64_t beams,
                              const std::string& name) {
  const Camera& camera = scene.camera;
  const glm::dvec3 light = CameraFrame::fromCamera(camera).pointToLocal(scene.lights[0].position);
  const double pw = camera.sensorWidthM / camera.pixelsX, ph = camera.sensorHeightM / camera.pixelsY;
  const double n = double(beams);
  double worst = 0.0, chi2 = 0.0;
  uint64_t total = 0;
  double totalP = 0.0;
  int failures = 0;
  for (int row = 0; row < camera.pixelsY; ++row)
    for (int col = 0; col < camera.pixelsX; ++col) {
      const double x1 = -0.5 * camera.sensorWidthM + col * pw, y2 = 0.5 * camera.sensorHeightM - row * ph;
      const double p = rectangleSolidAngle(x1, x1 + pw, y2 - ph, y2, light.x, light.y, light.z) / (4.0 * M_PI);
      uint64_t count = 0;
      const uint32_t pixel = uint32_t(row * camera.pixelsX + col);
      for (uint32_t b = 0; b < histogram.bins; ++b) count += histogram.at(pixel, b);
      const double z = (double(count) - n * p) / std::sqrt(n * p * (1.0 - p));
      worst = std::max(worst, std::abs(z));
      chi2 += z * z;
      total += count;
      totalP += p;
      if (std::abs(z) > kSigmas && ++failures <= 10)
        ADD_FAILURE() << name << ": pixel (" << col << ", " << row << ") counted " << count << ", expected "
                      << n * p << " (" << z << " sigma)";
    }
  const int cells = camera.pixelsX * camera.pixelsY;
  const double zTotal = (double(total) - n * totalP) / std::sqrt(n * totalP * (1.0 - totalP));
  EXPECT_LE(std::abs(zTotal), kSigmas) << name << ": total";
  const double pValue = testing::chiSquareUpperTail(chi2, cells);
  std::printf("%s: %llu hits (%+.2f sigma), chi2/dof %.3f (p %.3f), worst pixel %.2f sigma\n", name.c_str(),
              (unsigned long long)total, zTotal, chi2 / cells, pValue, worst);
  ::testing::Test::RecordProperty(propertyKey(name + "_worst_sigma"), std::to_string(worst));
  return std::max(worst, std::abs(zTotal));
}

TEST(CountsNumerics, RendersAtBeamIndicesNear2To32And2To40) {
  const uint64_t kBeams = testing::scaledBeams(8'000'000, 800'000) / 4 * 4;
  Scene scene = testing::bareSensorScene(0.036, 0.024, 48, 32, 16);
  scene.lights = {pointLight({0.004, -0.003, 0.012}, 2.0, *cieIlluminant("D65"))};
  const CompiledScene plan = compileScene(scene, 2718);
  struct Start {
    const char* name;
    uint64_t firstBeam;
  };
  const Start starts[] = {{"beams straddling 2^32", k2To32 - kBeams / 2},
                          {"beams straddling 2^40", k2To40 - kBeams / 2},
                          {"beams from 2^40 + 2^32", k2To40 + k2To32},
                          {"the last beams below 2^64", UINT64_MAX - kBeams + 1}};
  VulkanTracer gpu(testing::sharedVulkan(), plan);
  for (const Start& s : starts) {
    gpu.clear();
    gpu.trace(s.firstBeam, kBeams);
    const SpectralHistogram fromGpu = gpu.download();
    expectPointLightCounts(fromGpu, scene, kBeams, std::string(s.name) + " (GPU)");
    // The CPU reference draws the same beams (a quarter of them, for time).
    SpectralHistogram cpuPart;
    traceOnCpu(plan, s.firstBeam, kBeams / 4, cpuPart);
    expectPointLightCounts(cpuPart, scene, kBeams / 4, std::string(s.name) + " (CPU)");
    gpu.clear();
    gpu.trace(s.firstBeam, kBeams / 4);
    const SpectralHistogram gpuPart = gpu.download();
    uint64_t moved = 0;
    for (size_t i = 0; i < cpuPart.counts().size(); ++i)
      moved += cpuPart.counts()[i] > gpuPart.counts()[i] ? cpuPart.counts()[i] - gpuPart.counts()[i] : 0;
    std::printf("%s: CPU and GPU histograms of %llu beams differ by %llu counts\n", s.name,
                (unsigned long long)(kBeams / 4), (unsigned long long)moved);
    EXPECT_EQ(cpuPart.total(), gpuPart.total()) << s.name;
    EXPECT_LE(moved, cpuPart.total() / 10'000) << s.name;
  }
}

}  // namespace
}  // namespace spectrace
