#include "compile/estimators.h"
#include <algorithm>

#include "materials/material_type.h"

namespace spectrace {

std::string cameraPathsUselessBecause(const Scene& scene, const DeviceScene& device) {
  if (!scene.camera.model->cameraPathEntranceAreaM2()) return scene.camera.model->cameraPathsAbsentBecause();
  bool seen = false, lightsPoints = false;
  for (const device::LightRecord& light : device.lights) {
    seen = seen || light.type == device::kLightDisk || light.type == device::kLightRect ||
           light.type == device::kLightObject;
    lightsPoints = lightsPoints || light.type != device::kLightLaser;
  }
  bool diffuse = false;
  for (const SceneObject& object : scene.objects)
    diffuse = diffuse || materialTypeUnit(object.material.type).connectsToCamera;
  if (seen || (diffuse && lightsPoints)) return "";
  return diffuse ? "no traced light but lasers, which camera paths cannot reach"
                 : "no traced light has an area to be seen, and no object is diffuse";
}

uint32_t estimatorsFor(const CompileOptions& options, const std::string& cameraPathsUseless) {
  uint32_t estimators = options.lightPaths ? device::kEstimatorLightPaths : 0u;
  if (options.cameraPaths && cameraPathsUseless.empty()) estimators |= device::kEstimatorCameraPaths;
  return estimators;
}

void setCameraPathWeights(const Scene& scene, CompiledScene& compiled) {
  DeviceScene& device = compiled.device;
  size_t traced = 0;
  for (const LightSummary& summary : compiled.summaries) {
    if (!summary.traced) continue;
    device::LightRecord& light = device.lights[traced];
    // The alias table draws a light with probability (its CDF width) / 2^64.
    const uint64_t next = traced + 1 < device.lights.size() ? device.lights[traced + 1].selectCdfLow : 0;
    const uint64_t width = next - light.selectCdfLow;  // mod 2^64; 0 only for a lone light: probability 1
    const double chosen = device.lights.size() == 1 || width == 0 ? 1.0 : double(width) * 0x1p-64;
    light.cameraPathWeight = float(summary.tracedPowerW / compiled.sampledPowerW / chosen);
    ++traced;
  }
  const auto entrance = scene.camera.model->cameraPathEntranceAreaM2();
  const double frontZ = scene.camera.model->frontZ();
  const double windowArea = double(compiled.film.storedPixelCount()) * compiled.film.pixelAreaM2;
  device.constants.cameraPathScale = entrance && frontZ > 0.0 ? float(windowArea * *entrance / (frontZ * frontZ)) : 0.0f;
}

const char* estimatorsDescription(uint32_t estimators) {
  switch (estimators) {
    case device::kEstimatorLightPaths: return "light paths";
    case device::kEstimatorCameraPaths: return "camera paths";
    default: return "light and camera paths, each path of light counted by one of them";
  }
}

uint64_t countsPerPathBound(const device::TraceConstants& c) {
  uint64_t events = 0;
  if (c.estimators & device::kEstimatorLightPaths) events += 1 + (c.connect ? c.maxBounces : 0);
  if (c.estimators & device::kEstimatorCameraPaths) events += 1 + uint64_t(c.maxBounces);
  return events * std::max<uint64_t>(c.wavelengthsPerPath, 1);  // each event counts every wavelength
}

}  // namespace spectrace
