// The one home of the scene's semantic rules: value ranges, world bounds,
// and relations between fields. The loader reads types (json_fields) and
// leaves the rest to these checks; scenes built in code get the same.
#include "scene/validate_scene.h"

#include <cmath>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "lights/light_type.h"
#include "materials/material_type.h"
#include "scene/obj_mesh.h"
#include "scene/scene_limits.h"

namespace spectrace {

namespace jf = json_fields;

void SceneChecker::fail(const std::string& ptr, const std::string& what, const std::string& note) const {
  throw SceneError(file + ": " + ptr + ": " + what + note);
}

const jf::Json* SceneChecker::given(const std::string& ptr) const {
  if (!source) return nullptr;
  try {
    const jf::Json::json_pointer pointer(ptr);
    return source->contains(pointer) ? &source->at(pointer) : nullptr;
  } catch (const jf::Json::exception&) {
    return nullptr;  // not a pointer into the file (a label set in code)
  }
}

namespace {

// As a person would write it: integral values without ".0", as the file's
// own defaults are written.
std::string describeNumber(double x) {
  if (!std::isfinite(x)) return jf::fmtNum(x);
  if (std::floor(x) == x && std::abs(x) < 9e15) return jf::describe(jf::Json(int64_t(x)));
  return jf::describe(jf::Json(x));
}

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

std::string SceneChecker::got(const std::string& ptr, double fallback) const {
  const jf::Json* v = given(ptr);
  return v ? jf::describe(*v) : describeNumber(fallback);
}

std::string SceneChecker::got(const std::string& ptr, const glm::dvec3& fallback) const {
  if (const jf::Json* v = given(ptr)) return jf::describe(*v);
  return fmt::format("[{}, {}, {}]", describeNumber(fallback.x), describeNumber(fallback.y), describeNumber(fallback.z));
}

namespace {

// The camera model's view of the checker: keys relative to /camera.
class CameraChecker final : public CameraFieldCheck {
 public:
  explicit CameraChecker(const SceneChecker& c) : c_(c) {}
  [[noreturn]] void fail(const std::string& key, const std::string& what) const override {
    c_.fail("/camera/" + key, what);
  }
  std::string got(const std::string& key, double fallback) const override { return c_.got("/camera/" + key, fallback); }
  void checkLength(const std::string& key, double value) const override;

