// Materials, dispatched like emit.h's lights: one kernel unit per kind in
// materials/<kind>.h (host/materials/<kind>_material.cpp is its host side),
// chosen by the Material record's type. A unit reads the beam's surface hit
// and its bounce's Philox words, and either sends the beam on (a new origin
// and direction) or ends it. The absorber has no kernel unit: it ends every
// beam before the hit's point is worked out.
#ifndef SPECTRACE_MATERIAL_H
#define SPECTRACE_MATERIAL_H

// Where a beam meets a surface, for the material's unit.
struct SurfaceHit {
  vec3 point;        // on the surface (objects.h: pointOnSurface)
  vec3 facing;       // the unit normal on the side the beam came from
  bool fromOutside;  // the beam came from the side the normal points to
};

#include "wavelengths.h"
#include "materials/surface_shared.h"
#include "materials/diffuse.h"
#include "materials/mirror.h"
#include "materials/dielectric.h"

// Whether the material ends every beam that meets it.
FN bool materialEndsEveryBeam(Material material) { return material.type == kMaterialAbsorber; }

// What the material does to the beam (origin, direction, the wavelengths
// it carries) at `hit`, through its kind's unit; false: the beam ends
// there. `words` are the bounce's Philox block (kRngBlockBounce + 2 bounce).
FN bool scatterAtSurface(Material material, SurfaceHit hit, uvec4 words, uint64_t beamIndex, uint bounce, float ratio,
                         INOUT(PathWavelengths) w, INOUT(BeamTally) tally, INOUT(vec3) origin, INOUT(vec3) direction,
                         INOUT(bool) afterDiffuse) {
  if (isMaterial(material, kMaterialDiffuse))
    return scatterDiffuse(material, hit, words, beamIndex, bounce, ratio, w, tally, origin, direction, afterDiffuse);
  if (isMaterial(material, kMaterialMirror))
    return scatterMirror(material, hit, words, w, origin, direction, afterDiffuse);
  if (isMaterial(material, kMaterialDielectric))
    return scatterDielectric(material, hit, words, w, origin, direction, afterDiffuse);
  return false;
}

#endif  // SPECTRACE_MATERIAL_H
