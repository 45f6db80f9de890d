// Diffuse material (kernel unit; host unit: host/materials/diffuse_material.cpp):
// Lambertian reflection, cosine-distributed about the facing normal, kept by
// the roulette at the wavelengths' reflectances (wavelengths.h:
// surviveReflectance; with one wavelength, reflected with probability
// rho); with camera connections on, it first connects its vertex to the
// camera.
#ifndef SPECTRACE_MATERIALS_DIFFUSE_H
#define SPECTRACE_MATERIALS_DIFFUSE_H

// A cosine-distributed direction about the side `hit.facing` from the
// bounce's words y and z, leaving from just off the surface (beams and
// camera paths alike).
FN void bounceDiffusely(SurfaceHit hit, uvec4 words, OUT(vec3) origin, OUT(vec3) direction) {
  vec3 tangent;
  vec3 bitangent;
  frameAround(hit.facing, tangent, bitangent);
  direction = toFrame(sampleCosineHemisphere(uniformFromWord(words.y), uniformFromWord(words.z)), tangent, bitangent,
                      hit.facing);
  origin = offsetOffSurface(hit.point, hit.facing);
}

FN bool scatterDiffuse(Material material, SurfaceHit hit, uvec4 words, uint64_t beamIndex, uint bounce, float ratio,
                       INOUT(PathWavelengths) w, INOUT(BeamTally) tally, INOUT(vec3) origin, INOUT(vec3) direction,
                       INOUT(bool) afterDiffuse) {
  WavelengthFactors rho = reflectancesAt(material, w);
  if (constants.connect != 0u) connectToCamera(beamIndex, bounce, hit.point, hit.facing, ratio, rho, w, tally);
  if (!surviveReflectance(rho, uniformFromWord(words.x), w)) return false;
  bounceDiffusely(hit, words, origin, direction);
  afterDiffuse = true;
  return true;
}

#endif  // SPECTRACE_MATERIALS_DIFFUSE_H