 private:
  const SceneChecker& c_;
};

// A point within the world bounds.
void checkPoint(const SceneChecker& c, const std::string& ptr, const glm::dvec3& p, const std::string& note = {}) {
  if (!finite(p)) c.fail(ptr, "must be finite", note);
  for (int i = 0; i < 3; ++i) {
    const std::string ip = ptr + "/" + std::to_string(i);
    if (std::abs(p[i]) > kMaxCoordinateM)
      c.fail(ip, fmt::format("must be a coordinate with magnitude <= {:g} m (got {})", kMaxCoordinateM, c.got(ip, p[i])),
             note);
  }
}

void checkLength(const SceneChecker& c, const std::string& ptr, double value) {
  if (!(std::isfinite(value) && value > 0.0 && value <= kMaxCoordinateM))
    c.fail(ptr, fmt::format("must be a length in metres, > 0 and <= {:g} (got {})", kMaxCoordinateM, c.got(ptr, value)));
}

void CameraChecker::checkLength(const std::string& key, double value) const {
  spectrace::checkLength(c_, "/camera/" + key, value);
}

void checkPositive(const SceneChecker& c, const std::string& ptr, double value) {
  if (!(std::isfinite(value) && value > 0.0))
    c.fail(ptr, fmt::format("must be a finite number > 0 (got {})", c.got(ptr, value)));
}

void validateCamera(const Camera& camera, const SceneChecker& c) {
  checkPoint(c, "/camera/position", camera.position);
  checkPoint(c, "/camera/look_at", camera.lookAt);
  if (!finite(camera.up)) c.fail("/camera/up", "must be finite");
  // The camera frame normalises these in plain double: their lengths must
  // neither underflow to 0 nor overflow.
  const glm::dvec3 difference = camera.lookAt - camera.position;
  const auto view = jf::safeNormalize(difference);
  if (!view || !(glm::length(difference) > 0.0))
    c.fail("/camera/look_at", fmt::format("must differ from the camera position {} (zero-length view direction)",
                                          c.got("/camera/position", camera.position)));
  const auto up = jf::safeNormalize(camera.up);
  if (!up) c.fail("/camera/up", fmt::format("must not be zero-length (got {})", c.got("/camera/up", camera.up)));
  if (!std::isfinite(glm::length(camera.up))) c.fail("/camera/up", "must have a finite length");
  if (!(glm::length(glm::cross(*view, *up)) >= kCollinearEps))
    c.fail("/camera/up", fmt::format("{} is parallel to the view direction (look_at - position); choose an up "
                                     "vector that is not collinear with it",
                                     c.got("/camera/up", camera.up)));

  checkLength(c, "/camera/sensor/width_m", camera.sensorWidthM);
  checkLength(c, "/camera/sensor/height_m", camera.sensorHeightM);
  const int pixels[2] = {camera.pixelsX, camera.pixelsY};
  for (int i = 0; i < 2; ++i) {
    const std::string ptr = "/camera/sensor/pixels/" + std::to_string(i);
    if (pixels[i] < 1 || pixels[i] > kMaxPixelsPerAxis)
      c.fail(ptr, fmt::format("must be an integer in 1..{} (got {})", kMaxPixelsPerAxis, c.got(ptr, pixels[i])));
  }
  const int64_t total = int64_t(camera.pixelsX) * camera.pixelsY;
  if (total > kMaxPixelsTotal)
    c.fail("/camera/sensor/pixels", fmt::format("too many pixels: {} x {} = {} (at most {})", camera.pixelsX,
                                                camera.pixelsY, total, kMaxPixelsTotal));
  camera.model->validate(CameraChecker(c));
  checkPositive(c, "/camera/exposure_s", camera.exposureS);
}

// A unit's view of the checker: keys relative to the light, messages with
// the light's name.
class LightChecker final : public LightFieldCheck {
 public:
  LightChecker(const SceneChecker& c, std::string at, std::string note)
      : c_(c), at_(std::move(at)), note_(std::move(note)) {}
  [[noreturn]] void fail(const std::string& key, const std::string& what) const override {
    c_.fail(pointer(key), what, note_);
  }
  std::string got(const std::string& key, double fallback) const override { return c_.got(pointer(key), fallback); }
  std::string got(const std::string& key, const glm::dvec3& fallback) const override {
    return c_.got(pointer(key), fallback);
  }
  std::string pointer(const std::string& key) const { return at_ + "/" + key; }

