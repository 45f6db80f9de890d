// The entrance disk a pinhole and a thin lens share: a disk on the view
// axis at cameraFrontZ, of radius squared cameraParams.x.
#ifndef SPECTRACE_CAMERAS_ENTRANCE_DISK_H
#define SPECTRACE_CAMERAS_ENTRANCE_DISK_H

FN float entranceDiskRadiusSq() { return constants.cameraParams.x; }

// Where a beam from beyond the disk's plane travelling towards -z crosses
// that plane, and whether inside the disk.
FN bool crossesEntranceDisk(vec3 origin, vec3 direction, OUT(vec2) atDisk) {
  PRECISE float ta = (origin.z - constants.cameraFrontZ) / -direction.z;
  PRECISE float ax = origin.x + ta * direction.x;
  PRECISE float ay = origin.y + ta * direction.y;
  atDisk = vec2(ax, ay);
  return ax * ax + ay * ay <= entranceDiskRadiusSq();
}

// A camera connection's end: a uniform point of the disk, and the disk's
// area (the density's inverse).
FN vec3 entranceDiskPoint(float u, float v, OUT(float) area) {
  PRECISE float radius = sqrt(entranceDiskRadiusSq());
  vec2 disk = sampleDisk(u, v, radius);
  PRECISE float diskArea = 3.14159265358979f * entranceDiskRadiusSq();
  area = diskArea;
  return vec3(disk.x, disk.y, constants.cameraFrontZ);
}

#endif  // SPECTRACE_CAMERAS_ENTRANCE_DISK_H
