// Lavapipe walks the packed BVH nodes (compile/packed_bvh.h), the CPU
// reference the full ones: the films must be the same bits, through a mesh
// whose nodes the trace reads from a uniform buffer (a few hundred
// triangles) and from a storage buffer (tens of thousands).
#include <gtest/gtest.h>

#include "bench/optics_bench.h"
#include "support/device_renders.h"

namespace spectrace {
namespace {

TEST(PackedNodesOnDevices, ASmallMeshGivesTheCpuFilm) {
  const Scene scene = opticsMeshScene(300);
  testing::renderOnBothDevices(scene, 200'000, 41);
}

TEST(PackedNodesOnDevices, ALargeMeshGivesTheCpuFilm) {
  const Scene scene = opticsMeshScene(30'000);
  testing::renderOnBothDevices(scene, 200'000, 43);
}

}  // namespace
}  // namespace spectrace
