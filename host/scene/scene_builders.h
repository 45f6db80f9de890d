#pragma once
// Scenes built in code (benchmarks, tests): a bare sensor and lights, with
// the same defaults the scene loader applies.
#include "scene/scene.h"
#include "spectrum/spd.h"

namespace spectrace {

// A bare sensor at the origin looking along +z, spectrum 360-830 nm. Beams
// carry one wavelength (the loader's default is 4), so a film of unit
// weights counts hits, which these scenes' closed forms count; a caller
// that tests several wavelengths sets render.wavelengthsPerBeam.
inline Scene bareSensorScene(double widthM, double heightM, int pixelsX, int pixelsY, int bins = 32) {
  Scene scene;
  scene.render.wavelengthsPerBeam = 1;
  scene.spectrum = {360.0, 830.0, bins};
  scene.camera.sensorWidthM = widthM;
  scene.camera.sensorHeightM = heightM;
  scene.camera.pixelsX = pixelsX;
  scene.camera.pixelsY = pixelsY;
  return scene;
}

inline Light pointLight(glm::dvec3 position, double powerW, Spd spd, std::string spdLabel = "test") {
  Light light;
  light.type = LightType::Point;
  light.label = "/lights/0";
  light.position = position;
  light.powerW = powerW;
  light.spdLabel = std::move(spdLabel);
  light.spd = std::move(spd);
  return light;
}

// A disk, rect or laser (set radiusM or sizeM after), or a spot (set the
// cone), emitting along `direction`.
inline Light surfaceLight(LightType type, glm::dvec3 center, glm::dvec3 direction, double powerW, Spd spd,
                          std::string spdLabel = "test") {
  Light light = pointLight(center, powerW, std::move(spd), std::move(spdLabel));
  light.type = type;
  light.direction = direction;
  return light;
}

}  // namespace spectrace
