// Diffuse material (kernel unit; host unit: host/materials/diffuse_material.cpp):
// Lambertian reflection with probability rho (the reflectance at the
// beam's wavelength), cosine-distributed about the facing normal; with
// camera connections on, it first connects its vertex to the camera.
#ifndef SPECTRACE_MATERIALS_DIFFUSE_H
#define SPECTRACE_MATERIALS_DIFFUSE_H

FN bool scatterDiffuse(Material material, SurfaceHit hit, uvec4 words, uint64_t beamIndex, uint bounce, float ratio,
                       float lambda, uint bin, INOUT(BeamTally) tally, INOUT(vec3) origin, INOUT(vec3) direction,
                       INOUT(bool) afterDiffuse) {
  float choice = uniformFromWord(words.x);
  float rho = reflectanceAt(material, lambda);
  if (constants.connect != 0u)
    connectToCamera(beamIndex, bounce, hit.point, hit.facing, rho * ratio, lambda, bin, tally);
  if (!(choice < rho)) return false;
  vec3 tangent;
  vec3 bitangent;
  frameAround(hit.facing, tangent, bitangent);
  direction = toFrame(sampleCosineHemisphere(uniformFromWord(words.y), uniformFromWord(words.z)), tangent, bitangent,
                      hit.facing);
  origin = offsetOffSurface(hit.point, hit.facing);
  afterDiffuse = true;
  return true;
}

#endif  // SPECTRACE_MATERIALS_DIFFUSE_H
