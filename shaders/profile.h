// The bench's cost profile (spectrace bench, "Profile"): the kernel cut
// after one of its stages (device_shared.h, ProfileStage), built by calling
// trace.h's own functions with the same random words, so it follows the
// kernel as that changes. The stages run in the order, with the
// wavelength drawn for every beam, where traceBeam draws it for counted
// beams only: each stage's row is that stage's whole cost. Never used to
// render. Included after trace.h.
#ifndef SPECTRACE_PROFILE_H
#define SPECTRACE_PROFILE_H

// A word that depends on everything a truncated stage computed.
FN uint profileMix(uint hash, uint word) { return (hash ^ word) * 0x9E3779B1u + 0x7F4A7C15u; }

// Keeps a truncated stage's results alive: the compiler cannot drop work
// whose hash guards a write, and the hash equals the constant for about
// one beam in 2^32 (which then adds one to the film's first counter).
FN bool profileKeep(uint hash) {
  if (hash == 0x5EC7AC3Eu) addCount(0u, 0u, 1ul);
  return false;
}

// The objects profile's first stage: traceLightPath up to transportBeam's
// first intersectObjects, emission aimed as the kernel aims it, so the
// next stage (the whole kernel, no connections) adds the rest of the path.
FN bool profileFirstHit(uint64_t beamIndex) {
  LightRecord light = readLight(chooseLight(constants.seed, beamIndex, kRngBlockLight));
  uvec4 geometry = philox4x32(constants.seed, beamIndex, kRngBlockGeometry);
  vec3 origin;
  vec3 direction;
  float ratio = emitLightBeam(light, geometry, beamIndex, origin, direction);
  uvec4 spectral = philox4x32(constants.seed, beamIndex, kRngBlockSpectral);
  PathWavelengths w = drawPathWavelengths(light, joinWords(spectral.x, spectral.y), uniformFromWord(spectral.z),
                                          constants.wavelengthsPerPath);
  ObjectHit hit;
  bool met = intersectObjects(origin, direction, 3.0e38f, false, hit);
  uint hash = profileMix(floatBitsToUint(ratio) ^ spectral.w, floatBitsToUint(w.lambda[0]) ^ w.bin[0]);
  hash = profileMix(hash, met ? floatBitsToUint(hit.t) ^ hit.primitive : 1u);
  return profileKeep(hash);
}

// Beam `beamIndex` through the kernel up to and including `stage`. Returns
// whether it was counted (only stages from kProfileStageCounting count).
// Stages up to kProfileStageColour emit unaimed beams with unit weight;
// kProfileStageCounting assumes the tracer switched exact colour off.
FN bool profileBeam(uint64_t beamIndex, uint stage) {
  if (stage == kProfileStageObjectsFirstHit) return profileFirstHit(beamIndex);
  // The tracer switched connections off for the no-connection stage.
  if (stage >= kProfileStageFull) return traceAndCountBeam(beamIndex);
  uvec4 spectral = philox4x32(constants.seed, beamIndex, kRngBlockSpectral);
  uvec4 geometry = philox4x32(constants.seed, beamIndex, kRngBlockGeometry);
  uint hash = profileMix(profileMix(spectral.x ^ spectral.y, spectral.z ^ spectral.w), geometry.x ^ geometry.y);
  hash = profileMix(hash, geometry.z ^ geometry.w);
  if (stage == kProfileStagePhilox) return profileKeep(hash);

  LightRecord light = readLight(chooseLight(constants.seed, beamIndex, kRngBlockLight));
  hash = profileMix(hash, light.spectralFirst ^ light.spectralCount ^ light.type);
  if (stage == kProfileStageLight) return profileKeep(hash);

  float lambda = drawWavelength(light, joinWords(spectral.x, spectral.y), uniformFromWord(spectral.z));
  // As traceBeam: the bin of the full spectrum, then among the stored bins.
  uint bin = storedBinOf(lambda);
  hash = profileMix(profileMix(hash, floatBitsToUint(lambda)), bin);
  if (stage == kProfileStageWavelength) return profileKeep(hash);

  vec3 origin;
  vec3 direction;
  light.aimed = 0u;  // aiming belongs to the last stage
  float ratio = emitLightBeam(light, geometry, beamIndex, origin, direction);
  hash = profileMix(hash, floatBitsToUint(origin.x) ^ floatBitsToUint(origin.y) ^ floatBitsToUint(origin.z));
  hash = profileMix(hash, floatBitsToUint(direction.x) ^ floatBitsToUint(direction.y) ^ floatBitsToUint(direction.z));
  hash = profileMix(hash, floatBitsToUint(ratio));
  if (stage == kProfileStageEmission) return profileKeep(hash);

  uvec2 cell;
  float transmission;
  bool hit = hitSensor(origin, direction, lambda, cell, transmission);
  if (stage == kProfileStageSensor) return profileKeep(profileMix(hash, hit ? cell.x ^ (cell.y << 16u) : 0u));

  // Counting with unit weight; exact colour as the tracer set it.
  return hit && countBeam(cell, bin, lambda, 1.0f, uniformFromWord(spectral.w));
}

#endif  // SPECTRACE_PROFILE_H
