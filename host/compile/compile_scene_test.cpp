// The trace plan's aiming decisions and weights, against closed forms.
#include "compile/compile_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>

#include "camera/pinhole_camera.h"
#include "kernel/beam_kernel.h"
#include "spectrum/wavelength_sampler.h"

#include "scene/scene_builders.h"

namespace spectrace {
namespace {

Scene pinholeScene(double distanceM, double radiusM) {
  Scene scene = bareSensorScene(0.036, 0.024, 36, 24, 16);
  scene.camera.model = pinholeModel({distanceM, radiusM});
  return scene;
}

// 1 - cos(asin(s)).
double oneMinusCos(double s) { return s * s / (1.0 + std::sqrt(1.0 - s * s)); }

TEST(AimedPlan, AnEntranceFloatsCannotResolveIsRefused) {
  // A light sees a 1e-9 m pinhole from 1.1 m under 9e-10 rad: where its
  // beams cross the aperture is rounding (about 6.6e-8 m at 1.1 m), and the
  // image came out 85 times too bright. The limit is 4e-6 rad (ten times
  // the aiming slack): 4.4e-6 m at 1.1 m.
  for (const double radius : {1e-9, 4.3e-6}) {
    Scene scene = pinholeScene(0.024, radius);
    scene.lights = {pointLight({0.0, 0.0, 1.124}, 1.0, *cieIlluminant("D65"))};
    try {
      compileScene(scene, 1);
      ADD_FAILURE() << "a pinhole of " << radius << " m at 1.1 m was accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("/camera: the camera's entrance"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("below the 4e-06 rad"), std::string::npos) << e.what();
    }
  }
  for (const double radius : {4.5e-6, 25e-6}) {
    Scene scene = pinholeScene(0.024, radius);
    scene.lights = {pointLight({0.0, 0.0, 1.124}, 1.0, *cieIlluminant("D65"))};
    EXPECT_NO_THROW(compileScene(scene, 1)) << radius;
  }
}

TEST(AimedPlan, PointLightSamplesTheConeOfThePinhole) {
  // A point light 1 m in front of a 0.5 mm pinhole at 50 mm: the cone holding
  // the pinhole's sphere has 1 - cos = h with sin = r / d, and the largest
  // (and only) weight is its share of the sphere, h / 2. The slack added to
  // the sine (4e-7 against r / d = 5e-4) changes h by under 2e-3 relative.
  Scene scene = pinholeScene(0.05, 0.0005);
  scene.lights = {pointLight({0.0, 0.0, 1.05}, 2.0, *cieIlluminant("D65"))};
  const CompiledScene plan = compileScene(scene, 1);
  ASSERT_EQ(plan.device.lights.size(), 1u);
  EXPECT_EQ(plan.device.lights[0].aimed, 1u);
  const double exact = 0.5 * oneMinusCos(0.0005 / 1.0);
  EXPECT_NEAR(plan.summaries[0].largestWeight / exact, 1.0, 2e-3);
  EXPECT_GT(plan.summaries[0].largestWeight, exact) << "the sampled cone must hold the whole pinhole";
  EXPECT_NEAR(plan.sampledPowerW, plan.tracedPowerW * plan.summaries[0].largestWeight, 1e-15);
  EXPECT_FALSE(plan.film.weighted()) << "point-light weights are all 1: plain hit counts";
  // One light: exact colour comes from the bins, with no colour counters.
  EXPECT_TRUE(plan.film.colourFromBins);
  EXPECT_EQ(plan.film.countersPerPixel(), plan.film.storedBins);
  CompileOptions perBeam;
  perBeam.colourFromBins = false;
  EXPECT_EQ(compileScene(scene, 1, perBeam).film.countersPerPixel(), plan.film.storedBins + 3u);
}

TEST(AimedPlan, LightChoiceFollowsPowerTimesLargestWeight) {
  // Two equal point lights, at 0.5 m and 1 m: the nearer sees the pinhole
  // under 4x the solid angle, so it gets 4/5 of the beams.
  Scene scene = pinholeScene(0.05, 0.0005);
  scene.lights = {pointLight({0.0, 0.0, 0.55}, 1.0, *cieIlluminant("D65")),
                  pointLight({0.0, 0.0, 1.05}, 1.0, *cieIlluminant("D65"))};
  const CompiledScene plan = compileScene(scene, 1);
  ASSERT_EQ(plan.device.lights.size(), 2u);
  const double shareOfFirst = double(plan.device.lights[1].selectCdfLow) / 18446744073709551616.0;
  EXPECT_NEAR(shareOfFirst, 0.8, 2e-3);
}

TEST(AimedPlan, AimsOnlyWhereItNarrowsTheSampling) {
  Scene scene = pinholeScene(0.05, 0.0005);
  // A spot narrower than the cone towards the pinhole, a laser thinner than
  // the pinhole, a point light inside the pinhole's sphere and a panel
  // almost touching it stay analog.
  Light spot = surfaceLight(LightType::Spot, {0.0, 0.0, 0.06}, {0, 0, -1}, 1.0, *cieIlluminant("A"));
  spot.coneHalfAngleDeg = 0.5;  // the pinhole subtends 2.9 degrees from 10 mm
  Light laser = surfaceLight(LightType::Laser, {0.0, 0.0, 0.2}, {0, 0, -1}, 1.0, makeLineSpd(532.0));
  laser.radiusM = 0.0002;
  Light inside = pointLight({0.0001, 0.0, 0.0502}, 1.0, *cieIlluminant("A"));
  Light panel = surfaceLight(LightType::Disk, {0.0, 0.0, 0.0505}, {0, 0, -1}, 1.0, *cieIlluminant("A"));
  panel.radiusM = 0.01;
  scene.lights = {spot, laser, inside, panel};
  CompileOptions lightPaths;  // camera paths would make the film weighted for the disk
  lightPaths.cameraPaths = false;
  const CompiledScene plan = compileScene(scene, 1, lightPaths);
  ASSERT_EQ(plan.device.lights.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(plan.device.lights[i].aimed, 0u) << plan.summaries[i].label;
    EXPECT_EQ(plan.summaries[i].largestWeight, 1.0) << plan.summaries[i].label;
  }
  EXPECT_EQ(plan.sampledPowerW, plan.tracedPowerW);
  EXPECT_FALSE(plan.film.weighted());
}

TEST(AimedPlan, AreaLightsGetFractionalWeightsAndASquaredWeightCounter) {
  // A disk 1 m away: its closest point sees the pinhole's sphere under
  // sin = r / 1 m, so the largest weight 2h (times 1 + 1e-4 for the shader's
  // float rounding).
  Scene scene = pinholeScene(0.05, 0.0005);
  Light disk = surfaceLight(LightType::Disk, {0.0, 0.0, 1.05}, {0, 0, -1}, 1.0, *cieIlluminant("D65"));
  disk.radiusM = 0.1;
  scene.lights = {disk};
  const CompiledScene plan = compileScene(scene, 1);
  EXPECT_EQ(plan.device.lights[0].aimed, 1u);
  EXPECT_TRUE(plan.film.weighted());
  EXPECT_EQ(plan.device.constants.weighted, 1u);
  // Colour from the bins; two words per counter (weighted).
  EXPECT_EQ(plan.film.countersPerPixel(), 2u * (plan.film.storedBins + 1u));
  CompileOptions perBeam;
  perBeam.colourFromBins = false;
  EXPECT_EQ(compileScene(scene, 1, perBeam).film.countersPerPixel(), 2u * (plan.film.storedBins + 3u + 1u));
  const double exact = 2.0 * oneMinusCos(0.0005);
  EXPECT_NEAR(plan.summaries[0].largestWeight / exact, 1.0, 2e-3);
  EXPECT_NEAR(double(plan.device.lights[0].aimWeightScale) * plan.summaries[0].largestWeight, 1.0, 1e-15);
  const SpectralHistogram h = plan.film.emptyHistogram();
  EXPECT_TRUE(h.isWeighted());
  EXPECT_EQ(h.squaredWeightSums().size(), 2 * plan.film.pixelCount());
}

TEST(AimedPlan, NoAimIsTheAnalogPlan) {
  Scene scene = pinholeScene(0.05, 0.0005);
  Light disk = surfaceLight(LightType::Disk, {0.0, 0.0, 1.05}, {0, 0, -1}, 1.0, *cieIlluminant("D65"));
  disk.radiusM = 0.1;
  scene.lights = {disk, pointLight({0.0, 0.0, 1.05}, 2.0, *cieIlluminant("A"))};
  CompileOptions options;
  options.aim = false;
  options.cameraPaths = false;  // they would weight the disk's counts
  const CompiledScene plan = compileScene(scene, 1, options);
  for (const auto& light : plan.device.lights) EXPECT_EQ(light.aimed, 0u);
  EXPECT_EQ(plan.sampledPowerW, plan.tracedPowerW);
  EXPECT_FALSE(plan.film.weighted());
  EXPECT_EQ(plan.film.countersPerPixel(), plan.film.storedBins + 3u);
}

// Lights of one SPD share one spectral table and its alias columns; each
// light still draws from a table equal, bit for bit, to its own.
TEST(SpectralTables, LightsOfOneSpdShareOneTable) {
  Scene scene = pinholeScene(0.05, 0.0005);
  scene.lights = {pointLight({0.0, 0.0, 1.05}, 1.0, *cieIlluminant("D65")),
                  pointLight({0.01, 0.0, 1.05}, 2.0, *cieIlluminant("A")),
                  pointLight({0.0, 0.01, 1.05}, 3.0, *cieIlluminant("D65")),
                  pointLight({0.01, 0.01, 1.05}, 1.0, *cieIlluminant("A"))};
  const CompiledScene plan = compileScene(scene, 1);
  const auto& lights = plan.device.lights;
  ASSERT_EQ(lights.size(), 4u);
  EXPECT_EQ(lights[2].spectralFirst, lights[0].spectralFirst);
  EXPECT_EQ(lights[2].spectralAliasFirst, lights[0].spectralAliasFirst);
  EXPECT_EQ(lights[3].spectralFirst, lights[1].spectralFirst);
  EXPECT_EQ(lights[3].spectralAliasFirst, lights[1].spectralAliasFirst);
  EXPECT_NE(lights[1].spectralFirst, lights[0].spectralFirst);
  EXPECT_NE(lights[1].spectralAliasFirst, lights[0].spectralAliasFirst);
  // Two tables stored, not four.
  EXPECT_EQ(plan.device.intervals.size(), size_t(lights[0].spectralCount + lights[1].spectralCount));
  // The alias columns: the light choice's (4 lights: 4 columns), then the
  // two spectral tables'.
  EXPECT_EQ(plan.device.aliasColumns.size(),
            size_t(4 + (1u << lights[0].spectralAliasBits) + (1u << lights[1].spectralAliasBits)));
  for (size_t l = 0; l < lights.size(); ++l) {
    const SpectralTable own = buildSpectralTable(scene.lights[l].spd.clipped(scene.spectrum.minNm, scene.spectrum.maxNm));
    ASSERT_EQ(own.intervals.size(), lights[l].spectralCount) << "light " << l;
    for (size_t i = 0; i < own.intervals.size(); ++i) {
      const auto& stored = plan.device.intervals[lights[l].spectralFirst + i];
      EXPECT_EQ(stored.cdfLow, own.intervals[i].cdfLow) << "light " << l << ", interval " << i;
      EXPECT_EQ(stored.lambda0, own.intervals[i].lambda0) << "light " << l << ", interval " << i;
      EXPECT_EQ(stored.width, own.intervals[i].width) << "light " << l << ", interval " << i;
      EXPECT_EQ(stored.slope, own.intervals[i].slope) << "light " << l << ", interval " << i;
    }
  }
}

TEST(PixelWindow, HoldsEveryCountedBeamOfRandomScenes) {
  // Random lights of every type in front of random pinhole and bare
  // cameras: every beam the shared beam code counts (the CPU kernel runs the
  // shader's text) must land inside the stored window, or the device would
  // drop it. std::mt19937_64 with a fixed seed: the scenes are the same on
  // every run.
  std::mt19937_64 random(20261122);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(random); };
  int windowed = 0, beamsChecked = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Scene scene = bareSensorScene(0.036, 0.024, 48, 32, 8);
    const bool pinhole = trial % 2 == 0;
    if (pinhole) scene.camera.model = pinholeModel({uniform(0.005, 0.05), uniform(1e-4, 3e-3)});
    const double base = pinhole ? pinholeOf(scene.camera)->distanceM : 0.0;
    const LightType type = LightType(trial / 2 % 5);
    const glm::dvec3 centre(uniform(-0.05, 0.05), uniform(-0.05, 0.05), base + uniform(0.002, 0.3));
    const glm::dvec3 direction = glm::normalize(glm::dvec3(uniform(-0.5, 0.5), uniform(-0.5, 0.5), -1.0));
    Light light = surfaceLight(type, centre, direction, 1.0, makeLineSpd(550.0));
    light.radiusM = uniform(1e-4, 0.02);
    light.sizeM = {uniform(1e-3, 0.05), uniform(1e-3, 0.05)};
    light.uAxis = glm::normalize(glm::cross(direction, glm::dvec3(0.3, 1.0, 0.1)));
    light.coneHalfAngleDeg = uniform(1.0, 60.0);
    scene.lights = {light};
    CompiledScene plan;
    try {
      plan = compileScene(scene, uint64_t(trial));
    } catch (const SceneError&) {
      continue;  // the light cannot reach the sensor
    }
    windowed += plan.film.storedPixelCount() < plan.film.pixelCount();
    device::BeamKernel kernel(plan.device.constants, plan.device.lights, plan.device.intervals, plan.device.aliasColumns);
    const auto& c = plan.device.constants;
    int outside = 0;
    for (uint64_t i = 0; i < 20'000; ++i) {
      uint32_t pixel, bin;
      if (!kernel.trace(i, pixel, bin)) continue;
      ++beamsChecked;
      outside += !plan.film.storesPixel(pixel);
    }
    EXPECT_EQ(outside, 0) << "trial " << trial << " (" << lightTypeName(type) << (pinhole ? ", pinhole" : ", bare")
                          << "): window " << c.windowX0 << "+" << c.windowWidth << ", " << c.windowY0 << "+"
                          << c.windowHeight;
  }
  std::printf("%d scenes with a window smaller than the sensor; %d counted beams checked\n", windowed, beamsChecked);
  EXPECT_GT(windowed, 50);
  EXPECT_GT(beamsChecked, 100'000);
}

}  // namespace
}  // namespace spectrace

