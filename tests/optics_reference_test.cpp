// Exact optics references for scene objects, each on the CPU reference and
// on the Vulkan device (lavapipe here), with fixed seeds:
//   1. a point light over a diffuse plate seen through a pinhole: each
//      pixel against the closed form (radiance rho E / pi through the
//      finite aperture, by quadrature), with the camera connection and with
//      analog transport, and the two against each other;
//   2. a point light behind the camera seen in a plane mirror of
//      reflectance rho: rho times its mirror image seen directly, in closed
//      form and as a render of the mirror image;
//   3. an absorbing disk's geometric shadow: zero counts in the umbra, the
//      unoccluded closed form outside it;
//   4. a furnace: a diffuse sphere around a point light and a small sensor,
//      rho = 1 and rho = 0.5, analog and connected, against the closed form
//      of the sphere's interreflection;
//   5. every shape and material at once, beam by beam on both devices;
//   6. a closed mesh's faces seen from outside: the kernel's normals point
//      out, and a glass slab (a box mesh) transmits the Fresnel share.
// Tolerances come from each estimator's own variance; each assertion says
// how.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "camera/pinhole_camera.h"
#include "backend/cpu_tracer.h"
#include "backend/device.h"
#include "backend/vulkan_tracer.h"
#include "camera/camera_frame.h"
#include "compile/compile_scene.h"
#include "kernel/beam_kernel.h"
#include "render/renderer.h"
#include "spectrum/glass.h"
#include "support/object_scenes.h"
#include "support/p_values.h"
#include "support/render_comparison.h"
#include "support/test_scale.h"
#include "support/test_scenes.h"
#include "reference/exact_solution.h"  // rectangleSolidAngle

namespace spectrace {

// Test names in CTest: .../Cpu  # GetParam() = cpu.
static void PrintTo(DeviceChoice choice, std::ostream* os) { *os << (choice == DeviceChoice::Gpu ? "gpu" : "cpu"); }

namespace {

using testing::toWorld;

constexpr double kPi = 3.14159265358979323846;

// --- numerics ------------------------------------------------------------------

// Gauss-Legendre nodes and weights on [0, 1] (Newton on P_n from the
// Chebyshev guesses; exact for polynomials of degree 2n - 1).
struct Quadrature {
  std::vector<double> x, w;
};
Quadrature gaussLegendre01(int n) {
  Quadrature q;
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = 0.0;
      for (int k = 1; k <= n; ++k) {
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / k;
      }
      dp = n * (z * p0 - p1) / (z * z - 1.0);
      const double step = p0 / dp;
      z -= step;
      if (std::abs(step) < 1e-16) break;
    }
    q.x.push_back(0.5 * (1.0 - z));
    q.w.push_back(1.0 / ((1.0 - z * z) * dp * dp));  // 2 / ((1 - z^2) P'^2), halved for [0, 1]
  }
  return q;
}

// Standard error of a pixel's irradiance k C for plain counts (every beam
// adds 0 or 1 to the pixel, so C is binomial(N, p)), from its expected
// irradiance: mu = E / k counts expected, Var(C) = N p (1 - p) = mu (1 - mu / N).
double binomialSigma(double expectedIrradiance, double irradiancePerCount, uint64_t beams) {
  const double mu = expectedIrradiance / irradiancePerCount;
  return irradiancePerCount * std::sqrt(std::max(mu * (1.0 - mu / double(beams)), 0.0));
}

double chiSquarePValue(double chi2, int dof) {
  return dof > 0 ? testing::chiSquareUpperTail(chi2, dof) : 1.0;
}

// A pixel's counts over all its bins.
uint64_t pixelCounts(const SpectralHistogram& h, size_t pixel) {
  uint64_t sum = 0;
  for (uint32_t b = 0; b < h.bins; ++b) sum += h.counts()[pixel * h.bins + b];
  return sum;
}

// Pixel (column, row) of the image: its rectangle on the sensor, in the
// camera frame. A bare sensor's columns run along +x and its rows down from
// +y; a pinhole image is flipped upright (shaders/sensor.h).
struct SensorRect {
  double x1, x2, y1, y2;
};
SensorRect pixelOnSensor(const Camera& camera, int col, int row) {
  const double pw = camera.sensorWidthM / camera.pixelsX, ph = camera.sensorHeightM / camera.pixelsY;
  const double hx = 0.5 * camera.sensorWidthM, hy = 0.5 * camera.sensorHeightM;
  if (pinholeOf(camera)) return {hx - (col + 1) * pw, hx - col * pw, -hy + row * ph, -hy + (row + 1) * ph};
  return {-hx + col * pw, -hx + (col + 1) * pw, hy - (row + 1) * ph, hy - row * ph};
}

// --- devices -------------------------------------------------------------------

const char* deviceName(DeviceChoice choice) { return choice == DeviceChoice::Gpu ? "Gpu" : "Cpu"; }

class OpticsReference : public ::testing::TestWithParam<DeviceChoice> {
 protected:
  const Device& device() {
    if (!device_) device_ = Device::open(GetParam(), {}, PipelineCacheOptions{false, ""});
    return *device_;
  }
  RenderResult renderHere(const Scene& scene, uint64_t beams, uint64_t seed, const CompileOptions& plan = {}) {
    RenderOptions options;
    options.beams = beams;
    options.seed = seed;
    options.plan = plan;
    options.loop.checkpointSeconds = 0.0;
    const RenderResult result = render(scene, options, device());
    EXPECT_EQ(result.deviceKind, GetParam() == DeviceChoice::Gpu ? DeviceKind::Vulkan : DeviceKind::Cpu);
    std::printf("  [%s] %llu beams in %.2f s (%.1f Mbeam/s), %llu counted\n", deviceName(GetParam()),
                (unsigned long long)beams, result.traceWallSeconds,
                result.traceWallSeconds > 0 ? double(beams) / result.traceWallSeconds * 1e-6 : 0.0,
                (unsigned long long)result.summary.countedBeams);
    return result;
  }
  const char* name() const { return deviceName(GetParam()); }

 private:
  std::unique_ptr<Device> device_;
};

// Light paths (the estimators under test here), with connections or
// analog.
CompileOptions lightPathsOnly() {
  CompileOptions o;
  o.cameraPaths = false;
  return o;
}
CompileOptions analogTransport() {
  CompileOptions o = lightPathsOnly();
  o.connect = false;
  return o;
}

// --- 1. diffuse plate through a pinhole -------------------------------------------
//
// Camera frame: sensor 20 x 20 mm (8 x 8 pixels) at z = 0, pinhole at
// z = 20 mm of radius 9 mm (large, so that analog transport counts enough
// beams; the quadrature models the finite aperture exactly). A diffuse plate
// of reflectance 0.8 at z = 40 mm faces the camera, wider than anything the
// sensor sees through the aperture (the line from sensor point p through
// aperture point a meets it at 2a - p, so |x|, |y| <= 18 + 10 = 28 mm; its
// half size is 70 mm). The point light, at (20, 3, 28) mm, 12 mm below the
// plate, is off to the side: its own lines through the aperture (k = 20 /
// (28 - 20) = 2.5) meet the sensor plane at x = -20 k + a_x (1 + k) <=
// -50 + 31.5 mm, beside the sensor (|x| < 10 mm), so it lights the sensor
// only by the plate.
struct PlateScene {
  Scene scene;
  glm::dvec3 light;  // camera frame
  double plateZ, rho, power;
};

PlateScene plateScene() {
  PlateScene p;
  p.scene = testing::bareSensorScene(0.02, 0.02, 8, 8, 4);
  p.scene.camera.model = pinholeModel({0.02, 0.009});
  p.light = {0.02, 0.003, 0.028};
  p.plateZ = 0.04;
  p.rho = 0.8;
  p.power = 2.0;
  p.scene.lights = {testing::pointLight(toWorld(p.scene.camera, p.light), p.power, makeLineSpd(550.0))};
  p.scene.objects = {testing::namedObject(
      "plate", 0,
      testing::rectShape(p.scene.camera, {0.0, 0.0, p.plateZ}, {0.0, 0.0, -1.0}, {1.0, 0.0, 0.0}, {0.14, 0.14}),
      testing::diffuseMaterial(p.rho))};
  return p;
}

