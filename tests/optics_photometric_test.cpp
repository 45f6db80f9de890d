// Exact references for the photometric light (lights/photometric_light.cpp):
// a luminaire 0.25 m above a bare sensor gives each pixel the illuminance
// I(C, gamma) cos(theta) / r^2 averaged over it (host/reference,
// exactSolution), I the file's bilinear intensity in world coordinates.
// Each table is rendered with the same beams on lavapipe and the CPU
// reference, which must give the same film bit for bit; the CPU's render
// (Poisson counts: every beam weighs 1) is checked per pixel within 5
// sigma and by a chi-square over the pixels, and in total. Tables: a
// Lambertian and a batwing (IES, rotationally symmetric), an asymmetric
// 0-360 table on a tilted luminaire with its own c0_axis, and the batwing
// again as EULUMDAT. Then camera paths (the light's arrival) against light
// paths on a diffuse plate.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>

#include "lights/photometric_file.h"
#include "reference/exact_solution.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "support/object_scenes.h"
#include "support/device_renders.h"
#include "support/p_values.h"
#include "support/render_comparison.h"
#include "support/test_scale.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

constexpr double kPi = 3.14159265358979323846;

// An LM-63-2002 file with vertical angles `gamma` and horizontal `c`, one
// row of candela per horizontal angle, from intensity(c, gamma) in degrees.
template <class F>
std::string iesText(const std::vector<double>& c, const std::vector<double>& gamma, F intensity) {
  std::string text = "IESNA:LM-63-2002\n[TEST] spectrace\nTILT=NONE\n";
  text += fmt::format("1 -1 1 {} {} 1 2 0.1 0.1 0.05\n1 1 20\n", gamma.size(), c.size());
  for (double g : gamma) text += fmt::format("{} ", g);
  text += "\n";
  for (double a : c) text += fmt::format("{} ", a);
  text += "\n";
  for (double a : c) {
    for (double g : gamma) text += fmt::format("{:.9g} ", intensity(a, g));
    text += "\n";
  }
  return text;
}

std::vector<double> steps(double from, double to, double step) {
  std::vector<double> out;
  for (double a = from; a <= to + 1e-9; a += step) out.push_back(a);
  return out;
}

double lambertian(double, double g) { return 1000.0 * std::cos(g * kPi / 180.0); }
// Brightest near 40 degrees off nadir, dark at nadir's edge of 90.
double batwing(double, double g) {
  const double r = g * kPi / 180.0;
  return 200.0 + 1800.0 * std::pow(std::sin(r), 2) * std::cos(r);
}
// Different in every quadrant, so C = 90 and C = 270 cannot be swapped
// unseen, nor C = 0 and 180; lit above the horizon too, less.
double asymmetric(double c, double g) {
  const double cr = c * kPi / 180.0, r = g * kPi / 180.0;
  return 800.0 * (0.25 + std::max(std::cos(r), 0.0)) * (1.0 + 0.7 * std::cos(cr) + 0.4 * std::sin(cr));
}

// An EULUMDAT file of a rotationally symmetric luminaire (symmetry 1):
// intensities per 1000 lm of its one lamp set of `lumens`.
std::string ldtText(const std::vector<double>& gamma, double lumens, double (*intensity)(double, double)) {
  std::string t = "spectrace test\n1\n1\n4\n90\n" + std::to_string(gamma.size()) +
                  "\n" + fmt::format("{}", gamma[1] - gamma[0]) + "\nreport\ntest luminaire\nT-1\ntest.ldt\n2026\n";
  for (int k = 0; k < 9; ++k) t += "100\n";
  t += "100\n80\n1\n0\n1\n1\nLED\n" + fmt::format("{}", lumens) + "\n3000\n90\n20\n";
  for (int k = 0; k < 10; ++k) t += "0.5\n";
  for (double c : {0.0, 90.0, 180.0, 270.0}) t += fmt::format("{}\n", c);
  for (double g : gamma) t += fmt::format("{}\n", g);
  for (double g : gamma) t += fmt::format("{:.9g}\n", intensity(0.0, g) * 1000.0 / lumens);
  return t;
}

