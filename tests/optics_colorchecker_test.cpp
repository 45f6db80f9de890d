// The 24 ColorChecker patches (Ohta 1997, data/cie/colorchecker24_ohta.csv)
// as diffuse rects under a D65 rect light, seen through a pinhole with
// camera connections of light paths. Each patch's image has the expected
// chromaticity
//   xy of  ∫ ρ(λ) S(λ) cmf(λ) dλ  over the scene's spectrum range,
// ρ the patch's reflectance as the scene holds it (SurfaceMaterial::
// reflectanceAt: linear, its end values held), S the D65 SPD the light
// draws from, cmf the CIE 1931 2° observer, integrated here in double.
//
// Why that is the expectation: a beam leaves the light with its wavelength
// drawn from S, meets a patch and connects to the aperture with weight
// ρ(λ) times a geometric factor that does not depend on λ; the patches are
// coplanar, so nothing reaches the camera any other way (the light faces
// the board; it is not an object and blocks nothing). With exact colour
// each count adds its own ratio·cmf(λ), so a pixel's XYZ has expectation
// (geometry) × ∫ ρ S cmf, whose chromaticity is the one above.
//
// Exact colour is what the image's XYZ uses: the reflectances vary with λ,
// so compile/shortcuts.cpp (wavelengthDependentObject) refuses colour from
// the bins, and the test asserts that the plan holds per-beam colour sums.
//
// Each patch's mean XYZ is taken over the pixels whose centres see the
// patch. The pinhole's blur footprint on the board (radius r (1 + D/f)) plus
// half a pixel stays inside the gap between patches, so no pixel sees a
// neighbouring patch; mixing with the black gap does not move the
// chromaticity. Tolerance 1e-3 absolute in x and y; the statistical error
// of each mean chromaticity (delta method on the pixels' scatter) is
// checked to be below 1e-3 / 5, so the tolerance is not met by noise.
//
// The beam budget: one wavelength drawn from D65 gives each connection a
// chromaticity scatter of 0.15-0.41 (x or y, per patch, computed from the
// tables); with the four stratified wavelengths a beam carries (the
// default), light paths alone bring the worst patch's standard error to
// 3.1e-5 at 150 million beams, so 1.1e-4 at the 12 million traced here:
// 5 sigma 5.4e-4, under the tolerance. That is the CPU reference's part;
// lavapipe traces the first 4 million beams, which must give the CPU's film
// bit for bit. At a smaller test scale (tests/support/test_scale.h) both
// counts shrink and the tolerance grows as 1 / sqrt(beams), so it stays
// 5 standard errors above the noise.
//
// Light paths alone, because the default estimator, light and camera paths
// joined by MIS, measured a worst standard error of 1.75e-4 at 150 million
// beams, 5.7 times that of light paths at about the same cost a beam: it
// needs 30 times the beams for the tolerance. It is checked too, to 5 sigma
// of its own noise, on 2 million beams that both devices trace alike.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "colour/colour.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "support/device_renders.h"
#include "support/test_scale.h"

