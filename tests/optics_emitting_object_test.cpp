// Exact references for emitting objects (an object's "emission",
// lights/object_light.cpp), read from scene files as users write them, over
// a 0.6 m bare sensor of 24 x 24 pixels:
// - a rect and a disk facing the sensor give the configuration factor of a
//   parallel rectangle or disk times their exitance;
// - a sphere wholly above the sensor's plane lights it as a point of the
//   same flux at its centre;
// - a mesh that tiles the rect with triangles of unequal areas gives the
//   rect's image (its points are uniform by area only if the alias table
//   weighs triangles by area), and, two-sided, half of it; its exact image
//   by Lambert's polygon form factor is the rect's by its configuration
//   factor.
// Each is rendered with the same beams on lavapipe and the CPU reference,
// which must agree bit for bit; the CPU's film is checked per pixel within
// 5 sigma, by a chi-square over the pixels and in total
// (testing::expectMatchesExactImage). Then the refusals, each naming the
// field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>

#include "scene/scene.h"
#include "support/device_renders.h"
#include "support/render_comparison.h"
#include "support/test_scale.h"

namespace spectrace {
namespace {

namespace fs = std::filesystem;

// A directory for the scenes' OBJ files, removed when the program ends.
const fs::path& sceneDir() {
  struct Dir {
    fs::path path = fs::temp_directory_path() / fmt::format("spectrace_emitting_{}", ::getpid());
    Dir() { fs::create_directories(path); }
    ~Dir() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

// The scene with `objects` (JSON array entries) over the sensor, lit by
// them alone.
Scene sceneWith(const std::string& objects) {
  return parseScene(R"({"spectrum": {"min_nm": 360, "max_nm": 830, "bins": 16},
      "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 1, 0],
                 "sensor": {"width_m": 0.6, "height_m": 0.6, "pixels": [24, 24]}},
      "render": {"wavelengths_per_beam": 1},
      "objects": [)" + objects + "]}",
                    sceneDir() / "scene.json");
}

// The 0.2 x 0.1 m rect at height 0.25 m, facing the sensor, as a grid of
// cells of unequal widths, two triangles each, wound to face -z.
void writeTiledRect(const std::string& name) {
  const std::vector<double> xs = {-0.1, -0.07, 0.0, 0.02, 0.1}, ys = {-0.05, 0.01, 0.05};
  std::ofstream obj(sceneDir() / name);
  for (double y : ys)
    for (double x : xs) obj << fmt::format("v {} {} 0.25\n", x, y);
  const auto at = [&](size_t i, size_t j) { return j * xs.size() + i + 1; };
  for (size_t j = 0; j + 1 < ys.size(); ++j)
    for (size_t i = 0; i + 1 < xs.size(); ++i) {
      obj << fmt::format("f {} {} {}\n", at(i, j), at(i, j + 1), at(i + 1, j + 1));
      obj << fmt::format("f {} {} {}\n", at(i, j), at(i + 1, j + 1), at(i + 1, j));
    }
}

const char* kRect = R"({"type": "rect", "center": [0, 0, 0.25], "normal": [0, 0, -1], "u_axis": [1, 0, 0],
                        "size_m": [0.2, 0.1], "material": {"type": "absorber"},
                        "emission": {"power_w": %g, "spd": "D65"}})";

std::string rectWithPower(double watts) {
  std::string s = kRect;
  return s.replace(s.find("%g"), 2, fmt::format("{}", watts));
}

const uint64_t kBeams = testing::scaledBeams(2'000'000, 200'000);

TEST(OpticsEmittingObject, RectGivesItsConfigurationFactorOnBothDevices) {
  const Scene scene = sceneWith(R"({"type": "rect", "center": [0.03, -0.02, 0.25], "normal": [0, 0, -1],
      "u_axis": [1, 0.5, 0], "size_m": [0.2, 0.1], "material": {"type": "diffuse", "reflectance": 0.5},
      "emission": {"power_w": 2, "spd": "D65"}})");
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].type, LightType::Object);
  EXPECT_EQ(scene.lights[0].label, "/objects/0/emission");
  testing::expectMatchesExactImage(scene, testing::renderOnBothDevices(scene, kBeams, 1), kBeams, "emitting rect");
}

