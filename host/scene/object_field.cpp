// An entry of "objects": a shape and its material, each read by its kind's
// unit (shapes/shape_type.h, materials/material_type.h).
#include "scene/object_field.h"

#include <algorithm>
#include <limits>
#include <memory>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include "camera/camera_frame.h"
#include "materials/material_type.h"
#include "scene/spd_field.h"
#include "shapes/shape_type.h"

namespace spectrace {

namespace jf = json_fields;
using jf::Json;
using jf::Keys;
using jf::checkObject;
using jf::child;
using jf::describe;
using jf::find;
using jf::jsonQuoted;
using jf::require;

namespace {

Keys shapeTypeNames() {
  Keys names;
  for (const ShapeTypeUnit* unit : shapeTypeUnits()) names.push_back(unit->name);
  return names;
}

// Every key some object takes (to name a typo such as "typ" before
// complaining that "type" is missing).
Keys anyObjectKey() {
  Keys keys = {"name", "type", "material", "emission"};
  for (const ShapeTypeUnit* unit : shapeTypeUnits())
    for (std::string_view key : unit->keys)
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  return keys;
}

// The scene's spectrum forms (spd_field.h), for a material unit's
// spectrum-valued keys.
class SpdFieldReader final : public SpectrumFieldReader {
 public:
  SpdFieldReader(const jf::Source& c, const SpectrumRange& range) : c_(c), range_(range) {}
  FieldSpectrum read(const Json& v, const std::string& ptr) const override {
    ResolvedSpd resolved = resolveSpd(c_, v, ptr, range_);
    return {std::move(resolved.spd), std::move(resolved.label), std::move(resolved.file)};
  }

