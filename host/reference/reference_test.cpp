// The exact reference solutions: each closed form against an independent
// computation (brute-force quadrature, a different closed form, published
// CIE values), quadrature convergence, and the reference scenes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>
#include <string>

#include "camera/thin_lens_camera.h"
#include "colour/colour.h"
#include "compile/compile_scene.h"
#include "reference/exact_solution.h"
#include "scene/scene.h"

namespace spectrace {
namespace {

constexpr double kPi = std::numbers::pi;

const std::filesystem::path& sceneDir() {
  static const std::filesystem::path dir = std::filesystem::path(SPECTRACE_SOURCE_DIR) / "scenes" / "reference";
  return dir;
}
Scene referenceScene(const std::string& name) { return loadScene(sceneDir() / (name + ".json")); }
ExactImage solve(const Scene& scene, int nodes = 16) {
  auto image = exactSolution(scene, ExactOptions{nodes});
  if (!image) throw std::runtime_error("scene not recognised: " + scene.sourcePath.string());
  return *image;
}

// Brute force: F = (1/π) ∫_disk L cosθ cosθ' / r² dA with L = 1, for a point
// at distance rho from the axis of a disk of radius R at height h. Polar
// coordinates about the disk centre: Gauss–Legendre in radius (composite),
// trapezoid in angle (periodic integrand: exponential convergence).
double bruteForceDiskViewFactor(double h, double radius, double rho, int radialCells, int angles) {
  const GaussLegendreRule& g = gaussLegendre(16);
  double sum = 0.0;
  for (int cell = 0; cell < radialCells; ++cell) {
    const double r0 = radius * cell / radialCells, r1 = radius * (cell + 1) / radialCells;
    for (size_t i = 0; i < g.node.size(); ++i) {
      const double s = 0.5 * (r0 + r1) + 0.5 * (r1 - r0) * g.node[i];
      const double ws = 0.5 * (r1 - r0) * g.weight[i];
      double ring = 0.0;
      for (int k = 0; k < angles; ++k) {
        const double phi = 2.0 * kPi * (k + 0.5) / angles;
        const double dx = s * std::cos(phi) - rho, dy = s * std::sin(phi);
        const double r2 = dx * dx + dy * dy + h * h;
        const double cosTheta = h / std::sqrt(r2), cosThetaPrime = cosTheta;  // parallel planes
        ring += cosTheta * cosThetaPrime / r2;
      }
      sum += ws * s * ring * (2.0 * kPi / angles);
    }
  }
  return sum / kPi;
}

// ---------------------------------------------------------------- view factors

TEST(ParallelDiskViewFactor, OnAxisIsRSquaredOverHSquaredPlusRSquared) {
  EXPECT_NEAR(parallelDiskViewFactor(1.0, 1.0, 0.0), 0.5, 1e-15);
  for (double h : {0.01, 0.3, 1.0, 7.0})
    for (double r : {0.02, 0.5, 1.0, 40.0})
      EXPECT_NEAR(parallelDiskViewFactor(h, r, 0.0), r * r / (h * h + r * r), 1e-15 * r * r / (h * h + r * r))
          << h << " " << r;
  // Far away the disk is a small Lambertian patch (F -> R²/h²): no cancellation.
  EXPECT_NEAR(parallelDiskViewFactor(1e4, 1.0, 0.0) * (1e8 + 1.0), 1.0, 1e-15);
  EXPECT_NEAR(parallelDiskViewFactor(1e4, 1.0, 3.0) * 1e8, 1.0, 1e-6);
}

TEST(ParallelDiskViewFactor, OffAxisMatchesClassicFormulaAndBruteForce) {
  const double h = 1.0, radius = 1.0;
  // The classic formula, F = ½ (1 − (h² + ρ² − R²) / sqrt((h² + ρ² + R²)² − 4 ρ² R²)),
  // evaluated by hand: ρ = 0.5 R: ½ (1 − 0.25 / sqrt(4.0625)); ρ = 2R: ½ (1 − 4 / sqrt(20)).
  const double classicHalf = 0.5 * (1.0 - 0.25 / std::sqrt(4.0625));
  const double classicTwo = 0.5 * (1.0 - 4.0 / std::sqrt(20.0));
  EXPECT_NEAR(classicHalf, 0.437982632705396, 1e-14);
  EXPECT_NEAR(classicTwo, 0.052786404500042, 1e-14);
  EXPECT_NEAR(parallelDiskViewFactor(h, radius, 0.5 * radius), classicHalf, 1e-15);
  EXPECT_NEAR(parallelDiskViewFactor(h, radius, 2.0 * radius), classicTwo, 1e-15);
  for (double rho : {0.5 * radius, 2.0 * radius}) {
    const double coarse = bruteForceDiskViewFactor(h, radius, rho, 8, 256);
    const double fine = bruteForceDiskViewFactor(h, radius, rho, 16, 512);
    EXPECT_NEAR(coarse, fine, 1e-12) << "brute force not converged at rho " << rho;
    EXPECT_NEAR(parallelDiskViewFactor(h, radius, rho), fine, 1e-8) << rho;
  }
  // And at other shapes, including the point under the rim and a thin gap.
  for (auto [hh, rr, rho] : {std::array<double, 3>{0.5, 2.0, 2.0}, {0.2, 1.0, 0.3}, {3.0, 0.5, 1.7}, {0.1, 1.0, 1.5}}) {
    const double brute = bruteForceDiskViewFactor(hh, rr, rho, 64, 2048);
    EXPECT_NEAR(parallelDiskViewFactor(hh, rr, rho), brute, 1e-8) << hh << " " << rr << " " << rho;
  }
}

TEST(ParallelDiskViewFactor, GreenBoundaryIntegralAgrees) {
  // The pinhole's general machinery (disk ∩ polygon by Green's theorem)
  // must give π F for a polygon that contains the whole disk...
  const std::vector<std::array<double, 2>> big{{-10, -10}, {10, -10}, {10, 10}, {-10, 10}};
  for (double rho : {0.0, 0.5, 2.0})
    EXPECT_NEAR(polygonDiskKernelIntegral(big, rho, 0.0, 1.0, 1.0) / kPi, parallelDiskViewFactor(1.0, 1.0, rho), 1e-13);
  // ... the half-plane x < 0 of a centred disk gives half of it, a
  // clockwise polygon the same, and a polygon outside the disk nothing.
  const std::vector<std::array<double, 2>> left{{-10, -10}, {0, -10}, {0, 10}, {-10, 10}};
  const std::vector<std::array<double, 2>> leftCw{{-10, 10}, {0, 10}, {0, -10}, {-10, -10}};
  EXPECT_NEAR(polygonDiskKernelIntegral(left, 0.0, 0.0, 1.0, 0.7) / kPi, 0.5 * parallelDiskViewFactor(0.7, 1.0, 0.0),
              1e-14);
  EXPECT_NEAR(polygonDiskKernelIntegral(leftCw, 0.0, 0.0, 1.0, 0.7), polygonDiskKernelIntegral(left, 0.0, 0.0, 1.0, 0.7),
              1e-15);
  EXPECT_EQ(polygonDiskKernelIntegral(left, 3.0, 0.0, 1.0, 0.7), 0.0);
  // A small square inside the disk: the rectangle view factor.
  const std::vector<std::array<double, 2>> square{{0.1, -0.2}, {0.4, -0.2}, {0.4, 0.3}, {0.1, 0.3}};
  EXPECT_NEAR(polygonDiskKernelIntegral(square, 0.0, 0.0, 1.0, 0.5) / kPi,
              parallelRectViewFactor(0.1, 0.4, -0.2, 0.3, 0.5), 1e-14);
  // A rectangle cutting the disk off centre, against brute force in polar
  // coordinates about the disk's centre with the rectangle's indicator
  // (the indicator limits it to ~1e-6).
  const double h = 0.8, cx = 0.3, cy = -0.2, r = 1.0;
  const std::vector<std::array<double, 2>> cut{{-0.2, -2.0}, {5.0, -2.0}, {5.0, 0.1}, {-0.2, 0.1}};
  double brute = 0.0;
  const int nr = 2000, na = 4000;
  for (int i = 0; i < nr; ++i) {
    const double s = r * (i + 0.5) / nr;
    for (int k = 0; k < na; ++k) {
      const double phi = 2.0 * kPi * (k + 0.5) / na;
      const double x = cx + s * std::cos(phi), y = cy + s * std::sin(phi);
      if (x < -0.2 || y > 0.1) continue;
      const double r2 = x * x + y * y + h * h;
      brute += s * h * h / (r2 * r2);
    }
  }
  brute *= (r / nr) * (2.0 * kPi / na);
  EXPECT_NEAR(polygonDiskKernelIntegral(cut, cx, cy, r, h), brute, 2e-5 * brute);
}

TEST(ParallelRectViewFactor, MatchesBruteForce) {
  // F = (1/π) ∫_rect h² / (x² + y² + h²)² dA by 2D Gauss–Legendre.
  const auto brute = [](double x1, double x2, double y1, double y2, double h) {
    const GaussLegendreRule& g = gaussLegendre(64);
    const int cells = 8;
    double sum = 0.0;
    for (int ci = 0; ci < cells; ++ci)
      for (int cj = 0; cj < cells; ++cj) {
        const double a1 = x1 + (x2 - x1) * ci / cells, a2 = x1 + (x2 - x1) * (ci + 1) / cells;
        const double b1 = y1 + (y2 - y1) * cj / cells, b2 = y1 + (y2 - y1) * (cj + 1) / cells;
        for (size_t i = 0; i < g.node.size(); ++i)
          for (size_t j = 0; j < g.node.size(); ++j) {
            const double x = 0.5 * (a1 + a2) + 0.5 * (a2 - a1) * g.node[i];
            const double y = 0.5 * (b1 + b2) + 0.5 * (b2 - b1) * g.node[j];
            const double r2 = x * x + y * y + h * h;
            sum += 0.25 * (a2 - a1) * (b2 - b1) * g.weight[i] * g.weight[j] * h * h / (r2 * r2);
          }
      }
    return sum / kPi;
  };
  for (auto c : {std::array<double, 5>{-1, 1, -1, 1, 1}, {0.2, 1.5, -0.4, 0.3, 0.5}, {-3, -1, 2, 2.5, 0.7}})
    EXPECT_NEAR(parallelRectViewFactor(c[0], c[1], c[2], c[3], c[4]), brute(c[0], c[1], c[2], c[3], c[4]), 1e-12);
  // A huge rect fills the hemisphere.
  EXPECT_NEAR(parallelRectViewFactor(-1e6, 1e6, -1e6, 1e6, 1.0), 1.0, 1e-6);
}

// ---------------------------------------------------------------- furnace

TEST(Furnace, ShortfallIsHSquaredOverHSquaredPlusRSquaredOnAxis) {
  // On axis, F = (1/π) ∫_0^R 2π s h² / (s² + h²)² ds = h² (1/h² − 1/(R² + h²))
  // = R² / (h² + R²), so the furnace's shortfall 1 − E/(πL) = h² / (h² + R²).
  for (double h : {1e-3, 0.01, 1.0})
    for (double r : {0.02, 1.0, 100.0}) {
      const double expected = h * h / (h * h + r * r);
      EXPECT_NEAR(furnaceShortfall(h, r), expected, 1e-15 * expected) << h << " " << r;
    }
  // Off axis it is 1 − F, computed without cancellation; for h << R it
  // tends to R² h² / (R² − ρ²)² (larger towards the rim).
  for (double rho : {0.0, 0.1, 0.3, 0.6}) {
    const double h = 1e-3, r = 1.0;
    EXPECT_NEAR(furnaceShortfall(h, r, rho) + parallelDiskViewFactor(h, r, rho), 1.0, 4e-16);
    const double asymptotic = r * r * h * h / ((r * r - rho * rho) * (r * r - rho * rho));
    EXPECT_NEAR(furnaceShortfall(h, r, rho) / asymptotic, 1.0, 1e-5) << rho;
  }
}

TEST(Furnace, SceneIsAFurnaceWithTheDocumentedShortfall) {
  const Scene scene = referenceScene("furnace");
  const ExactImage image = solve(scene);
  const Light& disk = scene.lights.at(0);
  const double h = 0.001, r = disk.radiusM;
  const double radiance = image.tracedPowerW / (kPi * kPi * r * r);
  const double onAxis = h * h / (h * h + r * r);
  // The sensor's corners are at ρ = sqrt(2) · 4 mm.
  const double rhoMax = std::sqrt(2.0) * 0.004;
  const double atCorner = r * r * h * h / ((r * r - rhoMax * rhoMax) * (r * r - rhoMax * rhoMax));
  EXPECT_EQ(image.validCount(), image.pixelCount());
  for (size_t p = 0; p < image.pixelCount(); ++p) {
    const double shortfall = 1.0 - image.irradiance[p] / (kPi * radiance);
    EXPECT_GT(shortfall, onAxis);
    EXPECT_LT(shortfall, atCorner * 1.01);
  }
  // Hit fraction ≈ A_sensor / (π R²) · (1 − shortfall).
  EXPECT_NEAR(image.hitFraction, 0.008 * 0.008 / (kPi * r * r), 0.01 * image.hitFraction);
}

// ---------------------------------------------------------------- point light

// Solid angle of [0, a] x [0, b] from a height d above its corner, a form
// independent of the atan corner terms: asin(a b / sqrt((a² + d²)(b² + d²))).
double cornerSolidAngle(double a, double b, double d) {
  const double s = std::asin(std::abs(a * b) / std::sqrt((a * a + d * d) * (b * b + d * d)));
  return (a < 0) != (b < 0) ? -s : s;
}

double fluxOnSensor(const Scene& scene, const ExactImage& image) {
  const double area = scene.camera.sensorWidthM / scene.camera.pixelsX * scene.camera.sensorHeightM / scene.camera.pixelsY;
  double flux = 0.0;
  for (double e : image.irradiance) flux += e * area;
  return flux;
}

TEST(PointLight, PixelIrradianceSumsToTheFluxThroughTheSensor) {
  for (const char* name : {"point_on_axis", "point_off_axis"}) {
    const Scene scene = referenceScene(name);
    const ExactImage image = solve(scene);
    EXPECT_EQ(image.validCount(), image.pixelCount());
    const CompiledScene plan = compileScene(scene, 1);
    EXPECT_NEAR(image.tracedPowerW, plan.tracedPowerW, 1e-15 * plan.tracedPowerW);
    // The light in the camera frame (documented in scenes/reference/README.md).
    const glm::dvec3 light = std::string(name) == "point_on_axis" ? glm::dvec3(0, 0, 0.004) : glm::dvec3(0.005, -0.003, 0.006);
    const double hw = 0.5 * scene.camera.sensorWidthM, hh = 0.5 * scene.camera.sensorHeightM;
    const double omega =
        cornerSolidAngle(hw - light.x, hh - light.y, light.z) - cornerSolidAngle(-hw - light.x, hh - light.y, light.z) -
        cornerSolidAngle(hw - light.x, -hh - light.y, light.z) + cornerSolidAngle(-hw - light.x, -hh - light.y, light.z);
    if (std::string(name) == "point_on_axis") {  // 4 asin(a b / sqrt((a² + d²)(b² + d²)))
      EXPECT_NEAR(omega, 4.0 * std::asin(64.0 / std::sqrt(80.0 * 80.0)), 1e-14);
    }
    EXPECT_NEAR(fluxOnSensor(scene, image), image.tracedPowerW * omega / (4.0 * kPi), 1e-12 * image.tracedPowerW) << name;
    EXPECT_NEAR(image.hitFraction, omega / (4.0 * kPi), 1e-12) << name;
  }
}

TEST(PointLight, PixelsOrientedAsTheRenderer) {
  // point_off_axis: light at camera (5, -3) mm, i.e. right of and below the
  // centre, so the brightest pixel is in the right half, lower half.
  const Scene scene = referenceScene("point_off_axis");
  const ExactImage image = solve(scene);
  const size_t best = size_t(std::max_element(image.irradiance.begin(), image.irradiance.end()) - image.irradiance.begin());
  const int col = int(best % size_t(image.width)), row = int(best / size_t(image.width));
  // x = 5 mm is the edge between columns 33 and 34 ((5 + 12) / 0.5 = 34),
  // y = -3 mm the edge between rows 21 and 22 ((8 + 3) / 0.5 = 22).
  EXPECT_NEAR(col, 33.5, 0.6);
  EXPECT_NEAR(row, 21.5, 0.6);
}

// ---------------------------------------------------------------- uniform irradiance and colour

TEST(UniformIrradiance, EveryPixelGetsPowerOverBeamArea) {
  for (const char* name : {"uniform_d65", "uniform_a", "uniform_f2", "uniform_f11", "uniform_led_b3"}) {
    const Scene scene = referenceScene(name);
    const ExactImage image = solve(scene);
    const CompiledScene plan = compileScene(scene, 1);
    const double r = scene.lights.at(0).radiusM;
    const double expected = plan.tracedPowerW / (kPi * r * r);
    EXPECT_EQ(image.validCount(), image.pixelCount()) << name;
    for (size_t p = 0; p < image.pixelCount(); ++p) {
      EXPECT_NEAR(image.irradiance[p], expected, 1e-12 * expected) << name << " pixel " << p;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.xyz[p][c], image.xyz[0][c], 1e-12 * image.xyz[0][1]);
    }
    EXPECT_NEAR(image.hitFraction, 0.008 * 0.008 / (kPi * r * r), 1e-12) << name;
  }
}

TEST(UniformIrradiance, D65AndAChromaticityMatchCie) {
  // CIE 015:2004 Table T.3. Exact integration of the piecewise-linear
  // product differs from CIE's summation by ~2e-5.
  struct Case {
    const char* scene;
    double x, y;
  };
  for (const Case& c : {Case{"uniform_d65", 0.31271, 0.32902}, Case{"uniform_a", 0.44757, 0.40745}}) {
    const ExactImage image = solve(referenceScene(c.scene));
    const auto xy = chromaticity(image.xyz[0]);
    EXPECT_NEAR(xy[0], c.x, 1e-4) << c.scene;
    EXPECT_NEAR(xy[1], c.y, 1e-4) << c.scene;
    // The bin-averaged version is close but not the same thing.
    const auto xyBinned = chromaticity(image.xyzBinned[0]);
    EXPECT_NEAR(xyBinned[0], c.x, 2e-3) << c.scene;
    EXPECT_NEAR(xyBinned[1], c.y, 2e-3) << c.scene;
  }
  // Y = 683 E ∫S ȳ / ∫S: for D65 over 360–830 nm about 683 · 0.2... lm/W;
  // check against spdToXyz directly.
  const Scene scene = referenceScene("uniform_d65");
  const ExactImage image = solve(scene);
  const Spd clipped = scene.lights[0].spd.clipped(360.0, 830.0);
  const double y = 683.0 * spdToXyz(clipped, cie1931Observer())[1] / clipped.integral();
  EXPECT_NEAR(image.xyz[0][1] / image.irradiance[0], y, 1e-12 * y);
}

TEST(LaserLine, XyzIsTheCmfAt532nmTimes683) {
  const Scene scene = referenceScene("laser_532");
  const ExactImage image = solve(scene);
  const Observer& obs = cie1931Observer();
  // The table's own row at 532 nm (1 nm steps), not an interpolation.
  const auto it = std::find(obs.lambdaNm.begin(), obs.lambdaNm.end(), 532.0);
  ASSERT_NE(it, obs.lambdaNm.end());
  const size_t i = size_t(it - obs.lambdaNm.begin());
  const std::array<double, 3> cmf{obs.xbar[i], obs.ybar[i], obs.zbar[i]};
  int lit = 0;
  for (size_t p = 0; p < image.pixelCount(); ++p) {
    if (image.irradiance[p] == 0.0) continue;
    ++lit;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(image.xyz[p][c] / (683.0 * image.irradiance[p]), cmf[size_t(c)], 1e-14) << p;
  }
  EXPECT_GT(lit, 300);
  // Flux on the sensor: the spot (radius 3 mm at (1.5, 0.5) mm) loses the
  // circular segment beyond x = 4 mm, d = 2.5 mm from its centre.
  const double r = 0.003, d = 0.0025;
  const double segment = r * r * std::acos(d / r) - d * std::sqrt(r * r - d * d);
  const double onSensor = 1.0 - segment / (kPi * r * r);
  EXPECT_NEAR(fluxOnSensor(scene, image), 0.005 * onSensor, 1e-13);
  EXPECT_NEAR(image.hitFraction, onSensor, 1e-12);
  // Full pixels carry exactly Φ / (π r²).
  EXPECT_NEAR(*std::max_element(image.irradiance.begin(), image.irradiance.end()), 0.005 / (kPi * r * r), 1e-9);
}

TEST(DiskRectangleOverlap, MatchesStripIntegration) {
  // Midpoint strips; the chord's sqrt at the disk's sides limits this to
  // ~3e-8 (n^-1.5).
  const auto strips = [](double cx, double cy, double r, double x1, double x2, double y1, double y2) {
    const int n = 400000;
    double area = 0.0;
    for (int i = 0; i < n; ++i) {
      const double x = x1 + (x2 - x1) * (i + 0.5) / n;
      const double s2 = r * r - (x - cx) * (x - cx);
      if (s2 <= 0.0) continue;
      const double s = std::sqrt(s2);
      area += std::max(0.0, std::min(y2, cy + s) - std::max(y1, cy - s));
    }
    return area * (x2 - x1) / n;
  };
  for (auto c : {std::array<double, 7>{0, 0, 1, -2, 2, -2, 2}, {0.3, -0.2, 1, 0.5, 0.9, -0.1, 0.4},
                 {0, 0, 1, 0.6, 1.2, 0.6, 1.2}, {0, 0, 1, -0.3, 0.3, -2, -0.8}, {2, 2, 1, -1, 0, -1, 0}}) {
    const double exact = diskRectangleOverlap(c[0], c[1], c[2], c[3], c[4], c[5], c[6]);
    EXPECT_NEAR(exact, strips(c[0], c[1], c[2], c[3], c[4], c[5], c[6]), 2e-8) << c[3] << " " << c[5];
  }
  EXPECT_NEAR(diskRectangleOverlap(0, 0, 1, -2, 2, -2, 2), kPi, 1e-15);
  EXPECT_EQ(diskRectangleOverlap(2, 2, 1, -1, 0, -1, 0), 0.0);
}

// ---------------------------------------------------------------- quadrature

TEST(Quadrature, GaussLegendreIsExactForDegree2nMinus1) {
  for (int n : {1, 2, 5, 16, 33}) {
    const GaussLegendreRule& g = gaussLegendre(n);
    for (int k = 0; k <= 2 * n - 1; ++k) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) sum += g.weight[size_t(i)] * std::pow(g.node[size_t(i)], k);
      EXPECT_NEAR(sum, k % 2 ? 0.0 : 2.0 / (k + 1), 1e-14) << n << " " << k;
    }
  }
}

