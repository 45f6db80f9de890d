#pragma once
// Inside the scene module: the checks of validateScene with what the loader
// adds (the file's JSON, to quote values as written, and the file rules).
#include <string>

#include <glm/vec3.hpp>

#include "json/json_fields.h"
#include "scene/scene.h"

namespace spectrace {

struct SceneChecker {
  std::string file;                          // as shown in messages
  const json_fields::Json* source = nullptr;  // the file's JSON, when loaded
  // Files only: every light's spectrum has power inside the range, and some
  // light emits. (Scenes built in code may hold dark lights; the trace plan
  // reports them as not traced.)
  bool requireEmission = false;

  [[noreturn]] void fail(const std::string& ptr, const std::string& what, const std::string& note = {}) const;
  // The file's value at `ptr`, or nullptr.
  const json_fields::Json* given(const std::string& ptr) const;
  // For "(got ...)": the value as the file wrote it, else `fallback`.
  std::string got(const std::string& ptr, double fallback) const;
  std::string got(const std::string& ptr, const glm::dvec3& fallback) const;
};

// The loader checks the range as soon as it is read: the lights' spectra are
// built over it. validateScene checks the lights, then the objects (shapes,
// materials, and that a dielectric's shape is closed), then "render".
void validateSpectrum(const SpectrumRange& range, const SceneChecker& c);
void validateScene(const Scene& scene, const SceneChecker& c);

}  // namespace spectrace
