// Transport: what happens to a beam between its light and the camera.
// Nothing stands there yet, so every beam goes on unchanged; surfaces,
// mirrors and glass will intersect and scatter it here, each bounce with
// its own Philox block.
#ifndef SPECTRACE_TRANSPORT_H
#define SPECTRACE_TRANSPORT_H

// Returns whether the beam still travels towards the camera, with its
// (possibly new) origin, direction and weight ratio.
FN bool transportBeam(uint64_t beamIndex, INOUT(vec3) origin, INOUT(vec3) direction, INOUT(float) ratio) {
  UNUSED(beamIndex);
  UNUSED(origin);
  UNUSED(direction);
  UNUSED(ratio);
  return true;
}

#endif  // SPECTRACE_TRANSPORT_H
