// The camera's models, dispatched like emit.h's lights: one kernel unit per
// model in cameras/<model>.h (host/camera/<model>_camera.cpp is its host
// side), chosen by constants.cameraType or, in a specialised pipeline, by
// the constant SPECTRACE_CAMERA_TYPE fixes.
#ifndef SPECTRACE_CAMERA_H
#define SPECTRACE_CAMERA_H

#include "cameras/bare_sensor.h"
#include "cameras/pinhole.h"
#include "cameras/thin_lens.h"
#include "cameras/lens_system.h"

// Where a beam from beyond the camera's front plane, travelling towards -z,
// at wavelength lambda (nm), crosses the sensor plane, if the model lets it
// through; `flipped`: the model's image is inverted on the sensor, so the
// pixel mapping turns it upright; `transmission`: the share of the beam's
// flux that gets there (1 but through a lens system's glass).
FN bool cameraCrossing(vec3 origin, vec3 direction, float lambda, OUT(vec2) onSensor, OUT(bool) flipped,
                       OUT(float) transmission) {
  uint type = SPECTRACE_CAMERA_TYPE;
  flipped = type == kCameraPinhole || type == kCameraThinLens || type == kCameraLensSystem;
  transmission = 1.0f;
  if (type == kCameraPinhole) return pinholeCrossing(origin, direction, onSensor);
  if (type == kCameraThinLens) return thinLensCrossing(origin, direction, onSensor);
  if (type == kCameraLensSystem) return lensSystemCrossing(origin, direction, lambda, onSensor, transmission);
  return bareSensorCrossing(origin, direction, onSensor);
}

// Whether the model's crossing depends on the wavelength (a lens system
// with a dispersive glass).
FN bool cameraDisperses() {
  return SPECTRACE_CAMERA_TYPE == kCameraLensSystem && constants.cameraParams.w != 0.0f;
}

// The half width and height of the camera's body (objects.h:
// intersectCamera): the sensor's, or a lens system's barrel where wider.
FN vec2 cameraBodyHalfSize() {
  if (SPECTRACE_CAMERA_TYPE == kCameraLensSystem) return vec2(constants.cameraParams.y, constants.cameraParams.z);
  return constants.sensorHalfSize;
}

// A camera connection's end (light tracing: pbrt-v4's Camera::SampleWi,
// Mitsuba 3's Sensor::sample_direction) from two uniforms: a point of the
// model's entrance, uniform over it, and the entrance's area.
FN vec3 cameraConnectionPoint(float u, float v, OUT(float) area) {
  uint type = SPECTRACE_CAMERA_TYPE;
  if (type == kCameraPinhole || type == kCameraThinLens || type == kCameraLensSystem)
    return entranceDiskPoint(u, v, area);
  return bareSensorConnectionPoint(u, v, area);
}

// A camera path's direction into the scene from entrance point `entrance`,
// for the sensor point `onSensor` (the unit vector `throughEntrance` points
// from it to `entrance`): where the light arriving at that sensor point
// through that entrance point comes from.
FN vec3 cameraPathDirection(vec3 onSensor, vec3 entrance, vec3 throughEntrance) {
  uint type = SPECTRACE_CAMERA_TYPE;
  if (type == kCameraThinLens) return thinLensPathDirection(onSensor, entrance);
  return throughEntrance;
}

#endif  // SPECTRACE_CAMERA_H