TEST(Quadrature, PixelMeansConvergeTo1e9) {
  for (const char* name : {"disk_on_axis", "disk_off_axis", "furnace", "pinhole_rect"}) {
    const Scene scene = referenceScene(name);
    const ExactImage coarse = solve(scene, 16), fine = solve(scene, 32);
    const double peak = *std::max_element(fine.irradiance.begin(), fine.irradiance.end());
    double worst = 0.0;
    for (size_t p = 0; p < fine.pixelCount(); ++p) {
      if (!fine.valid[p]) continue;
      if (fine.irradiance[p] == 0.0) {
        EXPECT_EQ(coarse.irradiance[p], 0.0);
        continue;
      }
      worst = std::max(worst, std::abs(coarse.irradiance[p] / fine.irradiance[p] - 1.0));
    }
    EXPECT_LT(worst, 1e-9) << name;
    // The invalid (estimated) pinhole pixels agree to the documented ~1e-6 of the peak.
    for (size_t p = 0; p < fine.pixelCount(); ++p)
      if (!fine.valid[p]) {
        EXPECT_NEAR(coarse.irradiance[p], fine.irradiance[p], 1e-6 * peak) << name << " " << p;
      }
  }
}

// ---------------------------------------------------------------- disk and pinhole scenes

TEST(DiskLight, OnAxisCentrePixelIsCloseToTheCentreValue) {
  const Scene scene = referenceScene("disk_on_axis");
  const ExactImage image = solve(scene);
  // E(0) = Φ/(πR²) · R²/(h² + R²); the four centre pixels average a little less.
  const double h = 0.008, r = 0.005;
  const double centre = image.tracedPowerW / (kPi * r * r) * r * r / (h * h + r * r);
  const size_t p = size_t(15) * 32 + 15;
  EXPECT_LT(image.irradiance[p], centre);
  EXPECT_GT(image.irradiance[p], 0.995 * centre);
  // Symmetric under the sensor's mirror images.
  EXPECT_NEAR(image.irradiance[p], image.irradiance[size_t(16) * 32 + 16], 1e-12 * centre);
  EXPECT_NEAR(image.irradiance[size_t(3) * 32 + 7], image.irradiance[size_t(28) * 32 + 24], 1e-12 * centre);
}

