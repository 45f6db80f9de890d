// The one home of the scene's semantic rules: value ranges, world bounds,
// and relations between fields. The loader reads types (json_fields) and
// leaves the rest to these checks; scenes built in code get the same.
#include "scene/validate_scene.h"

#include <cmath>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "lights/light_type.h"
#include "materials/material_type.h"
#include "scene/scene_limits.h"
#include "shapes/shape_type.h"

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
  CameraChecker(const SceneChecker& c, const SpectrumRange& spectrum) : c_(c), spectrum_(spectrum) {}
  [[noreturn]] void fail(const std::string& key, const std::string& what) const override {
    c_.fail("/camera/" + key, what);
  }
  std::string got(const std::string& key, double fallback) const override { return c_.got("/camera/" + key, fallback); }
  void checkLength(const std::string& key, double value) const override;
  double spectrumMinNm() const override { return spectrum_.minNm; }
  double spectrumMaxNm() const override { return spectrum_.maxNm; }

 private:
  const SceneChecker& c_;
  const SpectrumRange& spectrum_;
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

void validateCamera(const Camera& camera, const SpectrumRange& spectrum, const SceneChecker& c) {
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
  camera.model->validate(CameraChecker(c, spectrum));
  checkPositive(c, "/camera/exposure_s", camera.exposureS);
}

// A unit's view of the checker: keys relative to its light or object
// (`at`), messages with its name (`note`).
template <class FieldCheck>
class ScopedChecker : public FieldCheck {
 public:
  ScopedChecker(const SceneChecker& c, std::string at, std::string note)
      : c_(c), at_(std::move(at)), note_(std::move(note)) {}
  [[noreturn]] void fail(const std::string& key, const std::string& what) const override {
    c_.fail(pointer(key), what, note_);
  }
  std::string got(const std::string& key, double fallback) const override { return c_.got(pointer(key), fallback); }
  std::string got(const std::string& key, const glm::dvec3& fallback) const override {
    return c_.got(pointer(key), fallback);
  }
  bool given(const std::string& key) const { return c_.given(pointer(key)) != nullptr; }
  std::string pointer(const std::string& key) const { return at_ + "/" + key; }

 private:
  const SceneChecker& c_;
  std::string at_, note_;
};
using LightChecker = ScopedChecker<LightFieldCheck>;

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
  if (unit.positionKey) checkPoint(c, check.pointer(unit.positionKey), light.position, note);
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

using ObjectChecker = ScopedChecker<ShapeFieldCheck>;

// A material unit's view of the checker: keys relative to the object's
// material.
class MaterialChecker final : public MaterialFieldCheck {
 public:
  explicit MaterialChecker(const ObjectChecker& object) : object_(object) {}
  [[noreturn]] void fail(const std::string& key, const std::string& what) const override { object_.fail(at(key), what); }
  std::string got(const std::string& key, double fallback) const override { return object_.got(at(key), fallback); }
  bool given(const std::string& key) const override { return object_.given(at(key)); }

 private:
  static std::string at(const std::string& key) { return key.empty() ? "material" : "material/" + key; }
  const ObjectChecker& object_;
};

void validateObject(const SceneObject& object, size_t index, const Scene& scene, const SceneChecker& c) {
  const ObjectChecker check(c, object.label.empty() ? "/objects/" + std::to_string(index) : object.label,
                            object.name.empty() ? "" : fmt::format(" (object {})", jf::jsonQuoted(object.name)));
  if (uint32_t(object.shape.type) >= shapeTypeUnits().size()) check.fail("type", "is not a shape type");
  const ShapeTypeUnit& shape = shapeTypeUnit(object.shape.type);
  shape.validate(object.shape, check);
  if (uint32_t(object.material.type) >= materialTypeUnits().size()) check.fail("material/type", "is not a material type");
  const MaterialTypeUnit& material = materialTypeUnit(object.material.type);
  material.validate(object.material, scene.spectrum.minNm, scene.spectrum.maxNm, MaterialChecker(check));
  // A material that refracts into its shape needs the shape to have an inside.
  if (material.needsClosedShape)
    if (const std::string why = shape.notClosedBecause(object.shape, material.name); !why.empty())
      check.fail("material", why);
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
  validateCamera(scene.camera, scene.spectrum, c);
  if (scene.lights.empty()) c.fail("/lights", "there are no lights");
  if (scene.lights.size() > size_t(kMaxLights))
    c.fail("/lights", fmt::format("has {} lights; a scene has at most {}", scene.lights.size(), kMaxLights));
  double total = 0.0;
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    validateLight(scene.lights[i], i, scene, c);
    total += scene.lights[i].powerW;
  }
  if (!std::isfinite(total)) c.fail("/lights", "the total power_w of all lights overflows");
  if (c.requireEmission && !(total > 0.0)) c.fail("/lights", "no light emits power: every power_w (or power_lm) is 0");

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
