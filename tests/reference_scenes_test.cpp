// Every reference scene (scenes/reference/, exact answers from
// host/reference) rendered on the Vulkan device at a modest beam count. The
// error bounds come from the render's own estimated standard errors, not
// from tuned constants:
// - honesty: the measured relative RMSE agrees with the estimated one within
//   a factor of 1.5;
// - bias: the mean signed relative error is within 5 sigma, where sigma is
//   the standard error of that mean, sqrt(sum of estimated relative
//   variances) / pixels;
// - colour: the chromaticity and the luminance of the whole image are
//   within 5 sigma;
// - convergence: relRMSE over three beam counts falls with slope -0.5 +- 0.1.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "bench/error_bench.h"

namespace spectrace {
namespace {

std::string sceneFile(const std::string& name) {
  return std::string(SPECTRACE_SOURCE_DIR) + "/scenes/reference/" + name + ".json";
}

DeviceSpec vulkanDevice() {
  const auto devices = listDevices("gpu");
  if (devices.empty()) throw std::runtime_error("no Vulkan device");
  return devices.front();
}

class ReferenceScene : public ::testing::TestWithParam<const char*> {};

// Light paths, whose counts are independent, so the film's sum of squared
// weights estimates each pixel's variance (camera paths: the test below).
TEST_P(ReferenceScene, ErrorMatchesItsEstimateAndHasNoBias) {
  SweepOptions options;
  options.scenes = {sceneFile(GetParam())};
  options.beamCounts = {4'000'000};
  options.plan.cameraPaths = false;
  const auto rows = runErrorSweep({vulkanDevice()}, options);
  ASSERT_EQ(rows.size(), 1u);
  const ErrorMetrics& m = rows[0].metrics;
  std::printf("%s: relRMSE %.4g, estimated %.4g (honesty %.3f), bias %+.3e over %zu pixels, dE2000 %.3f\n", GetParam(),
              m.relRmse, m.estimatedRelRmse, m.honesty, m.bias, m.pixels, m.deltaE2000Mean);
  ASSERT_GT(m.pixels, 0u);
  ASSERT_EQ(m.pixelsWithoutEstimate, 0u) << "every compared pixel needs counts at this beam count";
  EXPECT_GT(m.honesty, 1.0 / 1.5);
  EXPECT_LT(m.honesty, 1.5);
  // Standard error of the mean relative error of independent pixels.
  const double biasSigma = m.estimatedRelRmse / std::sqrt(double(m.pixels));
  EXPECT_LE(std::abs(m.bias), 5.0 * biasSigma) << "bias " << m.bias << ", sigma " << biasSigma;
  // Colour: the chromaticity of the whole image. x = X / (X + Y + Z) moves
  // by at most (|dX/X| + |dS/S|) x <= 2 r x for relative errors <= r in
  // X, Y, Z, and the image sums' relative errors are about biasSigma, so
  // 5 sigma is 10 x biasSigma x 0.75 (x, y < 0.75). (Weighted colour sums
  // scaled as counts once put every pinhole image's colour off by 2^24.)
  // Luminance: the whole image's Y within 5 sigma, sigma = 2 x the
  // estimated relative error of its irradiance (2 bounds the ybar spread;
  // see ErrorMetrics::estimatedTotalRelError).
  std::printf("  chromaticity error %.2e (bound %.2e), Y error %+.2e (bound %.2e)\n", m.meanChromaticityError,
              7.5 * biasSigma, m.luminanceError, 10.0 * m.estimatedTotalRelError);
  EXPECT_LE(m.meanChromaticityError, 7.5 * biasSigma);
  EXPECT_LE(std::abs(m.luminanceError), 10.0 * m.estimatedTotalRelError);
}

// Camera paths on the pinhole scenes (the default estimators): stratified
// over the pixels (shaders/camera_path.h), so the film's error estimate,
// which takes every count as drawn at random, is an upper bound: the
// measured error is at most 1.5 times it (never overconfident), and the
// bias within 5 of its sigma.
TEST(ReferenceSceneCameraPaths, ErrorIsWithinItsEstimateAndHasNoBias) {
  for (const char* name : {"pinhole_rect", "pinhole_small"}) {
    SweepOptions options;
    options.scenes = {sceneFile(name)};
    options.beamCounts = {1'000'000};
    const auto rows = runErrorSweep({vulkanDevice()}, options);
    ASSERT_EQ(rows.size(), 1u);
    const ErrorMetrics& m = rows[0].metrics;
    std::printf("%s, camera paths: relRMSE %.4g, estimated %.4g (honesty %.3f), bias %+.3e over %zu pixels\n", name,
                m.relRmse, m.estimatedRelRmse, m.honesty, m.bias, m.pixels);
    ASSERT_GT(m.pixels, 0u);
    EXPECT_LT(m.honesty, 1.5) << name;
    const double biasSigma = m.estimatedRelRmse / std::sqrt(double(m.pixels));
    EXPECT_LE(std::abs(m.bias), 5.0 * biasSigma) << name << ": bias " << m.bias << ", sigma " << biasSigma;
  }
}

INSTANTIATE_TEST_SUITE_P(AllReferenceScenes, ReferenceScene,
                         ::testing::Values("point_on_axis", "point_off_axis", "disk_on_axis", "disk_off_axis",
                                           "furnace", "uniform_d65", "uniform_a", "uniform_f2", "uniform_f11",
                                           "uniform_led_b3", "laser_532", "pinhole_rect", "pinhole_small"));

TEST(ReferenceConvergence, SlopeIsMinusOneHalf) {
  for (const char* name : {"disk_off_axis", "uniform_f11"}) {
    SweepOptions options;
    options.scenes = {sceneFile(name)};
    options.beamCounts = {250'000, 1'000'000, 4'000'000};
    const auto rows = runErrorSweep({vulkanDevice()}, options);
    const double slope = convergenceSlope(rows);
    std::printf("%s: slope %.3f\n", name, slope);
    EXPECT_NEAR(slope, -0.5, 0.1) << name;
  }
}

}  // namespace
}  // namespace spectrace
