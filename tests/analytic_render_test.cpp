// Analytic render: an isotropic point light of flux Phi over a bare sensor.
// A pixel [x1,x2] x [y1,y2] in the sensor plane, seen from the light at
// height d above (x0, y0), subtends the solid angle
//   Omega = sum over corners of +-atan(a b / (d sqrt(a^2 + b^2 + d^2))),
// (a, b the corner's offsets), so its mean irradiance is Phi Omega / (4 pi A)
// exactly; at the pixel centre it tends to Phi d / (4 pi (r^2 + d^2)^(3/2)).
// The count in a pixel is binomial(N, p = Omega / 4 pi), which gives each
// pixel's Monte Carlo standard error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "camera/camera_frame.h"
#include "backend/vulkan_tracer.h"
#include "film/spectral_histogram.h"
#include "render/renderer.h"
#include "spectrum/spd.h"
#include "support/p_values.h"
#include "support/statistics.h"
#include "support/test_scale.h"
#include "support/test_scenes.h"
#include "reference/exact_solution.h"  // rectangleSolidAngle

namespace spectrace {
namespace {

void expectPointLightIrradiance(glm::dvec3 lightWorld, uint64_t beams, const char* name) {
  constexpr double kPower = 3.0;
  Scene scene = testing::bareSensorScene(0.036, 0.024, 48, 32, 16);
  // A Dirac line keeps the whole flux inside the spectrum range.
  scene.lights = {testing::pointLight(lightWorld, kPower, makeLineSpd(550.0))};
  RenderOptions options;
  options.beams = beams;
  options.seed = 2024;
  options.device = DeviceChoice::Gpu;
  const RenderResult result = render(scene, options);
  ASSERT_EQ(result.deviceKind, DeviceKind::Vulkan);

  const CameraFrame frame = CameraFrame::fromCamera(scene.camera);
  const glm::dvec3 light = frame.pointToLocal(lightWorld);
  const double pw = scene.camera.sensorWidthM / scene.camera.pixelsX;
  const double ph = scene.camera.sensorHeightM / scene.camera.pixelsY;
  const double area = pw * ph;
  double chi2 = 0.0, worstSigmas = 0.0, meanRelError = 0.0;
  int pixels = 0;
  for (int row = 0; row < scene.camera.pixelsY; ++row) {
    for (int col = 0; col < scene.camera.pixelsX; ++col) {
      // Columns run along camera right, rows down from camera up.
      const double x1 = -0.5 * scene.camera.sensorWidthM + col * pw;
      const double y2 = 0.5 * scene.camera.sensorHeightM - row * ph;
      const double omega = rectangleSolidAngle(x1, x1 + pw, y2 - ph, y2, light.x, light.y, light.z);
      const double p = omega / (4.0 * M_PI);
      const double expected = kPower * omega / (4.0 * M_PI * area);
      const double sigma = kPower / (double(beams) * area) * std::sqrt(double(beams) * p * (1.0 - p));
      const double measured = result.image.irradiance[size_t(row) * scene.camera.pixelsX + col];
      const double z = (measured - expected) / sigma;
      chi2 += z * z;
      worstSigmas = std::max(worstSigmas, std::abs(z));
      meanRelError += std::abs(measured - expected) / expected;
      ++pixels;
      // 5 sigma per pixel: a correct renderer fails one of 1536 pixels with
      // probability ~1e-3.
      EXPECT_LE(std::abs(z), 5.0) << name << " pixel (" << col << ", " << row << ") measured " << measured
                                  << " W/m^2, expected " << expected << " +- " << sigma;
    }
  }
  const double pValue = testing::chiSquareUpperTail(chi2, pixels);
  std::printf("%s: %d pixels, chi2 = %.1f (p = %.3f), worst %.2f sigma, mean |rel. error| %.4f\n", name, pixels, chi2,
              pValue, worstSigmas, meanRelError / pixels);
  // Global test of all pixels together (p > 0.01 for this fixed seed).
  EXPECT_GT(pValue, 0.01);
}

TEST(AnalyticRender, PointLightOnTheAxisOfABareSensor) {
  expectPointLightIrradiance({0.0, 0.0, 0.01}, testing::scaledBeams(16'000'000, 2'000'000), "on axis");
}

TEST(AnalyticRender, PointLightOffAxis) {
  expectPointLightIrradiance({0.01, -0.004, 0.015}, testing::scaledBeams(16'000'000, 2'000'000), "off axis");
}

TEST(AnalyticRender, CpuReferenceToo) {
  // The same physics on the CPU path, through the CPU resolve.
  constexpr double kPower = 1.0, kDistance = 0.01;
  Scene scene = testing::bareSensorScene(0.02, 0.02, 8, 8, 4);
  scene.lights = {testing::pointLight({0.0, 0.0, kDistance}, kPower, makeLineSpd(600.0))};
  RenderOptions options;
  options.beams = 4'000'000;
  options.device = DeviceChoice::Cpu;
  const RenderResult result = render(scene, options);
  double measured = 0.0;
  for (float e : result.image.irradiance) measured += e;
  measured *= 0.0025 * 0.0025;  // flux onto the sensor
  const double omega = rectangleSolidAngle(-0.01, 0.01, -0.01, 0.01, 0.0, 0.0, kDistance);
  const double p = omega / (4.0 * M_PI);
  const double sigma = kPower * std::sqrt(p * (1.0 - p) / double(options.beams));
  EXPECT_NEAR(measured, kPower * p, 5.0 * sigma);
}

// Beams of four wavelengths (hero wavelength sampling, shaders/wavelengths.h)
// from D65 onto a bare sensor, on both devices. Each beam that lands counts
// a quarter of a beam in each of its four wavelengths' bins, so:
//  - every pixel holds exactly its landed beams over all bins, and the
//    image is the analog one's (binomial(N, Omega / 4 pi) a pixel);
//  - bin b over the sensor holds H p_b in expectation (H beams landed, p_b
//    D65's share of the bin), each of the four a draw from the table, with
//    variance at most H p_b (1 - p_b) / 4 (their steps of the CDF are
//    stratified, not independent);
//  - the film's error estimate squares each beam's whole weight, not its
//    four quarters, so it is the binomial standard error, not half of it;
//  - the CPU reference and lavapipe count the same film.
TEST(AnalyticRender, FourWavelengthsABeamKeepTheImageAndSpreadTheSpectrum) {
  constexpr double kPower = 1.0, kDistance = 0.01;
  constexpr int kBins = 16;
  Scene scene = testing::bareSensorScene(0.036, 0.024, 12, 8, kBins);
  scene.render.wavelengthsPerBeam = 4;
  const Spd d65 = *cieIlluminant("D65");
  scene.lights = {testing::pointLight({0.0, 0.0, kDistance}, kPower, d65)};
  RenderOptions options;
  options.beams = testing::scaledBeams(2'000'000, 400'000);
  options.seed = 77;
  options.device = DeviceChoice::Cpu;
  const RenderResult cpu = render(scene, options);
  options.device = DeviceChoice::Gpu;
  const RenderResult gpu = render(scene, options);
  ASSERT_TRUE(cpu.plan.film.weighted()) << "quarters of a beam need the weighted film";
  ASSERT_EQ(cpu.histogram.channel(device::kFilmChannelBins), gpu.histogram.channel(device::kFilmChannelBins));
  ASSERT_EQ(cpu.histogram.channel(device::kFilmChannelSquaredWeight),
            gpu.histogram.channel(device::kFilmChannelSquaredWeight));

  const SpectralHistogram& h = cpu.histogram;
  const double unit = double(h.unitsPerBeam);  // 2^63 a beam: quarters are exact
  const uint32_t pixels = h.pixelsX * h.pixelsY;
  std::vector<double> binBeams(h.bins, 0.0);
  double landed = 0.0;
  for (uint32_t p = 0; p < pixels; ++p) {
    double pixelBeams = 0.0;
    for (uint32_t b = 0; b < h.bins; ++b) {
      const double beams = realOf(h.count(p, b)) / unit;
      binBeams[b] += beams;
      pixelBeams += beams;
    }
    EXPECT_EQ(pixelBeams, std::round(pixelBeams)) << "pixel " << p << ": whole beams over its bins";
    landed += pixelBeams;
  }
  const double n = double(options.beams);
  const double omega = rectangleSolidAngle(-0.018, 0.018, -0.012, 0.012, 0.0, 0.0, kDistance);
  const double p = omega / (4.0 * M_PI);
  // 5 sigma of the binomial count of landed beams.
  EXPECT_NEAR(landed, n * p, 5.0 * std::sqrt(n * p * (1.0 - p)));

  const double inRange = d65.clipped(360.0, 830.0).integral();
  const double width = (830.0 - 360.0) / kBins;
  for (int b = 0; b < kBins; ++b) {
    const double share = d65.clipped(360.0 + b * width, 360.0 + (b + 1) * width).integral() / inRange;
    const double bound = std::sqrt(landed * share * (1.0 - share) / 4.0);
    // 5 sigma of four independent quarters: stratified, they vary less.
    EXPECT_NEAR(binBeams[size_t(b)], landed * share, 5.0 * bound + 1e-9) << "bin " << b;
  }

  // The same beams with one wavelength each land in the same pixels (a
  // bare sensor: no position depends on the wavelength), so the plain
  // film's image and binomial error are what these must be. Counting the
  // quarters as four samples would halve the error.
  scene.render.wavelengthsPerBeam = 1;
  options.device = DeviceChoice::Cpu;
  const RenderResult one = render(scene, options);
  ASSERT_FALSE(one.plan.film.weighted());
  double worstImage = 0.0, worstError = 0.0;
  for (size_t i = 0; i < one.image.irradiance.size(); ++i) {
    worstImage = std::max(worstImage, std::abs(cpu.image.irradiance[i] / one.image.irradiance[i] - 1.0));
    worstError = std::max(worstError, std::abs(cpu.image.irradianceError[i] / one.image.irradianceError[i] - 1.0));
  }
  std::printf("landed %.0f of %.0f (expected %.1f); against one wavelength a beam: image within %.1e, error within "
              "%.1e\n",
              landed, n, n * p, worstImage, worstError);
  EXPECT_LE(worstImage, 1e-6) << "the same beams in the same pixels, up to float rounding";
  EXPECT_LE(worstError, 1e-4) << "the error estimate of whole beams";
}

}  // namespace
}  // namespace spectrace
