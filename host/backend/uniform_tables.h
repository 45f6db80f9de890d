#pragma once
// Where the trace pipeline reads its small tables from: the lights, the
// spectral intervals, the CMF nodes and the alias columns, read by every
// beam. lavapipe loads a uniform buffer's values once for a group of lanes
// and a storage buffer's lane by lane (docs/benchmarks.md has what that is
// worth on the throughput scene).
//
// Valid when every table fits the device's maxUniformBufferRange, with its
// element count rounded up to a power of two (so scenes of similar size
// share one compiled pipeline in a batch); this function is the one place
// that checks it, for the tables and, apart, for the scene's objects.
// Otherwise, and in the general pipeline, they are read from their storage
// buffers. uniform_tables_test and tests/render_test.cpp check both paths
// bit for bit against each other.
#include <cstdint>
#include <vector>

#include "compile/compile_scene.h"

namespace spectrace {

struct UniformTableLayout {
  bool inUniform = false;
  // Array lengths of the uniform copies (1 when unused), in elements.
  uint32_t lights = 1, intervals = 1, cmfNodes = 1, aliasColumns = 1;
  // The same in bytes: each uniform copy's range.
  uint64_t lightBytes() const { return uint64_t(lights) * sizeof(device::LightRecord); }
  uint64_t intervalBytes() const { return uint64_t(intervals) * sizeof(device::SpectralInterval); }
  uint64_t cmfBytes() const { return uint64_t(cmfNodes) * sizeof(glm::vec3); }
  uint64_t aliasColumnBytes() const { return uint64_t(aliasColumns) * sizeof(device::AliasColumn); }

  // The scene's objects, the same way, on their own: a scene of a few
  // primitives (a prism, a room of boxes) fits where a mesh does not.
  bool objectsInUniform = false;
  uint32_t primitives = 1, bvhNodes = 1, materials = 1;
  uint64_t primitiveBytes() const { return uint64_t(primitives) * sizeof(device::Primitive); }
  uint64_t bvhNodeBytes() const { return uint64_t(bvhNodes) * sizeof(device::PackedBvhNode); }
  uint64_t materialBytes() const { return uint64_t(materials) * sizeof(device::Material); }
};

// `wanted`: the pipeline asks for uniform tables (kSpecialiseUniformTables).
UniformTableLayout uniformTableLayout(const DeviceScene& tables, uint64_t maxUniformBufferRange, bool wanted);

// `table` padded with zero elements to `length` (uniform copies are read as
// arrays of that length, so the buffer must hold all of them).
template <typename T>
std::vector<T> paddedTable(const std::vector<T>& table, uint32_t length) {
  std::vector<T> padded = table;
  if (padded.size() < length) padded.resize(length, T{});
  return padded;
}

}  // namespace spectrace
