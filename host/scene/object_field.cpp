// An entry of "objects": a shape and its material, each read by its kind's
// unit (shapes/shape_type.h, materials/material_type.h).
#include "scene/object_field.h"

#include <algorithm>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

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
  Keys keys = {"name", "type", "material"};
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

}  // namespace

SceneObject parseObject(const jf::Source& outer, const Json& v, const std::string& p, const SpectrumRange& range,
                        uint64_t& trianglesLeft) {
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
  Keys allowed = {"name", "type", "material"};
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
  return obj;
}

}  // namespace spectrace
