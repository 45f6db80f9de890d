#pragma once
// The estimators a render runs (device_shared.h kEstimator*): light paths,
// camera paths (shaders/camera_path.h), or both; and what camera paths need
// from the host, their weights in the film's units.
#include <cstdint>
#include <string>

#include "compile/compile_scene.h"
#include "scene/scene.h"

namespace spectrace {

// Why camera paths could count nothing in this compiled scene (its camera
// model starts none, or no traced light can be seen or light a diffuse
// object), or "" when they can.
std::string cameraPathsUselessBecause(const Scene& scene, const DeviceScene& device);

// The kEstimator* bits for `options` in this scene: camera paths only where
// they can count something (cameraPathsUselessBecause is empty).
uint32_t estimatorsFor(const CompileOptions& options, const std::string& cameraPathsUseless);

// Camera paths' weights, once the lights' choice and the film's window are
// final: per light, its traced power over the sampled power over its exact
// probability of being chosen (the alias table's quantised one); for the
// camera, the stored window's sensor area times the entrance's over the
// entrance's distance squared (TraceConstants.cameraPathScale).
void setCameraPathWeights(const Scene& scene, CompiledScene& compiled);

// "light paths", "camera paths" or "light and camera paths (...)", for the
// summary.
const char* estimatorsDescription(uint32_t estimators);

// The most counts one path index can make: its beam one at the camera and,
// with connections, one more per bounce; its camera path one per vertex
// (a light sample at each diffuse vertex, or the emitter it sees).
uint64_t countsPerPathBound(const device::TraceConstants& constants);

}  // namespace spectrace
