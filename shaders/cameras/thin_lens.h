// The thin lens (host/camera/thin_lens_camera.cpp): an ideal lens disk at
// cameraFrontZ = s in front of the sensor's centre, of radius squared
// cameraParams.x (cameras/entrance_disk.h), focused at distance d;
// cameraParams.y = 1 - s/f = -s/d. Camera connections end on a uniform
// point of the disk with the pinhole's weight: the ideal lens passes all
// the flux that reaches the point.
// Its image is inverted on the sensor.
#ifndef SPECTRACE_CAMERAS_THIN_LENS_H
#define SPECTRACE_CAMERAS_THIN_LENS_H

#include "cameras/entrance_disk.h"

// Where a beam from beyond the lens plane travelling towards -z lands on
// the sensor, when it passes the lens disk: at lens point p with slope
// m = direction.xy / -direction.z, p (1 - s/f) + s m (the chief ray of
// slope m meets the focal plane where every beam of that slope does).
FN bool thinLensCrossing(vec3 origin, vec3 direction, OUT(vec2) onSensor) {
  onSensor = vec2(0.0f, 0.0f);
  vec2 p;
  if (!crossesEntranceDisk(origin, direction, p)) return false;
  PRECISE float ts = constants.cameraFrontZ / -direction.z;
  PRECISE float hx = p.x * constants.cameraParams.y + ts * direction.x;
  PRECISE float hy = p.y * constants.cameraParams.y + ts * direction.y;
  onSensor = vec2(hx, hy);
  return true;
}

// The inverse of the crossing for a camera path: the light that reaches
// sensor point x through lens point p arrived with slope
// m = (x - p (1 - s/f)) / s, so the path leaves p along (-m, 1).
FN vec3 thinLensPathDirection(vec3 onSensor, vec3 entrance) {
  PRECISE float s = constants.cameraFrontZ;
  PRECISE float mx = (onSensor.x - entrance.x * constants.cameraParams.y) / s;
  PRECISE float my = (onSensor.y - entrance.y * constants.cameraParams.y) / s;
  PRECISE vec3 along = vec3(-mx, -my, 1.0f);
  return along * (1.0f / sqrt(dot3(along, along)));
}

#endif  // SPECTRACE_CAMERAS_THIN_LENS_H
