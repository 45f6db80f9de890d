#pragma once
// Scene description, loaded from JSON and validated. All lengths in metres,
// powers in watts, wavelengths in nanometres, world coordinates in double.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "camera/camera.h"
#include "lights/light.h"
#include "scene/scene_object.h"
#include "json/scene_error.h"
#include "json/sha256.h"  // sceneSha256Hex, as in Scene::sourceSha256
#include "spectrum/spd.h"

namespace spectrace {

struct SpectrumRange {
  double minNm = 360.0;
  double maxNm = 830.0;
  int bins = 94;
  double binWidthNm() const { return (maxNm - minNm) / bins; }
};

struct RenderSettings {
  uint64_t beams = 10'000'000;
  uint64_t seed = 1;
  // Surfaces a beam may scatter from (objects only); a beam that meets one
  // more is dropped, a bias the reference tests bound.
  uint32_t maxBounces = 64;
  // The wavelengths a camera path carries (shaders/wavelengths.h): 1, 2 or
  // 4, stratified over each light's spectrum; beams carry as many.
  uint32_t wavelengthsPerBeam = 4;
};

struct Scene {
  SpectrumRange spectrum;
  Camera camera;
  std::vector<Light> lights;
  std::vector<SceneObject> objects;  // between the lights and the camera; may be empty
  RenderSettings render;
  std::string observer = "CIE1931_2";
  // "output": {"spectral": true}: the EXR also holds one channel per bin.
  bool outputSpectral = false;
  std::filesystem::path sourcePath;  // empty for scenes built in code
  std::string sourceSha256;          // hex digest of the file's bytes
  // The fields overridden in the file's JSON before it was parsed (render
  // --set, a batch job's "set" and sweep values), as overridesText writes
  // them; empty when none.
  std::string overrides;
  // The bytes sourceSha256 is the digest of (the file's, or the compact dump
  // of a scene built from JSON): a render state carries them.
  std::string sourceText;
  // Hex digest of the files the scene names (CSV spectra and reflectances,
  // OBJ meshes; referencedFilesSha256), empty when it names none. A mesh's
  // part is the digest of the bytes its loader parsed (Shape::meshSha256).
  std::string referencedFilesSha256;
};

// Reads, parses and validates a scene file. Relative CSV and OBJ paths
// resolve against the scene file's folder.
Scene loadScene(const std::filesystem::path& file);

// Makes `light` (type object, with its power and spd set) the emission of
// the object objectIndex, of this shape: its surface (placed by the shape's unit at
// compile time) and its world box. How scene files read "emission", and
// how code builds an emitting object.
void placeEmission(const Shape& shape, bool twoSided, size_t objectIndex, Light& light);
// The scene's invariants, the same for scenes built in code and loaded
// ones (the loader calls it): finite coordinates within the world bounds,
// a spectrum range and bin count in range, a camera with a viewing direction
// and an up vector off it, a sensor of positive size and a bounded pixel
// count, lights with a non-zero direction, positive size, cone in
// (0, 180] degrees, and finite power >= 0, and objects with unit normals,
// positive sizes, meshes of in-range indices and triangles of non-zero area,
// reflectances in [0, 1], refractive indices finite and >= 1 over the
// spectrum range, and dielectrics only on closed shapes. Throws SceneError
// "<file or <scene>>: <field>: <what>".
void validateScene(const Scene& scene);

// Parses JSON text; `file` is used for messages and relative paths.
Scene parseScene(const std::string& jsonText, const std::filesystem::path& file);
// The same from a JSON value already read (e.g. a scene file with fields
// overridden by a batch job): the same schema and validator; `file` names
// the scene in messages and is where relative CSV paths resolve.
// sourceSha256 is the digest of the value's compact dump (its sourceText).
Scene parseSceneJson(const nlohmann::json& root, const std::filesystem::path& file);
// A scene file's bytes, and its JSON (comments tolerated, repeated keys
// refused); errors are SceneError "<file>: <what>", and for a missing file
// "<file>: scene file not found (looked for <absolute path>)".
std::string readSceneText(const std::filesystem::path& file);
// With `sha256`, also the file bytes' digest (as loadScene's sourceSha256);
// with `text`, the bytes themselves (as loadScene's sourceText).
nlohmann::json readSceneJson(const std::filesystem::path& file, std::string* sha256 = nullptr,
                             std::string* text = nullptr);
// The digest of the files `scene` names, in scene order (each light's CSV
// spectrum, then each object's OBJ mesh and reflectance CSV): SHA-256 of
// their digests, one a line; empty when it names none. A state's
// fingerprint holds it, so merges, resumes and MPI ranks never join films
// traced from other meshes or spectra under one scene file. Reads every
// file again (under BundledInputFiles, the bundle's bytes).
std::string referencedFilesSha256(const Scene& scene);
// Those files, in that order (a file named twice is listed twice), by the
// paths the loader resolved (relative to the working folder when the scene
// file's path was relative).
std::vector<std::filesystem::path> referencedFiles(const Scene& scene);

}  // namespace spectrace