TEST(OpticsEmittingObject, DiskGivesItsConfigurationFactorOnBothDevices) {
  const Scene scene = sceneWith(R"({"type": "disk", "center": [0.02, 0.01, 0.2], "normal": [0, 0, -1],
      "radius_m": 0.08, "material": {"type": "absorber"}, "emission": {"power_lm": 300, "spd": "A"}})");
  testing::expectMatchesExactImage(scene, testing::renderOnBothDevices(scene, kBeams, 2), kBeams, "emitting disk");
}

TEST(OpticsEmittingObject, SphereLightsLikeAPointOfItsFluxOnBothDevices) {
  const Scene scene = sceneWith(R"({"type": "sphere", "center": [0.03, -0.02, 0.2], "radius_m": 0.06,
      "material": {"type": "absorber"}, "emission": {"power_w": 2, "spd": {"blackbody_k": 3000}}})");
  testing::expectMatchesExactImage(scene, testing::renderOnBothDevices(scene, kBeams, 3), kBeams, "emitting sphere");
}

TEST(OpticsEmittingObject, MeshOfUnequalTrianglesGivesTheRectsImageOnBothDevices) {
  writeTiledRect("tiled.obj");
  const Scene mesh = sceneWith(R"({"type": "mesh", "file": "tiled.obj", "material": {"type": "absorber"},
      "emission": {"power_w": 2, "spd": "D65"}})");
  const Scene rect = sceneWith(rectWithPower(2.0));
  // Two closed forms of one image: Lambert's polygon form factor summed
  // over the triangles, and the parallel rectangle's configuration factor
  // (to the float rounding of the primitives' corners).
  const auto meshExact = exactSolution(mesh), rectExact = exactSolution(rect);
  ASSERT_TRUE(meshExact && rectExact);
  const double peak = *std::max_element(rectExact->irradiance.begin(), rectExact->irradiance.end());
  for (size_t p = 0; p < rectExact->irradiance.size(); ++p)
    ASSERT_NEAR(meshExact->irradiance[p], rectExact->irradiance[p], 1e-6 * peak) << "pixel " << p;
  testing::expectMatchesExactImage(rect, testing::renderOnBothDevices(mesh, kBeams, 4), kBeams, "emitting mesh");
}

TEST(OpticsEmittingObject, TwoSidedMeshSendsHalfItsPowerEachWay) {
  writeTiledRect("tiled_two_sided.obj");
  const Scene mesh = sceneWith(R"({"type": "mesh", "file": "tiled_two_sided.obj", "material": {"type": "absorber"},
      "emission": {"power_w": 2, "spd": "D65", "two_sided": true}})");
  const Scene halfRect = sceneWith(rectWithPower(1.0));
  testing::expectMatchesExactImage(halfRect, testing::renderOnBothDevices(mesh, kBeams, 5), kBeams,
                                   "two-sided emitting mesh");
}

