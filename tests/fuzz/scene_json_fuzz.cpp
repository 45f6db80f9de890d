// libFuzzer target: a scene file through the loader (readSceneJson,
// parseSceneJson with its validation) and, when accepted, compileScene and
// checkBeamScale, the host work before a device is needed. Bad input must
// end in SceneError, JsonFieldError or SpdError (exit code 2); an accepted
// scene must compile to finite scales or be refused with SceneError.
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "compile/compile_scene.h"
#include "fuzz_support.h"
#include "json/json_fields.h"
#include "scene/scene.h"

namespace fs = std::filesystem;
using namespace spectrace;

namespace {

// The scene sits beside a link to scenes/spd, so "csv": "spd/warm_led.csv"
// in a seed (scenes/showcase.json) resolves as it does in the repository.
fs::path sceneFile() {
  static const fs::path file = [] {
    const fs::path dir = fuzz::scratchDir();
    std::error_code ec;
    fs::create_directory_symlink(fs::path(SPECTRACE_SOURCE_DIR) / "scenes" / "spd", dir / "spd", ec);
    return dir / "scene.json";
  }();
  return file;
}

void checkCompiled(const Scene& scene, const CompiledScene& compiled) {
  const auto& c = compiled.device.constants;
  fuzz::requireFinite(compiled.tracedPowerW, "tracedPowerW");
  fuzz::requireFinite(compiled.sampledPowerW, "sampledPowerW");
  fuzz::requireFinite(compiled.film.pixelAreaM2, "film.pixelAreaM2");
  fuzz::require(compiled.film.pixelAreaM2 > 0.0, "film.pixelAreaM2 is not positive");
  fuzz::requireFinite(compiled.irradiancePerCount(scene.render.beams), "irradiancePerCount(render.beams)");
  for (float x : {c.sensorHalfSize.x, c.sensorHalfSize.y, c.pixelsPerMetre.x, c.pixelsPerMetre.y, c.lambdaMin,
                  c.binsPerNm, c.cameraFrontZ, c.cameraParams.x, c.cameraParams.y, c.cameraParams.z, c.cameraParams.w, c.aimRadius})
    fuzz::requireFinite(x, "a trace constant");
  for (const LightSummary& s : compiled.summaries) {
    fuzz::requireFinite(s.tracedPowerW, fmt::format("{}: tracedPowerW", s.label));
    fuzz::requireFinite(s.largestWeight, fmt::format("{}: largestWeight", s.label));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fs::path file = sceneFile();
  fuzz::writeBytes(file, data, size);
  Scene scene;
  try {
    scene = parseSceneJson(readSceneJson(file), file);
  } catch (const SceneError&) {
    return 0;
  } catch (const json_fields::JsonFieldError&) {
    return 0;
  } catch (const SpdError&) {
    return 0;
  }
  try {
    const CompiledScene compiled = compileScene(scene, scene.render.seed);
    checkBeamScale(scene, compiled, scene.render.beams);
    checkCompiled(scene, compiled);
  } catch (const SceneError&) {
  }
  return 0;
}
