// Transport: what happens to a beam between its light and the camera when
// the scene has objects (objects.h). The beam goes from surface to surface,
// each meeting ("bounce") with its own Philox block (device_shared.h:
// kRngBlockBounce), until the camera counts or absorbs it, it leaves the
// scene, a surface absorbs it, or it meets more than maxBounces surfaces.
//
// Beams carry flux, so scattering is analog: a surface reflects a beam by
// Russian roulette on the reflectances at its wavelengths (with one
// wavelength, with probability rho and the weight kept), a dielectric
// reflects with the Fresnel probability at the hero wavelength and
// refracts otherwise. Camera
// connections carry fractional weights (as aimed area lights do, which
// scenes whose objects are all absorbers keep).
#ifndef SPECTRACE_TRANSPORT_H
#define SPECTRACE_TRANSPORT_H

#include "camera_connection.h"
#include "material.h"

// A beam that reached the sensor in `cell` (hitSensor), keeping
// `transmission` of its flux through the camera's glass (a lens system's):
// kept whole with that probability (its own Philox block), so a plain film
// still counts whole beams and the count is unbiased; its hero wavelength
// alone through dispersive glass (keepWavelengthsThroughCamera).
FN void countAtCamera(uint64_t beamIndex, uvec2 cell, float transmission, PathWavelengths w, float ratio,
                      float spareUniform, INOUT(BeamTally) tally) {
  if (transmission < 1.0f) {
    uvec4 words = philox4x32(constants.seed, beamIndex, kRngBlockLensTransmission);
    if (!(uniformFromWord(words.x) < transmission)) return;
  }
  keepWavelengthsThroughCamera(w);
  contributeCounts(tally, cell, w, sharesTimes(w, ratio), spareUniform);
}

// The beam from its light (origin, direction, weight ratio), with the
// wavelengths it carries, through the scene's objects to the camera. With
// diffuseFirstIsCameras, a beam whose first surface is diffuse ends there:
// camera paths count those paths (camera_path.h).
FN void transportBeam(uint64_t beamIndex, vec3 origin, vec3 direction, float ratio, PathWavelengths w,
                      float spareUniform, bool diffuseFirstIsCameras, INOUT(BeamTally) tally) {
  bool connect = constants.connect != 0u;
  bool afterDiffuse = false;
  // The count is made after the loop, where the beam leaves it for the
  // camera: lavapipe runs a loop's every branch on every pass, so a count
  // inside would cost each bounce of every beam.
  bool countIt = false;
  uvec2 countCell = uvec2(0u, 0u);
  float countTransmission = 1.0f;
  for (uint bounce = 0u; bounce <= constants.maxBounces; ++bounce) {
    ObjectHit hit;
    bool metObject = intersectObjects(origin, direction, 3.0e38f, false, hit);
    bool counted;
    uvec2 cell;
    float transmission;
    float toCamera = intersectCamera(origin, direction, w.lambda[0], counted, cell, transmission);
    if (toCamera >= 0.0f && (!metObject || toCamera <= hit.t)) {
      // A beam straight from a diffuse vertex is the connection's (counted
      // there), so analog counts take the others only.
      countIt = counted && ratio > 0.0f && !(connect && afterDiffuse);
      countCell = cell;
      countTransmission = transmission;
      break;
    }
    if (!metObject || bounce == constants.maxBounces) return;
    Primitive surface = readPrimitive(hit.primitive);
    Material material = readMaterial(surface.material);
    if (materialEndsEveryBeam(material)) return;
    if (bounce == 0u && diffuseFirstIsCameras && material.type == kMaterialDiffuse) return;
    PRECISE vec3 found = origin + direction * hit.t;
    vec3 n = primitiveNormal(surface, found);
    SurfaceHit at;
    at.point = pointOnSurface(surface, found, n);
    at.fromOutside = dot3(direction, n) < 0.0f;
    at.facing = at.fromOutside ? n : -n;  // towards the side the beam came from
    uvec4 words = philox4x32(constants.seed, beamIndex, kRngBlockBounce + 2u * bounce);
    if (!scatterAtSurface(material, at, words, beamIndex, bounce, ratio, w, tally, origin, direction, afterDiffuse))
      return;
  }
  if (countIt) countAtCamera(beamIndex, countCell, countTransmission, w, ratio, spareUniform, tally);
}

#endif  // SPECTRACE_TRANSPORT_H
