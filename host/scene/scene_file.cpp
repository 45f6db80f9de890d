// Scene files: the schema (which keys, of which JSON types, where), read
// through json_fields; the value rules are validateScene's, which the loader
// runs on what it read. Every problem becomes a SceneError "<file>: <json
// pointer>: <what is wrong>"; nothing reaches the renderer unchecked (no NaN,
// no zero-length axes, no silently ignored keys).
//
// Format summary (all lengths in metres, powers in watts, wavelengths in nm;
// // and /* */ comments are tolerated):
//   spectrum  {min_nm, max_nm, bins}                       optional
//   observer  "CIE1931_2" | "CIE1964_10"                   optional
//   camera    {position, look_at, up, sensor{width_m, height_m, pixels},
//              pinhole{distance_m, radius_m}, exposure_s}  required
//   lights    [ {type, name, power_w or power_lm, spd, ...type fields} ] required, non-empty,
//             unless an object emits
//   objects   [ {type, name, material, emission, ...type fields} ] optional (docs/objects.md);
//             emission {power_w or power_lm, spd, two_sided}
//             rect {center, normal, u_axis, size_m}, disk {center, normal,
//             radius_m}, sphere {center, radius_m}, mesh {file (OBJ),
//             transform{translate, rotate_deg, scale}}; material {type:
//             absorber | diffuse | mirror (reflectance) | dielectric (glass |
//             sellmeier{b, c_um2} | ior)}
//   render    {beams, seed, max_bounces, wavelengths_per_beam} optional
//   output    {spectral}                                   optional
#include "scene/scene.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "json/input_file.h"
#include "camera/camera_types.h"
#include "colour/colour.h"
#include "json/json_fields.h"
#include "lights/light_type.h"
#include "scene/object_field.h"
#include "scene/scene_limits.h"
#include "scene/spd_field.h"
#include "scene/validate_scene.h"

