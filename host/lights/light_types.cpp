// The one table of light types.
#include <stdexcept>
#include <string>

#include "lights/light_shared.h"

namespace spectrace {

// Each defined in its own unit, lights/<type>_light.cpp, listed in
// host/lights/CMakeLists.txt (spectrace_unit_table).
#include "light_units.inc"

const std::vector<const LightTypeUnit*>& lightTypeUnits() {
  static const std::vector<const LightTypeUnit*> units = [] {
    std::vector<const LightTypeUnit*> all = {SPECTRACE_LIGHT_UNITS};
    for (size_t i = 0; i < all.size(); ++i)
      if (uint32_t(all[i]->type) != i) throw std::logic_error("light type units out of LightType order");
    return all;
  }();
  return units;
}

const LightTypeUnit& lightTypeUnit(LightType type) {
  const auto& units = lightTypeUnits();
  if (uint32_t(type) >= units.size())
    throw std::out_of_range("no light type " + std::to_string(uint32_t(type)));
  return *units[uint32_t(type)];
}

const LightTypeUnit* lightTypeUnitNamed(std::string_view name) {
  for (const LightTypeUnit* unit : lightTypeUnits())
    if (name == unit->name) return unit;
  return nullptr;
}

const char* lightTypeName(LightType type) {
  return uint32_t(type) < lightTypeUnits().size() ? lightTypeUnit(type).name : "unknown";
}

}  // namespace spectrace
