// The one table of material kinds.
#include <stdexcept>
#include <string>

#include "materials/material_type.h"

namespace spectrace {

// Each defined in its own unit, materials/<kind>_material.cpp, listed in
// host/materials/CMakeLists.txt (spectrace_unit_table).
#include "material_units.inc"

const std::vector<const MaterialTypeUnit*>& materialTypeUnits() {
  static const std::vector<const MaterialTypeUnit*> units = [] {
    std::vector<const MaterialTypeUnit*> all = {SPECTRACE_MATERIAL_UNITS};
    for (size_t i = 0; i < all.size(); ++i)
      if (uint32_t(all[i]->type) != i) throw std::logic_error("material type units out of MaterialType order");
    return all;
  }();
  return units;
}

const MaterialTypeUnit& materialTypeUnit(MaterialType type) {
  const auto& units = materialTypeUnits();
  if (uint32_t(type) >= units.size())
    throw std::out_of_range("no material type " + std::to_string(uint32_t(type)));
  return *units[uint32_t(type)];
}

const MaterialTypeUnit* materialTypeUnitNamed(std::string_view name) {
  for (const MaterialTypeUnit* unit : materialTypeUnits())
    if (name == unit->name) return unit;
  return nullptr;
}

const char* materialTypeName(MaterialType type) {
  return uint32_t(type) < materialTypeUnits().size() ? materialTypeUnit(type).name : "unknown";
}

}  // namespace spectrace
