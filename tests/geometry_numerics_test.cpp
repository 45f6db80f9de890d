// Numerical stability of the beam geometry, each render against its exact
// irradiance:
//  - scale: a spot and a laser 1e6 m from a 1 mm sensor, 1 µm pixels, and a
//    camera 1.7e5 m from the world origin in a scene 1e4 m across;
//  - angles: lasers at 1e-6 ... 1e-30 rad to the sensor plane, beams exactly
//    parallel to it, lights behind it, a pinhole of radius 1e-7 m;
//  - degenerate inputs: the library path (compileScene,
//    CameraFrame::fromCamera) must throw SceneError naming the problem
//    rather than put NaN into the device tables.
// A pixel's count is binomial(N, p) with p from exact geometry (pixel solid
// angles, cone solid angles, disk and ellipse areas), which gives its
// standard error; every check allows 5 sigma. Pixels expected to hold fewer
// than kMinExpected counts are pooled. The scale and grazing cases are also
// compared beam by beam with the CPU reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include <glm/geometric.hpp>

#include "camera/pinhole_camera.h"
#include "camera/camera_frame.h"
#include "kernel/beam_kernel.h"
#include "support/cpu_trace.h"
#include "film/develop.h"
#include "compile/compile_scene.h"
#include "backend/vulkan_tracer.h"
#include "render/renderer.h"
#include "support/p_values.h"
#include "support/statistics.h"
#include "support/beam_agreement.h"
#include "support/test_scenes.h"
#include "support/test_scale.h"
#include "reference/exact_solution.h"  // rectangleSolidAngle