Light photometricLight(const PhotometricTable& table, glm::dvec3 position, glm::dvec3 nadir, glm::dvec3 c0) {
  Light light =
      testing::surfaceLight(LightType::Photometric, position, glm::normalize(nadir), 2.0, *cieIlluminant("D65"));
  light.photometry = std::make_shared<const PhotometricTable>(table);
  light.uAxis = glm::normalize(c0 - light.direction * glm::dot(c0, light.direction));
  return light;
}

// A 0.6 m square sensor of 24 x 24 pixels, the luminaire 0.25 m above.
Scene sensorUnder(const Light& light) {
  Scene scene = testing::bareSensorScene(0.6, 0.6, 24, 24, 16);
  scene.lights = {light};
  return scene;
}

const uint64_t kBeams = testing::scaledBeams(4'000'000, 200'000);

TEST(OpticsPhotometric, LambertianTableGivesItsIlluminanceOnBothDevices) {
  const PhotometricTable table = parseIes(iesText({0.0}, steps(0, 90, 10), lambertian), "lambertian.ies");
  const Scene scene = sensorUnder(photometricLight(table, {0.0, 0.0, 0.25}, {0, 0, -1}, {1, 0, 0}));
  testing::expectMatchesExactImage(scene, testing::renderOnBothDevices(scene, kBeams, 1), kBeams, "Lambertian");
}

TEST(OpticsPhotometric, BatwingTableGivesItsIlluminanceOnBothDevices) {
  const PhotometricTable table = parseIes(iesText({0.0}, steps(0, 90, 5), batwing), "batwing.ies");
  const Scene scene = sensorUnder(photometricLight(table, {0.02, -0.01, 0.25}, {0, 0, -1}, {1, 0, 0}));
  testing::expectMatchesExactImage(scene, testing::renderOnBothDevices(scene, kBeams, 2), kBeams, "batwing");
}

TEST(OpticsPhotometric, AsymmetricTableFollowsItsC0AxisOnBothDevices) {
  const PhotometricTable table =
      parseIes(iesText(steps(0, 360, 30), steps(0, 180, 15), asymmetric), "asymmetric.ies");
  // Tilted, with C = 0 neither along a world axis nor the default.
  const Scene scene =
      sensorUnder(photometricLight(table, {-0.03, 0.02, 0.25}, {0.15, -0.1, -1.0}, {0.3, 1.0, 0.0}));
  testing::expectMatchesExactImage(scene, testing::renderOnBothDevices(scene, kBeams, 3), kBeams, "asymmetric 0-360");
}

TEST(OpticsPhotometric, EulumdatFileGivesTheSameIlluminance) {
  const std::vector<double> gamma = steps(0, 90, 5);
  const PhotometricTable ldt = parseEulumdat(ldtText(gamma, 2500.0, batwing), "batwing.ldt");
  const PhotometricTable ies = parseIes(iesText({0.0}, gamma, batwing), "batwing.ies");
  EXPECT_NEAR(ldt.tableLumens(), ies.tableLumens(), 1e-6 * ies.tableLumens());
  const Scene scene = sensorUnder(photometricLight(ldt, {0.0, 0.0, 0.25}, {0, 0, -1}, {1, 0, 0}));
  testing::expectMatchesExactImage(scene, testing::renderOnBothDevices(scene, kBeams, 4), kBeams, "batwing (EULUMDAT)");
}

// The scene file's form: the file beside the scene, nadir straight down by
// default, C = 0 along world X projected off nadir, the flux the table's
// own (in lumens) unless power_lm or power_w is given; refusals name the
// light's field.
TEST(OpticsPhotometric, SceneFileReadsTheLuminaireAndItsFlux) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / fmt::format("spectrace_photometric_{}", ::getpid());
  std::filesystem::create_directories(dir);
  struct RemovedAtExit {
    std::filesystem::path dir;
    ~RemovedAtExit() {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  } removed{dir};
  {
    std::ofstream(dir / "down.ies") << iesText({0.0}, steps(0, 90, 10), lambertian);
  }
  const auto sceneWith = [&](const std::string& extra, const std::string& file = "down.ies") {
    return parseScene(R"({"camera": {"position": [0, 0, 0], "look_at": [0, 1, 0], "up": [0, 0, 1],
                                      "sensor": {"width_m": 0.1, "height_m": 0.1, "pixels": [4, 4]}},
                          "lights": [{"type": "photometric", "position": [0, 1, 0.5], "spd": "D65", "file": ")" +
                          file + "\"" + extra + "}]}",
                      dir / "scene.json");
  };
  const Scene scene = sceneWith("");
  ASSERT_EQ(scene.lights.size(), 1u);
  const Light& light = scene.lights[0];
  EXPECT_EQ(light.type, LightType::Photometric);
  EXPECT_EQ(light.direction, glm::dvec3(0.0, -1.0, 0.0));
  EXPECT_EQ(light.uAxis, glm::dvec3(1.0, 0.0, 0.0));
  EXPECT_EQ(light.photometryFile, dir / "down.ies");
  ASSERT_TRUE(light.photometry);
  EXPECT_DOUBLE_EQ(light.powerLm, light.photometry->tableLumens());
  EXPECT_NEAR(light.powerLm, kPi * 1000.0, 0.003 * kPi * 1000.0);  // Lambertian: near pi I0
  EXPECT_DOUBLE_EQ(sceneWith(R"(, "power_lm": 500)").lights[0].powerLm, 500.0);
  EXPECT_DOUBLE_EQ(sceneWith(R"(, "power_w": 3)").lights[0].powerW, 3.0);
  EXPECT_EQ(sceneWith(R"(, "direction": [1, 0, 0])").lights[0].uAxis, glm::dvec3(0.0, 0.0, 1.0));
  const auto refusal = [&](const std::string& extra, const std::string& file = "down.ies") {
    try {
      sceneWith(extra, file);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refusal(R"(, "c0_axis": [0, 2, 0])").find("/lights/0/c0_axis"), std::string::npos);
  const std::string missing = refusal("", "none.ies");
  EXPECT_NE(missing.find("/lights/0/file"), std::string::npos) << missing;
  EXPECT_NE(missing.find("none.ies"), std::string::npos) << missing;
}

// A diffuse plate under an asymmetric downlight, seen through a pinhole:
// camera paths reach the light through its arrival (polyAtan2 to C and
// gamma, the bilinear table), light paths through its sampling; the two
// agree pixel by pixel (testing::compareRenders), and each estimator's film
// is the same on both devices. The downlight faces the plate, away from
// the pinhole, so no beam reaches the camera without the plate.
TEST(OpticsPhotometric, CameraPathsAgreeWithLightPathsOnADiffusePlate) {
  const PhotometricTable table = parseIes(iesText(steps(0, 360, 30), steps(0, 90, 15), asymmetric), "downlight.ies");
  Scene scene = testing::bareSensorScene(0.02, 0.02, 8, 8, 4);
  scene.camera.model = pinholeModel({0.02, 0.002});
  scene.objects = {testing::namedObject(
      "plate", 0, testing::rectShape(scene.camera, {0.0, 0.0, 0.1}, {0.0, 0.0, -1.0}, {1.0, 0.0, 0.0}, {0.14, 0.14}),
      testing::diffuseMaterial(0.8))};
  scene.lights = {photometricLight(table, testing::toWorld(scene.camera, {0.01, 0.003, 0.06}),
                                   testing::directionToWorld(scene.camera, {0.2, -0.1, 1.0}),
                                   testing::directionToWorld(scene.camera, {0.0, 1.0, 0.0}))};
  testing::expectCameraPathsMatchLightPaths(scene, testing::scaledBeams(100'000, 20'000),
                                            testing::scaledBeams(2'000'000, 400'000),
                                            testing::scaledBeams(400'000, 100'000), 5);
}

}  // namespace
}  // namespace spectrace