namespace spectrace {

namespace {

namespace fs = std::filesystem;
namespace jf = json_fields;
using jf::Json;
using jf::Keys;
using jf::checkObject;
using jf::child;
using jf::describe;
using jf::find;
using jf::require;

[[noreturn]] void raiseSceneError(const std::string& message) { throw SceneError(message); }

jf::Source sourceFor(const fs::path& file) {
  jf::Source c;
  c.file = file.string();
  c.dir = file.parent_path();
  if (c.dir.empty()) c.dir = ".";
  c.raise = raiseSceneError;
  return c;
}

SpectrumRange parseSpectrum(const jf::Source& c, const Json& v, const std::string& p) {
  checkObject(c, v, p, {"min_nm", "max_nm", "bins"}, "spectrum");
  SpectrumRange s;
  if (auto* x = find(v, "min_nm")) s.minNm = jf::getPositive(c, *x, child(p, "min_nm"));
  if (auto* x = find(v, "max_nm")) s.maxNm = jf::getPositive(c, *x, child(p, "max_nm"));
  if (auto* x = find(v, "bins")) s.bins = static_cast<int>(jf::getInt(c, *x, child(p, "bins"), 1, kMaxBins));
  return s;
}

// "pinhole, ..." : the keys of the camera models.
std::string cameraModelKeys() {
  std::string keys;
  for (const CameraTypeUnit* unit : cameraTypeUnits()) keys += (keys.empty() ? "" : ", ") + std::string(unit->key);
  return keys;
}

Camera parseCamera(const jf::Source& c, const Json& v, const std::string& p) {
  Keys keys = {"position", "look_at", "up", "sensor", "exposure_s"};
  for (const CameraTypeUnit* unit : cameraTypeUnits()) keys.push_back(unit->key);
  checkObject(c, v, p, keys, "camera");
  Camera cam;
  cam.position = jf::getPoint(c, require(c, v, p, "position"), child(p, "position"), kMaxCoordinateM);
  cam.lookAt = jf::getPoint(c, require(c, v, p, "look_at"), child(p, "look_at"), kMaxCoordinateM);
  if (auto* x = find(v, "up")) cam.up = jf::getDirection(c, *x, child(p, "up"));
  if (auto* s = find(v, "sensor")) {
    std::string sp = child(p, "sensor");
    checkObject(c, *s, sp, {"width_m", "height_m", "pixels"}, "camera.sensor");
    if (auto* x = find(*s, "width_m")) cam.sensorWidthM = jf::getLength(c, *x, child(sp, "width_m"), kMaxCoordinateM);
    if (auto* x = find(*s, "height_m")) cam.sensorHeightM = jf::getLength(c, *x, child(sp, "height_m"), kMaxCoordinateM);
    if (auto* x = find(*s, "pixels")) {
      std::string pp = child(sp, "pixels");
      if (!x->is_array() || x->size() != 2)
        c.fail(pp, fmt::format("must be an array of 2 positive integers [width, height] (got {})", describe(*x)));
      cam.pixelsX = static_cast<int>(jf::getInt(c, (*x)[0], child(pp, size_t(0)), 1, kMaxPixelsPerAxis));
      cam.pixelsY = static_cast<int>(jf::getInt(c, (*x)[1], child(pp, size_t(1)), 1, kMaxPixelsPerAxis));
    }
  }
  // At most one model before the sensor (none: a bare sensor).
  const CameraTypeUnit* chosen = nullptr;
  for (const CameraTypeUnit* unit : cameraTypeUnits()) {
    const Json* m = find(v, unit->key);
    if (!m) continue;
    if (chosen)
      c.fail(child(p, unit->key), fmt::format("a camera has one of {} in front of its sensor, not both \"{}\" and \"{}\"",
                                              cameraModelKeys(), chosen->key, unit->key));
    chosen = unit;
    cam.model = unit->parse(c, *m, child(p, unit->key));
  }
  if (auto* x = find(v, "exposure_s")) cam.exposureS = jf::getPositive(c, *x, child(p, "exposure_s"));
  return cam;
}

// The light type names, and every key some light type accepts (to name a
// typo such as "typ" before complaining that "type" is missing).
// The keys every light takes, whatever its type.
const Keys kCommonLightKeys = {"type", "name", "power_w", "power_lm", "spd"};

struct LightKeys {
  Keys types;
  Keys any = kCommonLightKeys;
};

const LightKeys& lightKeys() {
  static const LightKeys keys = [] {
    LightKeys k;
    for (const LightTypeUnit* unit : lightTypeUnits()) {
      if (unit->onObject) continue;  // an object's "emission", not a light of "lights"
      k.types.push_back(unit->name);
      for (std::string_view key : unit->keys)
        if (std::find(k.any.begin(), k.any.end(), key) == k.any.end()) k.any.push_back(key);
    }
    return k;
  }();
  return keys;
}

Light parseLight(const jf::Source& outer, const Json& v, const std::string& p, const SpectrumRange& range) {
  jf::Source c = outer;
  if (!v.is_object()) c.fail(p, fmt::format("a light must be an object (got {})", describe(v)));
  Light light;
  light.label = p;
  if (auto* n = find(v, "name")) {
    light.name = jf::getString(c, *n, child(p, "name"));
    c.note = fmt::format(" (light {})", jf::jsonQuoted(light.name));
  }
  const LightKeys& keys = lightKeys();
  if (!find(v, "type")) checkObject(c, v, p, keys.any, "a light");
  const Json& t = require(c, v, p, "type", fmt::format(" (one of: {})", jf::joinKeys(keys.types)));
  std::string type = jf::getString(c, t, child(p, "type"));
  const LightTypeUnit* unit = lightTypeUnitNamed(type);
  if (unit && unit->onObject)
    c.fail(child(p, "type"), fmt::format("{} is not a light type of \"lights\": an object emits through its "
                                         "\"emission\" (valid types: {})",
                                         jf::jsonQuoted(type), jf::joinKeys(keys.types)));
  if (!unit)
    c.fail(child(p, "type"), fmt::format("unknown light type {}{} (valid types: {})", jf::jsonQuoted(type),
                                         jf::suggestion(type, keys.types), jf::joinKeys(keys.types)));
  light.type = unit->type;
  Keys allowed = kCommonLightKeys;
  allowed.insert(allowed.end(), unit->keys.begin(), unit->keys.end());
  checkObject(c, v, p, allowed, fmt::format("a {} light", type));
  unit->parse(c, v, p, light);
  parseLightPower(c, v, p, range, light);
  return light;
}

RenderSettings parseRender(const jf::Source& c, const Json& v, const std::string& p) {
  checkObject(c, v, p, {"beams", "seed", "max_bounces", "wavelengths_per_beam"}, "render");
  RenderSettings r;
  if (auto* x = find(v, "beams")) r.beams = jf::getU64(c, *x, child(p, "beams"), 1);
  if (auto* x = find(v, "seed")) r.seed = jf::getU64(c, *x, child(p, "seed"), 0);
  if (auto* x = find(v, "max_bounces"))
    r.maxBounces = uint32_t(jf::getInt(c, *x, child(p, "max_bounces"), 1, kMaxBounces));
  if (auto* x = find(v, "wavelengths_per_beam")) {
    const int k = jf::getInt(c, *x, child(p, "wavelengths_per_beam"), 1, int(device::kMaxWavelengthsPerPath));
    if (k & (k - 1)) c.fail(child(p, "wavelengths_per_beam"), fmt::format("must be 1, 2 or 4 (got {})", k));
    r.wavelengthsPerBeam = uint32_t(k);
  }
  return r;
}

// What the EXR holds beyond the RGB, XYZ and irradiance channels.
bool parseOutputSpectral(const jf::Source& c, const Json& v, const std::string& p) {
  checkObject(c, v, p, {"spectral"}, "output");
  const Json* x = find(v, "spectral");
  if (!x) return false;
  if (!x->is_boolean())
    c.fail(child(p, "spectral"), fmt::format("must be true or false (got {})", describe(*x)));
  return x->get<bool>();
}

// A file the scene names, with the digest its loader took of the bytes it
// read, where it took one (an OBJ mesh's; empty otherwise).
struct NamedFile {
  fs::path path;
  std::string digestAsRead;
};

// referencedFiles, with their digests as read.
std::vector<NamedFile> namedFiles(const Scene& scene) {
  std::vector<NamedFile> files;
  for (const fs::path& f : scene.camera.model->files()) files.push_back({f, ""});
  for (const Light& light : scene.lights) {
    files.push_back({light.spdFile, ""});
    files.push_back({light.photometryFile, ""});
  }
  for (const SceneObject& object : scene.objects) {
    files.push_back({object.shape.meshFile, object.shape.meshSha256});
    files.push_back({object.material.reflectanceFile, ""});
  }
  std::erase_if(files, [](const NamedFile& f) { return f.path.empty(); });
  return files;
}

// referencedFilesSha256, taking each file's digest as its loader took it
// where `asRead` and it took one, else reading the file again.
std::string namedFilesSha256(const Scene& scene, bool asRead) {
  const std::vector<NamedFile> files = namedFiles(scene);
  if (files.empty()) return "";
  std::string digests;
  for (const NamedFile& f : files) {
    if (asRead && !f.digestAsRead.empty()) {
      digests += f.digestAsRead + "\n";
      continue;
    }
    try {
      digests += sceneSha256Hex(readInputFile(f.path, "file named by the scene", uint64_t(1) << 30)) + "\n";
    } catch (const InputFileError& e) {  // changed since it was parsed
      throw SceneError(fmt::format("{}: {}", scene.sourcePath.empty() ? "<scene>" : scene.sourcePath.string(), e.what()));
    }
  }
  return sceneSha256Hex(digests);
}

Scene parseRoot(const Json& root, const fs::path& file, std::string sourceText) {
  const jf::Source c = sourceFor(file);
  static const Keys kTop = {"spectrum", "observer", "camera", "lights", "objects", "render", "output"};
  if (!root.is_object()) c.fail("", fmt::format("the top level must be a JSON object (got {})", describe(root)));
  checkObject(c, root, "", kTop, "the top level");

  const SceneChecker checker{c.file, &root, /*requireEmission=*/true};
  Scene scene;
  scene.sourcePath = file;
  if (auto* x = find(root, "spectrum")) scene.spectrum = parseSpectrum(c, *x, "/spectrum");
  validateSpectrum(scene.spectrum, checker);  // the lights' spectra are built over it
  if (auto* x = find(root, "observer")) {
    static const Keys kObservers = {"CIE1931_2", "CIE1964_10"};
    std::string obs = jf::getString(c, *x, "/observer");
    if (std::find(kObservers.begin(), kObservers.end(), obs) == kObservers.end())
      c.fail("/observer", fmt::format("unknown observer {}{} (valid: {})", jf::jsonQuoted(obs),
                                      jf::suggestion(obs, kObservers), jf::joinKeys(kObservers)));
    scene.observer = obs;
  }
  scene.camera = parseCamera(c, require(c, root, "", "camera"), "/camera");

  // Lights, then the objects' emissions: "lights" may be empty (or absent)
  // when an object emits.
  const Json* lights = find(root, "lights");
  if (lights && !lights->is_array())
    c.fail("/lights", fmt::format("must be a non-empty array of lights, or empty when an object has an \"emission\" "
                                  "(got {})",
                                  describe(*lights)));
  if (lights && lights->size() > size_t(kMaxLights))
    c.fail("/lights", fmt::format("has {} lights; a scene has at most {}", lights->size(), kMaxLights));
  for (size_t i = 0; lights && i < lights->size(); ++i)
    scene.lights.push_back(parseLight(c, (*lights)[i], child("/lights", i), scene.spectrum));

  if (auto* objects = find(root, "objects")) {
    if (!objects->is_array())
      c.fail("/objects", fmt::format("must be an array of objects (got {})", describe(*objects)));
    if (objects->size() > size_t(kMaxObjects))
      c.fail("/objects", fmt::format("has {} objects; a scene has at most {}", objects->size(), kMaxObjects));
    uint64_t trianglesLeft = kMaxSceneTriangles;
    for (size_t i = 0; i < objects->size(); ++i) {
      scene.objects.push_back(
          parseObject(c, (*objects)[i], child("/objects", i), scene.spectrum, trianglesLeft, i, scene.lights));
      if (scene.lights.size() > size_t(kMaxLights))
        c.fail(child("/objects", i) + "/emission",
               fmt::format("makes {} lights with the emitting objects before it; a scene has at most {}",
                           scene.lights.size(), kMaxLights));
    }
  }
  if (scene.lights.empty())
    c.fail("/lights", fmt::format("{}, and no object has an \"emission\": the scene has nothing that emits",
                                  lights ? "must be a non-empty array of lights" : "missing required field (lights)"));

  if (auto* x = find(root, "render")) scene.render = parseRender(c, *x, "/render");
  if (auto* x = find(root, "output")) scene.outputSpectral = parseOutputSpectral(c, *x, "/output");
  scene.sourceSha256 = sceneSha256Hex(sourceText);
  scene.sourceText = std::move(sourceText);
  validateScene(scene, checker);
  // A mesh's digest is of the bytes it was read from, so the fingerprint
  // names what is rendered even if the file changes meanwhile.
  scene.referencedFilesSha256 = namedFilesSha256(scene, true);
  return scene;
}

}  // namespace

Scene parseScene(const std::string& jsonText, const fs::path& file) {
  const Json root = jf::parseJson(sourceFor(file), jsonText);
  return parseRoot(root, file, jsonText);
}

std::vector<fs::path> referencedFiles(const Scene& scene) {
  std::vector<fs::path> files;
  for (NamedFile& f : namedFiles(scene)) files.push_back(std::move(f.path));
  return files;
}

std::string referencedFilesSha256(const Scene& scene) { return namedFilesSha256(scene, false); }

Scene parseSceneJson(const nlohmann::json& root, const fs::path& file) {
  return parseRoot(root, file, root.dump());
}

nlohmann::json readSceneJson(const fs::path& file, std::string* sha256, std::string* text) {
  const jf::Source c = sourceFor(file);
  std::string bytes = readSceneText(file);
  if (sha256) *sha256 = sceneSha256Hex(bytes);
  nlohmann::json root = jf::parseJson(c, bytes);
  if (text) *text = std::move(bytes);
  return root;
}

Scene loadScene(const fs::path& file) { return parseScene(readSceneText(file), file); }

std::string readSceneText(const fs::path& file) {
  try {
    return readInputFile(file, "scene file");
  } catch (const InputFileError& e) {
    // A file that cannot be read has no field to point at. A missing one
    // also names the absolute path looked for: a relative path resolves
    // against the working folder, which the path as given does not show.
    std::string message = fmt::format("{}: {}", file.string(), e.reason);
    std::error_code ec;
    if (e.missing) message += fmt::format(" (looked for {})", fs::absolute(file, ec).lexically_normal().string());
    raiseSceneError(message);
  }
}

}  // namespace spectrace
