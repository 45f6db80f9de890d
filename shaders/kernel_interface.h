// The includer contract of the shared kernel (trace.h and what it
// includes). Each includer (shaders/trace_beams.comp, and the CPU instance
// host/kernel/beam_kernel.h) provides, besides the types of
// device_shared.h and a `constants` of type TraceConstants:
//   uvec4 philox4x32(uint64_t seed, uint64_t index, uint block)  random words
//   AliasColumn readAliasColumn(uint column)  light choice and spectral tables
//   LightRecord readLight(uint light)
//   SpectralInterval readInterval(uint interval)
//   vec3 readCmf(uint node)                   the observer's CMF table
//   Primitive readPrimitive(uint primitive)   scene objects (transport.h)
//   BvhNode readBvhNode(uint node)
//   void prefetchBvhChild(uint child, uint count)
//                                             a hint that a BVH node (count
//                                             0) or a leaf's primitives will
//                                             be read soon; may do nothing
//   Material readMaterial(uint material)
//   uint readSceneWord(uint word)             the scene data (device_shared.h)
//   void addCount(uint chunk, uint counter, uint64_t amount)
//                                             adds to one film counter
//   void addWideCount(uint chunk, uint counter, WideCount amount)
//                                             adds to a two-word counter
//                                             (words counter, counter + 1)
// GLSL gets the prototypes below, so a missing function fails at the
// shader's compile; C++ checks the same list with a concept.
#ifndef SPECTRACE_KERNEL_INTERFACE_H
#define SPECTRACE_KERNEL_INTERFACE_H

#ifdef __cplusplus
#include <concepts>
#include <cstdint>
namespace spectrace::device {
template <typename K>
concept KernelIncluder = requires(K& k, uint32_t i, uint64_t amount) {
  { K::philox4x32(amount, amount, i) };
  { k.readAliasColumn(i) } -> std::same_as<AliasColumn>;
  { k.readLight(i) } -> std::same_as<LightRecord>;
  { k.readInterval(i) } -> std::same_as<SpectralInterval>;
  { k.readCmf(i) };
  { k.readPrimitive(i) } -> std::same_as<Primitive>;
  { k.readBvhNode(i) } -> std::same_as<BvhNode>;
  { k.prefetchBvhChild(i, i) };
  { k.readMaterial(i) } -> std::same_as<Material>;
  { k.readSceneWord(i) } -> std::same_as<uint32_t>;
  { k.addCount(i, i, amount) };
  { k.addWideCount(i, i, WideCount{}) };
};
}  // namespace spectrace::device
#else
uvec4 philox4x32(uint64_t seed, uint64_t index, uint block);
AliasColumn readAliasColumn(uint column);
LightRecord readLight(uint light);
SpectralInterval readInterval(uint interval);
vec3 readCmf(uint node);
Primitive readPrimitive(uint primitive);
BvhNode readBvhNode(uint node);
void prefetchBvhChild(uint child, uint count);
Material readMaterial(uint material);
uint readSceneWord(uint word);
void addCount(uint chunk, uint counter, uint64_t amount);
void addWideCount(uint chunk, uint counter, WideCount amount);
#endif

#endif  // SPECTRACE_KERNEL_INTERFACE_H
