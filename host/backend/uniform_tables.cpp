#include "backend/uniform_tables.h"

#include <algorithm>
#include <bit>
#include <initializer_list>

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
  auto allFit = [&](std::initializer_list<uint64_t> bytes) {
    return std::all_of(bytes.begin(), bytes.end(), [&](uint64_t b) { return b <= maxUniformBufferRange; });
  };
  UniformTableLayout candidate{.inUniform = true,
                               .lights = arrayLength(tables.lights.size()),
                               .intervals = arrayLength(tables.intervals.size()),
                               .cmfNodes = arrayLength(tables.cmfTable.size()),
                               .aliasColumns = arrayLength(tables.aliasColumns.size())};
  if (allFit({candidate.lightBytes(), candidate.intervalBytes(), candidate.cmfBytes(), candidate.aliasColumnBytes()}))
    layout = candidate;
  if (tables.primitives.empty()) return layout;
  candidate = layout;
  candidate.objectsInUniform = true;
  candidate.primitives = arrayLength(tables.primitives.size());
  candidate.bvhNodes = arrayLength(tables.bvhNodes.size());
  candidate.materials = arrayLength(tables.materials.size());
  if (allFit({candidate.primitiveBytes(), candidate.bvhNodeBytes(), candidate.materialBytes()})) layout = candidate;
  return layout;
}

}  // namespace spectrace
