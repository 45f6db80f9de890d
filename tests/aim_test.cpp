// Aimed sampling must not change expected values: aimed and analog
// (--no-aim) renders of the same scene agree within their combined standard
// errors, for every light type, with a bare sensor and through a pinhole,
// pixel by pixel and in total (5 sigma) and globally (chi-square p > 1e-3).
// Aiming must also pay: more of the traced beams are counted.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "camera/pinhole_camera.h"
#include "kernel/beam_kernel.h"
#include "compile/compile_scene.h"
#include "backend/vulkan_tracer.h"
#include "support/render_comparison.h"
#include "support/test_scale.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

using testing::pointLight;
using testing::surfaceLight;

// One light of each type, placed so that aiming applies (the bare sensor's
// target sphere has radius 14 mm; the pinhole's 1 mm) and some of its
// awkward cases occur: the spot's cone edge crosses the target, the tilted
// disk and rect see the target off their normals, the laser is wider than
// the target, so some aimed origins fall outside it.
Light lightOfType(LightType type) {
  const Spd spd = *cieIlluminant("D65");
  switch (type) {
    case LightType::Point: return pointLight({0.002, 0.001, 0.03}, 1.0, spd);
    case LightType::Spot: {
      Light spot = surfaceLight(LightType::Spot, {0.0, 0.0, 0.04}, glm::normalize(glm::dvec3(0.5, 0.0, -1.0)), 1.0, spd);
      spot.coneHalfAngleDeg = 40.0;
      return spot;
    }
    case LightType::Disk: {
      Light disk = surfaceLight(LightType::Disk, {0.003, 0.0, 0.06}, glm::normalize(glm::dvec3(0.3, 0.1, -1.0)), 1.0, spd);
      disk.radiusM = 0.005;
      return disk;
    }
    case LightType::Rect: {
      Light rect = surfaceLight(LightType::Rect, {-0.004, 0.002, 0.05}, glm::normalize(glm::dvec3(-0.2, 0.3, -1.0)), 1.0,
                                spd);
      rect.sizeM = {0.008, 0.004};
      rect.uAxis = {1, 0, 0};
      return rect;
    }
    case LightType::Laser: {
      Light laser = surfaceLight(LightType::Laser, {0.004, -0.002, 0.04}, glm::normalize(glm::dvec3(0.05, 0.02, -1.0)),
                                 1.0, spd);
      laser.radiusM = 0.02;
      return laser;
    }
    case LightType::Photometric:  // never aimed (lights/photometric_light.cpp)
    case LightType::Object: break;  // never aimed (lights/object_light.cpp)
  }
  return {};
}

Scene aimScene(LightType type, bool pinhole) {
  Scene scene = testing::bareSensorScene(0.02, 0.02, 16, 16, 16);
  scene.lights = {lightOfType(type)};
  if (pinhole) {
    scene.camera.model = pinholeModel({0.01, 0.001});
    scene.lights[0].position.z += 0.01;
  }
  return scene;
}

testing::PixelEstimates renderOnGpu(const CompiledScene& plan, uint64_t beams) {
  VulkanTracer gpu(testing::sharedVulkan(), plan);
  gpu.trace(0, beams);
  return testing::pixelEstimates(gpu.download(), plan, beams);
}

struct AimCase {
  LightType type;
  bool pinhole;
};

class AimedVersusAnalog : public ::testing::TestWithParam<AimCase> {};