 private:
  const SceneChecker& c_;
  std::string at_, note_;
};

// The file rule: the light's spectrum carries power, some of it inside the
// simulated range.
void checkEmission(const Light& light, const SpectrumRange& range, const LightChecker& check) {
  const Spd& s = light.spd;
  if (s.lambdaNm.empty() || !std::isfinite(s.fullIntegral) || !(s.fullIntegral > 0.0))
    check.fail("spd", "the spectrum has no power (its integral is 0)");
  Spd inside = s.clipped(range.minNm, range.maxNm);
  if (inside.lambdaNm.empty() || !(inside.integral() > 0.0))
    check.fail("spd", fmt::format("the spectrum ({}) emits nothing inside the scene's spectrum range {}-{} nm",
                                  light.spdLabel, jf::fmtNum(range.minNm), jf::fmtNum(range.maxNm)));
}

void validateLight(const Light& light, size_t index, const Scene& scene, const SceneChecker& c) {
  const std::string at = light.label.empty() ? "/lights/" + std::to_string(index) : light.label;
  const std::string note = light.name.empty() ? "" : fmt::format(" (light {})", jf::jsonQuoted(light.name));
  if (uint32_t(light.type) >= kLightTypeCount) c.fail(at + "/type", "is not a light type", note);
  const LightTypeUnit& unit = lightTypeUnit(light.type);
  const LightChecker check(c, at, note);
  checkPoint(c, check.pointer(unit.positionKey), light.position, note);
  if (!(std::isfinite(light.powerW) && light.powerW >= 0.0))
    check.fail("power_w", fmt::format("must be a finite number >= 0 (got {})", check.got("power_w", light.powerW)));
  if (unit.directionKey) {
    const double length = glm::length(light.direction);
    if (!finite(light.direction) || !(length > 0.0) || !std::isfinite(length))
      check.fail(unit.directionKey, "must be finite and not zero-length");
  }
  unit.validate(light, check);
  if (c.requireEmission) checkEmission(light, scene.spectrum, check);
}

// An object's view of the checker: keys relative to the object, messages
// with its name.
struct ObjectChecker {
  const SceneChecker& c;
  std::string at, note;
  [[noreturn]] void fail(const std::string& key, const std::string& what) const { c.fail(at + "/" + key, what, note); }
  std::string got(const std::string& key, double fallback) const { return c.got(at + "/" + key, fallback); }
  std::string got(const std::string& key, const glm::dvec3& fallback) const { return c.got(at + "/" + key, fallback); }
};

void checkObjectLength(const ObjectChecker& check, const std::string& key, double value) {
  if (!(std::isfinite(value) && value > 0.0 && value <= kMaxCoordinateM))
    check.fail(key, fmt::format("must be a length in metres, > 0 and <= {:g} (got {})", kMaxCoordinateM,
                                check.got(key, value)));
}

// Placement vectors of shapes built in code must already be unit length
// (the loader normalises what a file gives).
constexpr double kUnitEps = 1e-9;

void checkUnit(const ObjectChecker& check, const std::string& key, const glm::dvec3& v) {
  const double length = glm::length(v);
  if (!finite(v) || !(std::abs(length - 1.0) <= kUnitEps))
    check.fail(key, fmt::format("must be a unit vector (got {}, of length {})", check.got(key, v), jf::fmtNum(length)));
}

void validateShape(const Shape& shape, const ObjectChecker& check) {
  if (shape.type != ShapeType::Mesh) checkPoint(check.c, check.at + "/center", shape.center, check.note);
  if (shape.type == ShapeType::Rect || shape.type == ShapeType::Disk) checkUnit(check, "normal", shape.normal);
  if (shape.type == ShapeType::Disk || shape.type == ShapeType::Sphere) checkObjectLength(check, "radius_m", shape.radiusM);
  switch (shape.type) {
    case ShapeType::Rect: {
      checkObjectLength(check, "size_m/0", shape.sizeM.x);
      checkObjectLength(check, "size_m/1", shape.sizeM.y);
      const glm::dvec3& u = shape.uAxis;
      if (!finite(u) || !jf::safeNormalize(u)) check.fail("u_axis", "must be finite and not zero-length");
      if (glm::length(glm::cross(*jf::safeNormalize(u), shape.normal)) < kCollinearEps)
        check.fail("u_axis", fmt::format("{} is parallel to the normal; u_axis must lie (roughly) in the rect's plane",
                                         check.got("u_axis", u)));
      if (!(std::abs(glm::length(u) - 1.0) <= kUnitEps && std::abs(glm::dot(u, shape.normal)) <= kUnitEps))
        check.fail("u_axis", fmt::format("must be a unit vector perpendicular to the normal (got {})",
                                         check.got("u_axis", u)));
      break;
    }
    case ShapeType::Disk:
    case ShapeType::Sphere: break;
    case ShapeType::Mesh: {
      const auto& vertices = shape.vertices;
      const auto& triangles = shape.triangles;
      if (triangles.empty()) check.fail("triangles", "a mesh needs at least one triangle");
      if (vertices.size() > kMaxMeshVertices)
        check.fail("vertices", fmt::format("has {} vertices; a mesh has at most {}", vertices.size(), kMaxMeshVertices));
      for (size_t i = 0; i < vertices.size(); ++i) {
        const glm::dvec3& p = vertices[i];
        if (!finite(p) || std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) > kMaxCoordinateM)
          check.fail(fmt::format("vertices/{}", i),
                     fmt::format("must be finite with every coordinate's magnitude <= {:g} m (got [{}, {}, {}])",
                                 kMaxCoordinateM, jf::fmtNum(p.x), jf::fmtNum(p.y), jf::fmtNum(p.z)));
      }
      for (size_t k = 0; k < triangles.size(); ++k)
        for (uint32_t v : triangles[k])
          if (v >= vertices.size())
            check.fail(fmt::format("triangles/{}", k), fmt::format("refers to vertex {}, but the mesh has {} vertices",
                                                                   v, vertices.size()));
      if (auto k = findDegenerateTriangle(vertices, triangles))
        check.fail(fmt::format("triangles/{}", *k),
                   fmt::format("has zero area (vertices {}, {}, {})", triangles[*k][0], triangles[*k][1],
                               triangles[*k][2]));
      break;
    }
  }
}

// A material unit's view of the checker: keys relative to the object's
// material.
class MaterialChecker final : public MaterialFieldCheck {
 public:
  explicit MaterialChecker(const ObjectChecker& object) : object_(object) {}
  [[noreturn]] void fail(const std::string& key, const std::string& what) const override { object_.fail(at(key), what); }
  std::string got(const std::string& key, double fallback) const override { return object_.got(at(key), fallback); }
  bool given(const std::string& key) const override { return object_.c.given(object_.at + "/" + at(key)) != nullptr; }