// The expected irradiance of each pixel: at a sensor point p, the plate
// point x seen through aperture point a (z = d) lies on the line p -> a at
// z = Z; the plate's radiance there is L(x) = rho / pi * E(x), with the
// point light's irradiance E(x) = Phi cos(theta_x) / (4 pi r^2). The
// irradiance at p is the integral over the aperture disk of
// L cos(theta_p) cos(theta_a) / |a - p|^2 dA_a, with both cosines d / |a - p|
// (sensor and aperture planes are parallel); the pixel's is its mean over
// the pixel. Gauss-Legendre over the pixel (n x n) and over the aperture in
// s = r^2 / r_a^2 (n nodes, so dA = r_a^2 / 2 ds dphi) times 4n equally
// spaced angles; the integrand is smooth (the plate covers every line).
std::vector<double> plateExpected(const PlateScene& p, int n) {
  const Camera& camera = p.scene.camera;
  const double d = pinholeOf(camera)->distanceM, ra = pinholeOf(camera)->radiusM;
  const Quadrature q = gaussLegendre01(n);
  const int angles = 4 * n;
  std::vector<double> out;
  for (int row = 0; row < camera.pixelsY; ++row)
    for (int col = 0; col < camera.pixelsX; ++col) {
      const SensorRect r = pixelOnSensor(camera, col, row);
      double sum = 0.0;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const glm::dvec3 sensor(r.x1 + (r.x2 - r.x1) * q.x[i], r.y1 + (r.y2 - r.y1) * q.x[j], 0.0);
          double atPoint = 0.0;
          for (int k = 0; k < n; ++k)
            for (int m = 0; m < angles; ++m) {
              const double radius = ra * std::sqrt(q.x[k]), phi = 2.0 * kPi * (m + 0.5) / angles;
              const glm::dvec3 a(radius * std::cos(phi), radius * std::sin(phi), d);
              const glm::dvec3 v = a - sensor;
              const double v2 = glm::dot(v, v);
              const glm::dvec3 x = sensor + v * (p.plateZ / d);
              const glm::dvec3 toLight = p.light - x;
              const double r2 = glm::dot(toLight, toLight);
              const double cosPlate = -toLight.z / std::sqrt(r2);  // the plate faces -z, the light is below it
              const double irradiance = p.power * cosPlate / (4.0 * kPi * r2);
              const double radiance = p.rho / kPi * irradiance;
              atPoint += q.w[k] * (0.5 * ra * ra) * (2.0 * kPi / angles) * radiance * d * d / (v2 * v2);
            }
          sum += q.w[i] * q.w[j] * atPoint;
        }
      out.push_back(sum);
    }
  return out;
}

struct PixelCheck {
  double chi2 = 0.0, worst = 0.0;
  int pixels = 0;
};

// Measured against expected, pixel by pixel: each within 5 sigma (a correct
// renderer fails a pixel with probability 5.7e-7, one of 64 with 4e-5), and
// chi-square over all pixels (Gaussian z's: hundreds of counts each) with
// p > 0.001.
//
// And their sum: every render here adds at most one count per beam to the
// film (analog: the camera ends the beam; connected: the scene has one
// diffuse vertex per beam at most), so pixels are multinomial-like with
// negative covariances and sqrt(sum sigma^2) bounds the sum's standard
// error: |total - expected| <= 5 of it.
PixelCheck expectPixels(const std::vector<float>& measured, const std::vector<double>& expected,
                        const std::vector<double>& sigma, const std::string& label) {
  PixelCheck c;
  double total = 0.0, expectedTotal = 0.0, variance = 0.0;
  for (size_t i = 0; i < expected.size(); ++i) {
    total += measured[i];
    expectedTotal += expected[i];
    variance += sigma[i] * sigma[i];
    const double z = (double(measured[i]) - expected[i]) / sigma[i];
    EXPECT_LE(std::abs(z), 5.0) << label << ": pixel " << i << " measured " << measured[i] << " W/m^2, expected "
                                << expected[i] << " +- " << sigma[i];
    c.chi2 += z * z;
    c.worst = std::max(c.worst, std::abs(z));
    ++c.pixels;
  }
  const double pValue = chiSquarePValue(c.chi2, c.pixels);
  const double totalZ = (total - expectedTotal) / std::sqrt(variance);
  std::printf("  %s: %d pixels, chi2 %.1f (p = %.3f), worst %.2f sigma; total %+.2f sigma (%.2f%%)\n", label.c_str(),
              c.pixels, c.chi2, pValue, c.worst, totalZ, 100.0 * std::sqrt(variance) / expectedTotal);
  EXPECT_GT(pValue, 0.001) << label;
  EXPECT_LE(std::abs(totalZ), 5.0) << label << ": total " << total << " vs " << expectedTotal;
  return c;
}

