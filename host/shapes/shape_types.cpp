// The one table of shape kinds.
#include <stdexcept>
#include <string>

#include "shapes/shape_type.h"

namespace spectrace {

// Each defined in its own unit, shapes/<kind>_shape.cpp, listed in
// host/shapes/CMakeLists.txt (spectrace_unit_table).
#include "shape_units.inc"

const std::vector<const ShapeTypeUnit*>& shapeTypeUnits() {
  static const std::vector<const ShapeTypeUnit*> units = [] {
    std::vector<const ShapeTypeUnit*> all = {SPECTRACE_SHAPE_UNITS};
    for (size_t i = 0; i < all.size(); ++i)
      if (uint32_t(all[i]->type) != i) throw std::logic_error("shape type units out of ShapeType order");
    return all;
  }();
  return units;
}

const ShapeTypeUnit& shapeTypeUnit(ShapeType type) {
  const auto& units = shapeTypeUnits();
  if (uint32_t(type) >= units.size()) throw std::out_of_range("no shape type " + std::to_string(uint32_t(type)));
  return *units[uint32_t(type)];
}

const ShapeTypeUnit* shapeTypeUnitNamed(std::string_view name) {
  for (const ShapeTypeUnit* unit : shapeTypeUnits())
    if (name == unit->name) return unit;
  return nullptr;
}

const char* shapeTypeName(ShapeType type) {
  return uint32_t(type) < shapeTypeUnits().size() ? shapeTypeUnit(type).name : "unknown";
}

}  // namespace spectrace