// The object stays an object: a point light 0.4 m above the sensor's
// centre and, halfway down, an absorbing disk of radius 0.1 m emitting
// upwards. The disk's shadow is the disk of radius 0.2 m about the centre
// (a point casts no penumbra) and its own light never comes down, so the
// pixels wholly inside the shadow get nothing, and those wholly outside
// get the point light's beams (five in six beams are the point's: at the
// smallest test scale, 200k beams, a corner pixel expects about 17 of
// them, so none gets 0 but with probability about 4e-8).
TEST(OpticsEmittingObject, BlocksOtherLightsAsItsMaterialSays) {
  const Scene withPoint = parseScene(R"({"spectrum": {"min_nm": 360, "max_nm": 830, "bins": 16},
      "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 1, 0],
                 "sensor": {"width_m": 0.6, "height_m": 0.6, "pixels": [24, 24]}},
      "render": {"wavelengths_per_beam": 1},
      "lights": [{"type": "point", "position": [0, 0, 0.4], "power_w": 1, "spd": "D65"}],
      "objects": [{"type": "disk", "center": [0, 0, 0.2], "normal": [0, 0, 1], "radius_m": 0.1,
                   "material": {"type": "absorber"}, "emission": {"power_w": 0.2, "spd": "D65"}}]})",
                               sceneDir() / "scene.json");
  ASSERT_EQ(withPoint.lights.size(), 2u);
  const RenderResult r = testing::renderOnBothDevices(withPoint, kBeams, 6);
  int inside = 0, outside = 0;
  for (int row = 0; row < 24; ++row)
    for (int col = 0; col < 24; ++col) {
      const double x0 = 0.025 * col - 0.3, y0 = 0.025 * row - 0.3;
      double farthest = 0.0;
      for (double x : {x0, x0 + 0.025})
        for (double y : {y0, y0 + 0.025}) farthest = std::max(farthest, std::hypot(x, y));
      const double cx = std::clamp(0.0, x0, x0 + 0.025), cy = std::clamp(0.0, y0, y0 + 0.025);
      const double nearest = std::hypot(cx, cy);
      const float e = r.image.irradiance[size_t(row) * 24 + col];
      if (farthest < 0.195) {
        EXPECT_EQ(e, 0.0f) << "pixel " << col << ", " << row << " lies in the disk's shadow";
        ++inside;
      } else if (nearest > 0.205) {
        EXPECT_GT(e, 0.0f) << "pixel " << col << ", " << row << " sees the point light";
        ++outside;
      }
    }
  EXPECT_GT(inside, 150);
  EXPECT_GT(outside, 300);
}

// Camera paths count every path from an emitting object. Seen directly:
// through a pinhole, an emitting rect facing the sensor gives the pinhole
// image of a uniform rect (the rect light's closed form), by camera paths
// alone and by the default (both estimators).
TEST(OpticsEmittingObject, CameraPathsSeeAnEmittingRectThroughAPinhole) {
  const Scene scene = parseScene(R"({"spectrum": {"min_nm": 380, "max_nm": 780, "bins": 8},
      "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 1, 0],
                 "sensor": {"width_m": 0.024, "height_m": 0.024, "pixels": [24, 24]},
                 "pinhole": {"distance_m": 0.05, "radius_m": 0.0015}},
      "render": {"wavelengths_per_beam": 1},
      "objects": [{"type": "rect", "center": [0.005, -0.004, 0.3], "normal": [0, 0, -1], "u_axis": [1, 0, 0],
                   "size_m": [0.13, 0.12], "material": {"type": "absorber"},
                   "emission": {"power_w": 1, "spd": "D65"}}]})",
                                 sceneDir() / "scene.json");
  CompileOptions cameraOnly;
  cameraOnly.lightPaths = false;
  const uint64_t paths = testing::scaledBeams(1'000'000, 200'000);
  testing::expectMatchesExactImage(scene, testing::renderOnBothDevices(scene, paths, 13, cameraOnly), paths,
                                   "emitting rect by camera paths");
  testing::expectMatchesExactImage(scene, testing::renderOnBothDevices(scene, paths, 14), paths,
                                   "emitting rect by both estimators");
}

