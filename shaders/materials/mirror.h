// Mirror material (kernel unit; host unit: host/materials/mirror_material.cpp):
// specular reflection, kept by the roulette at the wavelengths' reflectances
// (wavelengths.h: surviveReflectance; with one wavelength, reflected with
// probability rho).
#ifndef SPECTRACE_MATERIALS_MIRROR_H
#define SPECTRACE_MATERIALS_MIRROR_H

FN bool scatterMirror(Material material, SurfaceHit hit, uvec4 words, INOUT(PathWavelengths) w, INOUT(vec3) origin,
                      INOUT(vec3) direction, INOUT(bool) afterDiffuse) {
  if (!surviveReflectance(reflectancesAt(material, w), uniformFromWord(words.x), w)) return false;
  direction = reflected(direction, hit.facing);
  origin = offsetOffSurface(hit.point, hit.facing);
  afterDiffuse = false;
  return true;
}

#endif  // SPECTRACE_MATERIALS_MIRROR_H
