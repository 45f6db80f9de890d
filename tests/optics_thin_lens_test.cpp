// Exact references for the thin lens camera (camera/thin_lens_camera.cpp),
// each scene rendered on the CPU reference and on lavapipe, which must give
// the same film bit for bit; the statistics are checked on the CPU's
// render, which may go on with more beams.
//   1. Points in focus: every count of each point lands in the pixel of its
//      predicted image point (-P s / h, h its height over the lens), and
//      each pixel holds the flux the lens disk subtends from its point.
//   2. A point out of focus: its blur disk has radius a |s - v| / v (v the
//      point's image distance); no count lands outside it, and inside it
//      each pixel's irradiance matches the closed form (5 sigma, and a
//      chi-square over the disk), as does the total.
//   3. A diffuse plate out of focus: camera connections and camera paths
//      each against analog transport, per pixel within 5 sigma.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "camera/thin_lens_camera.h"
#include "reference/exact_solution.h"
#include "render/renderer.h"
#include "support/object_scenes.h"
#include "support/device_renders.h"
#include "support/p_values.h"
#include "support/render_comparison.h"
#include "support/test_scale.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

using testing::toWorld;

constexpr double kPi = 3.14159265358979323846;

CompileOptions estimators(bool lightPaths, bool cameraPaths, bool connect = true) {
  CompileOptions o;
  o.lightPaths = lightPaths;
  o.cameraPaths = cameraPaths;
  o.connect = connect;
  return o;
}

// Pixel (column, row) of the flipped-upright image: its centre on the
// sensor, in the camera frame (shaders/sensor.h, hitSensor).
glm::dvec2 pixelCentre(const Camera& camera, int col, int row) {
  const double pw = camera.sensorWidthM / camera.pixelsX, ph = camera.sensorHeightM / camera.pixelsY;
  return {0.5 * camera.sensorWidthM - (col + 0.5) * pw, -0.5 * camera.sensorHeightM + (row + 0.5) * ph};
}
// The pixel holding sensor point x (the inverse of pixelCentre).
std::pair<int, int> pixelOf(const Camera& camera, glm::dvec2 x) {
  const double pw = camera.sensorWidthM / camera.pixelsX, ph = camera.sensorHeightM / camera.pixelsY;
  return {int(std::floor((0.5 * camera.sensorWidthM - x.x) / pw)), int(std::floor((x.y + 0.5 * camera.sensorHeightM) / ph))};
}

// The share of a point's isotropic flux that crosses the lens disk: the
// solid angle of the disk from P (height h over the lens plane, offset
// P_xy from its axis) over 4 pi, by Gauss-Legendre in the radius and equal
// steps in the angle about the axis (the integrand h / r^3 is smooth over
// the disk).
double diskShare(const glm::dvec3& pointOverLens, double radius) {
  constexpr int kAngular = 192;
  const GaussLegendreRule& g = gaussLegendre(48);  // on [-1, 1]
  const double h = pointOverLens.z;
  double sum = 0.0;
  for (size_t i = 0; i < g.node.size(); ++i) {
    const double r = radius * 0.5 * (g.node[i] + 1.0), w = 0.5 * g.weight[i];
    for (int j = 0; j < kAngular; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / kAngular;
      const double dx = r * std::cos(phi) - pointOverLens.x, dy = r * std::sin(phi) - pointOverLens.y;
      const double d2 = h * h + dx * dx + dy * dy;
      sum += w * radius * r * (2.0 * kPi / kAngular) * h / (d2 * std::sqrt(d2));
    }
  }
  return sum / (4.0 * kPi);
}

// --- 1. points in focus ------------------------------------------------------------
//
// f = 50 mm focused at d = 1 m puts the lens s = f d / (d - f) = 52.6 mm
// before a 4.2 mm square sensor of 21 x 21 pixels (0.2 mm). Two points at
// distance d before the lens: one on the axis, imaged on the centre of the
// middle pixel, one off it, imaged at -P_xy s / d, 26 um or more inside its
// pixel's edges (float rounding moves a landing point by well under a
// micrometre).
struct FocusScene {
  Scene scene;
  ThinLens lens;
  std::vector<glm::dvec3> points;  // camera frame
  std::vector<double> power;
};