namespace spectrace {
namespace {

// Derived quantities out of range are refused before tracing, naming the
// field to change, instead of NaN or inf pixels.
std::string sceneErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(ImageRange, PixelsTooSmallToResolveNameTheSensor) {
  Scene scene = bareSensorScene(1e-310, 0.01, 4, 4);
  scene.lights = {pointLight({0.0, 0.0, 0.1}, 1.0, *cieIlluminant("D65"))};
  const std::string message = sceneErrorOf([&] { compileScene(scene, 1); });
  EXPECT_NE(message.find("/camera/sensor"), std::string::npos) << message;
}

TEST(ImageRange, PowerBeyondTheFloatImageNamesThePowerField) {
  for (double power : {1e38, 1e300}) {
    Scene scene = bareSensorScene(0.01, 0.01, 4, 4);
    Light weak = pointLight({0.0, 0.0, 0.1}, 1.0, *cieIlluminant("D65"));
    Light strong = pointLight({0.0, 0.001, 0.1}, power, *cieIlluminant("D65"));
    weak.label = "/lights/0";
    strong.label = "/lights/1";
    scene.lights = {weak, strong};
    const std::string message = sceneErrorOf([&] { compileScene(scene, 1); });
    EXPECT_NE(message.find("/lights/1/power_w"), std::string::npos) << power << ": " << message;
  }
  // A bright but representable scene is accepted.
  Scene scene = bareSensorScene(0.01, 0.01, 4, 4);
  scene.lights = {pointLight({0.0, 0.0, 0.1}, 1e20, *cieIlluminant("D65"))};
  EXPECT_NO_THROW(compileScene(scene, 1));
}

TEST(ImageRange, OneCountBelowTheSmallestFloatNamesThePowerField) {
  Scene scene = bareSensorScene(0.01, 0.01, 4, 4);
  scene.lights = {pointLight({0.0, 0.0, 0.1}, 1e-60, *cieIlluminant("D65"))};
  const CompiledScene plan = compileScene(scene, 1);
  const std::string message = sceneErrorOf([&] { checkBeamScale(scene, plan, 100'000'000); });
  EXPECT_NE(message.find("/lights/0/power_w"), std::string::npos) << message;
  EXPECT_NO_THROW(checkBeamScale(scene, compileScene([&] {
    Scene dim = scene;
    dim.lights[0].powerW = 1e-20;
    return dim;
  }(), 1), 100'000'000));
}

}  // namespace
}  // namespace spectrace
