#include "scene/scene_override.h"

#include <fmt/format.h>

#include "json/json_fields.h"

namespace spectrace {

namespace jf = json_fields;
using Json = nlohmann::json;

Json::json_pointer sceneOverridePointer(const std::string& text) {
  if (text.empty()) throw SceneOverrideError("cannot replace the whole scene (the pointer is empty)");
  try {
    return Json::json_pointer(text);
  } catch (const Json::exception&) {
    throw SceneOverrideError(
        fmt::format("{} is not a JSON pointer (it must start with '/', e.g. /lights/0/power_w)", jf::jsonQuoted(text)));
  }
}

void applySceneOverride(Json& scene, const SceneOverride& override, const std::filesystem::path& scenePath) {
  const std::string& text = override.pointer;
  const auto pointer = sceneOverridePointer(text);
  const auto parent = pointer.parent_pointer();
  if (!scene.contains(parent))
    throw SceneOverrideError(fmt::format("unknown pointer {}: {} has no {}", text, scenePath.string(),
                                         parent.empty() ? std::string("top level") : parent.to_string()));
  const Json& holder = scene[parent];
  if (holder.is_array()) {
    if (!scene.contains(pointer))
      throw SceneOverrideError(fmt::format("unknown pointer {}: {} has no {} (the array has {} element{})", text,
                                           scenePath.string(), text, holder.size(), holder.size() == 1 ? "" : "s"));
  } else if (!holder.is_object()) {
    throw SceneOverrideError(fmt::format("unknown pointer {}: {} is {}, not an object or array", text,
                                         parent.to_string(), jf::describe(holder)));
  }
  scene[pointer] = override.value;
}

std::string overridesText(const std::vector<SceneOverride>& overrides) {
  // Written by hand: a JSON object would sort the pointers and keep one
  // value per pointer, not the order they were applied in.
  std::string text = "{";
  for (const SceneOverride& o : overrides)
    text += fmt::format("{}{}:{}", text.size() > 1 ? "," : "", Json(o.pointer).dump(), o.value.dump());
  return text + "}";
}

}  // namespace spectrace