TEST(DiskLight, OffAxisIsBrightestUnderTheDisk) {
  // disk_off_axis: disk centre at camera (4, -3) mm on a 16 x 12 mm sensor of
  // 32 x 24 pixels: column floor((4 + 8) / 0.5) = 24, row floor((6 + 3) / 0.5) = 18.
  const ExactImage image = solve(referenceScene("disk_off_axis"));
  const size_t best = size_t(std::max_element(image.irradiance.begin(), image.irradiance.end()) - image.irradiance.begin());
  EXPECT_NEAR(double(best % 32), 23.5, 0.6);
  EXPECT_NEAR(double(best / 32), 17.5, 0.6);
}

TEST(PinholeRect, ValidRegionsAreWhereTheGeometrySaysSo) {
  const Scene scene = referenceScene("pinhole_rect");
  const ExactImage image = solve(scene);
  // Camera frame: aperture 16 mm above the sensor, radius 2 mm; rect at
  // height 32 mm covering x in [-16, 8], y in [-6, 10] mm. A sensor point p
  // sees the rect through the aperture's footprint of radius 4 mm centred at
  // -p on the rect's plane, so the whole aperture sees the rect for p in
  // [-4, 12] x [-6, 2] mm, i.e. (upright image, 1 mm pixels, one pixel of
  // margin) columns 9..22 and rows 10..15.
  const double d = 0.016, a = 0.002;
  const double radiance = image.tracedPowerW / (kPi * 0.024 * 0.016);
  int full = 0, empty = 0, invalid = 0;
  for (int row = 0; row < image.height; ++row)
    for (int col = 0; col < image.width; ++col) {
      const size_t p = size_t(row) * image.width + col;
      const bool inFull = col >= 9 && col <= 22 && row >= 10 && row <= 15;
      if (inFull) {
        ++full;
        ASSERT_TRUE(image.valid[p]);
        // Pixel centre in the camera frame: x = 20 - col - 0.5, y = row - 15 + 0.5 (mm).
        const double x = 0.001 * (19.5 - col), y = 0.001 * (row - 14.5);
        const double centre = kPi * radiance * parallelDiskViewFactor(d, a, std::hypot(x, y));
        EXPECT_NEAR(image.irradiance[p] / centre, 1.0, 3e-3) << col << " " << row;  // curvature over a pixel
      } else if (image.valid[p]) {
        ++empty;
        EXPECT_EQ(image.irradiance[p], 0.0) << col << " " << row;
      } else {
        ++invalid;
      }
    }
  EXPECT_EQ(full, 84);
  EXPECT_GT(empty, 200);
  EXPECT_GT(invalid, 300);
  // The aperture passes ≥ 1e-4 of the beams and most of them land on the sensor.
  EXPECT_GT(image.hitFraction, 1e-3);
  EXPECT_LT(image.hitFraction, 0.02);
}

