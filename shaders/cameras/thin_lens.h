// The thin lens (host/camera/thin_lens_camera.cpp): an ideal lens disk at
// cameraFrontZ = s in front of the sensor's centre, of radius squared
// cameraParams.x, focused at distance d; cameraParams.y = 1 - s/f = -s/d.
// Its image is inverted on the sensor.
#ifndef SPECTRACE_CAMERAS_THIN_LENS_H
#define SPECTRACE_CAMERAS_THIN_LENS_H

FN float thinLensRadiusSq() { return constants.cameraParams.x; }

// Where a beam from beyond the lens plane travelling towards -z lands on
// the sensor, when it passes the lens disk: at lens point p with slope
// m = direction.xy / -direction.z, p (1 - s/f) + s m (the chief ray of
// slope m meets the focal plane where every beam of that slope does).
FN bool thinLensCrossing(vec3 origin, vec3 direction, OUT(vec2) onSensor) {
  onSensor = vec2(0.0f, 0.0f);
  PRECISE float ta = (origin.z - constants.cameraFrontZ) / -direction.z;
  PRECISE float ax = origin.x + ta * direction.x;
  PRECISE float ay = origin.y + ta * direction.y;
  if (!(ax * ax + ay * ay <= thinLensRadiusSq())) return false;
  PRECISE float ts = constants.cameraFrontZ / -direction.z;
  PRECISE float hx = ax * constants.cameraParams.y + ts * direction.x;
  PRECISE float hy = ay * constants.cameraParams.y + ts * direction.y;
  onSensor = vec2(hx, hy);
  return true;
}

// A camera connection's end: a uniform point of the lens disk, and the
// disk's area (the density's inverse). The connection's weight is the
// pinhole's: the ideal lens passes all the flux that reaches the point.
FN vec3 thinLensConnectionPoint(float u, float v, OUT(float) area) {
  PRECISE float radius = sqrt(thinLensRadiusSq());
  vec2 disk = sampleDisk(u, v, radius);
  PRECISE float diskArea = 3.14159265358979f * thinLensRadiusSq();
  area = diskArea;
  return vec3(disk.x, disk.y, constants.cameraFrontZ);
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