 private:
  const jf::Source& c_;
  const SpectrumRange& range_;
};

Keys materialTypeNames() {
  Keys names;
  for (const MaterialTypeUnit* unit : materialTypeUnits()) names.push_back(unit->name);
  return names;
}

// Every key some material takes, "type" first.
Keys anyMaterialKey() {
  Keys keys = {"type"};
  for (const MaterialTypeUnit* unit : materialTypeUnits())
    for (std::string_view key : unit->keys)
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  return keys;
}

SurfaceMaterial parseMaterial(const jf::Source& c, const Json& v, const std::string& p, const SpectrumRange& range) {
  if (!v.is_object())
    c.fail(p, fmt::format("must be an object such as {{\"type\": \"diffuse\", \"reflectance\": 0.5}} (got {})",
                          describe(v)));
  if (!find(v, "type")) checkObject(c, v, p, anyMaterialKey(), "a material");
  const std::string tp = child(p, "type");
  const Keys types = materialTypeNames();
  const std::string type =
      jf::getString(c, require(c, v, p, "type", fmt::format(" (one of: {})", jf::joinKeys(types))), tp);
  const MaterialTypeUnit* unit = materialTypeUnitNamed(type);
  if (!unit)
    c.fail(tp, fmt::format("unknown material type {}{} (valid types: {})", jsonQuoted(type),
                           jf::suggestion(type, types), jf::joinKeys(types)));
  SurfaceMaterial m;
  m.type = unit->type;
  unit->parse(c, v, p, SpdFieldReader(c, range), m);
  return m;
}

// The object's "emission" (lights/object_light.cpp): its power and spd as a
// light's, and whether both faces emit.
Light parseEmission(const jf::Source& c, const Json& v, const std::string& p, const SpectrumRange& range,
                    const SceneObject& obj, size_t objectIndex) {
  if (!v.is_object())
    c.fail(p, fmt::format("must be an object such as {{\"power_w\": 10, \"spd\": \"D65\"}} (got {})", describe(v)));
  checkObject(c, v, p, {"power_w", "power_lm", "spd", "two_sided"}, "an object's emission");
  Light light;
  light.type = LightType::Object;
  light.label = p;
  light.name = obj.name;
  parseLightPower(c, v, p, range, light);
  bool twoSided = false;
  if (const Json* t = find(v, "two_sided")) {
    if (!t->is_boolean()) c.fail(child(p, "two_sided"), fmt::format("must be true or false (got {})", describe(*t)));
    twoSided = t->get<bool>();
    if (twoSided && obj.shape.type == ShapeType::Sphere)
      c.fail(child(p, "two_sided"), "a sphere emits outwards only: light from its inside could never leave it");
  }
  placeEmission(obj.shape, twoSided, objectIndex, light);
  return light;
}

}  // namespace

void placeEmission(const Shape& shape, bool twoSided, size_t objectIndex, Light& light) {
  auto surface = std::make_shared<EmittingSurface>();
  surface->twoSided = twoSided;
  surface->objectIndex = objectIndex;
  // The world box from the shape's primitives (read before validation: a
  // shape validateScene refuses never reaches a render).
  const CameraFrame world{.origin = {0.0, 0.0, 0.0}, .right = {1.0, 0.0, 0.0}, .up = {0.0, 1.0, 0.0},
                          .forward = {0.0, 0.0, 1.0}};
  std::vector<PlacedPrimitive> placed;
  shapeTypeUnit(shape.type).place(shape, world, 0u, placed);
  surface->boundsLo = placed.empty() ? shape.center : glm::dvec3(std::numeric_limits<double>::infinity());
  surface->boundsHi = placed.empty() ? shape.center : -surface->boundsLo;
  for (const PlacedPrimitive& p : placed) {
    surface->boundsLo = glm::min(surface->boundsLo, p.bounds.lo);
    surface->boundsHi = glm::max(surface->boundsHi, p.bounds.hi);
  }
  light.position = 0.5 * (surface->boundsLo + surface->boundsHi);
  light.direction = {0.0, 0.0, 1.0};
  light.uAxis = {1.0, 0.0, 0.0};
  // The shape is copied: a Scene (and its lights) may outlive or be copied
  // apart from the object it was read with.
  surface->place = [copy = std::make_shared<const Shape>(shape)](const CameraFrame& frame) {
    std::vector<PlacedPrimitive> out;
    shapeTypeUnit(copy->type).place(*copy, frame, 0u, out);
    std::vector<device::Primitive> primitives;
    primitives.reserve(out.size());
    for (const PlacedPrimitive& p : out) primitives.push_back(p.primitive);
    return primitives;
  };
  light.surface = std::move(surface);
}

SceneObject parseObject(const jf::Source& outer, const Json& v, const std::string& p, const SpectrumRange& range,
                        uint64_t& trianglesLeft, size_t objectIndex, std::vector<Light>& emitters) {
  jf::Source c = outer;
  if (!v.is_object())
    c.fail(p, fmt::format("an object must be a JSON object such as {{\"type\": \"sphere\", ...}} (got {})",
                          describe(v)));
  SceneObject obj;
  obj.label = p;
  if (auto* n = find(v, "name")) {
    obj.name = jf::getString(c, *n, child(p, "name"));
    c.note = fmt::format(" (object {})", jsonQuoted(obj.name));
  }
  if (!find(v, "type")) checkObject(c, v, p, anyObjectKey(), "an object");
  const std::string tp = child(p, "type");
  const Keys types = shapeTypeNames();
  const std::string type =
      jf::getString(c, require(c, v, p, "type", fmt::format(" (one of: {})", jf::joinKeys(types))), tp);
  const ShapeTypeUnit* unit = shapeTypeUnitNamed(type);
  if (!unit)
    c.fail(tp, fmt::format("unknown object type {}{} (valid types: {})", jsonQuoted(type), jf::suggestion(type, types),
                           jf::joinKeys(types)));
  obj.shape.type = unit->type;
  Keys allowed = {"name", "type", "material", "emission"};
  allowed.insert(allowed.end(), unit->keys.begin(), unit->keys.end());
  checkObject(c, v, p, allowed, fmt::format("a {} object", type));

  // The material first: it is cheap, and a mesh may take long to read.
  const std::string mp = child(p, "material");
  obj.material = parseMaterial(
      c, require(c, v, p, "material", " (e.g. {\"type\": \"diffuse\", \"reflectance\": 0.5})"), mp, range);
  const MaterialTypeUnit& material = materialTypeUnit(obj.material.type);
  const ShapeReading reading{.trianglesLeft = trianglesLeft,
                             .closedFor = material.needsClosedShape ? material.name : nullptr,
                             .materialPtr = mp};
  unit->parse(c, v, p, reading, obj.shape);
  trianglesLeft -= obj.shape.triangles.size();
  if (const Json* e = find(v, "emission"))
    emitters.push_back(parseEmission(c, *e, child(p, "emission"), range, obj, objectIndex));
  return obj;
}

}  // namespace spectrace