namespace spectrace {
namespace {

// The chart's order, row by row as it is seen (top left: dark skin).
const std::array<const char*, 24> kPatches = {
    "dark_skin", "light_skin",    "blue_sky",     "foliage",   "blue_flower",  "bluish_green",
    "orange",    "purplish_blue", "moderate_red", "purple",    "yellow_green", "orange_yellow",
    "blue",      "green",         "red",          "yellow",    "magenta",      "cyan",
    "white_9.5", "neutral_8",     "neutral_6.5",  "neutral_5", "neutral_3.5",  "black_2"};

// Geometry (metres; the camera at the origin looks along +z with up +y, so
// its right is -x and column c of the chart sits at x = -(c - 2.5) pitch). A large sensor at magnification 2 (f = 2 D) keeps the aperture's
// blur footprint on the board, r (1 + D / f) = 3.9 mm, and half a pixel
// (0.83 mm on the board) inside the 5 mm gaps between patches while the
// aperture stays wide (r / D = 1/115): a connection's weight is then about
// 7.5e-5 rho, well above the 2^-20 steps of the colour sums, whose
// stochastic rounding adds noise mainly on the darkest patch.
constexpr double kSensorW = 0.80, kSensorH = 0.54;
constexpr int kPixelsX = 240, kPixelsY = 162;
constexpr double kFocal = 0.6;        // pinhole distance f
constexpr double kPinholeR = 0.0026;  // aperture radius r
constexpr double kBoardZ = 0.9;       // board plane, D = kBoardZ - f from the aperture
constexpr double kPitch = 0.055, kPatch = 0.05;
constexpr double kMinNm = 380.0, kMaxNm = 780.0;

double patchX(int column) { return -(column - 2.5) * kPitch; }
double patchY(int row) { return (1.5 - row) * kPitch; }

Scene colorCheckerScene() {
  nlohmann::json objects = nlohmann::json::array();
  for (int i = 0; i < 24; ++i)
    objects.push_back({{"name", kPatches[i]},
                       {"type", "rect"},
                       {"center", {patchX(i % 6), patchY(i / 6), kBoardZ}},
                       {"normal", {0, 0, -1}},
                       {"u_axis", {1, 0, 0}},
                       {"size_m", {kPatch, kPatch}},
                       {"material", {{"type", "diffuse"}, {"reflectance", kPatches[i]}}}});
  const nlohmann::json root = {
      {"spectrum", {{"min_nm", kMinNm}, {"max_nm", kMaxNm}, {"bins", 40}}},
      {"observer", "CIE1931_2"},
      {"camera",
       {{"position", {0, 0, 0}},
        {"look_at", {0, 0, 1}},
        {"up", {0, 1, 0}},
        {"sensor", {{"width_m", kSensorW}, {"height_m", kSensorH}, {"pixels", {kPixelsX, kPixelsY}}}},
        {"pinhole", {{"distance_m", kFocal}, {"radius_m", kPinholeR}}}}},
      // A D65 panel 2 cm in front of the board, facing it, a little
      // smaller than the board: most of its beams land on a patch.
      {"lights",
       {{{"type", "rect"},
         {"center", {0, 0, kBoardZ - 0.02}},
         {"normal", {0, 0, 1}},
         {"u_axis", {1, 0, 0}},
         {"size_m", {6 * kPitch - 0.02, 4 * kPitch - 0.02}},
         {"power_w", 10},
         {"spd", "D65"}}}},
      {"objects", objects},
      {"render", {{"beams", 1000000}, {"seed", 1}}}};
  return parseSceneJson(root, "colorchecker_test.json");
}

// xy of ∫ ρ S cmf over the spectrum range, in double: the integrand is
// piecewise linear in each factor (ρ on 5 nm nodes, S and the CMF on 1 nm
// nodes), so the trapezoid rule on a 0.01 nm grid is exact to ~1e-9.
std::array<double, 2> expectedChromaticity(const SurfaceMaterial& material, const Spd& light) {
  const Observer& observer = cie1931Observer();
  std::array<double, 3> xyz{0.0, 0.0, 0.0};
  constexpr int kSteps = 40000;
  const double h = (kMaxNm - kMinNm) / kSteps;
  for (int i = 0; i <= kSteps; ++i) {
    const double lambda = kMinNm + h * i;
    const double w = (i == 0 || i == kSteps) ? 0.5 * h : h;
    const double f = material.reflectanceAt(lambda) * light.evaluate(lambda) * w;
    const auto cmf = cmfAt(observer, lambda);
    for (int k = 0; k < 3; ++k) xyz[k] += f * cmf[k];
  }
  return chromaticity(xyz);
}

struct PatchMeasurement {
  std::array<double, 2> xy{};
  std::array<double, 2> sigma{};  // standard error of x and y
  int pixels = 0;
};

// The mean XYZ over a window of the patch's image and its chromaticity;
// the standard error by the delta method from the pixels' covariance
// (x = X / (X + Y + Z) has gradient ((1 - x), -x, -x) / S). Variation of
// the brightness across the window scales X, Y, Z together and so adds
// nothing to first order.
PatchMeasurement measurePatch(const RenderImage& image, int index, double windowHalfM) {
  const double d = kBoardZ - kFocal;  // aperture to board
  const double scale = kFocal / d;    // board to sensor
  const double pixelW = kSensorW / kPixelsX, pixelH = kSensorH / kPixelsY;
  // The pinhole image is upright: image column u runs along camera right
  // (-x), row v down from +y; a board point (x, y) lands at sensor
  // position (-x, y) * f / D (upright after the flip).
  const double cx = -patchX(index % 6) * scale, cy = patchY(index / 6) * scale;
  const double half = windowHalfM * scale;
  std::vector<std::array<double, 3>> samples;
  for (int row = 0; row < image.height; ++row) {
    for (int col = 0; col < image.width; ++col) {
      const double px = -0.5 * kSensorW + (col + 0.5) * pixelW;
      const double py = 0.5 * kSensorH - (row + 0.5) * pixelH;
      if (std::abs(px - cx) > half || std::abs(py - cy) > half) continue;  // centres inside
      const size_t p = size_t(row) * image.width + col;
      samples.push_back({image.xyz[p * 3], image.xyz[p * 3 + 1], image.xyz[p * 3 + 2]});
    }
  }
  PatchMeasurement m;
  m.pixels = int(samples.size());
  if (samples.size() < 2) return m;
  std::array<double, 3> mean{0, 0, 0};
  for (const auto& s : samples)
    for (int k = 0; k < 3; ++k) mean[k] += s[k];
  for (double& v : mean) v /= double(samples.size());
  std::array<std::array<double, 3>, 3> cov{};
  for (const auto& s : samples)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) cov[a][b] += (s[a] - mean[a]) * (s[b] - mean[b]);
  const double n = double(samples.size());
  for (auto& r : cov)
    for (double& v : r) v /= (n - 1.0) * n;  // covariance of the mean
  m.xy = chromaticity(mean);
  const double sum = mean[0] + mean[1] + mean[2];
  for (int c = 0; c < 2; ++c) {
    std::array<double, 3> g{-m.xy[c] / sum, -m.xy[c] / sum, -m.xy[c] / sum};
    g[c] += 1.0 / sum;
    double var = 0.0;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) var += g[a] * cov[a][b] * g[b];
    m.sigma[c] = std::sqrt(var);
  }
  return m;
}

