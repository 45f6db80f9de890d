// An entry of "objects": a shape (rect, disk, sphere, or a mesh from an OBJ
// file) and its material. Placement keys mean what they mean for rect and
// disk lights; reflectances take every form a light's spd takes, plus a
// number and the ColorChecker patch names.
#include "scene/object_field.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "lights/light_shared.h"
#include "scene/obj_mesh.h"
#include "scene/scene_limits.h"
#include "scene/spd_field.h"
#include "spectrum/cie_data.h"
#include "spectrum/glass.h"

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

// A constant reflectance is one node; where it sits does not matter.
constexpr double kConstantNodeNm = 550.0;

const Keys kShapeTypes = {"rect", "disk", "sphere", "mesh"};
const Keys kMaterialTypes = {"absorber", "diffuse", "mirror", "dielectric"};
// Every key some object or material takes (to name a typo such as "typ"
// before complaining that "type" is missing).
const Keys kAnyObjectKey = {"name",     "type",     "material", "center", "normal",
                            "u_axis",   "size_m",   "radius_m", "file",   "transform"};
const Keys kAnyMaterialKey = {"type", "reflectance", "glass", "sellmeier", "ior"};
const Keys kSpdForms = {"blackbody_k", "csv", "table", "lambda_nm", "value"};

const char* kReflectanceHelp =
    "a number in [0, 1], a ColorChecker patch name such as \"dark_skin\", or a spectrum of values in [0, 1]: "
    "{\"csv\": \"file.csv\"}, {\"table\": [[nm, value], ...]}, {\"lambda_nm\": [...], \"value\": [...]}";

Keys shapeKeys(ShapeType type) {
  switch (type) {
    case ShapeType::Rect: return {"center", "normal", "u_axis", "size_m"};
    case ShapeType::Disk: return {"center", "normal", "radius_m"};
    case ShapeType::Sphere: return {"center", "radius_m"};
    case ShapeType::Mesh: return {"file", "transform"};
  }
  return {};
}

Keys patchNames() {
  const CsvTable& t = colorCheckerTable();
  return Keys(t.columns.begin(), t.columns.end());
}

void parseReflectance(const jf::Source& c, const Json& v, const std::string& p, const SpectrumRange& range,
                      SurfaceMaterial& m) {
  if (v.is_number()) {
    const double r = jf::getNumber(c, v, p);  // [0, 1] is validateScene's rule
    m.reflectanceNm = {kConstantNodeNm};
    m.reflectance = {r};
    m.reflectanceLabel = jf::fmtNum(r);
    return;
  }
  if (v.is_string()) {
    const std::string name = v.get<std::string>();
    const CsvTable& patches = colorCheckerTable();
    if (auto it = std::find(patches.columns.begin(), patches.columns.end(), name); it != patches.columns.end()) {
      m.reflectanceNm = patches.lambdaNm;
      m.reflectance = patches.data[size_t(it - patches.columns.begin())];
      m.reflectanceLabel = name;
      return;
    }
    if (!cieIlluminant(name)) {
      const Keys names = patchNames();
      c.fail(p, fmt::format("unknown reflectance {}{} (ColorChecker patches: {})", jsonQuoted(name),
                            jf::suggestion(name, names), jf::joinKeys(names)));
    }
    // A CIE illuminant name is a spectrum too; validateScene refuses its
    // values above 1.
  } else if (v.is_object()) {
    if (find(v, "line_nm"))
      c.fail(child(p, "line_nm"),
             "a spectral line is light, not a reflectance: a reflectance gives a value in [0, 1] at every "
             "wavelength (a number for a constant one, or a table)");
    if (std::none_of(kSpdForms.begin(), kSpdForms.end(), [&](std::string_view k) { return find(v, std::string(k)); })) {
      checkObject(c, v, p, {"blackbody_k", "csv", "column", "table", "lambda_nm", "value"}, "a reflectance");
      c.fail(p, fmt::format("must be {} (got an object with none of these)", kReflectanceHelp));
    }
  } else {
    c.fail(p, fmt::format("must be {} (got {})", kReflectanceHelp, describe(v)));
  }
  ResolvedSpd resolved = resolveSpd(c, v, p, range);
  if (resolved.spd.isLine())
    c.fail(p, "a single spectral line is not a reflectance: give a number for a constant reflectance, or a table");
  m.reflectanceNm = std::move(resolved.spd.lambdaNm);
  m.reflectance = std::move(resolved.spd.value);
  m.reflectanceLabel = std::move(resolved.label);
  m.reflectanceFile = std::move(resolved.file);
}

std::array<double, 3> getThree(const jf::Source& c, const Json& v, const std::string& p, const char* names) {
  if (!v.is_array() || v.size() != 3)
    c.fail(p, fmt::format("must be an array of 3 finite numbers {} (got {})", names, describe(v)));
  std::array<double, 3> out{};
  for (size_t i = 0; i < 3; ++i) out[i] = jf::getNumber(c, v[i], child(p, i));
  return out;
}

