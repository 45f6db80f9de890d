#pragma once
// Overrides of a scene file's fields by JSON pointer, before the scene is
// parsed and validated: a batch job's "set" and "sweep", render --set.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace spectrace {

// One field of a scene file replaced: `pointer` (RFC 6901) and its new value.
struct SceneOverride {
  std::string pointer;
  nlohmann::json value;
};

// An override that cannot be applied. The message says what is wrong
// without naming where the override came from (a job line, an option),
// which the caller adds.
struct SceneOverrideError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The pointer of an override: it must start with '/' (an empty pointer
// would replace the whole scene). Throws SceneOverrideError.
nlohmann::json::json_pointer sceneOverridePointer(const std::string& text);

// Sets the override's pointer in `scene` (a scene file's JSON, read from
// `scenePath`, which messages name). Its parent must exist (an object, or an
// array holding that index), so a typo cannot add a stray branch; a new key
// in an existing object is left to the scene's validator, which names the
// keys it knows. Throws SceneOverrideError.
void applySceneOverride(nlohmann::json& scene, const SceneOverride& override, const std::filesystem::path& scenePath);

// The overrides as one compact JSON object, in the order applied
// ({"/lights/0/spd/blackbody_k":3000}), for the image's metadata; a pointer
// set twice appears twice, the later value the one applied.
std::string overridesText(const std::vector<SceneOverride>& overrides);

}  // namespace spectrace