struct ChartResult {
  double worstError = 0.0;
  double worstSigma = 0.0;
};

// Every patch's mean chromaticity against the expectation. With
// `tolerance`, |error| <= tolerance and 5 sigma < tolerance; without, only
// |error| <= 5 sigma (a render with too few beams for the tolerance).
ChartResult checkChart(const Scene& scene, const RenderImage& image, const char* label, double tolerance) {
  // The blur footprint of the aperture on the board has radius
  // r (1 + D / f): a pixel whose centre's view of the board lies inside a
  // patch sees at most half a pixel and that radius beyond the patch's
  // edge along x or y, short of its neighbours.
  const double d = kBoardZ - kFocal;
  const double footprint = kPinholeR * (1.0 + d / kFocal);
  const double pixelOnBoard = std::max(kSensorW / kPixelsX, kSensorH / kPixelsY) * d / kFocal;
  EXPECT_LT(footprint + 0.5 * pixelOnBoard, kPitch - kPatch);
  ChartResult chart;
  std::printf("%s:\n", label);
  for (int i = 0; i < 24; ++i) {
    const SceneObject& patch = scene.objects[i];
    const auto expected = expectedChromaticity(patch.material, scene.lights[0].spd);
    const PatchMeasurement m = measurePatch(image, i, 0.5 * kPatch);
    EXPECT_GE(m.pixels, 800) << kPatches[i];
    for (int c = 0; c < 2; ++c) {
      const char* axis = c == 0 ? " x" : " y";
      const double error = m.xy[c] - expected[c];
      chart.worstSigma = std::max(chart.worstSigma, m.sigma[c]);
      chart.worstError = std::max(chart.worstError, std::abs(error));
      if (tolerance > 0.0) {
        EXPECT_NEAR(m.xy[c], expected[c], tolerance) << label << ": " << kPatches[i] << axis << " (standard error "
                                                     << m.sigma[c] << ")";
        // The tolerance must stand well above the noise, or passing says little.
        EXPECT_LT(5.0 * m.sigma[c], tolerance) << label << ": " << kPatches[i] << axis << ": too few beams";
      } else {
        EXPECT_NEAR(m.xy[c], expected[c], 5.0 * m.sigma[c]) << label << ": " << kPatches[i] << axis;
      }
    }
    std::printf("  %-14s %4d px  x %.5f (expected %.5f, %+.1e, sd %.1e)  y %.5f (expected %.5f, %+.1e, sd %.1e)\n",
                kPatches[i], m.pixels, m.xy[0], expected[0], m.xy[0] - expected[0], m.sigma[0], m.xy[1], expected[1],
                m.xy[1] - expected[1], m.sigma[1]);
  }
  std::printf("  worst |error| %.2e, worst standard error %.2e\n", chart.worstError, chart.worstSigma);
  return chart;
}

