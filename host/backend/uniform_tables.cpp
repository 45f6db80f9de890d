#include "backend/uniform_tables.h"

#include <algorithm>
#include <bit>

namespace spectrace {
namespace {

// A table's array length: its size (at least 1) rounded up to a power of two.
uint32_t arrayLength(size_t elements) {
  return uint32_t(std::bit_ceil(std::max<size_t>(elements, 1)));
}

}  // namespace

UniformTableLayout uniformTableLayout(const DeviceScene& tables, uint64_t maxUniformBufferRange, bool wanted) {
  UniformTableLayout layout;
  if (!wanted) return layout;
  UniformTableLayout candidate{.inUniform = true,
                               .lights = arrayLength(tables.lights.size()),
                               .intervals = arrayLength(tables.intervals.size()),
                               .cmfNodes = arrayLength(tables.cmfTable.size()),
                               .aliasColumns = arrayLength(tables.aliasColumns.size())};
  const uint64_t bytes[] = {candidate.lightBytes(), candidate.intervalBytes(), candidate.cmfBytes(),
                            candidate.aliasColumnBytes()};
  const bool fits = std::all_of(std::begin(bytes), std::end(bytes), [&](uint64_t b) { return b <= maxUniformBufferRange; });
  if (fits) layout = candidate;
  if (!tables.primitives.empty()) {
    const uint32_t primitives = arrayLength(tables.primitives.size());
    const uint32_t bvhNodes = arrayLength(tables.bvhNodes.size());
    const uint32_t materials = arrayLength(tables.materials.size());
    const uint64_t objectBytes[] = {uint64_t(primitives) * sizeof(device::Primitive),
                                    uint64_t(bvhNodes) * sizeof(device::BvhNode),
                                    uint64_t(materials) * sizeof(device::Material)};
    if (std::all_of(std::begin(objectBytes), std::end(objectBytes),
                    [&](uint64_t b) { return b <= maxUniformBufferRange; })) {
      layout.objectsInUniform = true;
      layout.primitives = primitives;
      layout.bvhNodes = bvhNodes;
      layout.materials = materials;
    }
  }
  return layout;
}

}  // namespace spectrace
