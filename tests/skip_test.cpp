// Skipping what a scene doesn't need must not change expected values.
// Lights that cannot reach the sensor are never sampled (and reported);
// renders with and without the skip agree within their combined standard
// errors, pixel by pixel and in total (5 sigma) and globally (chi-square,
// p > 0.01).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "camera/pinhole_camera.h"
#include "film/develop.h"
#include "compile/compile_scene.h"
#include "backend/vulkan_tracer.h"
#include "render/renderer.h"
#include "support/render_comparison.h"
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
    scene.camera.model = pinholeModel({0.004, 0.003});
    for (auto& l : scene.lights) l.position.z += 0.004;
  }
  return scene;
}

TEST(SkipUnreachableLights, AreNeverSampledAndSayWhy) {
  const CompiledScene plan = compileScene(sceneWithUnreachableLights(false), 1);
  ASSERT_EQ(plan.summaries.size(), 7u);
  EXPECT_EQ(plan.device.lights.size(), 2u);
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

testing::PixelEstimates renderPlan(const CompiledScene& plan, uint64_t beams) {
  VulkanTracer gpu(testing::sharedVulkan(), plan);
  gpu.trace(0, beams);
  return testing::pixelEstimates(gpu.download(), plan, beams);
}

void expectSameExpectation(bool pinhole, int minCells) {
  const Scene scene = sceneWithUnreachableLights(pinhole);
  // Light paths: the lights skipped would take camera paths' choices away
  // from the disk, whose sparse heavy counts the comparison's variance
  // model (one weight shape per image where a pixel is empty) does not fit.
  CompileOptions skipping;
  skipping.cameraPaths = false;
  CompileOptions unskipped = skipping;
  unskipped.skipUnreachableLights = false;
  const uint64_t beams = 4'000'000;
  const auto skipped = renderPlan(compileScene(scene, 11, skipping), beams);
  const auto all = renderPlan(compileScene(scene, 12, unskipped), beams);
  const auto comparison =
      testing::compareRenders(skipped, all, pinhole ? "pinhole, skipped vs all" : "bare, skipped vs all");
  ASSERT_GT(comparison.cells, minCells);
  // The skip puts more beams on the sensor for the same beam count.
  EXPECT_GT(skipped.countedBeams, all.countedBeams);
  EXPECT_GT(comparison.pValue, 0.01);
}

TEST(SkipUnreachableLights, SameExpectedImageAsTracingThemBareSensor) { expectSameExpectation(false, 200); }
TEST(SkipUnreachableLights, SameExpectedImageAsTracingThemPinhole) { expectSameExpectation(true, 50); }

}  // namespace
}  // namespace spectrace
