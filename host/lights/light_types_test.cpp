#include "lights/light_type.h"

#include <algorithm>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "device_shared.h"

namespace spectrace {
namespace {

TEST(LightTypes, OneUnitPerTypeInDeviceOrder) {
  const auto& units = lightTypeUnits();
  ASSERT_EQ(units.size(), size_t(kLightTypeCount));
  std::set<std::string> names;
  for (uint32_t i = 0; i < kLightTypeCount; ++i) {
    const LightTypeUnit& unit = lightTypeUnit(LightType(i));
    EXPECT_EQ(uint32_t(unit.type), i);
    EXPECT_EQ(lightTypeUnitNamed(unit.name), &unit);
    EXPECT_STREQ(lightTypeName(unit.type), unit.name);
    EXPECT_TRUE(names.insert(unit.name).second) << unit.name;
    // Every unit of "lights" reads its placement keys; an object's emission
    // is placed by its object.
    EXPECT_EQ(unit.onObject, unit.positionKey == nullptr) << unit.name;
    if (unit.positionKey) {
      EXPECT_NE(std::find(unit.keys.begin(), unit.keys.end(), std::string_view(unit.positionKey)), unit.keys.end());
    }
    if (unit.directionKey) {
      EXPECT_NE(std::find(unit.keys.begin(), unit.keys.end(), std::string_view(unit.directionKey)), unit.keys.end());
    }
  }
  EXPECT_EQ(uint32_t(lightTypeUnitNamed("laser")->type), device::kLightLaser);
  EXPECT_EQ(uint32_t(lightTypeUnitNamed("point")->type), device::kLightPoint);
  EXPECT_TRUE(lightTypeUnitNamed("object")->onObject);
  EXPECT_EQ(lightTypeUnitNamed("area"), nullptr);
  EXPECT_STREQ(lightTypeName(LightType(99)), "unknown");
}

}  // namespace
}  // namespace spectrace