TEST(PinholeRect, ImageFluxEqualsTheFluxThroughTheAperture) {
  // Independent of the image: every beam through the aperture lands on the
  // sensor (a ray from rect point r through aperture point q meets the
  // sensor at 2q - r, inside [-12, 20] x [-14, 10] mm), so the image's flux,
  // invalid pixels included, is the rect's flux through the aperture disk:
  // ∫_aperture (Φ / A_rect) F_rect(q) dA, with F_rect the closed-form view
  // factor of the rect 16 mm above the aperture plane.
  const Scene scene = referenceScene("pinhole_rect");
  const ExactImage image = solve(scene);
  const double a = 0.002, gap = 0.016;
  const double x1 = -0.016, x2 = 0.008, y1 = -0.006, y2 = 0.010;  // the rect, camera frame
  const GaussLegendreRule& g = gaussLegendre(24);
  const int angles = 96;
  double through = 0.0;
  for (size_t i = 0; i < g.node.size(); ++i) {
    const double s = 0.5 * a * (1.0 + g.node[i]), ws = 0.5 * a * g.weight[i];
    for (int k = 0; k < angles; ++k) {
      const double phi = 2.0 * kPi * (k + 0.5) / angles;
      const double qx = s * std::cos(phi), qy = s * std::sin(phi);
      through += ws * s * (2.0 * kPi / angles) * parallelRectViewFactor(x1 - qx, x2 - qx, y1 - qy, y2 - qy, gap);
    }
  }
  through *= image.tracedPowerW / (0.024 * 0.016);
  EXPECT_NEAR(fluxOnSensor(scene, image) / through, 1.0, 1e-6);
  EXPECT_NEAR(image.hitFraction * image.tracedPowerW / through, 1.0, 1e-6);
}

