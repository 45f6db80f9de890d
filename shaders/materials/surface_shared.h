// What more than one material's kernel unit uses: the reflectance table
// (diffuse, mirror; host/materials/material_shared.cpp packs it) and the
// specular reflection (mirror, dielectric).
#ifndef SPECTRACE_MATERIALS_SURFACE_SHARED_H
#define SPECTRACE_MATERIALS_SURFACE_SHARED_H

// Whether `m` is of `type` (kMaterial*); always false for a type the
// pipeline was specialised without (kernel_features.h).
FN bool isMaterial(Material m, uint type) { return SPECTRACE_MATERIAL_ENABLED(type) && m.type == type; }

// A material's reflectance at a wavelength: linear between its table's
// nodes, holding the end values outside.
FN float reflectanceAt(Material m, float lambda) {
  PRECISE float x = (lambda - m.reflectanceLambda0) * m.reflectanceNodesPerNm;
  float last = float(m.reflectanceCount - 1u);
  float clamped = min(max(x, 0.0f), last);
  uint node = min(uint(clamped), m.reflectanceCount > 1u ? m.reflectanceCount - 2u : 0u);
  float a = readSceneFloat(m.reflectanceFirst + node);
  float b = m.reflectanceCount > 1u ? readSceneFloat(m.reflectanceFirst + node + 1u) : a;
  PRECISE float t = clamped - float(node);
  PRECISE float value = a + (b - a) * t;
  return value;
}

// The reflectance at each wavelength a path carries (0 for those it no
// longer carries).
FN WavelengthFactors reflectancesAt(Material m, PathWavelengths w) {
  WavelengthFactors rho;
  for (uint j = 0u; j < kMaxWavelengthsPerPath; ++j) rho.value[j] = 0.0f;
  for (uint j = 0u; j < constants.wavelengthsPerPath; ++j)
    if (w.share[j] > 0.0f) rho.value[j] = reflectanceAt(m, w.lambda[j]);
  return rho;
}

FN vec3 reflected(vec3 direction, vec3 n) {
  PRECISE vec3 r = direction - n * (2.0f * dot3(direction, n));
  return r;
}

#endif  // SPECTRACE_MATERIALS_SURFACE_SHARED_H
