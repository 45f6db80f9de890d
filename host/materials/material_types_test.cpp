#include "materials/material_type.h"

#include <algorithm>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "device_shared.h"
#include "materials/material_shared.h"

namespace spectrace {
namespace {

TEST(MaterialTypes, OneUnitPerKindInDeviceOrder) {
  const auto& units = materialTypeUnits();
  std::set<std::string> names;
  for (uint32_t i = 0; i < units.size(); ++i) {
    const MaterialTypeUnit& unit = materialTypeUnit(MaterialType(i));
    EXPECT_EQ(uint32_t(unit.type), i);
    EXPECT_EQ(materialTypeUnitNamed(unit.name), &unit);
    EXPECT_STREQ(materialTypeName(unit.type), unit.name);
    EXPECT_TRUE(names.insert(unit.name).second) << unit.name;
  }
  EXPECT_EQ(uint32_t(materialTypeUnitNamed("absorber")->type), device::kMaterialAbsorber);
  EXPECT_EQ(uint32_t(materialTypeUnitNamed("dielectric")->type), device::kMaterialDielectric);
  EXPECT_EQ(materialTypeUnitNamed("glass"), nullptr);
  EXPECT_STREQ(materialTypeName(MaterialType(99)), "unknown");
  // Only an absorber keeps the "straight from the light" shortcuts.
  EXPECT_FALSE(materialTypeUnit(MaterialType::Absorber).redirectsBeams);
  EXPECT_TRUE(materialTypeUnit(MaterialType::Mirror).redirectsBeams);
}

TEST(ReflectanceTables, EvenlySpacedNodesAreReproducedExactly) {
  SurfaceMaterial m;
  m.type = MaterialType::Diffuse;
  m.reflectanceNm = {400.0, 405.0, 410.0, 415.0};
  m.reflectance = {0.1, 0.5, 0.25, 0.75};
  const ReflectanceTable table = reflectanceTable(m);
  ASSERT_EQ(table.values.size(), 4u);
  EXPECT_FLOAT_EQ(table.nodesPerNm, 0.2f);
  for (size_t i = 0; i < 4; ++i) EXPECT_FLOAT_EQ(table.values[i], float(m.reflectance[i]));
  m.reflectanceNm = {550.0};
  m.reflectance = {0.3};
  EXPECT_EQ(reflectanceTable(m).values, std::vector<float>{0.3f});
}

TEST(ReflectanceTables, EveryRecordPointsAtAWordOfTheSceneData) {
  SceneData data;
  for (const MaterialTypeUnit* unit : materialTypeUnits()) {
    SurfaceMaterial m;
    m.type = unit->type;
    m.reflectanceNm = {550.0};
    m.reflectance = {0.5};
    device::Material record{};
    unit->pack(m, record, data);
    EXPECT_GE(record.reflectanceCount, 1u) << unit->name;
    EXPECT_LE(record.reflectanceFirst + record.reflectanceCount, data.words().size()) << unit->name;
  }
}

}  // namespace
}  // namespace spectrace
