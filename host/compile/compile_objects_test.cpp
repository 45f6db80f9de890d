// Scene objects in the compiler: which shortcuts each kind of object turns
// off (compile/shortcuts.h), the primitives and their BVH, and the film's weights under camera connections.
#include "compile/compile_objects.h"

#include <gtest/gtest.h>

#include <set>

#include "camera/pinhole_camera.h"
#include "compile/shortcuts.h"
#include "scene/scene_builders.h"

namespace spectrace {
namespace {

SceneObject plate(MaterialType type, std::vector<double> nm = {550.0}, std::vector<double> reflectance = {0.5}) {
  SceneObject object;
  object.label = "/objects/0";
  object.shape.type = ShapeType::Rect;
  object.shape.center = {0.0, 0.0, 0.5};
  object.shape.normal = {0.0, 0.0, -1.0};
  object.shape.uAxis = {1.0, 0.0, 0.0};
  object.shape.sizeM = {0.2, 0.1};
  object.material.type = type;
  object.material.reflectanceNm = std::move(nm);
  object.material.reflectance = std::move(reflectance);
  return object;
}

Scene pointLightScene() {
  Scene scene = bareSensorScene(0.036, 0.024, 36, 24, 16);
  scene.camera.model = pinholeModel({0.05, 0.001});
  scene.lights = {pointLight({0.0, 0.0, 1.0}, 1.0, *cieIlluminant("D65"))};
  return scene;
}

const Shortcut kGeometricShortcuts[] = {Shortcut::SkipUnreachableLights, Shortcut::AimAtCamera, Shortcut::TrimPixels};

TEST(ObjectShortcuts, AbsorbersKeepEveryShortcut) {
  // An absorber only takes beams away: every beam that is still counted
  // went in a straight line from its light, as without it.
  Scene scene = pointLightScene();
  scene.objects = {plate(MaterialType::Absorber)};
  for (Shortcut s : kGeometricShortcuts) EXPECT_EQ(shortcutBlockedBecause(s, scene), "") << shortcutName(s);
  EXPECT_EQ(compileScene(scene, 1).device.lights[0].aimed, 1u);
}

TEST(ObjectShortcuts, SurfacesThatRedirectBeamsTurnOffTheGeometricShortcuts) {
  for (MaterialType type : {MaterialType::Diffuse, MaterialType::Mirror}) {
    Scene scene = pointLightScene();
    scene.objects = {plate(type)};
    for (Shortcut s : kGeometricShortcuts) {
      const std::string why = shortcutBlockedBecause(s, scene);
      EXPECT_NE(why.find("/objects/0"), std::string::npos) << shortcutName(s) << ": " << why;
      EXPECT_FALSE(shortcutApplies(s, true, scene));
    }
    const CompiledScene plan = compileScene(scene, 1);
    EXPECT_EQ(plan.device.lights[0].aimed, 0u) << "aiming must be off with a " << materialTypeName(type);
    EXPECT_EQ(plan.film.window.width, plan.film.pixelsX) << "the whole sensor must be stored";
    EXPECT_EQ(plan.film.window.height, plan.film.pixelsY);
  }
}

TEST(ObjectShortcuts, ALightBehindTheCameraIsTracedWhenAMirrorCanReturnIt) {
  // Without objects the light behind the sensor is skipped as unreachable;
  // a mirror in front of the camera can send its beams back.
  Scene scene = pointLightScene();
  scene.lights.push_back(pointLight({0.0, 0.0, -1.0}, 1.0, *cieIlluminant("D65")));
  EXPECT_FALSE(compileScene(scene, 1).summaries[1].traced);
  scene.objects = {plate(MaterialType::Mirror)};
  EXPECT_TRUE(compileScene(scene, 1).summaries[1].traced);
}

TEST(ObjectShortcuts, ColourFromBinsNeedsWavelengthIndependentObjects) {
  Scene scene = pointLightScene();
  scene.objects = {plate(MaterialType::Diffuse)};  // constant reflectance
  EXPECT_EQ(shortcutBlockedBecause(Shortcut::ColourFromBins, scene), "");
  EXPECT_TRUE(compileScene(scene, 1).film.colourFromBins);
  scene.objects = {plate(MaterialType::Diffuse, {400.0, 700.0}, {0.2, 0.8})};
  EXPECT_NE(shortcutBlockedBecause(Shortcut::ColourFromBins, scene), "");
  EXPECT_FALSE(compileScene(scene, 1).film.colourFromBins);
  EXPECT_TRUE(compileScene(scene, 1).film.exactColour) << "per-beam colour instead";
  SceneObject glass = plate(MaterialType::Dielectric);
  glass.shape.type = ShapeType::Sphere;
  glass.shape.radiusM = 0.1;
  glass.material.sellmeierB = {1.03961212, 0.231792344, 1.01046945};
  glass.material.sellmeierC = {0.00600069867, 0.0200179144, 103.560653};
  scene.objects = {glass};
  EXPECT_NE(shortcutBlockedBecause(Shortcut::ColourFromBins, scene), "") << "dispersion";
  glass.material.sellmeierB = {1.25, 0.0, 0.0};  // a constant ior of 1.5
  glass.material.sellmeierC = {0.0, 0.0, 0.0};
  scene.objects = {glass};
  EXPECT_EQ(shortcutBlockedBecause(Shortcut::ColourFromBins, scene), "");
  EXPECT_EQ(shortcutBlockedBecause(Shortcut::TrimSpectrum, scene), "") << "no material changes a wavelength";
}

TEST(CompiledObjects, ConnectionsGiveFractionalWeightsAndOnlyWithDiffuseSurfaces) {
  Scene scene = pointLightScene();
  scene.objects = {plate(MaterialType::Diffuse)};
  CompiledScene plan = compileScene(scene, 1);
  EXPECT_EQ(plan.device.constants.connect, 1u);
  EXPECT_EQ(plan.film.weightUnits, device::kWeightUnitsFractional);
  CompileOptions analog;
  analog.connect = false;
  analog.cameraPaths = false;
  plan = compileScene(scene, 1, analog);
  EXPECT_EQ(plan.device.constants.connect, 0u);
  EXPECT_EQ(plan.film.weightUnits, 1u) << "analog transport keeps every weight 1";
  scene.objects = {plate(MaterialType::Mirror)};
  EXPECT_EQ(compileScene(scene, 1).device.constants.connect, 0u) << "nothing to connect";
}

TEST(CompiledObjects, EveryPrimitiveOnceInTheBvhAndABoxHoldsEachOne) {
  Scene scene = pointLightScene();
  for (int i = 0; i < 40; ++i) {
    SceneObject object = plate(MaterialType::Absorber);
    object.label = "/objects/" + std::to_string(i);
    object.shape.center = {0.01 * i, -0.02 * i, 0.5 + 0.03 * i};
    if (i % 2) {
      object.shape.type = ShapeType::Sphere;
      object.shape.radiusM = 0.004;
    }
    scene.objects.push_back(object);
  }
  const CompiledScene plan = compileScene(scene, 1);
  ASSERT_EQ(plan.device.primitives.size(), 40u);
  EXPECT_EQ(plan.device.constants.objectPrimitives, 40u);
  std::set<uint32_t> materials;
  for (const auto& p : plan.device.primitives) materials.insert(p.material);
  EXPECT_EQ(materials.size(), 40u) << "each object's primitive, once";
  // Each leaf's box holds its spheres' centres.
  for (const auto& node : plan.device.bvhNodes)
    for (int slot = 0; slot < 4; ++slot) {
      const uint32_t count = node.count[slot];
      for (uint32_t i = node.child[slot]; i < node.child[slot] + count; ++i) {
        const auto& p = plan.device.primitives[i];
        const glm::vec3 lo(node.minX[slot], node.minY[slot], node.minZ[slot]);
        const glm::vec3 hi(node.maxX[slot], node.maxY[slot], node.maxZ[slot]);
        for (int k = 0; k < 3; ++k) {
          EXPECT_LE(lo[k], p.a[k]);
          EXPECT_GE(hi[k], p.a[k]);
        }
      }
    }
}

TEST(ObjectValidation, AGlassMeshMustFaceOutwards) {
  // A closed, consistently wound tetrahedron, outwards (counter-clockwise
  // from outside), then turned inside out: glass would refract every beam
  // the wrong way, so it is refused.
  Scene scene = pointLightScene();
  SceneObject glass;
  glass.label = "/objects/0";
  glass.shape.type = ShapeType::Mesh;
  glass.shape.closed = true;
  glass.shape.vertices = {{0.0, 0.0, 0.5}, {0.1, 0.0, 0.5}, {0.0, 0.1, 0.5}, {0.0, 0.0, 0.6}};
  glass.shape.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  glass.material.type = MaterialType::Dielectric;
  glass.material.sellmeierB = {1.25, 0.0, 0.0};
  scene.objects = {glass};
  EXPECT_NO_THROW(compileScene(scene, 1));
  for (auto& t : scene.objects[0].shape.triangles) std::swap(t[1], t[2]);
  try {
    compileScene(scene, 1);
    FAIL() << "an inside-out glass mesh was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/objects/0/material"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("face outwards"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace spectrace