constexpr uint64_t kSeed = 11;

// The scene on lavapipe and on the CPU reference with the same beams, whose
// films must be equal bit for bit; the CPU's render, with per-beam colour
// sums, not colour from the bins (the reflectances vary).
RenderResult renderOnBoth(const Scene& scene, uint64_t beams, bool cameraPaths) {
  CompileOptions plan;
  plan.cameraPaths = cameraPaths;
  RenderResult cpu = testing::renderOnBothDevices(scene, beams, kSeed, plan);
  EXPECT_TRUE(cpu.plan.film.exactColour);
  EXPECT_FALSE(cpu.plan.film.colourFromBins);
  return cpu;
}

// Lavapipe traces the first kGpuBeams beams; the CPU reference the same
// beams, which must give the same film bit for bit, and then goes on from
// that film to kCpuBeams. So everything the CPU's render shows about those
// beams holds for lavapipe's. The tolerance is checked on the CPU's full
// render, and the first beams' image (both devices') to 5 sigma of its noise.
const testing::ScaledBeams kGpuBeams = testing::scaledBeams(4'000'000, 400'000);
const testing::ScaledBeams kCpuBeams = testing::scaledBeams(12'000'000, 800'000);
const testing::ScaledBeams kBothEstimatorsBeams = testing::scaledBeams(2'000'000, 200'000);
const double kTolerance = kCpuBeams.tolerance(1e-3);

TEST(OpticsColorChecker, PatchChromaticityUnderD65OnLavapipeAndTheCpuReference) {
  const Scene scene = colorCheckerScene();
  const RenderResult prefix = renderOnBoth(scene, kGpuBeams, false);
  ASSERT_EQ(prefix.plan.device.constants.estimators, device::kEstimatorLightPaths);
  checkChart(scene, prefix.image, "the first beams, on both devices, to 5 sigma of their own noise", 0.0);

  RenderOptions options;
  options.beams = kCpuBeams;
  options.seed = kSeed;
  options.device = DeviceChoice::Cpu;
  options.plan.cameraPaths = false;
  options.loop.resumeFilm = &prefix.histogram;
  options.loop.resumedBeams = kGpuBeams;
  const RenderResult cpu = render(scene, options);
  ASSERT_EQ(cpu.beamsTraced, kCpuBeams.beams);
  std::printf("%s: %llu more beams in %.2f s\n", cpu.deviceName.c_str(), (unsigned long long)(kCpuBeams.beams - kGpuBeams.beams),
              cpu.wallSeconds);
  const ChartResult chart = checkChart(scene, cpu.image, "CPU reference", kTolerance);
  RecordProperty("worst_error", std::to_string(chart.worstError));
  RecordProperty("worst_standard_error", std::to_string(chart.worstSigma));

  // The default estimator, light and camera paths.
  const RenderResult both = renderOnBoth(scene, kBothEstimatorsBeams, true);
  ASSERT_EQ(both.plan.device.constants.estimators, device::kEstimatorLightPaths | device::kEstimatorCameraPaths);
  checkChart(scene, both.image, "light and camera paths, on both devices, to 5 sigma of their own noise", 0.0);
}

}  // namespace
}  // namespace spectrace
