// Where the trace reads its tables: the one check (uniformTableLayout) and
// the uniform path against the storage path on the device.
#include "backend/uniform_tables.h"

#include <gtest/gtest.h>

#include "backend/vulkan_tracer.h"
#include "camera/pinhole_camera.h"
#include "compile/compile_scene.h"
#include "scene/scene_builders.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

DeviceScene tablesOf(size_t lights, size_t intervals, size_t cmfNodes, size_t aliasColumns) {
  DeviceScene tables;
  tables.lights.resize(lights);
  tables.intervals.resize(intervals);
  tables.cmfTable.resize(cmfNodes);
  tables.aliasColumns.resize(aliasColumns);
  return tables;
}

TEST(UniformTables, LengthsArePowersOfTwoHoldingEveryElement) {
  const UniformTableLayout layout = uniformTableLayout(tablesOf(3, 471, 0, 513), 65536, true);
  EXPECT_TRUE(layout.inUniform);
  EXPECT_EQ(layout.lights, 4u);
  EXPECT_EQ(layout.intervals, 512u);
  EXPECT_EQ(layout.cmfNodes, 1u);  // an empty table still declares one element
  EXPECT_EQ(layout.aliasColumns, 1024u);
}

TEST(UniformTables, ATableOverTheRangeKeepsEveryTableInStorage) {
  // 2048 alias columns of 16 bytes are 32 KiB: over a 16 KiB range (the
  // smallest maxUniformBufferRange Vulkan allows), within 64 KiB.
  EXPECT_TRUE(uniformTableLayout(tablesOf(1, 10, 95, 2048), 65536, true).inUniform);
  const UniformTableLayout layout = uniformTableLayout(tablesOf(1, 10, 95, 2048), 16384, true);
  EXPECT_FALSE(layout.inUniform);
  EXPECT_EQ(layout.lights, 1u);
  EXPECT_EQ(layout.aliasColumns, 1u);
  // Exactly at the range fits: 1024 columns x 16 bytes.
  EXPECT_TRUE(uniformTableLayout(tablesOf(1, 10, 95, 1024), 16384, true).inUniform);
}

TEST(UniformTables, TheGeneralPipelineAsksForNone) {
  EXPECT_FALSE(uniformTableLayout(tablesOf(1, 10, 95, 16), 65536, false).inUniform);
}

DeviceScene objectsOf(size_t primitives, size_t bvhNodes, size_t materials) {
  DeviceScene scene = tablesOf(1, 10, 95, 16);
  scene.primitives.resize(primitives);
  scene.bvhNodes.resize(bvhNodes);
  scene.materials.resize(materials);
  return scene;
}

TEST(UniformTables, SmallObjectsGoToUniformBuffersOnTheirOwn) {
  // A prism: 8 triangles, a few nodes, one material.
  const UniformTableLayout prism = uniformTableLayout(objectsOf(8, 3, 1), 65536, true);
  EXPECT_TRUE(prism.inUniform);
  EXPECT_TRUE(prism.objectsInUniform);
  EXPECT_EQ(prism.primitives, 8u);
  EXPECT_EQ(prism.bvhNodes, 4u);
  EXPECT_EQ(prism.materials, 1u);
  // 1024 primitives of 48 bytes (48 KiB) fit 64 KiB; 2048 do not, and
  // the objects stay in storage while the tables still go uniform.
  EXPECT_TRUE(uniformTableLayout(objectsOf(1024, 300, 2), 65536, true).objectsInUniform);
  const UniformTableLayout mesh = uniformTableLayout(objectsOf(2000, 700, 2), 65536, true);
  EXPECT_TRUE(mesh.inUniform);
  EXPECT_FALSE(mesh.objectsInUniform);
  EXPECT_EQ(mesh.primitives, 1u);
  EXPECT_EQ(mesh.bvhNodes, 1u);
  // The trace reads packed nodes (64 bytes): 1024 are exactly 64 KiB;
  // 1025 round up to 2048.
  EXPECT_TRUE(uniformTableLayout(objectsOf(16, 1024, 1), 65536, true).objectsInUniform);
  EXPECT_FALSE(uniformTableLayout(objectsOf(16, 1025, 1), 65536, true).objectsInUniform);
  // Nothing to read without objects, and nothing in the general pipeline.
  EXPECT_FALSE(uniformTableLayout(objectsOf(0, 0, 0), 65536, true).objectsInUniform);
  EXPECT_FALSE(uniformTableLayout(objectsOf(8, 3, 1), 65536, false).objectsInUniform);
}