void parseDielectric(const jf::Source& c, const Json& v, const std::string& p, SurfaceMaterial& m) {
  static const Keys kForms = {"glass", "sellmeier", "ior"};
  checkObject(c, v, p, {"type", "glass", "sellmeier", "ior"}, "a dielectric material");
  std::vector<std::string_view> present;
  for (auto f : kForms)
    if (find(v, std::string(f))) present.push_back(f);
  const std::vector<std::string> glasses = glassNames();
  const Keys glassKeys(glasses.begin(), glasses.end());
  if (present.empty())
    c.fail(p, fmt::format("a dielectric needs one of \"glass\" (one of: {}), \"sellmeier\" ({{\"b\": [b1, b2, b3], "
                          "\"c_um2\": [c1, c2, c3]}}) or \"ior\" (a constant refractive index)",
                          jf::joinKeys(glassKeys)));
  if (present.size() > 1)
    c.fail(p, fmt::format("ambiguous refractive index: has both {} and {}; use exactly one of {}",
                          jsonQuoted(present[0]), jsonQuoted(present[1]), jf::joinKeys(kForms)));
  if (present[0] == "glass") {
    const std::string gp = child(p, "glass");
    const std::string name = jf::getString(c, v.at("glass"), gp);
    const SellmeierGlass* glass = glassNamed(name);
    if (!glass)
      c.fail(gp, fmt::format("unknown glass {}{} (known: {})", jsonQuoted(name), jf::suggestion(name, glassKeys),
                             jf::joinKeys(glassKeys)));
    m.sellmeierB = glass->b;
    m.sellmeierC = glass->cUm2;
    m.glassLabel = glass->name;
  } else if (present[0] == "sellmeier") {
    const std::string sp = child(p, "sellmeier");
    const Json& s = v.at("sellmeier");
    checkObject(c, s, sp, {"b", "c_um2"}, "sellmeier");
    m.sellmeierB = getThree(c, require(c, s, sp, "b"), child(sp, "b"), "[b1, b2, b3]");
    m.sellmeierC = getThree(c, require(c, s, sp, "c_um2", " (in square micrometres)"), child(sp, "c_um2"),
                            "[c1, c2, c3] in um^2");
    m.glassLabel = "sellmeier";
  } else {
    const std::string ip = child(p, "ior");
    const double n = jf::getNumber(c, v.at("ior"), ip);
    if (!(n >= 1.0 && n <= kMaxIor))
      c.fail(ip, fmt::format("must be a refractive index, >= 1 and <= {} (got {})", jf::fmtNum(kMaxIor),
                             describe(v.at("ior"))));
    m.sellmeierB = {n * n - 1.0, 0.0, 0.0};
    m.sellmeierC = {0.0, 0.0, 0.0};
    m.glassLabel = "ior " + jf::fmtNum(n);
  }
}

SurfaceMaterial parseMaterial(const jf::Source& c, const Json& v, const std::string& p, const SpectrumRange& range) {
  if (!v.is_object())
    c.fail(p, fmt::format("must be an object such as {{\"type\": \"diffuse\", \"reflectance\": 0.5}} (got {})",
                          describe(v)));
  if (!find(v, "type")) checkObject(c, v, p, kAnyMaterialKey, "a material");
  const std::string tp = child(p, "type");
  const std::string type =
      jf::getString(c, require(c, v, p, "type", fmt::format(" (one of: {})", jf::joinKeys(kMaterialTypes))), tp);
  SurfaceMaterial m;
  if (type == "absorber") {
    checkObject(c, v, p, {"type"}, "an absorber material");
    m.type = MaterialType::Absorber;
  } else if (type == "diffuse" || type == "mirror") {
    checkObject(c, v, p, {"type", "reflectance"}, fmt::format("a {} material", type));
    m.type = type == "diffuse" ? MaterialType::Diffuse : MaterialType::Mirror;
    const std::string rp = child(p, "reflectance");
    if (const Json* r = find(v, "reflectance")) {
      parseReflectance(c, *r, rp, range, m);
    } else if (m.type == MaterialType::Mirror) {
      m.reflectanceNm = {kConstantNodeNm};
      m.reflectance = {1.0};
      m.reflectanceLabel = jf::fmtNum(1.0);  // (not = "1": a GCC 12 -Wrestrict false positive)
    } else {
      require(c, v, p, "reflectance", fmt::format(" ({})", kReflectanceHelp));
    }
  } else if (type == "dielectric") {
    m.type = MaterialType::Dielectric;
    parseDielectric(c, v, p, m);
  } else {
    c.fail(tp, fmt::format("unknown material type {}{} (valid types: {})", jsonQuoted(type),
                           jf::suggestion(type, kMaterialTypes), jf::joinKeys(kMaterialTypes)));
  }
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
      if (obj.material.type == MaterialType::Dielectric && !notClosed.empty())
        c.fail(mp, fmt::format("a dielectric needs a closed shape: a sphere or a closed mesh; {} is not closed: {}",
                               jsonQuoted(rel), notClosed));
      break;
    }
  }
  return obj;
}

}  // namespace spectrace
