// Lights given in lumens (power_lm). The luminous flux of radiation with
// spectral power Φ_e S(λ)/∫S is 683 lm/W · Φ_e ∫V S / ∫S, V the CIE
// photopic curve (the 1931 ȳ), so power_lm L means Φ_e = L / (683 ∫V S/∫S),
// the integrals over the whole emission.
//
// Closed forms checked:
//  - a line at λ0 has efficacy 683 ȳ(λ0): 683 lm at 555 nm is 1 W;
//  - a blackbody's fraction against an independent quadrature of Planck's
//    law times ȳ over the exact total σT⁴/π;
//  - a tabulated spectrum (D65) against a trapezoid sum of its table times ȳ;
//  - rendered: an isotropic point light of L lumens at height d over a bare
//    sensor gives each pixel the illuminance L Ω / (4π A) in lux (Ω the solid
//    angle of the pixel from the light), for any spectrum: Y only sees the
//    part of the emission where ȳ > 0, which lies inside 360-830 nm (D65's
//    table runs from 300 nm: its ultraviolet carries watts but no lumens).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "colour/colour.h"
#include "reference/exact_solution.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "spectrum/spd.h"
#include "support/test_scale.h"

namespace spectrace {
namespace {

using nlohmann::json;

// A bare 2 x 2 cm sensor of 8 x 8 pixels looking up at one point light
// 1 cm above its centre, over the whole of ȳ's range.
json pointLightScene(const json& light) {
  return {{"spectrum", {{"min_nm", 360}, {"max_nm", 830}, {"bins", 47}}},
          {"camera",
           {{"position", {0, 0, 0}},
            {"look_at", {0, 0, 1}},
            {"up", {0, 1, 0}},
            {"sensor", {{"width_m", 0.02}, {"height_m", 0.02}, {"pixels", {8, 8}}}}}},
          {"lights", json::array({light})},
          {"render", {{"beams", 1000}}}};
}

json pointLight(const json& spd, const json& power) {
  json light = {{"type", "point"}, {"position", {0, 0, 0.01}}, {"spd", spd}};
  light.update(power);
  return light;
}

Scene parse(const json& root) { return parseSceneJson(root, "lumens.json"); }

std::string parseError(const json& root) {
  try {
    parse(root);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(LuminousPower, LumensBecomeWattsByTheSpectrumsEfficacy) {
  // Lines: 683 ȳ(λ0) lm/W, ȳ(555) = 1 and ȳ(600) = 0.631 in the CIE 1931 table.
  EXPECT_DOUBLE_EQ(parse(pointLightScene(pointLight({{"line_nm", 555}}, {{"power_lm", 683}}))).lights[0].powerW, 1.0);
  EXPECT_NEAR(parse(pointLightScene(pointLight({{"line_nm", 600}}, {{"power_lm", 100}}))).lights[0].powerW,
              100.0 / (683.0 * 0.631), 1e-12);

  // A blackbody at 2856 K (CIE illuminant A's temperature): Planck's law
  // times ȳ by Simpson's rule on 0.01 nm steps over 360-830 nm, over
  // σT⁴/π (σ from CODATA 2018), independent of the renderer's table.
  {
    constexpr double kKelvin = 2856.0, kSigma = 5.670374419e-8;
    const Observer& observer = cie1931Observer();
    const int steps = 47000;
    const double h = (830.0 - 360.0) / steps;
    double visible = 0.0;
    for (int i = 0; i <= steps; ++i) {
      const double lambda = 360.0 + h * i;
      const double w = (i == 0 || i == steps) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      visible += w * planckRadiance(lambda, kKelvin) * cmfAt(observer, lambda)[1];
    }
    visible *= h / 3.0;
    const double fraction = visible / (kSigma * std::pow(kKelvin, 4) / M_PI);
    const Light light = parse(pointLightScene(pointLight({{"blackbody_k", kKelvin}}, {{"power_lm", 1000}}))).lights[0];
    std::printf("blackbody 2856 K: %.4f lm/W\n", 683.0 * fraction);
    // Simpson's error on the piecewise-linear ȳ is below 1e-6 of the
    // integral at this step; the renderer's table is good to 1e-6.
    EXPECT_NEAR(light.powerW * 683.0 * fraction / 1000.0, 1.0, 5e-6);
    EXPECT_DOUBLE_EQ(light.powerLm, 1000.0);
  }

  // D65's table (300-830 nm) times ȳ, trapezoids on 0.01 nm steps: both
  // are linear between whole nanometres, so this is exact to ~1e-9.
  {
    const Spd d65 = *cieIlluminant("D65");
    const Observer& observer = cie1931Observer();
    double visible = 0.0;
    const int steps = 53000;
    const double h = (830.0 - 300.0) / steps;
    for (int i = 0; i <= steps; ++i) {
      const double lambda = 300.0 + h * i;
      const double w = (i == 0 || i == steps) ? 0.5 * h : h;
      visible += w * d65.evaluate(lambda) * cmfAt(observer, lambda)[1];
    }
    const double fraction = visible / d65.integral();
    const Light light = parse(pointLightScene(pointLight("D65", {{"power_lm", 500}}))).lights[0];
    std::printf("D65: %.4f lm/W\n", 683.0 * fraction);
    EXPECT_NEAR(light.powerW * 683.0 * fraction / 500.0, 1.0, 1e-7);
  }
  // Zero lumens is no power: beside a light that has some, or refused as
  // the only one, as power_w 0 is.
  json two = pointLightScene(pointLight("D65", {{"power_lm", 0}}));
  two["lights"].push_back(pointLight("D65", {{"power_w", 1}}));
  EXPECT_EQ(parse(two).lights[0].powerW, 0.0);
  EXPECT_NE(parseError(pointLightScene(pointLight("D65", {{"power_lm", 0}}))).find("no light emits power"),
            std::string::npos);
  // power_w stays as it was.
  const Light watts = parse(pointLightScene(pointLight("D65", {{"power_w", 2.5}}))).lights[0];
  EXPECT_EQ(watts.powerW, 2.5);
  EXPECT_LT(watts.powerLm, 0.0);
}

TEST(LuminousPower, ErrorsNameTheFieldAndWhatIsWrong) {
  const std::string both = parseError(pointLightScene(pointLight("D65", {{"power_lm", 10}, {"power_w", 1}})));
  EXPECT_NE(both.find("lumens.json: /lights/0/power_lm"), std::string::npos) << both;
  EXPECT_NE(both.find("not both"), std::string::npos) << both;

  const std::string neither = parseError(pointLightScene(pointLight("D65", json::object())));
  EXPECT_NE(neither.find("/lights/0"), std::string::npos) << neither;
  EXPECT_NE(neither.find("power_lm"), std::string::npos) << neither;

  // A near-infrared line carries no luminous flux: lumens cannot scale it.
  const std::string infrared = parseError(pointLightScene(pointLight({{"line_nm", 900}}, {{"power_lm", 10}})));
  EXPECT_NE(infrared.find("lumens.json: /lights/0/power_lm"), std::string::npos) << infrared;
  EXPECT_NE(infrared.find("line 900 nm"), std::string::npos) << infrared;
  EXPECT_NE(infrared.find("give power_w"), std::string::npos) << infrared;

  // null is absent: an override can switch a light from watts to lumens.
  const Light switched =
      parse(pointLightScene(pointLight({{"line_nm", 555}}, {{"power_w", nullptr}, {"power_lm", 683}}))).lights[0];
  EXPECT_DOUBLE_EQ(switched.powerW, 1.0);
  const std::string nulls = parseError(pointLightScene(pointLight("D65", {{"power_w", nullptr}, {"power_lm", nullptr}})));
  EXPECT_NE(nulls.find("lumens.json: /lights/0/power_w"), std::string::npos) << nulls;

  const std::string negative = parseError(pointLightScene(pointLight("D65", {{"power_lm", -5}})));
  EXPECT_NE(negative.find("lumens.json: /lights/0/power_lm"), std::string::npos) << negative;

  const std::string text = parseError(pointLightScene(pointLight("D65", {{"power_lm", "800"}})));
  EXPECT_NE(text.find("lumens.json: /lights/0/power_lm"), std::string::npos) << text;
}

// L lumens of D65 from a point 1 cm above the sensor: every pixel's Y is
// L Ω / (4π A) lux in expectation, on both devices (the same film).
TEST(LuminousPower, PointLightGivesTheIlluminanceItsLumensPredict) {
  constexpr double kLumens = 1000.0, kHeight = 0.01, kSensor = 0.02;
  const Scene scene = parse(pointLightScene(pointLight("D65", {{"power_lm", kLumens}})));
  const uint64_t beams = testing::scaledBeams(4'000'000, 400'000);
  RenderOptions options;
  options.beams = beams;
  options.seed = 7;
  options.device = DeviceChoice::Gpu;
  const RenderResult gpu = render(scene, options);
  options.device = DeviceChoice::Cpu;
  const RenderResult cpu = render(scene, options);
  // The same film (each device resolves it to XYZ in its own float order).
  EXPECT_TRUE(gpu.histogram.counts() == cpu.histogram.counts()) << "lavapipe and the CPU reference differ";
  EXPECT_TRUE(gpu.histogram.colourSums() == cpu.histogram.colourSums());

  // A landed beam's share of Y varies with its wavelength as ȳ(λ): with
  // one wavelength a beam, relative variance 1 + cv², cv² = E[ȳ²]/E[ȳ]² - 1
  // under D65 over 360-830 nm (computed here from the tables); four
  // stratified wavelengths, or colour from the bins, only lower it. So a
  // pixel's relative standard error is at most sqrt((1 + cv²) / (N p)).
  const Spd d65 = *cieIlluminant("D65");
  const Observer& observer = cie1931Observer();
  double s0 = 0.0, s1 = 0.0, s2 = 0.0;
  for (int i = 0; i <= 47000; ++i) {
    const double lambda = 360.0 + 0.01 * i;
    const double w = (i == 0 || i == 47000) ? 0.5 : 1.0;
    const double s = d65.evaluate(lambda) * w, y = cmfAt(observer, lambda)[1];
    s0 += s;
    s1 += s * y;
    s2 += s * y * y;
  }
  const double cv2 = s2 * s0 / (s1 * s1) - 1.0;

  const int n = 8;
  const double pixel = kSensor / n, area = pixel * pixel;
  double measuredTotal = 0.0, expectedTotal = 0.0, worst = 0.0;
  for (int row = 0; row < n; ++row) {
    for (int col = 0; col < n; ++col) {
      const double x1 = -0.5 * kSensor + col * pixel, y2 = 0.5 * kSensor - row * pixel;
      const double omega = rectangleSolidAngle(x1, x1 + pixel, y2 - pixel, y2, 0.0, 0.0, kHeight);
      const double expected = kLumens * omega / (4.0 * M_PI * area);
      const double p = omega / (4.0 * M_PI);
      const double sigma = expected * std::sqrt((1.0 + cv2) / (double(beams) * p));
      const double measured = gpu.image.xyz[(size_t(row) * n + col) * 3 + 1];
      worst = std::max(worst, std::abs(measured - expected) / sigma);
      // 5 sigma a pixel (a bound on sigma: the test is if anything looser).
      EXPECT_NEAR(measured, expected, 5.0 * sigma) << "pixel (" << col << ", " << row << ")";
      measuredTotal += measured * area;
      expectedTotal += expected * area;
    }
  }
  const double omegaSensor = rectangleSolidAngle(-0.5 * kSensor, 0.5 * kSensor, -0.5 * kSensor, 0.5 * kSensor, 0.0, 0.0,
                                                 kHeight);
  const double pSensor = omegaSensor / (4.0 * M_PI);
  const double sigmaTotal = expectedTotal * std::sqrt((1.0 + cv2) / (double(beams) * pSensor));
  std::printf("cv^2 %.3f; luminous flux on the sensor %.4f lm (expected %.4f, %+.2f sigma); worst pixel %.2f sigma\n",
              cv2, measuredTotal, expectedTotal, (measuredTotal - expectedTotal) / sigmaTotal, worst);
  EXPECT_NEAR(measuredTotal, expectedTotal, 5.0 * sigmaTotal);
}

}  // namespace
}  // namespace spectrace