TEST(PinholeRect, PointIrradianceAcrossTheEdgeIsContinuous) {
  // Along a line crossing the blurred edge, the exact point irradiance
  // (Green's theorem) runs from the full value to zero without jumps.
  Scene scene = referenceScene("pinhole_rect");
  // A strip sensor 40 x 0.1 mm of 400 x 1 pixels through the middle of the
  // image (y = 0) crosses the ramp x in [-12, -4] mm (and [12, 20]).
  scene.camera.sensorWidthM = 0.040;
  scene.camera.sensorHeightM = 0.0001;
  scene.camera.pixelsX = 400;
  scene.camera.pixelsY = 1;
  const ExactImage image = solve(scene, 8);
  double peak = 0.0, worstJump = 0.0;
  for (double e : image.irradiance) peak = std::max(peak, e);
  for (size_t p = 1; p < image.pixelCount(); ++p)
    worstJump = std::max(worstJump, std::abs(image.irradiance[p] - image.irradiance[p - 1]));
  EXPECT_GT(peak, 0.0);
  // The edge ramps over 8 mm = 80 pixels: each step is ~1/80 of the peak.
  EXPECT_LT(worstJump, 0.04 * peak);
}

// ---------------------------------------------------------------- recognition

TEST(ReferenceScenes, AllLoadAndAreRecognised) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(sceneDir()))
    if (entry.path().extension() == ".json") names.insert(entry.path().stem().string());
  const std::set<std::string> expected{"point_on_axis", "point_off_axis", "disk_on_axis", "disk_off_axis",
                                       "furnace",       "uniform_d65",    "uniform_a",    "uniform_f2",
                                       "uniform_f11",   "uniform_led_b3", "laser_532",    "pinhole_rect",
                                       "pinhole_small"};
  for (const auto& n : expected) EXPECT_TRUE(names.count(n)) << n;
  for (const auto& name : names) {
    Scene scene;
    ASSERT_NO_THROW(scene = referenceScene(name)) << name;
    const auto image = exactSolution(scene);
    ASSERT_TRUE(image.has_value()) << name;
    EXPECT_EQ(image->width, scene.camera.pixelsX);
    EXPECT_EQ(image->height, scene.camera.pixelsY);
    EXPECT_NEAR(image->tracedPowerW, compileScene(scene, 1).tracedPowerW, 1e-15) << name;
    // pinhole_small counts 4e-5 of analog beams: it is there for aimed
    // sampling, which counts about half.
    EXPECT_GT(image->hitFraction, 1e-5) << name;
    EXPECT_LT(image->hitFraction, 1.0) << name;
    if (name != "pinhole_rect") {
      EXPECT_EQ(image->validCount(), image->pixelCount()) << name;
    }
    for (size_t p = 0; p < image->pixelCount(); ++p) {
      ASSERT_TRUE(std::isfinite(image->irradiance[p]) && image->irradiance[p] >= 0.0) << name;
      ASSERT_GE(image->xyz[p][1], 0.0) << name;
    }
    std::printf("%-16s %-60s hit fraction %.5g, valid %zu/%zu\n", name.c_str(), image->configuration.c_str(),
                image->hitFraction, image->validCount(), image->pixelCount());
  }
}

