// The pinhole (host/camera/pinhole_camera.cpp): an aperture disk at
// cameraFrontZ in front of the sensor's centre, of radius squared
// cameraParams.x. Its image is inverted on the sensor.
#ifndef SPECTRACE_CAMERAS_PINHOLE_H
#define SPECTRACE_CAMERAS_PINHOLE_H

FN float pinholeRadiusSq() { return constants.cameraParams.x; }

// Where a beam from beyond the aperture plane travelling towards -z crosses
// the sensor plane, when it passes the aperture disk.
FN bool pinholeCrossing(vec3 origin, vec3 direction, OUT(vec2) onSensor) {
  onSensor = vec2(0.0f, 0.0f);
  PRECISE float ta = (origin.z - constants.cameraFrontZ) / -direction.z;
  PRECISE float ax = origin.x + ta * direction.x;
  PRECISE float ay = origin.y + ta * direction.y;
  if (!(ax * ax + ay * ay <= pinholeRadiusSq())) return false;
  PRECISE float ts = constants.cameraFrontZ / -direction.z;
  PRECISE float hx = ax + ts * direction.x;
  PRECISE float hy = ay + ts * direction.y;
  onSensor = vec2(hx, hy);
  return true;
}

// A camera connection's end: a uniform point of the aperture disk, and the
// disk's area (the density's inverse).
FN vec3 pinholeConnectionPoint(float u, float v, OUT(float) area) {
  PRECISE float radius = sqrt(pinholeRadiusSq());
  vec2 disk = sampleDisk(u, v, radius);
  PRECISE float diskArea = 3.14159265358979f * pinholeRadiusSq();
  area = diskArea;
  return vec3(disk.x, disk.y, constants.cameraFrontZ);
}

#endif  // SPECTRACE_CAMERAS_PINHOLE_H
