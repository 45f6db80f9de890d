// Dielectric material (kernel unit; host unit:
// host/materials/dielectric_material.cpp): reflects with the Fresnel
// probability at the beam's wavelength's Sellmeier index and refracts
// otherwise (Snell), into or out of its closed shape.
#ifndef SPECTRACE_MATERIALS_DIELECTRIC_H
#define SPECTRACE_MATERIALS_DIELECTRIC_H

// The Sellmeier index at a wavelength (nm); the host keeps poles out of the
// spectrum range.
FN float refractiveIndexAt(Material m, float lambda) { return sellmeierIndexAt(m.sellmeierB, m.sellmeierC, lambda); }

// Whether the index depends on the wavelength (any Sellmeier C set).
FN bool materialDisperses(Material m) {
  return m.type == kMaterialDielectric && (m.sellmeierC.x != 0.0f || m.sellmeierC.y != 0.0f || m.sellmeierC.z != 0.0f);
}

// A dispersive one keeps a path's hero wavelength only (wavelengths.h:
// keepHeroOnly): the others would leave in other directions.
FN void keepWavelengthsThrough(Material material, INOUT(PathWavelengths) w) {
  if (materialDisperses(material) && constants.wavelengthsPerPath > 1u) keepHeroOnly(w, constants.wavelengthsPerPath);
}

FN bool scatterDielectric(Material material, SurfaceHit hit, uvec4 words, INOUT(PathWavelengths) w,
                          INOUT(vec3) origin, INOUT(vec3) direction, INOUT(bool) afterDiffuse) {
  keepWavelengthsThrough(material, w);
  float choice = uniformFromWord(words.x);
  float index = refractiveIndexAt(material, w.lambda[0]);
  PRECISE float eta = hit.fromOutside ? 1.0f / index : index;
  PRECISE float cosIncident = -dot3(direction, hit.facing);
  PRECISE float sinSqTransmitted = eta * eta * max(1.0f - cosIncident * cosIncident, 0.0f);
  bool total = sinSqTransmitted >= 1.0f;  // total internal reflection
  PRECISE float cosTransmitted = total ? 0.0f : sqrt(1.0f - sinSqTransmitted);
  float fresnel = total ? 1.0f : fresnelDielectric(cosIncident, cosTransmitted, eta);
  if (choice < fresnel) {
    direction = reflected(direction, hit.facing);
    origin = offsetOffSurface(hit.point, hit.facing);
  } else {
    PRECISE vec3 refracted = direction * eta + hit.facing * (eta * cosIncident - cosTransmitted);
    PRECISE vec3 unit = refracted * (1.0f / sqrt(dot3(refracted, refracted)));
    direction = unit;
    origin = offsetOffSurface(hit.point, -hit.facing);
  }
  afterDiffuse = false;
  return true;
}

#endif  // SPECTRACE_MATERIALS_DIELECTRIC_H