TEST(ReferenceScenes, UnrecognisedConfigurationsAreRefused) {
  Scene scene = referenceScene("disk_on_axis");
  scene.lights[0].direction = glm::normalize(glm::dvec3(0.1, 0.0, 1.0));  // tilted disk
  EXPECT_FALSE(exactSolution(scene).has_value());
  scene = referenceScene("point_on_axis");
  scene.lights[0].type = LightType::Spot;
  scene.lights[0].direction = {0, 0, 1};
  scene.lights[0].coneHalfAngleDeg = 30;
  EXPECT_FALSE(exactSolution(scene).has_value());
  // The solver knows the bare sensor and the pinhole; a lens is neither.
  scene = referenceScene("point_on_axis");
  scene.camera.model = thinLensModel({0.05, 0.01, 1.0});
  EXPECT_FALSE(exactSolution(scene).has_value());
  scene = referenceScene("pinhole_rect");
  scene.lights.push_back(referenceScene("point_on_axis").lights[0]);
  scene.lights.back().position = {0, 0, -0.05};
  EXPECT_FALSE(exactSolution(scene).has_value());
  // A light that cannot reach the sensor is fine and adds nothing.
  scene.lights.back().position = {0, 0, 0.05};  // behind the sensor
  const auto image = exactSolution(scene);
  ASSERT_TRUE(image.has_value());
  const ExactImage alone = solve(referenceScene("pinhole_rect"));
  EXPECT_EQ(image->irradiance, alone.irradiance);
}

TEST(ReferenceScenes, LightsAdd) {
  Scene both = referenceScene("point_on_axis");
  both.lights.push_back(referenceScene("disk_on_axis").lights[0]);
  const ExactImage sum = solve(both);
  const ExactImage a = solve(referenceScene("point_on_axis")), b = solve(referenceScene("disk_on_axis"));
  for (size_t p = 0; p < sum.pixelCount(); ++p) {
    EXPECT_NEAR(sum.irradiance[p], a.irradiance[p] + b.irradiance[p], 1e-12 * sum.irradiance[p]);
    EXPECT_NEAR(sum.xyz[p][1], a.xyz[p][1] + b.xyz[p][1], 1e-12 * sum.xyz[p][1]);
  }
  EXPECT_NEAR(sum.hitFraction * sum.tracedPowerW, a.hitFraction * a.tracedPowerW + b.hitFraction * b.tracedPowerW, 1e-12);
}

}  // namespace
}  // namespace spectrace
