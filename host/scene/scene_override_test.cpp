#include "scene/scene_override.h"

#include <string>

#include <gtest/gtest.h>

namespace spectrace {
namespace {

using Json = nlohmann::json;

Json lampJson() {
  return Json::parse(R"({"camera": {"position": [0, 0, 0]},
                         "lights": [{"power_w": 1, "spd": {"blackbody_k": 2700}}]})");
}

// The message of the SceneOverrideError that applying `pointer` = 1 throws.
std::string refusal(const std::string& pointer) {
  Json scene = lampJson();
  try {
    applySceneOverride(scene, {pointer, 1}, "lamp.json");
  } catch (const SceneOverrideError& e) {
    EXPECT_EQ(scene, lampJson()) << "a refused override changed the scene";
    return e.what();
  }
  return "(no error)";
}

TEST(SceneOverrideTest, ReplacesFieldsAndArrayElementsAndAddsKeysToExistingObjects) {
  Json scene = lampJson();
  applySceneOverride(scene, {"/lights/0/spd/blackbody_k", 3000}, "lamp.json");
  applySceneOverride(scene, {"/camera/position", Json::parse("[0, 0, -1]")}, "lamp.json");
  applySceneOverride(scene, {"/camera/position/0", 0.5}, "lamp.json");
  // A new key: the scene's validator, which knows the keys, has the last word.
  applySceneOverride(scene, {"/lights/0/name", "lamp"}, "lamp.json");
  EXPECT_EQ(scene["lights"][0]["spd"]["blackbody_k"], 3000);
  EXPECT_EQ(scene["camera"]["position"], Json::parse("[0.5, 0, -1]"));
  EXPECT_EQ(scene["lights"][0]["name"], "lamp");
}

TEST(SceneOverrideTest, RefusesPointersWhoseParentIsNotThereNamingPointerAndFile) {
  EXPECT_EQ(refusal("/lights/1/power_w"), "unknown pointer /lights/1/power_w: lamp.json has no /lights/1");
  EXPECT_EQ(refusal("/lights/1"), "unknown pointer /lights/1: lamp.json has no /lights/1 (the array has 1 element)");
  EXPECT_EQ(refusal("/lights/0/power_w/x"),
            "unknown pointer /lights/0/power_w/x: /lights/0/power_w is 1, not an object or array");
}

TEST(SceneOverrideTest, RefusesAnEmptyPointerAndOneWithoutALeadingSlash) {
  EXPECT_EQ(refusal(""), "cannot replace the whole scene (the pointer is empty)");
  EXPECT_EQ(refusal("lights/0/power_w"),
            "\"lights/0/power_w\" is not a JSON pointer (it must start with '/', e.g. /lights/0/power_w)");
  EXPECT_THROW(sceneOverridePointer("power_w"), SceneOverrideError);
  EXPECT_EQ(sceneOverridePointer("/a~1b/0").to_string(), "/a~1b/0");
}

TEST(SceneOverrideTest, OverridesTextKeepsTheOrderApplied) {
  EXPECT_EQ(overridesText({{"/z", 1}, {"/a", Json::parse("[0, 0, -1]")}, {"/m", "N-BK7"}, {"/z", true}}),
            R"({"/z":1,"/a":[0,0,-1],"/m":"N-BK7","/z":true})");
  EXPECT_EQ(overridesText({}), "{}");
}

}  // namespace
}  // namespace spectrace
