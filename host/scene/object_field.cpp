// An entry of "objects": a shape (rect, disk, sphere, or a mesh from an OBJ
// file) and its material, read by the material kind's unit
// (materials/material_type.h). Placement keys mean what they mean for rect
// and disk lights.
#include "scene/object_field.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "lights/light_shared.h"
#include "materials/material_type.h"
#include "scene/obj_mesh.h"
#include "scene/scene_limits.h"
#include "scene/spd_field.h"

namespace spectrace {

namespace fs = std::filesystem;
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

const Keys kShapeTypes = {"rect", "disk", "sphere", "mesh"};
// Every key some object takes (to name a typo such as "typ"
// before complaining that "type" is missing).
const Keys kAnyObjectKey = {"name",     "type",     "material", "center", "normal",
                            "u_axis",   "size_m",   "radius_m", "file",   "transform"};

Keys shapeKeys(ShapeType type) {
  switch (type) {
    case ShapeType::Rect: return {"center", "normal", "u_axis", "size_m"};
    case ShapeType::Disk: return {"center", "normal", "radius_m"};
    case ShapeType::Sphere: return {"center", "radius_m"};
    case ShapeType::Mesh: return {"file", "transform"};
  }
  return {};
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

// "size_m": [along u_axis, across], each a length.
glm::dvec2 parseSize(const jf::Source& c, const Json& v, const std::string& p) {
  const std::string sp = child(p, "size_m");
  const Json& size = require(c, v, p, "size_m", " ([width along u_axis, height], in metres)");
  if (!size.is_array() || size.size() != 2)
    c.fail(sp, fmt::format("must be an array of 2 lengths > 0 [width, height] (got {})", describe(size)));
  return {jf::getLength(c, size[0], child(sp, size_t(0)), kMaxCoordinateM),
          jf::getLength(c, size[1], child(sp, size_t(1)), kMaxCoordinateM)};
}

MeshTransform parseTransform(const jf::Source& c, const Json& v, const std::string& p) {
  checkObject(c, v, p, {"translate", "rotate_deg", "scale"}, "a transform");
  MeshTransform t;
  if (auto* x = find(v, "translate")) t.translate = jf::getPoint(c, *x, child(p, "translate"), kMaxCoordinateM);
  if (auto* x = find(v, "rotate_deg")) t.rotateDeg = jf::getVec3(c, *x, child(p, "rotate_deg"));
  if (auto* x = find(v, "scale")) {
    const std::string sp = child(p, "scale");
    const auto factor = [&](const Json& e, const std::string& ep) {
      const double s = jf::getNumber(c, e, ep);
      if (s == 0.0) c.fail(ep, "must be a finite number other than 0 (a negative factor mirrors)");
      return s;
    };
    if (x->is_number()) {
      t.scale = glm::dvec3(factor(*x, sp));
    } else if (x->is_array() && x->size() == 3) {
      for (size_t i = 0; i < 3; ++i) t.scale[int(i)] = factor((*x)[i], child(sp, i));
    } else {
      c.fail(sp, fmt::format("must be a number or an array of 3 numbers [sx, sy, sz] (got {})", describe(*x)));
    }
  }
  return t;
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
  if (!find(v, "type")) checkObject(c, v, p, kAnyObjectKey, "an object");
  const std::string tp = child(p, "type");
  const std::string type =
      jf::getString(c, require(c, v, p, "type", fmt::format(" (one of: {})", jf::joinKeys(kShapeTypes))), tp);
  const auto known = std::find(kShapeTypes.begin(), kShapeTypes.end(), type);
  if (known == kShapeTypes.end())
    c.fail(tp, fmt::format("unknown object type {}{} (valid types: {})", jsonQuoted(type),
                           jf::suggestion(type, kShapeTypes), jf::joinKeys(kShapeTypes)));
  Shape& shape = obj.shape;
  shape.type = ShapeType(known - kShapeTypes.begin());
  Keys allowed = {"name", "type", "material"};
  const Keys own = shapeKeys(shape.type);
  allowed.insert(allowed.end(), own.begin(), own.end());
  checkObject(c, v, p, allowed, fmt::format("a {} object", type));

  // The material first: it is cheap, and a mesh may take long to read.
  const std::string mp = child(p, "material");
  obj.material = parseMaterial(
      c, require(c, v, p, "material", " (e.g. {\"type\": \"diffuse\", \"reflectance\": 0.5})"), mp, range);

  if (shape.type != ShapeType::Mesh)
    shape.center = jf::getPoint(c, require(c, v, p, "center"), child(p, "center"), kMaxCoordinateM);
  if (shape.type == ShapeType::Rect || shape.type == ShapeType::Disk) {
    shape.normal = jf::getDirection(c, require(c, v, p, "normal"), child(p, "normal"));
    shape.uAxis = defaultTangent(shape.normal);
  }
  if (shape.type == ShapeType::Disk || shape.type == ShapeType::Sphere)
    shape.radiusM = jf::getLength(c, require(c, v, p, "radius_m"), child(p, "radius_m"), kMaxCoordinateM);
  switch (shape.type) {
    case ShapeType::Rect:
      shape.sizeM = parseSize(c, v, p);
      if (auto* u = find(v, "u_axis")) {
        // Orthogonalised against the normal, as for rect lights; an axis
        // along the normal is kept as it is, for validateScene to refuse.
        const glm::dvec3 axis = jf::getDirection(c, *u, child(p, "u_axis"));
        const glm::dvec3 ortho = axis - shape.normal * glm::dot(shape.normal, axis);
        const auto unit = jf::safeNormalize(ortho);
        shape.uAxis = glm::length(glm::cross(axis, shape.normal)) < kCollinearEps || !unit ? axis : *unit;
      }
      break;
    case ShapeType::Disk: break;
    case ShapeType::Sphere: shape.closed = true; break;
    case ShapeType::Mesh: {
      const std::string fp = child(p, "file");
      const std::string rel = jf::getString(c, require(c, v, p, "file", " (an OBJ file)"), fp);
      MeshTransform transform;
      if (auto* t = find(v, "transform")) transform = parseTransform(c, *t, child(p, "transform"));
      const fs::path path(rel);
      const fs::path resolved = path.is_absolute() ? path : (c.dir / path).lexically_normal();
      const std::string notClosed = loadObjMesh(c, fp, resolved, rel, transform, trianglesLeft, shape);
      trianglesLeft -= shape.triangles.size();
      const MaterialTypeUnit& material = materialTypeUnit(obj.material.type);
      if (material.needsClosedShape && !notClosed.empty())
        c.fail(mp, fmt::format("a {} needs a closed shape: a sphere or a closed mesh; {} is not closed: {}",
                               material.name, jsonQuoted(rel), notClosed));
      break;
    }
  }
  return obj;
}

}  // namespace spectrace