TEST(UniformTables, PaddingAppendsZeroElementsOnly) {
  const std::vector<int> padded = paddedTable(std::vector<int>{7, 8, 9}, 4);
  EXPECT_EQ(padded, (std::vector<int>{7, 8, 9, 0}));
  EXPECT_EQ(paddedTable(std::vector<int>{7, 8, 9}, 1).size(), 3u);
}

// The uniform path's film against the storage path's (the general
// pipeline's), count for count.
void expectUniformAndStorageAgree(const CompiledScene& plan, uint64_t beams) {
  VulkanTracer uniform(testing::sharedVulkan(), plan, 64, kSpecialiseUniformTables);
  VulkanTracer storage(testing::sharedVulkan(), plan, 64, kSpecialiseNone);
  uniform.trace(0, beams);
  storage.trace(0, beams);
  const SpectralHistogram a = uniform.download();
  const SpectralHistogram b = storage.download();
  EXPECT_GT(a.countedBeams, 1000u);
  EXPECT_EQ(a.countedBeams, b.countedBeams);
  EXPECT_EQ(a.counts(), b.counts());
}

// Two lights of different spectra (so per-beam colour reads the CMF table
// and the light choice reads the alias columns), aimed: every table is read.
// The uniform path counts every beam where the storage path does.
TEST(UniformTables, UniformAndStorageTablesGiveTheSameFilm) {
  Scene scene = bareSensorScene(0.01, 0.01, 8, 8, 16);
  scene.camera.model = pinholeModel({0.005, 0.0005});
  Light panel = surfaceLight(LightType::Disk, {0.0, 0.0, 0.1}, {0, 0, -1}, 1.0, *cieIlluminant("D65"));
  panel.radiusM = 0.02;
  Light lamp = surfaceLight(LightType::Rect, {0.01, 0.0, 0.08}, {0, 0, -1}, 2.0, *cieIlluminant("F11"));
  lamp.sizeM = {0.01, 0.005};
  lamp.uAxis = {1, 0, 0};
  scene.lights = {panel, lamp};
  const CompiledScene plan = compileScene(scene, 7);
  ASSERT_TRUE(uniformTableLayout(plan.device, testing::sharedVulkan().info().maxUniformBufferRange, true).inUniform);
  expectUniformAndStorageAgree(plan, 300'000);
}

// Objects of two primitive types and two materials (a diffuse sphere and a
// mirror plate) before a pinhole: the beams that reach it walked the BVH
// and read the primitives and materials from the uniform buffers in one
// film, from the storage buffers in the other.
TEST(UniformTables, UniformAndStorageObjectsGiveTheSameFilm) {
  Scene scene = bareSensorScene(0.024, 0.024, 16, 16, 16);
  scene.camera.model = pinholeModel({0.04, 0.002});
  Light spot = surfaceLight(LightType::Spot, {0.3, 0.3, 0.5}, glm::normalize(glm::dvec3(-0.3, -0.3, 0.5)), 5.0,
                            *cieIlluminant("D65"));
  spot.coneHalfAngleDeg = 30.0;
  scene.lights = {spot};
  SceneObject ball;
  ball.label = "/objects/0";
  ball.shape.type = ShapeType::Sphere;
  ball.shape.center = {0.0, 0.0, 1.0};
  ball.shape.radiusM = 0.15;
  ball.shape.closed = true;
  ball.material.type = MaterialType::Diffuse;
  ball.material.reflectanceNm = {400.0, 700.0};
  ball.material.reflectance = {0.2, 0.8};
  SceneObject plate;
  plate.label = "/objects/1";
  plate.shape.type = ShapeType::Rect;
  plate.shape.center = {0.0, -0.2, 1.0};
  plate.shape.normal = glm::normalize(glm::dvec3(0.0, 1.0, -0.5));
  plate.shape.uAxis = {1.0, 0.0, 0.0};
  plate.shape.sizeM = {0.6, 0.3};
  plate.material.type = MaterialType::Mirror;
  plate.material.reflectanceNm = {550.0};
  plate.material.reflectance = {0.9};
  scene.objects = {ball, plate};
  const CompiledScene plan = compileScene(scene, 11);
  const UniformTableLayout layout =
      uniformTableLayout(plan.device, testing::sharedVulkan().info().maxUniformBufferRange, true);
  ASSERT_TRUE(layout.objectsInUniform);
  expectUniformAndStorageAgree(plan, 200'000);
}

}  // namespace
}  // namespace spectrace