TEST_P(OpticsReference, DiffusePlateThroughAPinhole) {
  const PlateScene p = plateScene();
  const std::vector<double> expected = plateExpected(p, 8);
  {
    // The quadrature has converged: doubling every node count changes no
    // pixel by more than 1e-6 of itself (the noise is percents).
    const std::vector<double> finer = plateExpected(p, 16);
    for (size_t i = 0; i < expected.size(); ++i) ASSERT_NEAR(expected[i], finer[i], 1e-6 * finer[i]);
  }

  // Analog: plain counts. A beam is counted at most once (the camera's body
  // ends it), so a pixel's count is binomial and its sigma follows from the
  // expected irradiance.
  // (At a smaller test scale, still tens of counts a pixel: z stays Gaussian.)
  const uint64_t kAnalogBeams = testing::scaledBeams(8'000'000, 1'000'000);
  const RenderResult analog = renderHere(p.scene, kAnalogBeams, 11, analogTransport());
  ASSERT_FALSE(analog.plan.film.weighted());
  const double k = analog.plan.irradiancePerCount(kAnalogBeams);
  std::vector<double> analogSigma;
  for (double e : expected) analogSigma.push_back(binomialSigma(e, k, kAnalogBeams));
  expectPixels(analog.image.irradiance, expected, analogSigma, std::string(name()) + " plate, analog");

  // Connected: every plate vertex sends one weighted count towards a
  // uniform point of the aperture. The plate is the only diffuse surface
  // and a beam leaving it never meets it again, so a beam makes at most one
  // count: the film's own error estimate (error.E: per pixel
  // S2 / S1^2 - 1 / N over the weights, the sample variance of the per-beam
  // contribution) is the estimator's standard error, here from hundreds of
  // counts per pixel.
  const uint64_t kConnectBeams = testing::scaledBeams(1'000'000, 250'000);
  const RenderResult connected = renderHere(p.scene, kConnectBeams, 12, lightPathsOnly());
  ASSERT_TRUE(connected.plan.film.weighted());
  ASSERT_EQ(connected.image.irradianceError.size(), expected.size());
  std::vector<double> connectedSigma;
  for (float s : connected.image.irradianceError) connectedSigma.push_back(double(s));
  for (double s : connectedSigma) ASSERT_GT(s, 0.0);
  expectPixels(connected.image.irradiance, expected, connectedSigma, std::string(name()) + " plate, connected");

  // The two estimators against each other: independent renders, so the
  // difference's variance is the sum of theirs (5 sigma per pixel, and
  // chi-square).
  std::vector<double> combined;
  std::vector<double> analogAsExpected(analog.image.irradiance.begin(), analog.image.irradiance.end());
  for (size_t i = 0; i < expected.size(); ++i)
    combined.push_back(std::hypot(analogSigma[i], connectedSigma[i]));
  expectPixels(connected.image.irradiance, analogAsExpected, combined,
               std::string(name()) + " plate, connected vs analog");
}

// --- 1b. the lit grey square matched with pbrt-v4 ---------------------------------
//
// scenes/bench/fom_lit_grey.json at 32 x 32 pixels: a grey Lambertian square
// (rho 0.5, z = 1.1 m) lit by a 1 W spot 0.25 m above the pinhole (25 deg
// half angle, uniform in solid angle: I = Phi / (2 pi (1 - cos 25 deg))),
// seen through a 25 um pinhole at 24 mm. Its closed form: the spot's
// irradiance on the square E = I cos / r^2, times rho / pi, times the
// pinhole's factor pi r_a^2 cos^4(theta) / d^2 on the sensor (the aperture's
// own extent changes it by ~1e-6 here), averaged over the pixel (Gauss-
// Legendre), in W/m^2 over the whole spectrum. Checked where the whole
// pixel sees the square inside the spot's cone. (The scene is symmetric in
// x, so the camera frame's x sense is moot.)
// A closed form's image: the pixels that lie wholly where `inside(x, y)`
// holds (checked at their corners, with a tenth of a pixel to spare), each
// with its mean of `integrand(x, y)` over the pixel (4 x 4 Gauss-Legendre);
// x, y are sensor-plane coordinates in metres.
struct ClosedFormPixels {
  std::vector<double> expected;  // W/m^2 of each checked pixel
  std::vector<size_t> pixels;    // the pixels checked
};
template <typename Inside, typename Integrand>
ClosedFormPixels closedFormPixels(const Camera& camera, Inside inside, Integrand integrand) {
  ClosedFormPixels out;
  const Quadrature q = gaussLegendre01(4);
  for (int row = 0; row < camera.pixelsY; ++row)
    for (int col = 0; col < camera.pixelsX; ++col) {
      const SensorRect r = pixelOnSensor(camera, col, row);
      const double mx = 0.1 * (r.x2 - r.x1), my = 0.1 * (r.y2 - r.y1);
      bool whole = true;
      for (double x : {r.x1 - mx, r.x2 + mx})
        for (double y : {r.y1 - my, r.y2 + my}) whole = whole && inside(x, y);
      if (!whole) continue;
      double sum = 0.0;
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
          sum += q.w[i] * q.w[j] * integrand(r.x1 + (r.x2 - r.x1) * q.x[i], r.y1 + (r.y2 - r.y1) * q.x[j]);
      out.expected.push_back(sum);
      out.pixels.push_back(size_t(row) * camera.pixelsX + col);
    }
  return out;
}

struct LitGreySquare {
  Scene scene;
  std::vector<double> expected;  // W/m^2 of each checked pixel
  std::vector<size_t> pixels;    // the pixels checked
};
LitGreySquare litGreySquare() {
  LitGreySquare s;
  Scene& scene = s.scene;
  scene = loadScene(std::string(SPECTRACE_SOURCE_DIR) + "/scenes/bench/fom_lit_grey.json");
  scene.camera.pixelsX = scene.camera.pixelsY = 32;
  // All of D65's table (300 to 830 nm), so the image holds the spot's whole
  // 1 W (the bench's 360 to 830 nm leaves out the ultraviolet's share).
  scene.spectrum = {300.0, 830.0, 53};
  const Light& spot = scene.lights.at(0);
  const double d = pinholeOf(scene.camera)->distanceM, ra = pinholeOf(scene.camera)->radiusM;
  const double z = 1.1, half = 0.3, rho = 0.5;
  const double cosCone = std::cos(spot.coneHalfAngleDeg * kPi / 180.0);
  const double intensity = spot.powerW / (2.0 * kPi * (1.0 - cosCone));
  const glm::dvec3 axis = glm::normalize(spot.direction);
  // The square's point seen from sensor point (x, y) through the aperture's centre.
  auto seen = [&](double x, double y) { return glm::dvec3(-x * (z - d) / d, -y * (z - d) / d, z); };
  auto lit = [&](const glm::dvec3& p) {
    return std::abs(p.x) < half && std::abs(p.y) < half && glm::dot(glm::normalize(p - spot.position), axis) > cosCone;
  };
  const ClosedFormPixels image = closedFormPixels(
      scene.camera, [&](double x, double y) { return lit(seen(x, y)); },
      [&](double x, double y) {
        const glm::dvec3 p = seen(x, y), toSpot = spot.position - p;
        const double r2 = glm::dot(toSpot, toSpot);
        const double irradiance = intensity * (-toSpot.z / std::sqrt(r2)) / r2;  // the square faces -z
        const double cosTheta = d / std::sqrt(x * x + y * y + d * d);
        return rho / kPi * irradiance * kPi * ra * ra * std::pow(cosTheta, 4) / (d * d);
      });
  s.expected = image.expected;
  s.pixels = image.pixels;
  return s;
}

CompileOptions withEstimators(bool lightPaths, bool cameraPaths) {
  CompileOptions o;
  o.lightPaths = lightPaths;
  o.cameraPaths = cameraPaths;
  return o;
}

// Light paths: the camera connections are worth ~1e-10 of a beam each,
// which the film must keep exactly (device_shared.h,
// kWeightUnitsFractional). A beam makes one count event at most (one
// diffuse vertex, and the spot cannot reach the aperture), and the film
// squares each event's whole weight over its wavelengths, so its own
// estimate is the standard error; with one and with four wavelengths a
// beam.
TEST_P(OpticsReference, LitGreySquareMatchesItsClosedFormWithLightPaths) {
  LitGreySquare s = litGreySquare();
  ASSERT_GT(s.pixels.size(), 300u) << "most of the image is the lit square";
  const uint64_t kBeams = testing::scaledBeams(GetParam() == DeviceChoice::Gpu ? 2'000'000 : 4'000'000, 400'000);
  for (const uint32_t k : {1u, 4u}) {
    s.scene.render.wavelengthsPerBeam = k;
    const RenderResult result = renderHere(s.scene, kBeams, 21, withEstimators(true, false));
    ASSERT_TRUE(result.plan.film.weighted());
    std::vector<float> measured;
    std::vector<double> sigma;
    for (size_t p : s.pixels) {
      measured.push_back(result.image.irradiance[p]);
      sigma.push_back(double(result.image.irradianceError[p]));
      ASSERT_GT(sigma.back(), 0.0) << "pixel " << p << " counted nothing";
    }
    expectPixels(measured, s.expected, sigma,
                 std::string(name()) + " lit grey square, light paths, k = " + std::to_string(k));
  }
}

// Camera paths (alone, and with light paths, which then count nothing
// here: every path's first surface is the diffuse square). Each path's
// count is the closed form's integrand at its own point of the pixel and
// the aperture (grey: the wavelength does not change it), and each pixel
// gets n or n + 1 of N paths (camera_path.h: whole rounds of one path per
// pixel, the last round part). So a pixel's relative error is at most
// the integrand's spread over the pixel (cos^4 and the irradiance change
// by under 3% across one) over sqrt(n), plus 1/n for the part round: 5 of
// that bounds it, far tighter than the film's own error estimate (the sum
// of squared weights, which takes the paths as drawn at random).
TEST_P(OpticsReference, LitGreySquareMatchesItsClosedFormWithCameraPaths) {
  const LitGreySquare s = litGreySquare();
  const uint64_t kPaths = testing::scaledBeams(1'000'000, 100'000);
  const double n = double(kPaths) / double(s.scene.camera.pixelsX * s.scene.camera.pixelsY);
  const double tolerance = 5.0 * (0.03 / std::sqrt(n) + 1.0 / n);
  // Camera paths alone, then both estimators, with four wavelengths a path
  // (the scene's default) and then one.
  Scene one = s.scene;
  one.render.wavelengthsPerBeam = 1;
  for (int run = 0; run < 3; ++run) {
    const bool lightPaths = run > 0;
    const RenderResult result = renderHere(run == 2 ? one : s.scene, kPaths, 22, withEstimators(lightPaths, true));
    ASSERT_TRUE(result.plan.film.weighted());
    double worst = 0.0;
    for (size_t i = 0; i < s.pixels.size(); ++i) {
      const double measured = result.image.irradiance[s.pixels[i]];
      const double relative = std::abs(measured / s.expected[i] - 1.0);
      worst = std::max(worst, relative);
      EXPECT_LE(relative, tolerance) << name() << (lightPaths ? " both" : " camera") << ": pixel " << s.pixels[i]
                                     << " measured " << measured << " W/m^2, expected " << s.expected[i];
    }
    std::printf("  %s, %s, k = %d: %zu pixels, worst relative error %.2e (tolerance %.2e)\n", name(),
                lightPaths ? "both" : "camera paths", run == 2 ? 1 : 4, s.pixels.size(), worst, tolerance);
  }
}

// Scene A of the bench (scenes/bench/fom_emitter.json at 32 x 32, over all
// of D65's table): a 0.6 m square Lambertian emitter of 1 W at z = 1.1 m
// facing the pinhole. Its radiance is L = Phi / (pi A); a sensor point that
// sees it through the aperture gets L pi r_a^2 cos^4(theta) / d^2, averaged
// over the pixel (Gauss-Legendre), checked where the whole pixel sees the
// square. Light paths (aimed beams through the pinhole, one count each: the
// film's own error is the standard error) and camera paths (seen directly;
// the same bound as the lit grey square's).
TEST_P(OpticsReference, EmitterSquareMatchesItsClosedForm) {
  Scene scene = loadScene(std::string(SPECTRACE_SOURCE_DIR) + "/scenes/bench/fom_emitter.json");
  scene.camera.pixelsX = scene.camera.pixelsY = 32;
  scene.spectrum = {300.0, 830.0, 53};
  const Light& square = scene.lights.at(0);
  const double d = pinholeOf(scene.camera)->distanceM, ra = pinholeOf(scene.camera)->radiusM;
  const double z = 1.1, half = 0.3;
  const double radiance = square.powerW / (kPi * square.sizeM.x * square.sizeM.y);
  const auto [expected, pixels] = closedFormPixels(
      scene.camera,
      [&](double x, double y) { return std::abs(x * (z - d) / d) < half && std::abs(y * (z - d) / d) < half; },
      [&](double x, double y) {
        const double cosTheta = d / std::sqrt(x * x + y * y + d * d);
        return radiance * kPi * ra * ra * std::pow(cosTheta, 4) / (d * d);
      });
  ASSERT_GT(pixels.size(), 300u) << "the square fills the middle of the image";

  for (const uint32_t k : {1u, 4u}) {  // wavelengths a beam
    scene.render.wavelengthsPerBeam = k;
    const RenderResult beams =
        renderHere(scene, testing::scaledBeams(4'000'000, 400'000), 23, withEstimators(true, false));
    std::vector<float> measured;
    std::vector<double> sigma;
    for (size_t p : pixels) {
      measured.push_back(beams.image.irradiance[p]);
      sigma.push_back(double(beams.image.irradianceError[p]));
      ASSERT_GT(sigma.back(), 0.0) << "pixel " << p << " counted nothing";
    }
    expectPixels(measured, expected, sigma, std::string(name()) + " emitter square, light paths, k = " + std::to_string(k));
  }
  scene.render.wavelengthsPerBeam = 4;

  const uint64_t kPaths = testing::scaledBeams(1'000'000, 100'000);
  const double n = double(kPaths) / double(scene.camera.pixelsX * scene.camera.pixelsY);
  const double tolerance = 5.0 * (0.03 / std::sqrt(n) + 1.0 / n);
  for (const bool lightPaths : {false, true}) {
    const RenderResult result = renderHere(scene, kPaths, 24, withEstimators(lightPaths, true));
    double worst = 0.0;
    for (size_t i = 0; i < pixels.size(); ++i) {
      const double value = result.image.irradiance[pixels[i]];
      const double relative = std::abs(value / expected[i] - 1.0);
      worst = std::max(worst, relative);
      EXPECT_LE(relative, tolerance) << name() << (lightPaths ? " both" : " camera") << ": pixel " << pixels[i]
                                     << " measured " << value << " W/m^2, expected " << expected[i];
    }
    std::printf("  %s, %s: %zu pixels, worst relative error %.2e (tolerance %.2e)\n", name(),
                lightPaths ? "both" : "camera paths", pixels.size(), worst, tolerance);
  }
}

// --- 2. plane mirror -------------------------------------------------------------
//
// Bare sensor 20 x 20 mm (8 x 8) at z = 0; the point light at (30, 2, -3) mm
// is behind the camera, so it reaches the sensor only by the mirror (z = 20
// mm, facing the sensor, reflectance 0.7): skipping the light or aiming it
// at the sensor would leave the image black. Its mirror image is at
// z = 2 * 20 + 3 = 43 mm. Every line from the image to the sensor meets
// the mirror at x in [8.6, 19.3] mm, |y| < 7.3 mm (the mirror spans x in
// [-10, 40] mm, |y| <= 25 mm), and its first leg crosses the sensor plane at
// x in [27, 29] mm, beside the sensor, whose back would absorb it.
TEST_P(OpticsReference, PointLightInAPlaneMirror) {
  constexpr double kPower = 1.0, kRho = 0.7, kMirrorZ = 0.02;
  const glm::dvec3 light(0.03, 0.002, -0.003);
  const glm::dvec3 image(light.x, light.y, 2.0 * kMirrorZ - light.z);
  Scene mirror = testing::bareSensorScene(0.02, 0.02, 8, 8, 4);
  mirror.lights = {testing::pointLight(toWorld(mirror.camera, light), kPower, makeLineSpd(550.0))};
  mirror.objects = {testing::namedObject(
      "mirror", 0,
      testing::rectShape(mirror.camera, {0.015, 0.0, kMirrorZ}, {0.0, 0.0, -1.0}, {1.0, 0.0, 0.0}, {0.05, 0.05}),
      testing::mirrorMaterial(kRho))};
  Scene direct = testing::bareSensorScene(0.02, 0.02, 8, 8, 4);
  direct.lights = {testing::pointLight(toWorld(direct.camera, image), kPower, makeLineSpd(550.0))};

  const uint64_t kBeams = testing::scaledBeams(8'000'000, 1'000'000);
  const uint64_t kDirectBeams = testing::scaledBeams(2'000'000, 250'000);
  const RenderResult seen = renderHere(mirror, kBeams, 21);
  const RenderResult reference = renderHere(direct, kDirectBeams, 22);  // shortcuts on: aimed at the sensor
  ASSERT_FALSE(seen.plan.film.weighted());
  ASSERT_GT(seen.summary.countedBeams, 0u) << "the light behind the camera was skipped or aimed away";

  // Closed form: rho x the image's irradiance, Phi Omega / (4 pi A) per
  // pixel; each beam lands at most once, so counts are binomial with
  // p = rho Omega / 4 pi.
  const Camera& camera = mirror.camera;
  const double area = (camera.sensorWidthM / camera.pixelsX) * (camera.sensorHeightM / camera.pixelsY);
  const double k = seen.plan.irradiancePerCount(kBeams);
  std::vector<double> expected, sigma;
  for (int row = 0; row < camera.pixelsY; ++row)
    for (int col = 0; col < camera.pixelsX; ++col) {
      const SensorRect r = pixelOnSensor(camera, col, row);
      const double omega = rectangleSolidAngle(r.x1, r.x2, r.y1, r.y2, image.x, image.y, image.z);
      expected.push_back(kRho * kPower * omega / (4.0 * kPi * area));
      sigma.push_back(binomialSigma(expected.back(), k, kBeams));
    }
  expectPixels(seen.image.irradiance, expected, sigma, std::string(name()) + " mirror vs rho x closed form");

  // Against the render of the mirror image itself, scaled by rho (its
  // estimate rho E has variance rho^2 v E = (rho v)(rho E)):
  // render_comparison.h's per-pixel 5 sigma, chi-square and total.
  const testing::PixelEstimates a = testing::pixelEstimates(seen.histogram, seen.plan, kBeams);
  testing::PixelEstimates b = testing::pixelEstimates(reference.histogram, reference.plan, kDirectBeams);
  for (double& e : b.irradiance) e *= kRho;
  for (double& v : b.variancePerMean) v *= kRho;
  b.totalVariance *= kRho * kRho;
  const testing::RenderComparison c = testing::compareRenders(a, b, std::string(name()) + " mirror vs rho x image");
  EXPECT_EQ(c.cells, camera.pixelsX * camera.pixelsY);
  EXPECT_GT(c.pValue, 0.001);
}

// --- 3. an absorbing disk's shadow ----------------------------------------------
//
// Bare sensor 20 x 20 mm (16 x 16), point light at (3, -1.5, 30) mm, an
// absorbing disk of radius 2 mm at (2.5, 1, 15) mm parallel to the sensor.
// From a point, the shadow of a disk on a parallel plane is the disk scaled
// by k = 30 / (30 - 15) = 2 about the light's foot: centre L + (c - L) k =
// (2, 3.5) mm, radius 2k = 4 mm. A point light has no penumbra; pixels the
// shadow's edge crosses are left out. Absorbers only take beams away, so the
// shortcuts stay on: run aimed (the light is outside the sphere round the
// sensor, so it is aimed) and analog.
TEST_P(OpticsReference, AbsorbingDiskCastsItsGeometricShadow) {
  constexpr double kPower = 1.0;
  const glm::dvec3 light(0.003, -0.0015, 0.03), disk(0.0025, 0.001, 0.015);
  constexpr double kDiskRadius = 0.002;
  Scene scene = testing::bareSensorScene(0.02, 0.02, 16, 16, 4);
  scene.lights = {testing::pointLight(toWorld(scene.camera, light), kPower, makeLineSpd(550.0))};
  scene.objects = {testing::namedObject("occluder", 0, testing::diskShape(scene.camera, disk, {0, 0, 1}, kDiskRadius),
                                        testing::absorberMaterial())};
  const double scale = light.z / (light.z - disk.z);
  const glm::dvec2 shadowCentre = glm::dvec2(light) + (glm::dvec2(disk) - glm::dvec2(light)) * scale;
  const double shadowRadius = kDiskRadius * scale;
  // 10 um margins: far beyond float rounding of the hit points (~1e-9 m).
  constexpr double kMargin = 1e-5;

  const Camera& camera = scene.camera;
  const double area = (camera.sensorWidthM / camera.pixelsX) * (camera.sensorHeightM / camera.pixelsY);
  for (bool aim : {true, false}) {
    CompileOptions options;
    options.aim = aim;
    const testing::ScaledBeams kBeams = testing::scaledBeams(aim ? 1'000'000 : 8'000'000, aim ? 125'000 : 1'000'000);
    const RenderResult result = renderHere(scene, kBeams, aim ? 31 : 32, options);
    ASSERT_FALSE(result.plan.film.weighted());
    ASSERT_EQ(result.plan.summaries.at(0).aimed, aim);
    const double k = result.plan.irradiancePerCount(kBeams);
    const std::string label = std::string(name()) + (aim ? " shadow, aimed" : " shadow, analog");
    std::vector<float> outsideMeasured;
    std::vector<double> outsideExpected, outsideSigma;
    int umbra = 0;
    double leastUmbraCounts = 1e300;
    for (int row = 0; row < camera.pixelsY; ++row)
      for (int col = 0; col < camera.pixelsX; ++col) {
        const SensorRect r = pixelOnSensor(camera, col, row);
        double farthest = 0.0;
        for (double x : {r.x1, r.x2})
          for (double y : {r.y1, r.y2}) farthest = std::max(farthest, glm::length(glm::dvec2(x, y) - shadowCentre));
        const glm::dvec2 nearestPoint(std::clamp(shadowCentre.x, r.x1, r.x2), std::clamp(shadowCentre.y, r.y1, r.y2));
        const double nearest = glm::length(nearestPoint - shadowCentre);
        const size_t pixel = size_t(row) * camera.pixelsX + col;
        const double omega = rectangleSolidAngle(r.x1, r.x2, r.y1, r.y2, light.x, light.y, light.z);
        const double unoccluded = kPower * omega / (4.0 * kPi * area);
        if (farthest <= shadowRadius - kMargin) {
          // Fully in the umbra (the disk is convex, so all four corners
          // inside means the whole pixel): exactly nothing.
          ++umbra;
          leastUmbraCounts = std::min(leastUmbraCounts, unoccluded / k);
          EXPECT_EQ(pixelCounts(result.histogram, pixel), 0u) << label << ": pixel (" << col << ", " << row << ")";
          EXPECT_EQ(result.image.irradiance[pixel], 0.0f) << label << ": pixel (" << col << ", " << row << ")";
        } else if (nearest >= shadowRadius + kMargin) {
          outsideMeasured.push_back(result.image.irradiance[pixel]);
          outsideExpected.push_back(unoccluded);
          outsideSigma.push_back(binomialSigma(unoccluded, k, kBeams));
        }
      }
    // The zero counts mean something: without the disk each umbra pixel
    // would expect thousands of counts at full scale (P(0) = e^-mu), in
    // proportion at a smaller one.
    std::printf("  %s: %d umbra pixels (each would expect >= %.0f counts unoccluded), %zu outside the shadow\n",
                label.c_str(), umbra, leastUmbraCounts, outsideExpected.size());
    EXPECT_GE(umbra, 12);
    EXPECT_GT(leastUmbraCounts, 1000.0 * double(kBeams.beams) / double(kBeams.full));
    EXPECT_GE(outsideExpected.size(), 150u);
    expectPixels(outsideMeasured, outsideExpected, outsideSigma, label + ", outside the shadow");
  }
}

// --- 4. furnace -------------------------------------------------------------------
//
// A diffuse sphere of radius R = 0.25 m and reflectance rho centred on a
// bare sensor (20 x 20 mm, 4 x 4, facing +z; its body is a flat plate that
// absorbs on both faces), a point light of power Phi at (0.3 R, 0, -1 mm),
// just behind the sensor's plane, so no beam reaches the sensor's front
// without a bounce. max_bounces = D: a beam scatters from at most D wall
// points and each can send light to the sensor (the camera counts the beam
// leaving the D-th).
//
// Derivation (S = 4 pi R^2, A the sensor's area, B_k the wall's radiosity
// after the k-th hit, F_k = integral of B_k over the wall, the flux leaving
// it). A Lambertian patch on a sphere's inside irradiates the whole sphere
// uniformly (cos at both ends = d / 2R), so without the sensor the wall's
// irradiance at the (k+1)-th hit is F_k / S whatever B_k is, and the
// sensor's front, which sees the whole front hemisphere of wall, receives
//   E_1 = (1 / pi) integral_front B_1 cos = rho I+,
//   I+- = (1 / pi) integral over the front (back) hemisphere of E_dir |cos|,
//   E_(k+1) = rho F_k / S,  F_1 = rho Phi,  F_(k+1) = rho F_k,
// i.e. the brief's E = rho I+ + rho sum_{k=2..D} Phi rho^(k-1) / S.
// The plate (both faces) removes, to first order in A / R^2:
//  - flux: it absorbs a_k = A (1 / pi) integral_all B_k |cos| of F_k
//    (a_1 = A rho (I+ + I-), a_k = 2 A B_k for uniform B_k, k >= 2), so
//    F_(k+1) = rho (F_k - a_k);
//  - a shadow: wall point y misses the radiance of its antipode -y over the
//    plate's solid angle A |cos theta_y| / R^2, an irradiance deficit
//    delta_k(y) = B_k(-y) A |cos theta_y| / (pi R^2) that the sensor's front
//    weighs with cos theta_y: E_(k+1) loses rho (1 / pi) integral_front
//    delta_k cos, which is rho^2 A J- / (pi^2 R^2) for k = 1 (J- = integral
//    over the back hemisphere of E_dir cos^2) and rho B_k 2 A / (3 pi R^2)
//    for uniform B_k.
// Both are ~1e-3 of E per bounce here (comparable to the noise, so they
// are included); what is left is O((A / R^2)^2) ~ 1e-6. The light's own
// beams that the plate's back stops (solid angle g 4 pi, g ~ 2e-5) come off
// F_1 (g ~ 8e-5); the wall they would have lit (~1e-4 m^2 at z ~ 4 mm, where
// the sensor's cos is ~0.02) adds < 1e-5 of I+, left out. I+- is averaged
// over the sensor (3 x 3 Gauss points; for uniform B the front irradiance is
// B anywhere on it). Quadrature over the hemisphere in cos theta and phi
// (smooth after integrating over phi).
struct FurnaceScene {
  Scene scene;
  glm::dvec3 light;
  double radius, rho, power, sensorSide;
  uint32_t bounces;
};

FurnaceScene furnaceScene(double rho, uint32_t bounces) {
  FurnaceScene f;
  f.radius = 0.25;
  f.rho = rho;
  f.power = 1.0;
  f.sensorSide = 0.02;
  f.bounces = bounces;
  f.light = {0.3 * f.radius, 0.0, -0.001};
  f.scene = testing::bareSensorScene(f.sensorSide, f.sensorSide, 4, 4, 4);
  f.scene.render.maxBounces = bounces;
  f.scene.lights = {testing::pointLight(toWorld(f.scene.camera, f.light), f.power, makeLineSpd(550.0))};
  f.scene.objects = {testing::namedObject("furnace", 0, testing::sphereShape(f.scene.camera, {0, 0, 0}, f.radius),
                                          testing::diffuseMaterial(rho))};
  return f;
}

// The point light's irradiance on the wall point x (inward normal -x / R).
double directIrradiance(const FurnaceScene& f, const glm::dvec3& x) {
  const glm::dvec3 toLight = f.light - x;
  const double r2 = glm::dot(toLight, toLight);
  const double cosWall = glm::dot(-x / f.radius, toLight) / std::sqrt(r2);
  return cosWall > 0.0 ? f.power * cosWall / (4.0 * kPi * r2) : 0.0;
}

// integral over the hemisphere (sign: +1 front, -1 back) seen from sensor
// point p of E_dir(wall point along omega) |cos theta|^power d omega.
double hemisphereIntegral(const FurnaceScene& f, const glm::dvec3& p, double sign, int cosPower, int n) {
  const Quadrature q = gaussLegendre01(n);
  const int angles = 2 * n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double c = q.x[i], s = std::sqrt(1.0 - c * c);
    for (int j = 0; j < angles; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / angles;
      const glm::dvec3 omega(s * std::cos(phi), s * std::sin(phi), sign * c);
      // p + t omega on the sphere: t^2 + 2 (p.omega) t + |p|^2 - R^2 = 0.
      const double b = glm::dot(p, omega);
      const double t = -b + std::sqrt(b * b - glm::dot(p, p) + f.radius * f.radius);
      sum += q.w[i] * (2.0 * kPi / angles) * directIrradiance(f, p + omega * t) * std::pow(c, cosPower);
    }
  }
  return sum;
}

// The expected mean irradiance of the sensor's front (see above).
double furnaceExpected(const FurnaceScene& f, int n) {
  const double area = f.sensorSide * f.sensorSide, r2 = f.radius * f.radius, sphere = 4.0 * kPi * r2;
  const double rho = f.rho;
  // I+ and I-, averaged over the sensor.
  const Quadrature g = gaussLegendre01(3);
  double iFront = 0.0, iBack = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const glm::dvec3 p((g.x[i] - 0.5) * f.sensorSide, (g.x[j] - 0.5) * f.sensorSide, 0.0);
      iFront += g.w[i] * g.w[j] * hemisphereIntegral(f, p, 1.0, 1, n) / kPi;
      iBack += g.w[i] * g.w[j] * hemisphereIntegral(f, p, -1.0, 1, n) / kPi;
    }
  const double jBack = hemisphereIntegral(f, glm::dvec3(0.0), -1.0, 2, n);
  // The light's beams that meet the plate's back (the light is below its
  // plane): the plate's solid angle from the light.
  const double h = f.sensorSide / 2;
  const double gShare = rectangleSolidAngle(-h, h, -h, h, f.light.x, f.light.y, -f.light.z) / (4.0 * kPi);
  double e = rho * iFront;                      // E_1
  double flux = rho * f.power * (1.0 - gShare);  // F_1
  double absorbed = area * rho * (iFront + iBack);  // a_1
  double shadow = rho * rho * area * jBack / (kPi * kPi * r2);  // what E_2 loses to the plate's shadow
  for (uint32_t k = 2; k <= f.bounces; ++k) {
    e += rho * flux / sphere - shadow;  // E_k
    const double radiosity = rho * flux / sphere;  // B_k, uniform to zeroth order
    flux = rho * (flux - absorbed);                // F_k
    absorbed = 2.0 * area * radiosity;             // a_k
    shadow = rho * radiosity * 2.0 * area / (3.0 * kPi * r2);
  }
  return e;
}

// The sensor's mean irradiance: its total counts times the irradiance of a
// count, over the pixels.
double meanIrradiance(const SpectralHistogram& h, const CompiledScene& plan, uint64_t beams) {
  return plan.irradiancePerCount(beams) * double(h.total()) / double(h.pixelsX * h.pixelsY);
}

void expectFurnace(double rho, uint32_t bounces, bool connect, uint64_t beams, const Device& device, const char* name) {
  const FurnaceScene f = furnaceScene(rho, bounces);
  const double expected = furnaceExpected(f, 48);
  // Quadrature converged: doubling the nodes moves the result < 1e-7.
  ASSERT_NEAR(expected, furnaceExpected(f, 96), 1e-7 * expected);
  // Zeroth order (no plate), the brief's formula, for the record.
  double zeroth = 0.0;
  {
    const Quadrature g = gaussLegendre01(3);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const glm::dvec3 p((g.x[i] - 0.5) * f.sensorSide, (g.x[j] - 0.5) * f.sensorSide, 0.0);
        zeroth += g.w[i] * g.w[j] * rho * hemisphereIntegral(f, p, 1.0, 1, 48) / kPi;
      }
    for (uint32_t k = 2; k <= bounces; ++k) zeroth += rho * f.power * std::pow(rho, k - 1) / (4.0 * kPi * f.radius * f.radius);
  }

  CompileOptions options;
  options.connect = connect;
  const CompiledScene plan = compileScene(f.scene, connect ? 41 : 42, options);
  ASSERT_EQ(plan.film.weighted(), connect);
  std::unique_ptr<Tracer> tracer = device.makeTracer(plan);
  const std::string label = std::string(name) + " furnace rho " + std::to_string(rho).substr(0, 3) + ", D " +
                            std::to_string(bounces) + (connect ? ", connected" : ", analog");
  if (!connect) {
    // Analog: plain counts, each beam counted at most once (the sensor ends
    // it), so the total count is binomial(N, p): sigma from the expected
    // mean irradiance E, mu = E n_pixels / k counts.
    tracer->trace(0, beams);
    const SpectralHistogram h = tracer->download();
    const double k = plan.irradiancePerCount(beams), pixels = double(h.pixelsX * h.pixelsY);
    const double measured = meanIrradiance(h, plan, beams);
    const double sigma = binomialSigma(expected * pixels, k, beams) / pixels;
    std::printf("  %s: %.6g W/m^2 vs %.6g (no plate: %.6g), %+.2f sigma (%.2f%%), %llu counts\n", label.c_str(),
                measured, expected, zeroth, (measured - expected) / sigma, 100.0 * sigma / expected,
                (unsigned long long)h.total());
    // 5 sigma: a correct renderer fails with probability 6e-7.
    EXPECT_NEAR(measured, expected, 5.0 * sigma) << label;
    return;
  }
  // Connected: every wall vertex makes a count, so one beam adds up to D
  // correlated weights, and the film's per-count squared weights do not
  // give the variance of the total. Independent batches (disjoint beam
  // ranges: every beam's random numbers depend on its index only) do: the
  // batch means' spread gives a t statistic with batches - 1 = 15 degrees
  // of freedom, and |t| <= 5 fails a correct renderer with probability
  // 1.6e-4.
  constexpr int kBatches = 16;
  const uint64_t perBatch = beams / kBatches;
  std::vector<double> means;
  for (int b = 0; b < kBatches; ++b) {
    tracer->clear();
    tracer->trace(uint64_t(b) * perBatch, perBatch);
    means.push_back(meanIrradiance(tracer->download(), plan, perBatch));
  }
  double mean = 0.0, var = 0.0;
  for (double m : means) mean += m / kBatches;
  for (double m : means) var += (m - mean) * (m - mean) / (kBatches - 1);
  const double sigma = std::sqrt(var / kBatches);
  const double t = (mean - expected) / sigma;
  const double pValue = 2.0 * testing::studentTUpperTail(std::abs(t), kBatches - 1);
  std::printf("  %s: %.6g W/m^2 vs %.6g (no plate: %.6g), t = %+.2f (p = %.3f), sigma %.2f%%\n", label.c_str(), mean,
              expected, zeroth, t, pValue, 100.0 * sigma / expected);
  EXPECT_LE(std::abs(t), 5.0) << label << ": " << mean << " vs " << expected;
}

// Reflectance 1: nothing is lost but what the sensor's plate takes, and
// D = 8 stops the beams.
TEST_P(OpticsReference, WhiteFurnaceAnalog) {
  expectFurnace(1.0, 8, false, testing::scaledBeams(4'000'000, 400'000), device(), name());
}

// Connected, a beam makes up to D counts: this once overran the CPU
// reference's queue of pending film adds (now flushed when full).
TEST_P(OpticsReference, WhiteFurnaceConnected) {
  expectFurnace(1.0, 8, true, testing::scaledBeams(1'600'000, 160'000), device(), name());
}

// rho = 0.5 with D = 40 (rho^40 ~ 1e-12: the depth limit is all but never
// reached, yet the sum runs to D exactly).
TEST_P(OpticsReference, GreyFurnaceAnalog) {
  expectFurnace(0.5, 40, false, testing::scaledBeams(8'000'000, 800'000), device(), name());
}
TEST_P(OpticsReference, GreyFurnaceConnected) {
  expectFurnace(0.5, 40, true, testing::scaledBeams(1'600'000, 160'000), device(), name());
}

// --- 6. closed meshes face outwards, and a glass slab transmits ------------------
//
// docs/objects.md: a mesh's faces run counter-clockwise seen from outside,
// so their normal points out; shaders/objects.h: primitiveNormal is outward
// for closed meshes, and transport.h decides from it whether a beam enters
// or leaves a dielectric. The kernel works in the camera frame, which is a
// reflection of the world (right = forward x up), so the winding seen from
// outside reverses there unless the compiler turns the triangles round.
//
// The compiler turns the triangles round (compile_objects.cpp); without
// that, every closed mesh's normal pointed inwards and a beam entering glass
// was refracted as if leaving it.
TEST(OpticsReferenceMesh, KernelNormalsOfAClosedMeshPointOutwards) {
  Scene scene = testing::bareSensorScene(0.02, 0.02, 4, 4, 4);
  scene.lights = {testing::pointLight({0.0, 0.0, 0.05}, 1.0, makeLineSpd(550.0))};
  const glm::dvec3 centre = toWorld(scene.camera, {0.0, 0.0, 0.1});
  scene.objects = {testing::namedObject("octahedron", 0, testing::worldOctahedron(centre, 0.02), testing::iorMaterial(1.5))};
  ASSERT_GT(testing::signedVolume6(scene.objects[0].shape.vertices, scene.objects[0].shape.triangles), 0.0)
      << "the test's mesh must run counter-clockwise from outside";
  const CompiledScene plan = compileScene(scene, 1);
  const CameraFrame frame = CameraFrame::fromCamera(scene.camera);
  const glm::vec3 localCentre(frame.pointToLocal(centre));
  device::BeamKernel kernel(plan.device.constants, plan.device.lights, plan.device.intervals, plan.device.aliasColumns);
  kernel.setObjects(plan.device.primitives, plan.device.bvhNodes, plan.device.materials, plan.device.data.words());
  ASSERT_EQ(plan.device.primitives.size(), 8u);
  int inward = 0;
  for (const device::Primitive& p : plan.device.primitives) {
    const glm::vec3 centroid = p.a + (p.b + p.c) / 3.0f;
    const glm::vec3 n = kernel.primitiveNormal(p, centroid);
    inward += glm::dot(n, centroid - localCentre) < 0.0f;
  }
  EXPECT_EQ(inward, 0) << inward << " of 8 faces have a kernel normal pointing into the mesh";
}

// The physical consequence. A laser (collimated, radius 1 mm) at 45 degrees
// through a glass slab of n = 1.5 (a closed box mesh, 10 mm thick, 80 mm
// wide) onto a bare sensor 60 mm wide. Each interface reflects the
// unpolarised Fresnel share R(45 deg) = (rs^2 + rp^2) / 2 = 0.0502 (the same
// for the internal angle, 28.1 deg, by reciprocity), so the beam that reaches
// the sensor after 2j internal reflections carries (1 - R)^2 R^(2j): it
// leaves the slab 2 * 10 mm * tan 28.1 deg = 10.7 mm further along x each
// time, and lands at x = 5.4, 16.0, 26.8 mm (j = 0, 1, 2; j = 3 misses the
// sensor, R^6 ~ 1e-8). The reflected beams go up and away. Plain counts,
// one per beam at most: binomial.
//
// With inward normals every beam met total internal reflection on entry
// (sin^2 = 1.125) and none was transmitted.
// The laser at 550 nm and the slab of `glass` above.
Scene glassSlabScene(const SurfaceMaterial& glass) {
  Scene scene = testing::bareSensorScene(0.06, 0.06, 6, 6, 4);
  const glm::dvec3 direction = glm::normalize(glm::dvec3(1.0, 0.0, -1.0));
  Light laser = testing::surfaceLight(LightType::Laser, toWorld(scene.camera, {-0.02, 0.0, 0.03}),
                                      testing::directionToWorld(scene.camera, direction), 1.0, makeLineSpd(550.0));
  laser.radiusM = 0.001;
  scene.lights = {laser};
  // The box's corners in the world: the camera frame's (x, y, z) is the
  // world's (-x, y, z) for this camera, so [lo, hi] maps to itself mirrored.
  const glm::dvec3 a = toWorld(scene.camera, {-0.04, -0.04, 0.005}), b = toWorld(scene.camera, {0.04, 0.04, 0.015});
  scene.objects = {testing::namedObject("slab", 0, testing::worldBox(glm::min(a, b), glm::max(a, b)), glass)};
  return scene;
}

TEST_P(OpticsReference, GlassSlabMeshTransmitsTheFresnelShare) {
  constexpr double kN = 1.5;
  const Scene scene = glassSlabScene(testing::iorMaterial(kN));

  const double cosI = std::sqrt(0.5), sinT = std::sqrt(0.5) / kN, cosT = std::sqrt(1.0 - sinT * sinT);
  const double rs = (cosI - kN * cosT) / (cosI + kN * cosT), rp = (kN * cosI - cosT) / (kN * cosI + cosT);
  const double r = 0.5 * (rs * rs + rp * rp);
  const double expected = (1.0 - r) * (1.0 - r) * (1.0 + r * r + r * r * r * r);

  constexpr uint64_t kBeams = 400'000;
  const RenderResult result = renderHere(scene, kBeams, 61);
  ASSERT_FALSE(result.plan.film.weighted());
  const double share = double(result.histogram.total()) / double(kBeams);
  const double sigma = std::sqrt(expected * (1.0 - expected) / double(kBeams));
  std::printf("  %s slab: transmitted %.5f, expected %.5f (R = %.4f), %+.1f sigma\n", name(), share, expected, r,
              (share - expected) / sigma);
  EXPECT_NEAR(share, expected, 5.0 * sigma);
}

// The same slab of dispersive N-BK7, with the laser's line at 550 nm, at
// one, two and four wavelengths a beam. Dispersive glass keeps a beam's
// hero wavelength alone, its share k times 1/k; the beam crosses two faces
// (more after internal reflections), and the share must be raised once
// only: before, each face multiplied it by k again, and the transmitted
// power came out k times too large. Each beam carries weight 1 or 0 at the
// sensor, so its share of the power is binomial at every k.
TEST_P(OpticsReference, DispersiveSlabTransmitsTheFresnelShareAtEveryWavelengthsPerBeam) {
  const SellmeierGlass* glass = glassNamed("N-BK7");
  ASSERT_NE(glass, nullptr);
  const double n = sellmeierIndex(glass->b, glass->cUm2, 550.0);
  Scene scene = glassSlabScene(testing::glassMaterial("N-BK7"));

  const double cosI = std::sqrt(0.5), sinT = std::sqrt(0.5) / n, cosT = std::sqrt(1.0 - sinT * sinT);
  const double rs = (cosI - n * cosT) / (cosI + n * cosT), rp = (n * cosI - cosT) / (n * cosI + cosT);
  const double r = 0.5 * (rs * rs + rp * rp);
  const double expected = (1.0 - r) * (1.0 - r) * (1.0 + r * r + r * r * r * r);
  constexpr uint64_t kBeams = 200'000;
  for (uint32_t k : {1u, 2u, 4u}) {
    scene.render.wavelengthsPerBeam = k;
    const RenderResult result = renderHere(scene, kBeams, 62);
    const SpectralHistogram& h = result.histogram;
    const double share = h.total() / double(h.unitsPerBeam) / double(kBeams);
    const double sigma = std::sqrt(expected * (1.0 - expected) / double(kBeams));
    std::printf("  %s N-BK7 slab, k = %u: transmitted %.5f, expected %.5f (n = %.5f, R = %.4f), %+.1f sigma\n",
                name(), k, share, expected, n, r, (share - expected) / sigma);
    EXPECT_NEAR(share, expected, 5.0 * sigma) << "k = " << k;  // 5 sigma of the binomial share
  }
}

INSTANTIATE_TEST_SUITE_P(Devices, OpticsReference, ::testing::Values(DeviceChoice::Cpu, DeviceChoice::Gpu),
                         [](const ::testing::TestParamInfo<DeviceChoice>& info) { return deviceName(info.param); });

// --- 5. every shape and material, beam by beam ------------------------------------
//
// A pinhole camera looks at a ColorChecker floor and back wall (diffuse,
// varying reflectance), a mirror disk, an N-BK7 sphere and octahedron (a
// closed mesh), a diffuse ColorChecker sphere and an absorbing disk, lit by
// a D65 point light (so wavelengths, reflectances and indices vary). The
// CPU reference and lavapipe run the same kernel with NoContraction and the
// same Philox blocks, so every record (pixel, bin, units, count of
// contributions) must be identical.
Scene everyObjectScene() {
  Scene scene = testing::bareSensorScene(0.036, 0.024, 36, 24, 32);
  scene.camera.model = pinholeModel({0.02, 0.006});
  const Camera& c = scene.camera;
  scene.lights = {testing::pointLight(toWorld(c, {0.0, 0.024, 0.06}), 2.0, *cieIlluminant("D65"))};
  using testing::namedObject;
  scene.objects = {
      namedObject("floor", 0, testing::rectShape(c, {0.0, -0.024, 0.08}, {0, 1, 0}, {1, 0, 0}, {0.2, 0.2}),
                  testing::colorCheckerMaterial("orange")),
      namedObject("wall", 1, testing::rectShape(c, {0.0, 0.0, 0.14}, {0, 0, -1}, {1, 0, 0}, {0.2, 0.12}),
                  testing::colorCheckerMaterial("bluish_green")),
      namedObject("mirror", 2, testing::diskShape(c, {-0.028, 0.0, 0.088}, {1.0, 0.0, -0.6}, 0.016),
                  testing::mirrorMaterial(0.9)),
      namedObject("lens", 3, testing::sphereShape(c, {0.016, -0.008, 0.072}, 0.014), testing::glassMaterial("N-BK7")),
      namedObject("prism", 4, testing::worldOctahedron(toWorld(c, {-0.008, 0.0, 0.056}), 0.01),
                  testing::glassMaterial("N-BK7")),
      namedObject("ball", 5, testing::sphereShape(c, {-0.012, -0.015, 0.104}, 0.008),
                  testing::colorCheckerMaterial("yellow")),
      namedObject("blind", 6, testing::diskShape(c, {0.024, 0.02, 0.1}, {0, 0, -1}, 0.012), testing::absorberMaterial()),
  };
  return scene;
}

// Records of paths [0, count) from the CPU reference and lavapipe; the
// number that differ is reported, up to five of them as failures.
struct RecordComparison {
  uint64_t differ = 0, counted = 0, several = 0;
  uint32_t most = 0;
};
RecordComparison compareRecords(const CompiledScene& plan, uint32_t count, const char* label) {
  VulkanTracer gpu(testing::sharedVulkan(), plan);
  CpuTracer cpu(plan, 1);
  const std::vector<device::BeamRecord> fromGpu = gpu.traceRecorded(0, count);
  const std::vector<device::BeamRecord> fromCpu = cpu.traceRecorded(0, count);
  RecordComparison c;
  if (fromGpu.size() != size_t(count) || fromCpu.size() != size_t(count)) {
    ADD_FAILURE() << label << ": " << fromCpu.size() << " and " << fromGpu.size() << " records, not " << count;
    return c;
  }
  for (uint32_t i = 0; i < count; ++i) {
    const device::BeamRecord& a = fromCpu[i];
    const device::BeamRecord& b = fromGpu[i];
    c.counted += a.pixel != device::kBeamMissed;
    c.several += a.contributions > 1;
    c.most = std::max(c.most, a.contributions);
    if (a.pixel != b.pixel || a.bin != b.bin || a.ratioBits != b.ratioBits || a.contributions != b.contributions) {
      if (++c.differ <= 5)
        ADD_FAILURE() << label << ": path " << i << ": cpu (pixel " << a.pixel << ", bin " << a.bin << ", ratio bits "
                      << a.ratioBits << ", contributions " << a.contributions << "), gpu (pixel " << b.pixel << ", bin "
                      << b.bin << ", ratio bits " << b.ratioBits << ", contributions " << b.contributions << ")";
    }
  }
  std::printf("%s: %u paths, %llu differ, %llu counted (%.2f%%), %llu with several counts (most %u)\n", label, count,
              (unsigned long long)c.differ, (unsigned long long)c.counted, 100.0 * double(c.counted) / count,
              (unsigned long long)c.several, c.most);
  return c;
}

void expectIdenticalRecords(bool connect, uint32_t count, uint32_t wavelengthsPerBeam = 1) {
  Scene scene = everyObjectScene();
  scene.render.wavelengthsPerBeam = wavelengthsPerBeam;
  CompileOptions options;
  options.connect = connect;
  options.cameraPaths = false;  // light paths alone
  const CompiledScene plan = compileScene(scene, 2025, options);
  ASSERT_EQ(plan.device.constants.connect, connect ? 1u : 0u);
  const std::string label =
      std::string(connect ? "connected" : "analog") + ", k = " + std::to_string(wavelengthsPerBeam);
  const auto [differ, counted, several, most] = compareRecords(plan, count, label.c_str());
  EXPECT_EQ(differ, 0u);
  // A meaningful share is counted, and connections make beams count more
  // than once.
  EXPECT_GT(counted, count / (connect ? 20 : 1000));
  if (connect) EXPECT_GT(several, count / 1000);
  else EXPECT_EQ(most, counted > 0 ? wavelengthsPerBeam : 0u);  // analog: one count a wavelength at most
}

TEST(OpticsReferenceBeams, EveryShapeAndMaterialConnectedBeamByBeam) { expectIdenticalRecords(true, 200'000); }
// Four wavelengths a beam: per-wavelength roulette, connections and the
// hero alone through dispersive glass.
TEST(OpticsReferenceBeams, EveryShapeAndMaterialConnectedFourWavelengthsBeamByBeam) {
  expectIdenticalRecords(true, uint32_t(testing::scaledBeams(200'000, 40'000)), 4);
}

// Camera paths (with the light paths they leave over) through the same
// objects, lit also by a spot, a disk and a rect light, which camera paths
// see directly and sample at diffuse vertices: every record identical.
TEST(OpticsReferenceBeams, EveryShapeAndMaterialCameraPathsPathByPath) {
  Scene scene = everyObjectScene();
  const Camera& c = scene.camera;
  Light spot = testing::pointLight(toWorld(c, {0.02, 0.02, 0.03}), 1.0, *cieIlluminant("A"));
  spot.type = LightType::Spot;
  spot.direction = testing::directionToWorld(c, glm::normalize(glm::dvec3(-0.2, -0.3, 1.0)));
  spot.coneHalfAngleDeg = 30.0;
  Light disk = surfaceLight(LightType::Disk, toWorld(c, {-0.03, 0.02, 0.12}),
                            testing::directionToWorld(c, glm::normalize(glm::dvec3(0.3, -0.2, -1.0))),
                            1.0, makeBlackbodySpd(2700, 360, 830));
  disk.radiusM = 0.01;
  Light rect = surfaceLight(LightType::Rect, toWorld(c, {0.03, 0.0, 0.1}),
                            testing::directionToWorld(c, glm::normalize(glm::dvec3(-0.5, 0.0, -1.0))),
                            1.0, *cieIlluminant("F11"));
  rect.sizeM = {0.02, 0.01};
  rect.uAxis = testing::directionToWorld(c, glm::normalize(glm::dvec3(1.0, 0.0, -0.5)));
  scene.lights.push_back(spot);
  scene.lights.push_back(disk);
  scene.lights.push_back(rect);
  scene.render.wavelengthsPerBeam = 4;
  const CompiledScene plan = compileScene(scene, 2026);
  ASSERT_EQ(plan.device.constants.estimators, device::kEstimatorLightPaths | device::kEstimatorCameraPaths);
  const uint32_t count = uint32_t(testing::scaledBeams(200'000, 40'000));
  const RecordComparison c2 = compareRecords(plan, count, "light and camera paths");
  EXPECT_EQ(c2.differ, 0u);
  EXPECT_GT(c2.counted, count / 4) << "most camera paths see something lit";
  EXPECT_GT(c2.several, count / 100) << "paths with light samples at several diffuse vertices";
}
// Analog transport through a pinhole counts few beams (~0.3%): more of them.
TEST(OpticsReferenceBeams, EveryShapeAndMaterialAnalogBeamByBeam) {
  expectIdenticalRecords(false, uint32_t(testing::scaledBeams(1'000'000, 200'000)));
}

}  // namespace
}  // namespace spectrace
