// The camera's models, dispatched like emit.h's lights: one kernel unit per
// model in cameras/<model>.h (host/camera/<model>_camera.cpp is its host
// side), chosen by constants.cameraType or, in a specialised pipeline, by
// the constant SPECTRACE_CAMERA_TYPE fixes.
#ifndef SPECTRACE_CAMERA_H
#define SPECTRACE_CAMERA_H

#include "cameras/bare_sensor.h"
#include "cameras/pinhole.h"
#include "cameras/thin_lens.h"

// Where a beam from beyond the camera's front plane, travelling towards -z,
// crosses the sensor plane, if the model lets it through; `flipped`: the
// model's image is inverted on the sensor, so the pixel mapping turns it
// upright.
FN bool cameraCrossing(vec3 origin, vec3 direction, OUT(vec2) onSensor, OUT(bool) flipped) {
  uint type = SPECTRACE_CAMERA_TYPE;
  flipped = type == kCameraPinhole || type == kCameraThinLens;
  if (type == kCameraPinhole) return pinholeCrossing(origin, direction, onSensor);
  if (type == kCameraThinLens) return thinLensCrossing(origin, direction, onSensor);
  return bareSensorCrossing(origin, direction, onSensor);
}

// A camera connection's end (light tracing: pbrt-v4's Camera::SampleWi,
// Mitsuba 3's Sensor::sample_direction) from two uniforms: a point of the
// model's entrance, uniform over it, and the entrance's area.
FN vec3 cameraConnectionPoint(float u, float v, OUT(float) area) {
  uint type = SPECTRACE_CAMERA_TYPE;
  if (type == kCameraPinhole || type == kCameraThinLens) return entranceDiskPoint(u, v, area);
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
