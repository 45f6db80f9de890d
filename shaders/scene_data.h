// Reading the scene data (device_shared.h): 32-bit words by offset, floats
// as their bits. The includer provides readSceneWord (kernel_interface.h).
#ifndef SPECTRACE_SCENE_DATA_H
#define SPECTRACE_SCENE_DATA_H

FN float readSceneFloat(uint word) { return uintBitsToFloat(readSceneWord(word)); }

// aliasLookup (emit.h) over alias columns a unit keeps in the scene data,
// four words each (host/lights/light_shared.h, appendAliasColumns).
FN uint sceneAliasLookup(uint first, uint bits, uint64_t u) {
  uint column = bits == 0u ? 0u : uint(u >> (64u - bits));
  uint at = first + 4u * column;
  uint64_t threshold = joinWords(readSceneWord(at), readSceneWord(at + 1u));
  return (u << bits) < threshold ? column : readSceneWord(at + 2u);
}

#endif  // SPECTRACE_SCENE_DATA_H
