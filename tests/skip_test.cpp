// Skipping what a scene doesn't need must not change expected values.
// Lights that cannot reach the sensor are never sampled (and reported);
// renders with and without the skip agree within their combined standard
// errors, pixel by pixel (5 sigma) and globally (chi-square, p > 0.01).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cpu/resolve_cpu.h"
#include "lights/trace_plan.h"
#include "render/gpu_tracer.h"
#include "render/renderer.h"
#include "support/statistics.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

using testing::pointLight;
using testing::surfaceLight;

// Two lights that reach the sensor and five that cannot.
Scene sceneWithUnreachableLights(bool pinhole) {
  Scene scene = testing::bareSensorScene(0.02, 0.02, 16, 16, 16);
  Light disk = surfaceLight(LightType::Disk, {0.002, 0.0, 0.01}, {0, 0, -1}, 1.0, *cieIlluminant("D65"));
  disk.radiusM = 0.004;
  Light behind = pointLight({0.0, 0.0, -0.01}, 5.0, *cieIlluminant("A"));
  Light facingAway = surfaceLight(LightType::Rect, {0.0, 0.0, 0.02}, {0, 0, 1}, 5.0, *cieIlluminant("F11"));
  facingAway.sizeM = {0.01, 0.01};
  facingAway.uAxis = {1, 0, 0};
  Light spotAway = pointLight({0.0, 0.0, 0.02}, 5.0, *cieIlluminant("D65"));
  spotAway.type = LightType::Spot;
  spotAway.direction = {0, 0, 1};
  spotAway.coneHalfAngleDeg = 30.0;
  Light laserMisses = surfaceLight(LightType::Laser, {0.05, 0.0, 0.02}, {0, 0, -1}, 5.0, makeLineSpd(600.0));
  laserMisses.radiusM = 0.001;
  Light outOfRange = pointLight({0.0, 0.0, 0.01}, 5.0, makeLineSpd(1064.0));
  scene.lights = {disk, behind, pointLight({-0.003, 0.004, 0.006}, 0.5, *cieIlluminant("LED-B3")), facingAway, spotAway,
                  laserMisses, outOfRange};
  if (pinhole) {
    scene.camera.pinhole = Pinhole{0.004, 0.003};
    for (auto& l : scene.lights) l.position.z += 0.004;
  }
  return scene;
}

TEST(SkipUnreachableLights, AreNeverSampledAndSayWhy) {
  const TracePlan plan = buildTracePlan(sceneWithUnreachableLights(false), 1);
  ASSERT_EQ(plan.summaries.size(), 7u);
  EXPECT_EQ(plan.lights.size(), 2u);
  const char* expected[] = {"", "behind the sensor plane", "", "faces away", "points away", "misses the sensor",
                            "no power inside the spectrum range"};
  for (size_t i = 0; i < 7; ++i) {
    EXPECT_EQ(plan.summaries[i].traced, std::string(expected[i]).empty()) << i;
    EXPECT_NE(plan.summaries[i].notTracedBecause.find(expected[i]), std::string::npos)
        << i << ": " << plan.summaries[i].notTracedBecause;
  }
  // Power is only spent on the two lights that can reach the sensor.
  EXPECT_NEAR(plan.tracedPowerW, plan.summaries[0].tracedPowerW + plan.summaries[2].tracedPowerW, 1e-12);
}

// Per-pixel counts and the irradiance one count carries.
struct PixelCounts {
  std::vector<uint64_t> counts;
  double perCount = 0.0;
};

PixelCounts renderPlan(const TracePlan& plan, uint64_t beams) {
  GpuTracer gpu(testing::sharedVulkan(), plan);
  gpu.trace(0, beams);
  const SpectralHistogram h = gpu.downloadHistogram();
  PixelCounts result;
  result.perCount = plan.irradiancePerCount(beams);
  for (uint64_t p = 0; p < plan.pixelCount(); ++p) {
    uint64_t c = 0;
    for (uint32_t b = 0; b < h.bins; ++b) c += h.at(uint32_t(p), b);
    result.counts.push_back(c);
  }
  return result;
}

// Two renders of the same expected image E with counts c1, c2 (Poisson, p
// small) carrying k1, k2 each: Var(k1 c1 - k2 c2) = (k1 + k2) E. Under the
// hypothesis of equal expectations E is estimated from both counts
// together, (c1 + c2) / (1/k1 + 1/k2); estimating each side's variance from
// its own count would understate it where that count is low.
void expectSameExpectation(bool pinhole, int minCells) {
  const Scene scene = sceneWithUnreachableLights(pinhole);
  TracePlanOptions unskipped;
  unskipped.skipUnreachableLights = false;
  const uint64_t beams = 4'000'000;
  const PixelCounts skipped = renderPlan(buildTracePlan(scene, 11), beams);
  const PixelCounts all = renderPlan(buildTracePlan(scene, 12, unskipped), beams);
  const double k1 = skipped.perCount, k2 = all.perCount;
  double chi2 = 0.0;
  int cells = 0;
  uint64_t hitsSkipped = 0, hitsAll = 0;
  for (size_t p = 0; p < skipped.counts.size(); ++p) {
    const double c1 = double(skipped.counts[p]), c2 = double(all.counts[p]);
    hitsSkipped += skipped.counts[p];
    hitsAll += all.counts[p];
    if (c1 + c2 < 20.0) continue;  // too few counts for the normal approximation
    const double pooled = (c1 + c2) / (1.0 / k1 + 1.0 / k2);
    const double z = (k1 * c1 - k2 * c2) / std::sqrt((k1 + k2) * pooled);
    EXPECT_LT(std::abs(z), 5.0) << "pixel " << p;
    chi2 += z * z;
    ++cells;
  }
  ASSERT_GT(cells, minCells);
  boost::math::chi_squared dist(cells);
  const double pValue = boost::math::cdf(boost::math::complement(dist, chi2));
  std::printf("%s: %llu hits with the skip, %llu without; chi2 %.1f over %d pixels, p = %.3f\n",
              pinhole ? "pinhole" : "bare", (unsigned long long)hitsSkipped, (unsigned long long)hitsAll, chi2, cells,
              pValue);
  // The skip puts more beams on the sensor for the same beam count.
  EXPECT_GT(hitsSkipped, hitsAll);
  EXPECT_GT(pValue, 0.01);
}

TEST(SkipUnreachableLights, SameExpectedImageAsTracingThemBareSensor) { expectSameExpectation(false, 200); }
TEST(SkipUnreachableLights, SameExpectedImageAsTracingThemPinhole) { expectSameExpectation(true, 50); }

}  // namespace
}  // namespace spectrace
