// The CPU reference's interleaved walks (backend/walk_interleaver.h): a
// thread's beams in flight, their BVH walks stepped in turn, must make the
// film of one beam at a time bit for bit, on meshes (the vector leaf test)
// and on leaves of spheres, rects and disks (the scalar one), through
// glass, mirrors and diffuse surfaces, on light paths with their camera
// connections (visibility walks that stop at the first hit) and on camera
// paths, and in each machine code.
#include <gtest/gtest.h>

#include <atomic>
#include <string>

#include "backend/cpu_tracer.h"
#include "bench/optics_bench.h"
#include "compile/compile_scene.h"
#include "scene/scene.h"
#include "support/same_film.h"
#include "support/test_scale.h"

namespace spectrace {
namespace {

using testing::expectSameFilm;

// A tessellated sphere (diffuse) behind a glass ball, a mirror and a disk,
// through a pinhole, lit by a spot and a lamp: every primitive type, with
// leaves of triangles and leaves of the others.
Scene mixedObjectsScene(uint64_t triangles) {
  Scene scene = opticsMeshScene(triangles);
  const Scene extras = parseScene(R"({"spectrum": {"min_nm": 360, "max_nm": 830, "bins": 16},
      "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 1, 0],
                 "sensor": {"width_m": 0.024, "height_m": 0.024, "pixels": [16, 16]}},
      "lights": [{"name": "lamp", "type": "point", "position": [0.2, 0.3, 0.3], "power_w": 2, "spd": "D65"}],
      "objects": [
        {"type": "sphere", "center": [0.1, 0.1, 0.6], "radius_m": 0.08,
         "material": {"type": "dielectric", "glass": "N-BK7"}},
        {"type": "rect", "center": [-0.2, 0.0, 0.9], "normal": [1, 0, -0.3], "u_axis": [0, 1, 0],
         "size_m": [0.3, 0.3], "material": {"type": "mirror"}},
        {"type": "disk", "center": [0.0, -0.25, 0.8], "normal": [0, 1, -0.2], "radius_m": 0.1,
         "material": {"type": "diffuse", "reflectance": 0.8}}]})",
                                  "extras.json");
  for (const SceneObject& object : extras.objects) scene.objects.push_back(object);
  for (const Light& light : extras.lights) scene.lights.push_back(light);
  return scene;
}

SpectralHistogram render(const CompiledScene& plan, WalkInterleaving interleaving, CpuCode code, uint64_t beams) {
  CpuTracer tracer(plan, 2, device::kProfileStageFull, code, interleaving);
  EXPECT_EQ(tracer.interleavesWalks(), interleaving == WalkInterleaving::Always);
  EXPECT_EQ(tracer.trace(0, beams), beams);
  return tracer.download();
}

void expectInterleavingChangesNothing(const Scene& scene, const CompileOptions& options, const std::string& what) {
  const CompiledScene plan = compileScene(scene, 31337, options);
  const uint64_t beams = testing::scaledBeams(200'000, 50'000);
  for (CpuCode code : {CpuCode::Baseline, fastestCpuCode()}) {
    const SpectralHistogram alone = render(plan, WalkInterleaving::Never, code, beams);
    const SpectralHistogram interleaved = render(plan, WalkInterleaving::Always, code, beams);
    EXPECT_GT(alone.countedBeams, beams / 100) << what << ": too few beams counted to compare";
    expectSameFilm(alone, interleaved, what + ", " + cpuCodeName(code));
  }
}

TEST(InterleavedWalks, LightPathsWithConnectionsMakeTheSameFilm) {
  CompileOptions options;
  options.cameraPaths = false;
  expectInterleavingChangesNothing(mixedObjectsScene(20'000), options, "light paths");
}

TEST(InterleavedWalks, CameraPathsMakeTheSameFilm) {
  CompileOptions options;
  options.lightPaths = false;
  expectInterleavingChangesNothing(mixedObjectsScene(20'000), options, "camera paths");
}

TEST(InterleavedWalks, BothEstimatorsAndAnalogBeamsMakeTheSameFilm) {
  CompileOptions options;
  options.aim = false;
  expectInterleavingChangesNothing(mixedObjectsScene(2'000), options, "both estimators, analog");
}

TEST(InterleavedWalks, AutomaticOnlyWhereTheTreeOutgrowsTheCacheAndNeverInTheProfile) {
  // Ten triangles and a few other primitives: far below any cache.
  const CompiledScene small = compileScene(mixedObjectsScene(10), 1);
  EXPECT_FALSE(CpuTracer(small, 1).interleavesWalks());
  EXPECT_TRUE(CpuTracer(small, 1, device::kProfileStageFull, fastestCpuCode(), WalkInterleaving::Always)
                  .interleavesWalks());
  // 200,000 triangles: about 12 MB of nodes and primitives.
  const CompiledScene large = compileScene(mixedObjectsScene(200'000), 1);
  const CpuTracer profiled(large, 1, device::kProfileStageObjectsFirstHit);
  EXPECT_FALSE(profiled.interleavesWalks());
  EXPECT_FALSE(CpuTracer(large, 1, device::kProfileStageFull, fastestCpuCode(), WalkInterleaving::Never)
                   .interleavesWalks());
}

TEST(InterleavedWalks, ACancelledTraceKeepsAContiguousPrefix) {
  const CompiledScene plan = compileScene(mixedObjectsScene(2'000), 5);
  std::atomic<bool> cancel{true};
  CpuTracer tracer(plan, 2, device::kProfileStageFull, fastestCpuCode(), WalkInterleaving::Always);
  // Cancelled before it starts: each thread stops at its first block, so
  // nothing is reported traced, and nothing was counted beyond it.
  EXPECT_EQ(tracer.trace(0, 1'000'000, &cancel), 0u);
  // Then a whole trace: the film is that of the whole trace alone.
  EXPECT_EQ(tracer.trace(0, 20'000), 20'000u);
  CpuTracer alone(plan, 2, device::kProfileStageFull, fastestCpuCode(), WalkInterleaving::Never);
  EXPECT_EQ(alone.trace(0, 20'000), 20'000u);
  expectSameFilm(tracer.download(), alone.download(), "after a cancelled trace");
}

}  // namespace
}  // namespace spectrace