// Lighting a diffuse plate: an emitting rect and a one-sided emitting mesh
// facing the plate (away from the camera) light it; the image by camera
// paths alone (their light samples) and by light paths alone (with camera
// connections) must agree within their noise, and the default (both) with
// them. Each on both devices, bit for bit.
TEST(OpticsEmittingObject, CameraPathsAgreeWithLightPathsOnADiffusePlate) {
  writeTiledRect("tiled_for_camera.obj");
  const Scene scene = parseScene(R"({"spectrum": {"min_nm": 380, "max_nm": 780, "bins": 4},
      "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 1, 0],
                 "sensor": {"width_m": 0.02, "height_m": 0.02, "pixels": [8, 8]},
                 "pinhole": {"distance_m": 0.02, "radius_m": 0.002}},
      "render": {"wavelengths_per_beam": 1},
      "objects": [
        {"type": "rect", "center": [0, 0, 0.3], "normal": [0, 0, -1], "u_axis": [1, 0, 0], "size_m": [0.4, 0.4],
         "material": {"type": "diffuse", "reflectance": 0.8}},
        {"type": "rect", "center": [0.04, 0.03, 0.12], "normal": [0.3, 0.2, 1], "size_m": [0.05, 0.03],
         "material": {"type": "diffuse", "reflectance": 0.3}, "emission": {"power_w": 1, "spd": "D65"}},
        {"type": "mesh", "file": "tiled_for_camera.obj",
         "transform": {"scale": 0.3, "rotate_deg": [180, 0, 0], "translate": [-0.03, -0.02, 0.25]},
         "material": {"type": "absorber"}, "emission": {"power_w": 2, "spd": "A"}}]})",
                                 sceneDir() / "scene.json");
  const uint64_t small = testing::scaledBeams(100'000, 20'000);
  const uint64_t paths = testing::scaledBeams(400'000, 100'000);
  const testing::PixelEstimates lightEstimates = testing::expectCameraPathsMatchLightPaths(
      scene, small, testing::scaledBeams(2'000'000, 400'000), paths, 7);
  testing::renderOnBothDevices(scene, small, 11);
  const RenderResult both = testing::renderOn(DeviceChoice::Cpu, scene, paths, 12);
  const auto bothResult = testing::compareRenders(
      lightEstimates, testing::pixelEstimates(both.histogram, both.plan, paths), "light paths vs both");
  EXPECT_EQ(bothResult.cells, 64);
  EXPECT_GT(bothResult.pValue, 1e-3);
}

// The scene may have no "lights"; an emitter's spd and power read as a
// light's.
TEST(OpticsEmittingObject, SceneFileFormsAndRefusals) {
  const Scene scene = sceneWith(R"({"name": "panel", "type": "disk", "center": [0, 0, 0.2], "normal": [0, 0, -1],
      "radius_m": 0.05, "material": {"type": "absorber"}, "emission": {"power_lm": 683, "spd": {"line_nm": 555}}})");
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].name, "panel");
  EXPECT_NEAR(scene.lights[0].powerW, 1.0 / 1.0, 1e-3);  // V(555 nm) = 1.0000 to four places
  const auto refusal = [](const std::string& object) {
    try {
      sceneWith(object);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string rect = R"({"type": "rect", "center": [0, 0, 0.25], "normal": [0, 0, -1], "size_m": [0.1, 0.1],
                               "material": {"type": "absorber"}, "emission": )";
  const struct {
    std::string object, field, what;
  } cases[] = {
      {rect + "3}", "/objects/0/emission", "must be an object"},
      {rect + R"({"power_w": 1, "power_lm": 2, "spd": "D65"}})", "/objects/0/emission/power_lm", "not both"},
      {rect + R"({"power_w": 1, "spd": "D65", "colour": 1}})", "/objects/0/emission", "colour"},
      {rect + R"({"power_w": 1}})", "/objects/0/emission", "spd"},
      {rect + R"({"power_w": -1, "spd": "D65"}})", "/objects/0/emission/power_w", ""},
      {rect + R"({"power_w": 1, "spd": "D65", "two_sided": "yes"}})", "/objects/0/emission/two_sided", "true or false"},
      {R"({"type": "sphere", "center": [0, 0, 1], "radius_m": 0.1, "material": {"type": "absorber"},
           "emission": {"power_w": 1, "spd": "D65", "two_sided": true}})",
       "/objects/0/emission/two_sided", "outwards only"},
      {R"({"type": "sphere", "center": [0, 0, 1], "radius_m": 0.1, "material": {"type": "absorber"}})", "/lights",
       "nothing that emits"},
  };
  for (const auto& c : cases) {
    const std::string message = refusal(c.object);
    EXPECT_NE(message.find(c.field), std::string::npos) << c.object << "\n" << message;
    EXPECT_NE(message.find(c.what), std::string::npos) << c.object << "\n" << message;
  }
  // "object" is not a type "lights" may name.
  try {
    parseScene(R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 1, 0],
                              "sensor": {"width_m": 0.1, "height_m": 0.1, "pixels": [4, 4]}},
                   "lights": [{"type": "object", "power_w": 1, "spd": "D65"}]})",
               sceneDir() / "scene.json");
    ADD_FAILURE() << "a light of type object was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/lights/0/type"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("emission"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace spectrace