 private:
  static std::string at(const std::string& key) { return key.empty() ? "material" : "material/" + key; }
  const ObjectChecker& object_;
};

// A material that refracts into its shape needs the shape to have an inside.
void checkClosedFor(const MaterialTypeUnit& material, const Shape& shape, const ObjectChecker& check) {
  if (shape.type == ShapeType::Rect || shape.type == ShapeType::Disk)
    check.fail("material", fmt::format("a {} needs a closed shape: a sphere or a closed mesh (a {} has no inside)",
                                       material.name, shapeTypeName(shape.type)));
  if (shape.type == ShapeType::Mesh)
    if (auto fault = findEdgeFault(shape.triangles))
      check.fail("material", fmt::format("a {} needs a closed shape: a sphere or a closed mesh; this mesh is "
                                         "not closed: {}",
                                         material.name, describeEdgeFault(*fault, 0, [](size_t k) {
                                           return fmt::format("triangle {}", k);
                                         })));
  // Consistent winding can still be inside out: glass then refracts every
  // beam the wrong way. Outward faces enclose a positive signed volume.
  if (shape.type == ShapeType::Mesh) {
    double volume6 = 0.0;  // six times the signed volume
    for (const auto& t : shape.triangles)
      volume6 += glm::dot(shape.vertices[t[0]], glm::cross(shape.vertices[t[1]], shape.vertices[t[2]]));
    if (!(volume6 > 0.0))
      check.fail("material", fmt::format("a {} mesh must face outwards (counter-clockwise seen from outside), "
                                         "but {}'s faces enclose a signed volume of {:g} m^3; turn every face round",
                                         material.name,
                                         shape.meshFile.empty() ? std::string("this mesh")
                                                                : jf::jsonQuoted(shape.meshFile.string()),
                                         volume6 / 6.0));
  }
}

void validateObject(const SceneObject& object, size_t index, const Scene& scene, const SceneChecker& c) {
  const ObjectChecker check{c, object.label.empty() ? "/objects/" + std::to_string(index) : object.label,
                            object.name.empty() ? "" : fmt::format(" (object {})", jf::jsonQuoted(object.name))};
  if (uint32_t(object.shape.type) > uint32_t(ShapeType::Mesh)) check.fail("type", "is not a shape type");
  validateShape(object.shape, check);
  if (uint32_t(object.material.type) >= materialTypeUnits().size()) check.fail("material/type", "is not a material type");
  const MaterialTypeUnit& material = materialTypeUnit(object.material.type);
  material.validate(object.material, scene.spectrum.minNm, scene.spectrum.maxNm, MaterialChecker(check));
  if (material.needsClosedShape) checkClosedFor(material, object.shape, check);
}

}  // namespace

void validateSpectrum(const SpectrumRange& range, const SceneChecker& c) {
  for (const auto& [key, nm] : {std::pair{"min_nm", range.minNm}, std::pair{"max_nm", range.maxNm}}) {
    const std::string ptr = std::string("/spectrum/") + key;
    checkPositive(c, ptr, nm);
    if (nm < kMinWavelengthNm)
      c.fail(ptr, fmt::format("must be at least {} nm (got {})", jf::fmtNum(kMinWavelengthNm), c.got(ptr, nm)));
    if (nm > kMaxWavelengthNm)
      c.fail(ptr, fmt::format("must be at most {} nm (got {})", jf::fmtNum(kMaxWavelengthNm), c.got(ptr, nm)));
  }
  if (range.bins < 1 || range.bins > kMaxBins)
    c.fail("/spectrum/bins", fmt::format("must be an integer in 1..{} (got {})", kMaxBins, c.got("/spectrum/bins", range.bins)));
  if (!(range.minNm < range.maxNm)) {
    // Name the field the file gave (a lone min_nm above the default max).
    const bool atMax = !c.source || c.given("/spectrum/max_nm");
    c.fail(atMax ? "/spectrum/max_nm" : "/spectrum/min_nm",
           fmt::format("spectrum range is empty: min_nm ({} nm) must be less than max_nm ({} nm)",
                       jf::fmtNum(range.minNm), jf::fmtNum(range.maxNm)));
  }
}

void validateScene(const Scene& scene, const SceneChecker& c) {
  validateSpectrum(scene.spectrum, c);
  validateCamera(scene.camera, c);
  if (scene.lights.empty()) c.fail("/lights", "there are no lights");
  if (scene.lights.size() > size_t(kMaxLights))
    c.fail("/lights", fmt::format("has {} lights; a scene has at most {}", scene.lights.size(), kMaxLights));
  double total = 0.0;
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    validateLight(scene.lights[i], i, scene, c);
    total += scene.lights[i].powerW;
  }
  if (!std::isfinite(total)) c.fail("/lights", "the total power_w of all lights overflows");
  if (c.requireEmission && !(total > 0.0)) c.fail("/lights", "no light emits power: every power_w is 0");

  if (scene.objects.size() > size_t(kMaxObjects))
    c.fail("/objects", fmt::format("has {} objects; a scene has at most {}", scene.objects.size(), kMaxObjects));
  uint64_t triangles = 0;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    validateObject(scene.objects[i], i, scene, c);
    triangles += scene.objects[i].shape.triangles.size();
  }
  if (triangles > kMaxSceneTriangles)
    c.fail("/objects", fmt::format("the meshes have {} triangles; a scene has at most {}", triangles, kMaxSceneTriangles));
  if (scene.render.maxBounces < 1 || scene.render.maxBounces > uint32_t(kMaxBounces))
    c.fail("/render/max_bounces", fmt::format("must be an integer in 1..{} (got {})", kMaxBounces,
                                              c.got("/render/max_bounces", scene.render.maxBounces)));
}

void validateScene(const Scene& scene) {
  SceneChecker c;
  c.file = scene.sourcePath.empty() ? std::string("<scene>") : scene.sourcePath.string();
  validateScene(scene, c);
}

}  // namespace spectrace