FocusScene focusScene() {
  FocusScene f;
  f.lens = {0.05, 0.01, 1.0};
  f.scene = testing::bareSensorScene(0.0042, 0.0042, 21, 21, 8);
  f.scene.camera.model = thinLensModel(f.lens);
  const double s = f.lens.lensDistanceM();
  f.points = {{0.0, 0.0, s + 1.0}, {0.02, 0.01, s + 1.0}};
  f.power = {1.0, 3.0};
  for (size_t i = 0; i < f.points.size(); ++i)
    f.scene.lights.push_back(testing::pointLight(toWorld(f.scene.camera, f.points[i]), f.power[i], makeLineSpd(550.0)));
  for (size_t i = 0; i < f.scene.lights.size(); ++i) f.scene.lights[i].label = "/lights/" + std::to_string(i);
  return f;
}

TEST(OpticsThinLens, PointsInFocusLandInTheirImagePixelWithTheFluxTheLensSubtends) {
  const FocusScene f = focusScene();
  const Camera& camera = f.scene.camera;
  const uint64_t beams = testing::scaledBeams(2'000'000, 200'000);
  const RenderResult r = testing::renderOnBothDevices(f.scene, beams, 3, estimators(true, false));
  const testing::PixelEstimates e = testing::pixelEstimates(r.histogram, r.plan, beams);
  const double s = f.lens.lensDistanceM();
  const double pixelArea = (camera.sensorWidthM / camera.pixelsX) * (camera.sensorHeightM / camera.pixelsY);
  std::vector<size_t> imagePixels;
  for (size_t i = 0; i < f.points.size(); ++i) {
    const glm::dvec3& p = f.points[i];
    const glm::dvec2 image = -glm::dvec2(p.x, p.y) * (s / (p.z - s));
    const auto [col, row] = pixelOf(camera, image);
    // Its image point lies well inside the pixel, so rounding cannot move a beam across an edge.
    const glm::dvec2 offset = glm::abs(image - pixelCentre(camera, col, row));
    ASSERT_LT(std::max(offset.x, offset.y), 0.1e-3 - 20e-6) << "point " << i;
    const size_t pixel = size_t(row) * camera.pixelsX + col;
    imagePixels.push_back(pixel);
    // Flux in the pixel: its irradiance times its area, against the
    // point's power times the disk's share of its sphere; 5 standard
    // errors of the pixel's estimate (from the film's own variance model:
    // thousands of counts, so Gaussian).
    const double expected = f.power[i] * diskShare({p.x, p.y, p.z - s}, f.lens.apertureRadiusM);
    const double measured = e.irradiance[pixel] * pixelArea;
    const double sigma = std::sqrt(e.variancePerMean[pixel] * e.irradiance[pixel]) * pixelArea;
    std::printf("  point %zu: pixel (%d, %d), flux %.6e W, expected %.6e (%+.2f sigma)\n", i, col, row, measured,
                expected, (measured - expected) / sigma);
    EXPECT_NEAR(measured, expected, 5.0 * sigma) << "point " << i;
    EXPECT_LT(sigma, 0.01 * expected) << "too few beams for the check to mean anything";
  }
  // Every count lands in one of the two image pixels.
  for (size_t pixel = 0; pixel < e.irradiance.size(); ++pixel) {
    if (std::find(imagePixels.begin(), imagePixels.end(), pixel) == imagePixels.end()) {
      EXPECT_EQ(e.irradiance[pixel], 0.0) << "pixel " << pixel << " holds counts outside the image points";
    }
  }
}

// --- 2. a point out of focus ----------------------------------------------------------
//
// The same lens (f = 50 mm, focused at 1 m), aperture radius a = 12.5 mm,
// and a point on the axis u = 0.25 m before it: its image distance
// v = 1 / (1/f - 1/u) = 62.5 mm lies behind the sensor (s = 52.6 mm), so
// its blur disk has radius R = a (v - s) / v = 1.97 mm, about 9.9 pixels
// on a 4.2 mm sensor of 21 x 21. A beam through lens point q lands at
// q R / a (the crossing's p (1 - s/f) + s m, with m = q / u), so the
// irradiance at x in the disk is the flux density through the lens at
// q = x a / R over (R / a)^2: Phi / (4 pi) u / (u^2 + q^2)^(3/2) (a / R)^2,
// within 0.1% of uniform.
TEST(OpticsThinLens, OutOfFocusPointFillsItsBlurDiskAsTheClosedFormSays) {
  const ThinLens lens{0.05, 0.0125, 1.0};
  Scene scene = testing::bareSensorScene(0.0042, 0.0042, 21, 21, 8);
  scene.camera.model = thinLensModel(lens);
  const double s = lens.lensDistanceM(), u = 0.25, power = 2.0, a = lens.apertureRadiusM;
  scene.lights = {testing::pointLight(toWorld(scene.camera, {0.0, 0.0, s + u}), power, makeLineSpd(550.0))};
  const double v = 1.0 / (1.0 / lens.focalLengthM - 1.0 / u);
  const double blur = a * std::abs(s - v) / v;
  ASSERT_NEAR(blur, 1.974e-3, 1e-6);

  const uint64_t beams = testing::scaledBeams(3'000'000, 300'000);
  const RenderResult r = testing::renderOnBothDevices(scene, beams, 5, estimators(true, false));
  const testing::PixelEstimates e = testing::pixelEstimates(r.histogram, r.plan, beams);
  const Camera& camera = scene.camera;
  const double pw = camera.sensorWidthM / camera.pixelsX;
  const double margin = 1e-3 * pw;  // float rounding of a landing point: ~1e-9 m
  const auto irradianceAt = [&](double x, double y) {
    const double q2 = (x * x + y * y) * (a / blur) * (a / blur);
    return power / (4.0 * kPi) * u / ((u * u + q2) * std::sqrt(u * u + q2)) * (a / blur) * (a / blur);
  };
  // 4 x 4 Gauss-Legendre over a pixel (the integrand is smooth there).
  const GaussLegendreRule& g = gaussLegendre(4);  // on [-1, 1]
  double chi2 = 0.0, worst = 0.0, total = 0.0;
  int inside = 0;
  for (int row = 0; row < camera.pixelsY; ++row)
    for (int col = 0; col < camera.pixelsX; ++col) {
      const size_t pixel = size_t(row) * camera.pixelsX + col;
      total += e.irradiance[pixel] * pw * pw;
      const glm::dvec2 c = pixelCentre(camera, col, row);
      const double nearest = glm::length(glm::max(glm::abs(c) - 0.5 * pw, glm::dvec2(0.0)));
      const double farthest = glm::length(glm::abs(c) + 0.5 * pw);
      if (nearest > blur + margin) {
        EXPECT_EQ(e.irradiance[pixel], 0.0) << "pixel (" << col << ", " << row << ") lies outside the blur disk";
      } else if (farthest < blur - margin) {
        double expected = 0.0;
        for (size_t i = 0; i < g.node.size(); ++i)
          for (size_t j = 0; j < g.node.size(); ++j)
            expected += 0.25 * g.weight[i] * g.weight[j] *
                        irradianceAt(c.x + 0.5 * g.node[i] * pw, c.y + 0.5 * g.node[j] * pw);
        // Poisson-like counts: Var(E) = v E with the expected E (thousands
        // of counts a pixel, so z is Gaussian).
        const double sigma = std::sqrt(e.variancePerMean[pixel] * expected);
        const double z = (e.irradiance[pixel] - expected) / sigma;
        EXPECT_LE(std::abs(z), 5.0) << "pixel (" << col << ", " << row << "): " << e.irradiance[pixel]
                                    << " W/m^2, expected " << expected;
        chi2 += z * z;
        worst = std::max(worst, std::abs(z));
        ++inside;
      }
    }
  const double pValue = testing::chiSquareUpperTail(chi2, inside);
  std::printf("  blur radius %.4f mm: %d pixels inside, chi2 %.1f (p = %.3f), worst %.2f sigma\n", blur * 1e3, inside,
              chi2, pValue, worst);
  EXPECT_GE(inside, 200);
  EXPECT_GT(pValue, 0.001);  // a correct renderer fails one run in a thousand
  // The total flux: the disk's share of the point's power; 5 sigma of the
  // sum of the pixels' (independent-count) variances.
  const double expectedTotal = power * diskShare({0.0, 0.0, u}, a);
  const double totalSigma = std::sqrt(e.totalVariance) * pw * pw;
  std::printf("  total %.6e W, expected %.6e (%+.2f sigma)\n", total, expectedTotal, (total - expectedTotal) / totalSigma);
  EXPECT_NEAR(total, expectedTotal, 5.0 * totalSigma);
}

// --- 3. a diffuse plate through the lens, three estimators ------------------------------
//
// f = 20 mm focused at 40 mm puts the lens (radius 9 mm) at s = 40 mm
// before a 20 mm sensor of 8 x 8 pixels. A plate of reflectance 0.8 at
// 100 mm (60 mm before the lens: its image at 30 mm, a blur of a / 3)
// faces the camera, 140 mm wide: a line from sensor point x through lens
// point q leaves with slope -(x + q) / s and meets it at -q / 2 - 3 x / 2,
// inside 26 mm of the axis. The point light at (30, 3, 85) mm, under the
// plate, images at -(30, 3) 40 / 45 mm with a 1 mm blur, off the sensor, so
// it lights the sensor only through the plate.
Scene plateScene() {
  Scene scene = testing::bareSensorScene(0.02, 0.02, 8, 8, 4);
  scene.camera.model = thinLensModel({0.02, 0.009, 0.04});
  scene.lights = {testing::pointLight(toWorld(scene.camera, {0.03, 0.003, 0.085}), 2.0, makeLineSpd(550.0))};
  scene.objects = {testing::namedObject(
      "plate", 0, testing::rectShape(scene.camera, {0.0, 0.0, 0.1}, {0.0, 0.0, -1.0}, {1.0, 0.0, 0.0}, {0.14, 0.14}),
      testing::diffuseMaterial(0.8))};
  return scene;
}

TEST(OpticsThinLens, PlateThroughTheLensAgreesAcrossEstimators) {
  const Scene scene = plateScene();
  // Each estimator's film is equal on both devices at a smaller count.
  const uint64_t small = testing::scaledBeams(100'000, 20'000);
  testing::renderOnBothDevices(scene, small, 21, estimators(true, false, false));
  const RenderResult connectedSmall = testing::renderOnBothDevices(scene, small, 22, estimators(true, false));
  testing::renderOnBothDevices(scene, small, 23, estimators(false, true));
  // Lavapipe's general pipeline (the camera model chosen at run time, not
  // specialised to the scene) gives the same film.
  const RenderResult general = testing::renderOn(DeviceChoice::Gpu, scene, small, 22, estimators(true, false), true);
  EXPECT_TRUE(general.histogram.counts() == connectedSmall.histogram.counts()) << "general pipeline differs";
  EXPECT_TRUE(general.histogram.squaredWeightSums() == connectedSmall.histogram.squaredWeightSums());

  // Then each against analog transport on the CPU reference, pixel by
  // pixel within 5 sigma of their combined standard errors, by chi-square
  // and in total (testing::compareRenders).
  const uint64_t analogBeams = testing::scaledBeams(8'000'000, 1'000'000);
  const RenderResult analog =
      testing::renderOn(DeviceChoice::Cpu, scene, analogBeams, 11, estimators(true, false, false));
  const testing::PixelEstimates reference = testing::pixelEstimates(analog.histogram, analog.plan, analogBeams);
  const uint64_t connectBeams = testing::scaledBeams(1'000'000, 200'000);
  const RenderResult connected = testing::renderOn(DeviceChoice::Cpu, scene, connectBeams, 12, estimators(true, false));
  const auto vsConnected = testing::compareRenders(
      reference, testing::pixelEstimates(connected.histogram, connected.plan, connectBeams), "analog vs connected");
  EXPECT_EQ(vsConnected.cells, 64);
  EXPECT_GT(vsConnected.pValue, 0.001);
  const uint64_t paths = testing::scaledBeams(400'000, 100'000);
  const RenderResult camera = testing::renderOn(DeviceChoice::Cpu, scene, paths, 13, estimators(false, true));
  const auto vsCamera = testing::compareRenders(
      reference, testing::pixelEstimates(camera.histogram, camera.plan, paths), "analog vs camera paths");
  EXPECT_EQ(vsCamera.cells, 64);
  EXPECT_GT(vsCamera.pValue, 0.001);
}

}  // namespace
}  // namespace spectrace
