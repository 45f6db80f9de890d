// The bare sensor (host/camera/bare_sensor_camera.cpp): nothing before it.
// cameraFrontZ is 0, the sensor's own plane.
#ifndef SPECTRACE_CAMERAS_BARE_SENSOR_H
#define SPECTRACE_CAMERAS_BARE_SENSOR_H

// Where a beam from z > 0 travelling towards -z crosses the sensor plane
// (always: nothing stands in its way).
FN bool bareSensorCrossing(vec3 origin, vec3 direction, OUT(vec2) onSensor) {
  PRECISE float t = origin.z / -direction.z;
  PRECISE float hx = origin.x + t * direction.x;
  PRECISE float hy = origin.y + t * direction.y;
  onSensor = vec2(hx, hy);
  return true;
}

// A camera connection's end: a uniform point of the sensor, and the
// sensor's area (the density's inverse).
FN vec3 bareSensorConnectionPoint(float u, float v, OUT(float) area) {
  PRECISE vec2 onSensor = (vec2(u, v) * 2.0f - 1.0f) * constants.sensorHalfSize;
  PRECISE float sensorArea = 4.0f * constants.sensorHalfSize.x * constants.sensorHalfSize.y;
  area = sensorArea;
  return vec3(onSensor.x, onSensor.y, 0.0f);
}

#endif  // SPECTRACE_CAMERAS_BARE_SENSOR_H
