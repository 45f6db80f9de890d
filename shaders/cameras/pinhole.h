// The pinhole (host/camera/pinhole_camera.cpp): an aperture disk at
// cameraFrontZ in front of the sensor's centre, of radius squared
// cameraParams.x (cameras/entrance_disk.h). Its image is inverted on the
// sensor.
#ifndef SPECTRACE_CAMERAS_PINHOLE_H
#define SPECTRACE_CAMERAS_PINHOLE_H

#include "cameras/entrance_disk.h"

// Where a beam from beyond the aperture plane travelling towards -z crosses
// the sensor plane, when it passes the aperture disk.
FN bool pinholeCrossing(vec3 origin, vec3 direction, OUT(vec2) onSensor) {
  onSensor = vec2(0.0f, 0.0f);
  vec2 a;
  if (!crossesEntranceDisk(origin, direction, a)) return false;
  PRECISE float ts = constants.cameraFrontZ / -direction.z;
  PRECISE float hx = a.x + ts * direction.x;
  PRECISE float hy = a.y + ts * direction.y;
  onSensor = vec2(hx, hy);
  return true;
}

#endif  // SPECTRACE_CAMERAS_PINHOLE_H
