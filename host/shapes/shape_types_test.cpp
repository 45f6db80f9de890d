#include "shapes/shape_type.h"

#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "device_shared.h"

namespace spectrace {
namespace {

TEST(ShapeTypes, OneUnitPerKindInShapeTypeOrder) {
  const auto& units = shapeTypeUnits();
  std::set<std::string> names;
  for (uint32_t i = 0; i < units.size(); ++i) {
    const ShapeTypeUnit& unit = shapeTypeUnit(ShapeType(i));
    EXPECT_EQ(uint32_t(unit.type), i);
    EXPECT_EQ(shapeTypeUnitNamed(unit.name), &unit);
    EXPECT_STREQ(shapeTypeName(unit.type), unit.name);
    EXPECT_TRUE(names.insert(unit.name).second) << unit.name;
    EXPECT_FALSE(unit.keys.empty()) << unit.name;
  }
  EXPECT_EQ(shapeTypeUnitNamed("box"), nullptr);
  EXPECT_STREQ(shapeTypeName(ShapeType(99)), "unknown");
}

// A tetrahedron wound counter-clockwise seen from outside.
Shape tetrahedron() {
  Shape s;
  s.type = ShapeType::Mesh;
  s.vertices = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  s.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return s;
}

TEST(ShapeTypes, OnlySolidsFacingOutwardsAreClosed) {
  const auto whyNot = [](const Shape& s) { return shapeTypeUnit(s.type).notClosedBecause(s, "dielectric"); };
  Shape flat;
  flat.type = ShapeType::Rect;
  EXPECT_NE(whyNot(flat).find("a rect has no inside"), std::string::npos) << whyNot(flat);
  flat.type = ShapeType::Disk;
  EXPECT_NE(whyNot(flat).find("a disk has no inside"), std::string::npos) << whyNot(flat);
  Shape sphere;
  sphere.type = ShapeType::Sphere;
  EXPECT_EQ(whyNot(sphere), "");

  EXPECT_EQ(whyNot(tetrahedron()), "");
  Shape open = tetrahedron();
  open.triangles.pop_back();
  EXPECT_NE(whyNot(open).find("this mesh is not closed"), std::string::npos) << whyNot(open);
  Shape inward = tetrahedron();
  for (auto& t : inward.triangles) std::swap(t[1], t[2]);
  EXPECT_NE(whyNot(inward).find("a dielectric mesh must face outwards"), std::string::npos) << whyNot(inward);
}

bool inside(const PrimitiveBounds& b, const glm::vec3& p) {
  for (int i = 0; i < 3; ++i)
    if (!(double(p[i]) >= b.lo[i] && double(p[i]) <= b.hi[i])) return false;
  return true;
}

// Points the kernel can find on the primitive (corners, rims, poles).
std::vector<glm::vec3> pointsOn(const device::Primitive& p) {
  switch (p.type) {
    case device::kPrimitiveTriangle: return {p.a, p.a + p.b, p.a + p.c};
    case device::kPrimitiveRect: return {p.a + p.b + p.c, p.a + p.b - p.c, p.a - p.b + p.c, p.a - p.b - p.c};
    case device::kPrimitiveDisk: {
      const glm::vec3 u = glm::normalize(glm::cross(p.b, glm::vec3(0.3f, 1.0f, 0.2f)));
      const glm::vec3 v = glm::cross(p.b, u);
      const float r = std::sqrt(p.c.x);
      return {p.a + u * r, p.a - u * r, p.a + v * r, p.a - v * r};
    }
    default: {
      std::vector<glm::vec3> poles;
      for (int i = 0; i < 3; ++i) {
        glm::vec3 axis(0.0f);
        axis[i] = p.b.x;
        poles.push_back(p.a + axis);
        poles.push_back(p.a - axis);
      }
      return poles;
    }
  }
}

TEST(ShapeTypes, EveryPrimitiveLiesInsideItsBounds) {
  const CameraFrame frame{{0.5, -1.0, 2.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  std::vector<Shape> shapes(4);
  shapes[0].type = ShapeType::Rect;
  shapes[0].center = {1.0, 2.0, 3.0};
  shapes[0].normal = glm::normalize(glm::dvec3(1.0, 1.0, 0.0));
  shapes[0].uAxis = glm::normalize(glm::dvec3(1.0, -1.0, 0.0));
  shapes[0].sizeM = {0.5, 2.0};
  shapes[1].type = ShapeType::Disk;
  shapes[1].center = {-1.0, 0.0, 4.0};
  shapes[1].normal = glm::normalize(glm::dvec3(0.2, 0.3, 1.0));
  shapes[1].radiusM = 0.7;
  shapes[2].type = ShapeType::Sphere;
  shapes[2].center = {0.0, 3.0, 5.0};
  shapes[2].radiusM = 1.5;
  shapes[3] = tetrahedron();
  const uint32_t expectedType[] = {device::kPrimitiveRect, device::kPrimitiveDisk, device::kPrimitiveSphere,
                                   device::kPrimitiveTriangle};
  const size_t expectedCount[] = {1, 1, 1, 4};  // a mesh: one triangle primitive per triangle
  for (size_t k = 0; k < shapes.size(); ++k) {
    std::vector<PlacedPrimitive> placed;
    shapeTypeUnit(shapes[k].type).place(shapes[k], frame, uint32_t(k + 7), placed);
    ASSERT_EQ(placed.size(), expectedCount[k]) << shapeTypeName(shapes[k].type);
    for (const PlacedPrimitive& p : placed) {
      EXPECT_EQ(p.primitive.type, expectedType[k]);
      EXPECT_EQ(p.primitive.material, uint32_t(k + 7));
      for (const glm::vec3& point : pointsOn(p.primitive))
        EXPECT_TRUE(inside(p.bounds, point)) << shapeTypeName(shapes[k].type);
    }
  }
}

}  // namespace
}  // namespace spectrace