namespace spectrace {
namespace {

using testing::pointLight;
using testing::surfaceLight;

using testing::propertyKey;

constexpr double kSigmas = 5.0;
constexpr double kMinExpected = 25.0;  // below this a pixel joins the pooled cell

// ---------------------------------------------------------------------------
// Exact geometry (rectangleSolidAngle: reference/exact_solution.h)

// Share of a unit disk's area with s < v (v in [-1, 1]).
double diskShareBelow(double v) {
  v = std::clamp(v, -1.0, 1.0);
  return 0.5 + (v * std::sqrt(1.0 - v * v) + std::asin(v)) / M_PI;
}

// 1 - cos(a) = 2 sin^2(a / 2), without cancellation.
double oneMinusCos(double a) {
  const double s = std::sin(0.5 * a);
  return 2.0 * s * s;
}

// A pixel of a bare sensor in the camera frame: columns along +x, rows down from +y.
struct PixelRect {
  double x1, x2, y1, y2;
};
PixelRect bareSensorPixel(const Camera& camera, int col, int row) {
  const double pw = camera.sensorWidthM / camera.pixelsX;
  const double ph = camera.sensorHeightM / camera.pixelsY;
  const double x1 = -0.5 * camera.sensorWidthM + col * pw;
  const double y2 = 0.5 * camera.sensorHeightM - row * ph;
  return {x1, x1 + pw, y2 - ph, y2};
}

glm::dvec3 worldPoint(const CameraFrame& f, glm::dvec3 local) {
  return f.origin + f.right * local.x + f.up * local.y + f.forward * local.z;
}
glm::dvec3 worldDirection(const CameraFrame& f, glm::dvec3 local) {
  return f.right * local.x + f.up * local.y + f.forward * local.z;
}

// ---------------------------------------------------------------------------
// Tracing and comparing

struct GpuRun {
  SpectralHistogram histogram;
  RenderImage image;  // resolved on the device
};

GpuRun traceOnGpu(const Scene& scene, const CompiledScene& plan, uint64_t firstBeam, uint64_t beams) {
  VulkanTracer gpu(testing::sharedVulkan(), plan);
  gpu.trace(firstBeam, beams);
  GpuRun run;
  run.histogram = gpu.download();
  run.image = gpu.develop(resolveParametersFor(scene, plan, beams));
  return run;
}

std::vector<uint64_t> pixelCounts(const SpectralHistogram& h) {
  std::vector<uint64_t> counts(size_t(h.pixelsX) * h.pixelsY, 0);
  for (size_t p = 0; p < counts.size(); ++p)
    for (uint32_t b = 0; b < h.bins; ++b) counts[p] += h.counts()[p * h.bins + b];
  return counts;
}

void expectFiniteImage(const RenderImage& image, const std::string& name) {
  size_t bad = 0;
  for (float v : image.irradiance) bad += !(std::isfinite(v) && v >= 0.0f);
  for (float v : image.xyz) bad += !std::isfinite(v);
  for (float v : image.rgb) bad += !std::isfinite(v);
  EXPECT_EQ(bad, 0u) << name << ": non-finite or negative values in the resolved image";
}

struct MatchStats {
  double worstSigmas = 0.0;
  uint64_t hits = 0;
  double expectedHits = 0.0;
};

// How much likelier an aimed beam is to be counted than an analog one:
// tracedPowerW / sampledPowerW, for plans whose beams all have weight ratio
// 1 (counts are then plain hits: point, spot and laser lights).
double aimGain(const CompiledScene& plan) {
  EXPECT_FALSE(plan.film.weighted()) << "these checks count hits; weighted plans need their weights";
  return plan.tracedPowerW / plan.sampledPowerW;
}

// Compares each pixel's count with beams * gain * p(pixel), where p is an
// analog beam's probability of landing there and gain is aimGain(plan).
// p == 0 demands a zero count; pixels expected to hold fewer than
// kMinExpected are pooled; the total is checked too. Returns the worst |z|
// over all these cells.
MatchStats expectCountsMatch(const SpectralHistogram& histogram, const Camera& camera, uint64_t beams, double gain,
                             const std::function<double(const PixelRect&)>& probability, const std::string& name) {
  const std::vector<uint64_t> counts = pixelCounts(histogram);
  const double n = double(beams);
  MatchStats stats;
  double pooledCount = 0.0, pooledExpected = 0.0, pooledVariance = 0.0, totalP = 0.0;
  double chi2 = 0.0;
  int cells = 0, failures = 0;
  for (int row = 0; row < camera.pixelsY; ++row) {
    for (int col = 0; col < camera.pixelsX; ++col) {
      const double p = gain * probability(bareSensorPixel(camera, col, row));
      const uint64_t count = counts[size_t(row) * camera.pixelsX + col];
      stats.hits += count;
      totalP += p;
      if (p <= 0.0) {
        if (count != 0 && ++failures <= 10)
          ADD_FAILURE() << name << ": pixel (" << col << ", " << row << ") has " << count
                        << " counts where no beam can land";
        continue;
      }
      const double expected = n * p;
      if (expected < kMinExpected) {
        pooledCount += double(count);
        pooledExpected += expected;
        pooledVariance += expected * (1.0 - p);
        continue;
      }
      const double z = (double(count) - expected) / std::sqrt(expected * (1.0 - p));
      chi2 += z * z;
      ++cells;
      stats.worstSigmas = std::max(stats.worstSigmas, std::abs(z));
      if (std::abs(z) > kSigmas && ++failures <= 10)
        ADD_FAILURE() << name << ": pixel (" << col << ", " << row << ") counted " << count << ", expected "
                      << expected << " +- " << std::sqrt(expected * (1.0 - p)) << " (" << z << " sigma)";
    }
  }
  if (pooledExpected > 0.0) {
    const double z = (pooledCount - pooledExpected) / std::sqrt(pooledVariance);
    stats.worstSigmas = std::max(stats.worstSigmas, std::abs(z));
    EXPECT_LE(std::abs(z), kSigmas) << name << ": pooled sparse pixels counted " << pooledCount << ", expected "
                                    << pooledExpected;
  }
  stats.expectedHits = n * totalP;
  const double totalSigma = std::sqrt(n * totalP * (1.0 - std::min(totalP, 1.0)));
  const double totalZ = totalSigma > 0.0 ? (double(stats.hits) - stats.expectedHits) / totalSigma : 0.0;
  stats.worstSigmas = std::max(stats.worstSigmas, std::abs(totalZ));
  EXPECT_LE(std::abs(totalZ), kSigmas) << name << ": " << stats.hits << " hits in all, expected "
                                       << stats.expectedHits << " +- " << totalSigma;
  double pValue = 1.0;
  if (cells > 0) pValue = testing::chiSquareUpperTail(chi2, cells);
  std::printf("%s: %llu beams, %llu hits (expected %.1f, %+.2f sigma), %d pixels checked, chi2/dof %.3f (p %.3f), "
              "worst %.2f sigma\n",
              name.c_str(), (unsigned long long)beams, (unsigned long long)stats.hits, stats.expectedHits, totalZ,
              cells, cells ? chi2 / cells : 0.0, pValue, stats.worstSigmas);
  ::testing::Test::RecordProperty(propertyKey(name + "_worst_sigma"), std::to_string(stats.worstSigmas));
  return stats;
}

// Traces beams [firstBeam, firstBeam + count) on both devices and compares
// their (pixel, bin) beam by beam. Returns the share that agrees.
double beamByBeamAgreement(const CompiledScene& plan, uint64_t firstBeam, uint32_t count, const std::string& name,
                           uint64_t* hitsOut = nullptr) {
  const testing::BeamAgreement agreement = testing::beamByBeam(plan, firstBeam, count, name);
  if (hitsOut) *hitsOut = agreement.hits;
  return agreement.rate;
}

// The whole check of one plan: `beams` on the GPU and a quarter of them on
// the CPU against beams * gain * p(pixel), the GPU's resolved image finite,
// and the two devices beam by beam on the first `agreementBeams`. Returns
// the GPU's statistics.
MatchStats expectCountsMatchOnBothDevices(const Scene& scene, const CompiledScene& plan, uint64_t beams,
                                          const std::function<double(const PixelRect&)>& probability,
                                          const std::string& name, uint32_t agreementBeams) {
  const GpuRun run = traceOnGpu(scene, plan, 0, beams);
  const MatchStats stats = expectCountsMatch(run.histogram, scene.camera, beams, aimGain(plan), probability, name + " (GPU)");
  expectFiniteImage(run.image, name);
  SpectralHistogram cpu;
  traceOnCpu(plan, 0, beams / 4, cpu);
  expectCountsMatch(cpu, scene.camera, beams / 4, aimGain(plan), probability, name + " (CPU)");
  EXPECT_GE(beamByBeamAgreement(plan, 0, agreementBeams, name), 0.9999);
  return stats;
}

Scene bareSensor(double widthM, double heightM, int pixelsX, int pixelsY) {
  return testing::bareSensorScene(widthM, heightM, pixelsX, pixelsY, 4);
}

Light laserLight(glm::dvec3 origin, glm::dvec3 direction, double radiusM, double powerW = 1.0) {
  Light laser = surfaceLight(LightType::Laser, origin, direction, powerW, makeLineSpd(532.0));
  laser.label = "/lights/laser";
  laser.radiusM = radiusM;
  return laser;
}

Light spotLight(glm::dvec3 position, glm::dvec3 direction, double halfAngleRad, double powerW = 1.0) {
  Light spot = surfaceLight(LightType::Spot, position, direction, powerW, makeLineSpd(600.0));
  spot.label = "/lights/spot";
  spot.coneHalfAngleDeg = halfAngleRad * 180.0 / M_PI;
  return spot;
}

// ---------------------------------------------------------------------------
// Scale

TEST(GeometryNumericsScale, SpotAMillionMetresFromAMillimetreSensor) {
  // A cone of half angle 8e-10 rad lights a disk of radius 0.8 mm at 1e6 m,
  // which holds the whole 1 mm sensor: a pixel receives the share
  // Omega(pixel) / (2 pi (1 - cos a)) of the beams.
  constexpr double kDistance = 1e6, kHalfAngle = 8e-10;
  const uint64_t kBeams = testing::scaledBeams(8'000'000, 1'000'000);
  Scene scene = bareSensor(1e-3, 1e-3, 16, 16);
  scene.lights = {spotLight({0.0, 0.0, kDistance}, {0.0, 0.0, -1.0}, kHalfAngle)};
  const CompiledScene plan = compileScene(scene, 11);
  const glm::dvec3 light = CameraFrame::fromCamera(scene.camera).pointToLocal(scene.lights[0].position);
  const double coneSolidAngle = 2.0 * M_PI * oneMinusCos(kHalfAngle);
  ASSERT_LT(std::hypot(0.5e-3, 0.5e-3) / kDistance, std::tan(kHalfAngle)) << "the cone must cover the sensor";
  auto probability = [&](const PixelRect& r) {
    return rectangleSolidAngle(r.x1, r.x2, r.y1, r.y2, light.x, light.y, light.z) / coneSolidAngle;
  };
  const MatchStats stats = expectCountsMatchOnBothDevices(scene, plan, kBeams, probability, "spot at 1e6 m", 500'000);
  EXPECT_GT(stats.hits, kBeams / 3);
}

TEST(GeometryNumericsScale, LaserAMillionMetresFromAMillimetreSensor) {
  // A collimated beam of radius 1 mm, slightly off axis, covers the whole
  // sensor: each pixel receives area / (pi r^2) of the beams.
  constexpr double kRadius = 1e-3;
  const uint64_t kBeams = testing::scaledBeams(8'000'000, 1'000'000);
  Scene scene = bareSensor(1e-3, 1e-3, 16, 16);
  scene.lights = {laserLight({1e-4, -5e-5, 1e6}, {0.0, 0.0, -1.0}, kRadius)};
  const CompiledScene plan = compileScene(scene, 12);
  const glm::dvec3 centre = CameraFrame::fromCamera(scene.camera).pointToLocal(scene.lights[0].position);
  auto probability = [&](const PixelRect& r) {
    // Every corner must lie inside the disk (true for this layout).
    for (double x : {r.x1, r.x2})
      for (double y : {r.y1, r.y2})
        if (std::hypot(x - centre.x, y - centre.y) >= kRadius) ADD_FAILURE() << "pixel not inside the laser disk";
    return (r.x2 - r.x1) * (r.y2 - r.y1) / (M_PI * kRadius * kRadius);
  };
  expectCountsMatchOnBothDevices(scene, plan, kBeams, probability, "laser at 1e6 m", 500'000);
}

TEST(GeometryNumericsScale, MicrometrePixels) {
  // 64 x 64 pixels of 1 µm, a point light 50 µm above and a little off centre.
  const uint64_t kBeams = testing::scaledBeams(16'000'000, 2'000'000);
  Scene scene = bareSensor(64e-6, 64e-6, 64, 64);
  scene.lights = {pointLight({3e-6, -7e-6, 50e-6}, 1.0, makeLineSpd(550.0))};
  const CompiledScene plan = compileScene(scene, 13);
  const glm::dvec3 light = CameraFrame::fromCamera(scene.camera).pointToLocal(scene.lights[0].position);
  auto probability = [&](const PixelRect& r) {
    return rectangleSolidAngle(r.x1, r.x2, r.y1, r.y2, light.x, light.y, light.z) / (4.0 * M_PI);
  };
  const GpuRun run = traceOnGpu(scene, plan, 0, kBeams);
  expectCountsMatch(run.histogram, scene.camera, kBeams, aimGain(plan), probability, "1 um pixels (GPU)");
  expectFiniteImage(run.image, "1 um pixels");
  EXPECT_GE(beamByBeamAgreement(plan, 0, 500'000, "1 um pixels"), 0.9999);
}

// A camera at (1e5, 1e5, 1e5) looking along an oblique direction, a point
// light 3 cm in front of the sensor (and off its centre), and a second light
// 8.5 km away on the other side of a 1e4 m scene. Both lights share the beams
// by power; the far one adds its (negligible) exact share too.
Scene farCameraScene(const glm::dvec3& position, const glm::dvec3& viewDirection, const glm::dvec3& up,
                     const glm::dvec3& nearLocal, const glm::dvec3& farLocal) {
  Scene scene = testing::bareSensorScene(0.036, 0.024, 48, 32, 4);
  scene.camera.position = position;
  scene.camera.lookAt = position + 5e3 * glm::normalize(viewDirection);
  scene.camera.up = up;
  const CameraFrame frame = CameraFrame::fromCamera(scene.camera);
  scene.lights = {pointLight(worldPoint(frame, nearLocal), 1.0, makeLineSpd(550.0)),
                  pointLight(worldPoint(frame, farLocal), 1.0, makeLineSpd(610.0))};
  return scene;
}

TEST(GeometryNumericsScale, CameraFarFromTheOriginMatchesTheSameSetupAtTheOrigin) {
  const uint64_t kBeams = testing::scaledBeams(16'000'000, 2'000'000);
  const glm::dvec3 nearLocal(0.004, -0.002, 0.03), farLocal(3000.0, -500.0, 8000.0);
  struct Case {
    const char* name;
    glm::dvec3 position, view, up;
  };
  const Case cases[] = {
      {"far camera at (1e5, 1e5, 1e5)", {1e5, 1e5, 1e5}, {-3.0, -2.4, 3.2}, {0.0, 0.0, 1.0}},
      {"same setup at the origin", {0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {0.0, 1.0, 0.0}},
  };
  // The exact answer from the intended camera-frame positions (not from the
  // frame's rounded transforms): both lights carry half the power.
  auto probability = [&](const PixelRect& r) {
    double p = 0.0;
    for (const glm::dvec3& l : {nearLocal, farLocal})
      p += 0.5 * rectangleSolidAngle(r.x1, r.x2, r.y1, r.y2, l.x, l.y, l.z) / (4.0 * M_PI);
    return p;
  };
  SpectralHistogram first;
  for (const Case& c : cases) {
    const Scene scene = farCameraScene(c.position, c.view, c.up, nearLocal, farLocal);
    const CameraFrame frame = CameraFrame::fromCamera(scene.camera);
    const glm::dvec3 roundTrip = frame.pointToLocal(scene.lights[0].position);
    EXPECT_LT(glm::length(roundTrip - nearLocal), 1e-9) << c.name << ": the camera frame loses precision";
    const CompiledScene plan = compileScene(scene, 14);
    // The float light position in the device table is the camera-frame one.
    EXPECT_NEAR(plan.device.lights[0].position.x, nearLocal.x, 1e-8) << c.name;
    EXPECT_NEAR(plan.device.lights[0].position.y, nearLocal.y, 1e-8) << c.name;
    EXPECT_NEAR(plan.device.lights[0].position.z, nearLocal.z, 1e-8) << c.name;
    const GpuRun run = traceOnGpu(scene, plan, 0, kBeams);
    expectCountsMatch(run.histogram, scene.camera, kBeams, aimGain(plan), probability, std::string(c.name) + " (GPU)");
    expectFiniteImage(run.image, c.name);
    EXPECT_GE(beamByBeamAgreement(plan, 0, 500'000, c.name), 0.9999);
    if (first.counts().empty()) {
      first = run.histogram;
    } else {
      // Informational: the float tables of the two setups may differ by an
      // ulp, so a few beams may land elsewhere; both match the exact answer.
      uint64_t differing = 0;
      for (size_t i = 0; i < first.counts().size(); ++i) differing += first.counts()[i] != run.histogram.counts()[i];
      std::printf("far camera vs origin: %llu of %zu histogram cells differ\n", (unsigned long long)differing,
                  first.counts().size());
    }
  }
}

// ---------------------------------------------------------------------------
// Angles

// A laser at angle eps to the sensor plane, travelling along +x and down,
// whose axis meets the sensor at (3 µm, 50 µm). Its footprint is the
// ellipse x = s / sin(eps), y = t for (s, t) on the beam's disk of radius
// r = 1.5e-4 sin(eps): 0.3 mm long in x, 2r wide in y, all inside pixel row
// 1 (y in [0, 0.1 mm]). The origin is 1 mm back along the beam, so its
// height above the sensor is 1e-3 sin(eps).
struct GrazingSetup {
  Scene scene;
  glm::dvec3 hit{3e-6, 5e-5, 0.0};
  double footprintHalfLength = 1.5e-4;
};

GrazingSetup grazingLaser(double eps) {
  GrazingSetup g;
  g.scene = bareSensor(4e-4, 4e-4, 16, 4);
  const CameraFrame frame = CameraFrame::fromCamera(g.scene.camera);
  const glm::dvec3 direction(std::cos(eps), 0.0, -std::sin(eps));
  const glm::dvec3 origin = g.hit - 1e-3 * direction;
  const double radius = g.footprintHalfLength * std::sin(eps);
  g.scene.lights = {laserLight(worldPoint(frame, origin), worldDirection(frame, direction), radius)};
  return g;
}

std::string format(const char* pattern, double value) {
  char text[128];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finiteRecord(const device::LightRecord& r) {
  return finite(r.position) && finite(r.axis) && finite(r.tangent) && finite(r.bitangent) &&
         std::isfinite(r.param0) && std::isfinite(r.param1);
}

TEST(GeometryNumericsAngles, GrazingLaserMatchesItsEllipticFootprint) {
  const uint64_t kBeams = testing::scaledBeams(4'000'000, 500'000);
  for (double eps : {1e-6, 1e-12, 1e-20, 1e-30}) {
    const std::string name = format("laser at %g rad to the sensor", eps);
    const GrazingSetup g = grazingLaser(eps);
    const CompiledScene plan = compileScene(g.scene, 21);
    ASSERT_TRUE(finiteRecord(plan.device.lights[0])) << name;
    auto probability = [&](const PixelRect& r) {
      if (!(r.y1 <= g.hit.y && g.hit.y < r.y2)) return 0.0;
      return diskShareBelow((r.x2 - g.hit.x) / g.footprintHalfLength) -
             diskShareBelow((r.x1 - g.hit.x) / g.footprintHalfLength);
    };
    const MatchStats stats = expectCountsMatchOnBothDevices(g.scene, plan, kBeams, probability, name, 200'000);
    EXPECT_GT(stats.hits, kBeams * 99 / 100) << name << ": the whole footprint lies on the sensor";
  }
}

TEST(GeometryNumericsAngles, SubnormalGrazingAngleStaysFinite) {
  // At 1e-39 rad the beam's height above the sensor (1e-42 m) and its
  // direction's z (-1e-39) are subnormal floats. No exact answer survives
  // float rounding here, but nothing may turn into NaN, crash or count
  // outside the footprint's pixel row.
  constexpr uint64_t kBeams = 200'000;
  const GrazingSetup g = grazingLaser(1e-39);
  const CompiledScene plan = compileScene(g.scene, 22);
  const GpuRun run = traceOnGpu(g.scene, plan, 0, kBeams);
  const auto counts = pixelCounts(run.histogram);
  uint64_t hits = 0, outsideRow = 0;
  for (int row = 0; row < g.scene.camera.pixelsY; ++row)
    for (int col = 0; col < g.scene.camera.pixelsX; ++col) {
      const uint64_t c = counts[size_t(row) * g.scene.camera.pixelsX + col];
      hits += c;
      if (row != 1) outsideRow += c;
    }
  EXPECT_LE(hits, kBeams);
  EXPECT_EQ(outsideRow, 0u);
  expectFiniteImage(run.image, "laser at 1e-39 rad");
  std::printf("laser at 1e-39 rad: %llu of %llu beams hit on the GPU\n", (unsigned long long)hits,
              (unsigned long long)kBeams);
  SpectralHistogram cpu;
  traceOnCpu(plan, 0, kBeams, cpu);
  std::printf("laser at 1e-39 rad: %llu of %llu beams hit on the CPU\n", (unsigned long long)cpu.total(),
              (unsigned long long)kBeams);
  beamByBeamAgreement(plan, 0, 100'000, "laser at 1e-39 rad");  // reported, not required
}

TEST(GeometryNumericsAngles, BeamsParallelToTheSensorNeverCount) {
  // Direction exactly in the sensor plane: direction.z == 0 in the device
  // table, so no beam may count (and nothing may divide by zero).
  constexpr uint64_t kBeams = 500'000;
  Scene scene = bareSensor(4e-4, 4e-4, 16, 4);
  const CameraFrame frame = CameraFrame::fromCamera(scene.camera);
  scene.lights = {
      laserLight(worldPoint(frame, {-1e-3, 5e-5, 1e-9}), worldDirection(frame, {1.0, 0.0, 0.0}), 1e-10),
      // Origins from 1 mm above to 1 mm below the sensor plane.
      laserLight(worldPoint(frame, {-1e-3, 0.0, 0.0}), worldDirection(frame, {1.0, 0.0, 0.0}), 1e-3),
      laserLight(worldPoint(frame, {0.0, 1e-3, 1e-6}), worldDirection(frame, {0.0, -1.0, 0.0}), 1e-6)};
  // By default such lights are never sampled: none can reach the sensor.
  EXPECT_THROW(compileScene(scene, 23), SceneError);
  // Traced anyway, the shader maths must count nothing and never divide by 0.
  CompileOptions traceAll;
  traceAll.skipUnreachableLights = false;
  const CompiledScene plan = compileScene(scene, 23, traceAll);
  for (const auto& record : plan.device.lights) {
    ASSERT_TRUE(finiteRecord(record));
    ASSERT_EQ(record.axis.z, 0.0f);
  }
  const GpuRun run = traceOnGpu(scene, plan, 0, kBeams);
  EXPECT_EQ(run.histogram.total(), 0u);
  expectFiniteImage(run.image, "parallel lasers");
  SpectralHistogram cpu;
  traceOnCpu(plan, 0, kBeams, cpu);
  EXPECT_EQ(cpu.total(), 0u);
}

TEST(GeometryNumericsAngles, LightsBehindTheSensorNeverCount) {
  // The sensor counts only beams travelling towards -z from z > 0 (and,
  // with a pinhole, from beyond the aperture plane).
  constexpr uint64_t kBeams = 500'000;
  Scene bare = bareSensor(0.02, 0.02, 8, 8);
  Light disk = surfaceLight(LightType::Disk, {0.0, 0.0, -0.01}, {0.0, 0.0, 1.0}, 1.0, makeLineSpd(500.0));
  disk.radiusM = 0.005;
  Light rect = surfaceLight(LightType::Rect, {0.0, 0.0, -1e-3}, {0.0, 0.0, 1.0}, 1.0, makeLineSpd(500.0));
  rect.sizeM = {0.01, 0.01};
  bare.lights = {laserLight({0.0, 0.0, -0.01}, {0.0, 0.0, 1.0}, 1e-3),
                 spotLight({0.0, 0.0, -0.01}, {0.0, 0.0, 1.0}, 0.5),
                 pointLight({0.001, 0.0, -0.01}, 1.0, makeLineSpd(500.0)),
                 pointLight({0.001, 0.002, 0.0}, 1.0, makeLineSpd(500.0)),  // in the sensor plane
                 disk,
                 rect};
  Scene pinhole = bare;
  pinhole.camera.model = pinholeModel({0.01, 0.002});
  // Between the sensor and the aperture, and in the aperture plane.
  pinhole.lights.push_back(pointLight({0.0, 0.0, 0.005}, 1.0, makeLineSpd(500.0)));
  pinhole.lights.push_back(pointLight({0.0, 0.0, 0.01}, 1.0, makeLineSpd(500.0)));
  for (const Scene* scene : {&bare, &pinhole}) {
    const char* name = scene == &bare ? "behind a bare sensor" : "behind a pinhole";
    EXPECT_THROW(compileScene(*scene, 24), SceneError) << name << ": the default skips every light here";
    CompileOptions traceAll;
    traceAll.skipUnreachableLights = false;
    const CompiledScene plan = compileScene(*scene, 24, traceAll);
    const GpuRun run = traceOnGpu(*scene, plan, 0, kBeams);
    EXPECT_EQ(run.histogram.total(), 0u) << name;
    expectFiniteImage(run.image, name);
    SpectralHistogram cpu;
    traceOnCpu(plan, 0, kBeams, cpu);
    EXPECT_EQ(cpu.total(), 0u) << name;
  }
}

TEST(GeometryNumericsAngles, PinholeOfRadius1e7Metres) {
  // A point light on the axis at height D above an aperture of radius r sees
  // it under the solid angle 2 pi (1 - D / sqrt(D^2 + r^2)), so the share of
  // beams through it is r^2 / (2 sqrt(D^2 + r^2) (sqrt(D^2 + r^2) + D)). The
  // aperture sits at 2^-7 m and D = 2^-23 m or 2^-20 m, all exact in float;
  // the check uses r^2 and D as stored in the device table.
  struct Case {
    double heightAboveAperture;
    uint64_t beams;
  };
  constexpr double kAperture = 0.0078125, kRadius = 1e-7;
  for (const Case c : {Case{std::ldexp(1.0, -23), 2'000'000}, Case{std::ldexp(1.0, -20), 4'000'000}}) {
    Scene scene = bareSensor(0.024, 0.024, 16, 16);
    scene.camera.model = pinholeModel({kAperture, kRadius});
    scene.lights = {pointLight({0.0, 0.0, kAperture + c.heightAboveAperture}, 1.0, makeLineSpd(550.0))};
    const CompiledScene plan = compileScene(scene, 25);
    const double d = double(plan.device.lights[0].position.z) - double(plan.device.constants.cameraFrontZ);
    ASSERT_EQ(d, c.heightAboveAperture) << "the light height should be exact in float";
    const double r2 = double(plan.device.constants.cameraParams.x);
    const double root = std::sqrt(d * d + r2);
    const double p = aimGain(plan) * r2 / (2.0 * root * (root + d));
    const double n = double(c.beams);
    const double sigma = std::sqrt(n * p * (1.0 - p));
    const std::string name = format("pinhole r = 1e-7 m, light %.3g m above it", d);

    const GpuRun run = traceOnGpu(scene, plan, 0, c.beams);
    const double zGpu = (double(run.histogram.total()) - n * p) / sigma;
    SpectralHistogram cpu;
    traceOnCpu(plan, 0, c.beams, cpu);
    const double zCpu = (double(cpu.total()) - n * p) / sigma;
    std::printf("%s: share %.6g, expected %.1f +- %.1f hits; GPU %llu (%+.2f sigma), CPU %llu (%+.2f sigma)\n",
                name.c_str(), p, n * p, sigma, (unsigned long long)run.histogram.total(), zGpu,
                (unsigned long long)cpu.total(), zCpu);
    ::testing::Test::RecordProperty(propertyKey(format("pinhole_%g_gpu_sigma", d)), std::to_string(zGpu));
    EXPECT_LE(std::abs(zGpu), kSigmas) << name << " (GPU)";
    EXPECT_LE(std::abs(zCpu), kSigmas) << name << " (CPU)";
    expectFiniteImage(run.image, name);
    // The image of the aperture: every hit lies within r (D + f) / D of the
    // sensor centre (plus a pixel).
    const double imageRadius = std::sqrt(r2) * (d + kAperture) / d + 0.024 / 16 * std::sqrt(2.0);
    const auto counts = pixelCounts(run.histogram);
    uint64_t outside = 0;
    for (int row = 0; row < 16; ++row)
      for (int col = 0; col < 16; ++col) {
        const PixelRect r = bareSensorPixel(scene.camera, col, row);
        const double cx = 0.5 * (r.x1 + r.x2), cy = 0.5 * (r.y1 + r.y2);
        if (std::hypot(cx, cy) > imageRadius) outside += counts[size_t(row) * 16 + col];
      }
    EXPECT_EQ(outside, 0u) << name << ": hits outside the image of the aperture";
  }
}

// ---------------------------------------------------------------------------
// Degenerate inputs: a SceneError that says what is wrong, never NaN.

std::string describeRecord(const device::LightRecord& r) {
  char text[512];
  std::snprintf(text, sizeof text,
                "type %u, position (%g, %g, %g), axis (%g, %g, %g), tangent (%g, %g, %g), bitangent (%g, %g, %g), "
                "param0 %g, param1 %g",
                r.type, r.position.x, r.position.y, r.position.z, r.axis.x, r.axis.y, r.axis.z, r.tangent.x,
                r.tangent.y, r.tangent.z, r.bitangent.x, r.bitangent.y, r.bitangent.z, r.param0, r.param1);
  return text;
}

// Expects compileScene(scene) to throw SceneError whose message contains
// one of `words`.
void expectPlanRejected(const Scene& scene, std::initializer_list<const char*> words, const std::string& what) {
  try {
    const CompiledScene plan = compileScene(scene, 1);
    std::string records;
    for (const auto& r : plan.device.lights) records += "\n    " + describeRecord(r);
    ADD_FAILURE() << what << ": compileScene accepted it silently; device light records:" << records;
  } catch (const SceneError& e) {
    const std::string message = e.what();
    bool named = false;
    for (const char* w : words) named = named || message.find(w) != std::string::npos;
    EXPECT_TRUE(named) << what << ": the message \"" << message << "\" does not say what is wrong";
    std::printf("%s: SceneError \"%s\"\n", what.c_str(), message.c_str());
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": threw something other than SceneError: " << e.what();
  }
}

TEST(GeometryNumericsDegenerate, LookAtEqualToThePosition) {
  for (const glm::dvec3 position : {glm::dvec3(0.0), glm::dvec3(1e5, 1e5, 1e5), glm::dvec3(-3.0, 2.0, 1e-300)}) {
    Scene scene = bareSensor(0.036, 0.024, 36, 24);
    scene.lights = {pointLight({0.0, 0.0, 0.01}, 1.0, makeLineSpd(550.0))};
    scene.camera.position = position;
    scene.camera.lookAt = position;
    try {
      CameraFrame::fromCamera(scene.camera);
      ADD_FAILURE() << "CameraFrame::fromCamera accepted look_at == position";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("look_at"), std::string::npos) << e.what();
    }
    expectPlanRejected(scene, {"look_at"}, "look_at == position");
  }
}

TEST(GeometryNumericsDegenerate, UpCollinearWithTheView) {
  for (const glm::dvec3 up : {glm::dvec3(0.0, 0.0, 1.0), glm::dvec3(0.0, 0.0, -3.0), glm::dvec3(1e-14, 0.0, 1.0),
                              glm::dvec3(0.0)}) {
    Scene scene = bareSensor(0.036, 0.024, 36, 24);
    scene.lights = {pointLight({0.0, 0.0, 0.01}, 1.0, makeLineSpd(550.0))};
    scene.camera.up = up;
    const std::string what = format("up (..., %g) along the view", up.z);
    try {
      CameraFrame::fromCamera(scene.camera);
      ADD_FAILURE() << what << ": CameraFrame::fromCamera accepted it";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("up"), std::string::npos) << e.what();
    }
    expectPlanRejected(scene, {"up"}, what);
  }
}

TEST(GeometryNumericsDegenerate, ZeroAreaLights) {
  Scene scene = bareSensor(0.036, 0.024, 36, 24);
  Light disk = surfaceLight(LightType::Disk, {0.0, 0.0, 0.01}, {0.0, 0.0, -1.0}, 1.0, makeLineSpd(550.0));
  disk.label = "/lights/0";
  disk.radiusM = 0.0;
  scene.lights = {disk};
  expectPlanRejected(scene, {"radius"}, "disk of radius 0");

  for (const glm::dvec2 size : {glm::dvec2(0.0, 0.01), glm::dvec2(0.01, 0.0), glm::dvec2(0.0)}) {
    Light rect = surfaceLight(LightType::Rect, {0.0, 0.0, 0.01}, {0.0, 0.0, -1.0}, 1.0, makeLineSpd(550.0));
    rect.label = "/lights/0";
    rect.sizeM = size;
    rect.uAxis = {1.0, 0.0, 0.0};
    scene.lights = {rect};
    expectPlanRejected(scene, {"size", "area"}, format("rect of width %g", size.x) + format(" and height %g", size.y));
  }
}

TEST(GeometryNumericsDegenerate, ZeroDirection) {
  struct Case {
    LightType type;
    const char* what;
  };
  for (const Case c : {Case{LightType::Spot, "spot with direction (0, 0, 0)"},
                       Case{LightType::Laser, "laser with direction (0, 0, 0)"},
                       Case{LightType::Disk, "disk with normal (0, 0, 0)"},
                       Case{LightType::Rect, "rect with normal (0, 0, 0)"}}) {
    Scene scene = bareSensor(0.036, 0.024, 36, 24);
    Light light = surfaceLight(c.type, {0.0, 0.0, 0.01}, glm::dvec3(0.0), 1.0, makeLineSpd(550.0));
    light.label = "/lights/0";
    light.coneHalfAngleDeg = 10.0;
    light.radiusM = 1e-3;
    light.sizeM = {1e-3, 1e-3};
    light.uAxis = {1.0, 0.0, 0.0};
    scene.lights = {light};
    expectPlanRejected(scene, {"direction", "normal", "zero"}, c.what);
  }
}

TEST(GeometryNumericsDegenerate, NonFiniteLightPosition) {
  // Beyond the brief's list, the same rule: no NaN or infinity may reach the
  // device tables (the scene loader rejects these; the library should too).
  for (const double bad : {std::nan(""), HUGE_VAL}) {
    Scene scene = bareSensor(0.036, 0.024, 36, 24);
    scene.lights = {pointLight({0.0, bad, 0.01}, 1.0, makeLineSpd(550.0))};
    scene.lights[0].label = "/lights/0";
    expectPlanRejected(scene, {"position", "finite"}, format("point light at (0, %g, 0.01)", bad));
  }
}

}  // namespace
}  // namespace spectrace
