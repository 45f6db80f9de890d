// Mirror material (kernel unit; host unit: host/materials/mirror_material.cpp):
// specular reflection with probability rho (the reflectance at the beam's
// wavelength).
#ifndef SPECTRACE_MATERIALS_MIRROR_H
#define SPECTRACE_MATERIALS_MIRROR_H

FN bool scatterMirror(Material material, SurfaceHit hit, uvec4 words, float lambda, INOUT(vec3) origin,
                      INOUT(vec3) direction, INOUT(bool) afterDiffuse) {
  float choice = uniformFromWord(words.x);
  if (!(choice < reflectanceAt(material, lambda))) return false;
  direction = reflected(direction, hit.facing);
  origin = offsetOffSurface(hit.point, hit.facing);
  afterDiffuse = false;
  return true;
}

#endif  // SPECTRACE_MATERIALS_MIRROR_H