TEST_P(AimedVersusAnalog, SameExpectedImage) {
  const AimCase c = GetParam();
  const Scene scene = aimScene(c.type, c.pinhole);
  // Aiming is the light paths' (camera paths would count these scenes' area
  // lights in both plans alike).
  CompileOptions aimedOptions;
  aimedOptions.cameraPaths = false;
  CompileOptions analogOptions = aimedOptions;
  analogOptions.aim = false;
  const CompiledScene aimed = compileScene(scene, 101, aimedOptions);
  const CompiledScene analog = compileScene(scene, 202, analogOptions);
  ASSERT_EQ(aimed.device.lights.size(), 1u);
  EXPECT_EQ(aimed.device.lights[0].aimed, 1u) << "the scene is meant to be aimed";
  EXPECT_EQ(analog.device.lights[0].aimed, 0u);
  EXPECT_EQ(analog.sampledPowerW, analog.tracedPowerW);
  // Area lights carry varying weights; the others weights of 1 or 0.
  const bool area = c.type == LightType::Disk || c.type == LightType::Rect;
  EXPECT_EQ(aimed.film.weighted(), area);

  // Analog beams through a 1 mm pinhole are rare: give that side more. (A
  // smaller test scale keeps a quarter at least, so enough pixels still
  // hold the counts the comparison needs.)
  const uint64_t aimedBeams = testing::scaledBeams(2'000'000, 500'000);
  const uint64_t analogBeams = testing::scaledBeams(c.pinhole ? 16'000'000 : 4'000'000, c.pinhole ? 4'000'000 : 1'000'000);
  const auto a = renderOnGpu(aimed, aimedBeams);
  const auto b = renderOnGpu(analog, analogBeams);
  const std::string name = std::string(lightTypeName(c.type)) + (c.pinhole ? ", pinhole" : ", bare sensor");
  const auto comparison = testing::compareRenders(a, b, name + ": aimed vs analog");
  EXPECT_GE(comparison.cells, c.pinhole ? 2 : 50) << name;
  EXPECT_GT(comparison.pValue, 1e-3) << name;
  // Per traced beam, aiming counts more beams: at least 1.5x here (the
  // least is the laser on the bare sensor, 2x: its target's disk has half
  // the laser's cross-section).
  EXPECT_GT(double(a.countedBeams) / double(aimedBeams), 1.5 * double(b.countedBeams) / double(analogBeams)) << name;
}

INSTANTIATE_TEST_SUITE_P(EveryLightType, AimedVersusAnalog,
                         ::testing::Values(AimCase{LightType::Point, false}, AimCase{LightType::Point, true},
                                           AimCase{LightType::Spot, false}, AimCase{LightType::Spot, true},
                                           AimCase{LightType::Disk, false}, AimCase{LightType::Disk, true},
                                           AimCase{LightType::Rect, false}, AimCase{LightType::Rect, true},
                                           AimCase{LightType::Laser, false}, AimCase{LightType::Laser, true}),
                         [](const auto& info) {
                           return std::string(lightTypeName(info.param.type)) + (info.param.pinhole ? "Pinhole" : "Bare");
                         });

TEST(AimedSampling, MixedLightsKeepTheirSharesOfTheImage) {
  // Light choice moves to power x largest weight: a faint point light close
  // to a pinhole and a bright panel far from it still add up to the analog
  // image.
  Scene scene = aimScene(LightType::Disk, true);
  scene.lights.push_back(pointLight({-0.001, 0.0, 0.025}, 0.05, *cieIlluminant("A")));
  scene.lights.push_back(lightOfType(LightType::Rect));
  scene.lights.back().position.z += 0.01;
  CompileOptions aimedOptions;  // light paths, as above
  aimedOptions.cameraPaths = false;
  CompileOptions analogOptions = aimedOptions;
  analogOptions.aim = false;
  const CompiledScene aimed = compileScene(scene, 303, aimedOptions);
  const CompiledScene analog = compileScene(scene, 404, analogOptions);
  const auto a = renderOnGpu(aimed, testing::scaledBeams(2'000'000, 500'000));
  const auto b = renderOnGpu(analog, testing::scaledBeams(24'000'000, 6'000'000));
  const auto comparison = testing::compareRenders(a, b, "three lights, pinhole: aimed vs analog");
  EXPECT_GE(comparison.cells, 10);
  EXPECT_GT(comparison.pValue, 1e-3);
}

TEST(AimedSampling, ColourSumsCarryTheSameWeightsAsTheBins) {
  // A 550 nm line: every counted beam adds ybar(550) x ratio x 2^63 to Y and
  // ratio x 2^63 to its bin (a weighted film's units), each exact for
  // ratios above 2^-39 but for the float product ybar x ratio, rounded to
  // within 2^-24 relative. So the sums' ratio is ybar(550) to within
  // 2^-24 relative, a bound, not a statistical tolerance.
  Scene scene = aimScene(LightType::Disk, true);
  scene.lights[0].spd = makeLineSpd(550.0);
  CompileOptions perBeamColour;
  perBeamColour.colourFromBins = false;  // the per-beam colour counters are under test
  const CompiledScene plan = compileScene(scene, 505, perBeamColour);
  ASSERT_TRUE(plan.film.weighted());
  VulkanTracer gpu(testing::sharedVulkan(), plan);
  gpu.trace(0, 1'000'000);
  const SpectralHistogram h = gpu.download();
  double y = 0.0;
  for (size_t p = 0; p < plan.film.pixelCount(); ++p) y += realOf(h.counter(device::kFilmChannelColour, p * 3 + 1));
  const double units = double(h.total());
  ASSERT_GT(h.countedBeams, 10'000u);
  const float ybar = device::BeamKernel(plan.device.constants, plan.device.lights, plan.device.intervals, plan.device.aliasColumns, plan.device.cmfTable).cmfAtWavelength(550.0f).y;
  const double expected = double(ybar);
  const double tolerance = 0x1p-24 + 1e-12;  // the float product's rounding, and the sums' in double
  std::printf("Y sum / bin sum = %.9f, ybar(550) = %.9f (tolerance %.2g relative)\n", y / units, expected, tolerance);
  EXPECT_NEAR(y / units / expected, 1.0, tolerance);
}

}  // namespace
}  // namespace spectrace
