// The trace shader's text (trace_beams.comp, trace_camera_paths.comp, and
// their bench-only *_profile.comp variants): beam generation and counting,
// one invocation per path index, through the shared kernel (trace.h). Hits
// are counted with 64-bit integer atomics (exact, order-independent; float
// atomics stop growing at 2^24).
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_atomic_int64 : require
#include "device_shared.h"
#include "kernel_lang.h"
#include "kernel_interface.h"
#include "packed_bvh_node.h"

layout(local_size_x_id = kSpecWorkgroupSize) in;
layout(constant_id = kSpecRecordBeams) const uint recordBeams = 0u;
// Scene specialisation (device_shared.h: SpecConstantId); the defaults give
// the general pipeline, which decides everything at run time.
layout(constant_id = kSpecLightTypes) const uint enabledLightTypes = kAllLightTypes;  // bit per light type
layout(constant_id = kSpecSelectLight) const uint selectLight = 1u;  // 0: one light, no choice
layout(constant_id = kSpecCameraType) const uint cameraTypeMode = kCameraTypeAtRunTime;  // kCamera*, or at run time
layout(constant_id = kSpecExactColour) const uint exactColourMode = 2u;  // 0 off, 1 on, 2 run time
layout(constant_id = kSpecAim) const uint aimMode = 2u;              // 0 no light aimed, 1 some, 2 run time
// Always set from the film (not a scene feature).
layout(constant_id = kSpecHistogramChunks) const uint histogramChunks = kMaxHistogramChunks + 1u;
layout(constant_id = kSpecCountBeams) const uint countBeamsOnDevice = 1u;
// Scene objects: 0 none (transport compiled out), 1 some, 2 decided at run
// time. The host always sets the scene's value, the general pipeline too:
// a scene without objects never reads the object buffers either way.
layout(constant_id = kSpecObjects) const uint objectsMode = 2u;
// A bit per primitive type and per material type present (objects.h,
// material.h); the defaults keep every type.
layout(constant_id = kSpecPrimitiveTypes) const uint enabledPrimitiveTypes = kAllPrimitiveTypes;
layout(constant_id = kSpecMaterialTypes) const uint enabledMaterialTypes = kAllMaterialTypes;
// Camera paths (camera_path.h): 0 none, 1 some, 2 decided at run time; the
// host always sets the scene's value.
layout(constant_id = kSpecCameraPaths) const uint cameraPathsMode = 2u;
#define SPECTRACE_LIGHT_ENABLED(type) ((enabledLightTypes & (1u << (type))) != 0u)
#define SPECTRACE_SELECT_LIGHT (selectLight != 0u && constants.lightCount > 1u)
#define SPECTRACE_CAMERA_TYPE (cameraTypeMode == kCameraTypeAtRunTime ? constants.cameraType : cameraTypeMode)
#define SPECTRACE_AIM (aimMode != 0u)
#define SPECTRACE_EXACT_COLOUR (exactColourMode == 2u ? constants.exactColour != 0u : exactColourMode == 1u)
// A weighted film is the one whose beams are counted on the device.
#define SPECTRACE_WEIGHTED (countBeamsOnDevice != 0u && constants.weighted != 0u)
#ifdef SPECTRACE_WITH_CAMERA_PATHS
#define SPECTRACE_CAMERA_PATHS \
  (cameraPathsMode == 2u ? (constants.estimators & kEstimatorCameraPaths) != 0u : cameraPathsMode == 1u)
#else
#define SPECTRACE_CAMERA_PATHS false
#endif
#define SPECTRACE_OBJECTS (objectsMode == 2u ? constants.objectPrimitives > 0u : objectsMode == 1u)
#define SPECTRACE_PRIMITIVE_ENABLED(type) ((enabledPrimitiveTypes & (1u << (type))) != 0u)
#define SPECTRACE_MATERIAL_ENABLED(type) ((enabledMaterialTypes & (1u << (type))) != 0u)
#define SPECTRACE_RECORDING (recordBeams != 0u)
#define SPECTRACE_SINGLE_CHUNK (histogramChunks == 1u)

// The constants, read by every beam, in a uniform buffer: lavapipe loads
// uniform-buffer values once per group of lanes; storage-buffer loads go
// lane by lane (host/backend/uniform_tables.h has the measurement).
layout(set = 0, binding = kBindingTraceConstants, scalar) uniform TraceConstantsBlock {
  TraceConstants constants;
};
layout(set = 0, binding = kBindingLights, scalar) readonly buffer LightBlock {
  LightRecord lights[];
};
layout(set = 0, binding = kBindingSpectralIntervals, scalar) readonly buffer SpectralBlock {
  SpectralInterval intervals[];
};
layout(set = 0, binding = kBindingHistogram, scalar) buffer HistogramChunk {
  uint64_t counts[];
} histogram[kMaxHistogramChunks];
layout(set = 0, binding = kBindingBeamRecords, scalar) writeonly buffer BeamRecordBlock {
  BeamRecord beamRecords[];
};
layout(set = 0, binding = kBindingAliasColumns, scalar) readonly buffer AliasBlock {
  AliasColumn aliasColumns[];
};
layout(set = 0, binding = kBindingCmfTable, scalar) readonly buffer CmfBlock {
  vec3 cmfTable[];
};
// The tables again as uniform buffers, sized by the host (kSpecUniform*),
// read instead of the storage buffers above when uniformTables is 1.
layout(constant_id = kSpecUniformTables) const uint uniformTables = 0u;
layout(constant_id = kSpecUniformLights) const uint uniformLightCount = 1u;
layout(constant_id = kSpecUniformIntervals) const uint uniformIntervalCount = 1u;
layout(constant_id = kSpecUniformCmfNodes) const uint uniformCmfNodeCount = 1u;
layout(constant_id = kSpecUniformAliasColumns) const uint uniformAliasColumnCount = 1u;
layout(set = 0, binding = kBindingLightsUniform, scalar) uniform LightUniformBlock {
  LightRecord uniformLights[uniformLightCount];
};
layout(set = 0, binding = kBindingSpectralIntervalsUniform, scalar) uniform SpectralUniformBlock {
  SpectralInterval uniformIntervals[uniformIntervalCount];
};
layout(set = 0, binding = kBindingCmfTableUniform, scalar) uniform CmfUniformBlock {
  vec3 uniformCmfTable[uniformCmfNodeCount];
};
layout(set = 0, binding = kBindingAliasColumnsUniform, scalar) uniform AliasUniformBlock {
  AliasColumn uniformAliasColumns[uniformAliasColumnCount];
};
layout(set = 0, binding = kBindingPrimitives, scalar) readonly buffer PrimitiveBlock {
  Primitive primitives[];
};
layout(set = 0, binding = kBindingBvhNodes, scalar) readonly buffer BvhBlock {
  PackedBvhNode bvhNodes[];
};
layout(set = 0, binding = kBindingMaterials, scalar) readonly buffer MaterialBlock {
  Material materials[];
};
layout(set = 0, binding = kBindingSceneData, scalar) readonly buffer SceneDataBlock {
  uint sceneData[];
};
// The objects again as uniform buffers, read instead when uniformObjects is
// 1: lavapipe loads a storage buffer lane by lane, a pass over the lanes
// for each word of a 16-word packed BVH node, and gathers a uniform buffer's.
layout(constant_id = kSpecUniformObjects) const uint uniformObjects = 0u;
layout(constant_id = kSpecUniformPrimitives) const uint uniformPrimitiveCount = 1u;
layout(constant_id = kSpecUniformBvhNodes) const uint uniformBvhNodeCount = 1u;
layout(constant_id = kSpecUniformMaterials) const uint uniformMaterialCount = 1u;
layout(set = 0, binding = kBindingPrimitivesUniform, scalar) uniform PrimitiveUniformBlock {
  Primitive uniformPrimitives[uniformPrimitiveCount];
};
layout(set = 0, binding = kBindingBvhNodesUniform, scalar) uniform BvhUniformBlock {
  PackedBvhNode uniformBvhNodes[uniformBvhNodeCount];
};
layout(set = 0, binding = kBindingMaterialsUniform, scalar) uniform MaterialUniformBlock {
  Material uniformMaterials[uniformMaterialCount];
};
layout(set = 0, binding = kBindingTraceStats, scalar) buffer TraceStatsBlock {
  TraceStats stats;
};
layout(push_constant, scalar) uniform PushBlock {
  TracePush push;
};

// The includer contract (kernel_interface.h).
#include "philox.glsl"
// (Returns, not a ?: of the two loads: glslang gives the uniform and storage
// struct types apart, and a ?: of them stored the one as the other.)
AliasColumn readAliasColumn(uint i) {
  if (uniformTables != 0u) return uniformAliasColumns[i];
  return aliasColumns[i];
}
LightRecord readLight(uint i) {
  if (uniformTables != 0u) return uniformLights[i];
  return lights[i];
}
SpectralInterval readInterval(uint i) {
  if (uniformTables != 0u) return uniformIntervals[i];
  return intervals[i];
}
vec3 readCmf(uint i) {
  if (uniformTables != 0u) return uniformCmfTable[i];
  return cmfTable[i];
}
Primitive readPrimitive(uint i) {
  if (uniformObjects != 0u) return uniformPrimitives[i];
  return primitives[i];
}
BvhNode readBvhNode(uint i) {
  if (uniformObjects != 0u) return unpackBvhNode(uniformBvhNodes[i]);
  return unpackBvhNode(bvhNodes[i]);
}
// GLSL has no prefetch; a GPU hides latency with other invocations.
void prefetchBvhChild(uint child, uint count) {}
Material readMaterial(uint i) {
  if (uniformObjects != 0u) return uniformMaterials[i];
  return materials[i];
}
uint readSceneWord(uint i) { return sceneData[i]; }
// Constant indices only: no non-uniform descriptor indexing needed. With
// one chunk there is no switch: on lavapipe each case of a divergent switch
// costs a pass over the lanes.
// Returns the word's value before the add.
uint64_t addToWord(uint chunk, uint index, uint64_t amount) {
  if (histogramChunks == 1u) return atomicAdd(histogram[0].counts[index], amount);
  switch (chunk) {
    case 0u: return atomicAdd(histogram[0].counts[index], amount);
    case 1u: return atomicAdd(histogram[1].counts[index], amount);
    case 2u: return atomicAdd(histogram[2].counts[index], amount);
    case 3u: return atomicAdd(histogram[3].counts[index], amount);
    case 4u: return atomicAdd(histogram[4].counts[index], amount);
    case 5u: return atomicAdd(histogram[5].counts[index], amount);
    case 6u: return atomicAdd(histogram[6].counts[index], amount);
    default: return atomicAdd(histogram[7].counts[index], amount);
  }
}
void addCount(uint chunk, uint index, uint64_t amount) { addToWord(chunk, index, amount); }
// The low word's carry, seen by exactly the add that wrapped it, goes to
// the high word: the two words hold the exact sum in any order of adds.
void addWideCount(uint chunk, uint index, WideCount amount) {
  uint64_t carry = 0ul;
  if (amount.low != 0ul) {
    uint64_t before = addToWord(chunk, index, amount.low);
    carry = before + amount.low < before ? 1ul : 0ul;
  }
  if (amount.high + carry != 0ul) addToWord(chunk, index + 1u, amount.high + carry);
}

#include "trace.h"

// The path of `beamIndex`, noted in `tally`: the whole kernel, or in the
// profile modules (trace_*_profile.comp, the bench's) the kernel cut after
// profileStage. One call site, so the kernel is inlined once: Mesa inlines
// every call before it drops the branches that specialisation constants
// rule out, and lavapipe's compile time grows with what it inlined (two
// more copies of the kernel, for the profile and the beam records, cost
// about 1 s in every process).
#ifdef SPECTRACE_WITH_PROFILE
// The stage the kernel is cut after (profile.h); the default is the whole
// kernel. Render modules do not declare it, and the host's value for it is
// then ignored.
layout(constant_id = kSpecProfileStage) const uint profileStage = kProfileStageFull;
#include "profile.h"
FN bool tracePath(uint64_t beamIndex, INOUT(BeamTally) tally) { return profileBeam(beamIndex, profileStage); }
#else
FN bool tracePath(uint64_t beamIndex, INOUT(BeamTally) tally) { return traceBeam(beamIndex, tally); }
#endif

// Counted beams of this workgroup, added to stats with one atomic. Not
// needed when every counted beam adds one unit to its bin: the host sums the
// bins instead, and the shader has no barrier (which lavapipe runs by
// splitting the shader into coroutines).
shared uint groupCounted;

void main() {
  if (countBeamsOnDevice != 0u) {
    if (gl_LocalInvocationIndex == 0u) groupCounted = 0u;
    barrier();
  }
  uint local = gl_GlobalInvocationID.y * push.beamsPerRow + gl_GlobalInvocationID.x;
  if (local < push.beamCount) {
    uint64_t beamIndex = push.beamBase + uint64_t(local);
    BeamTally tally = emptyTally();
    bool hit = tracePath(beamIndex, tally);
    if (recordBeams != 0u) {
      beamRecords[local] = hit ? BeamRecord(pixelOfCell(tally.cell, constants.pixelsX), tally.bin, floatBitsToUint(tally.ratio),
                                            tally.contributions)
                               : BeamRecord(kBeamMissed, kBeamMissed, 0u, 0u);
    } else if (hit && countBeamsOnDevice != 0u) {
      atomicAdd(groupCounted, 1u);
    }
  }
  if (countBeamsOnDevice != 0u) {
    barrier();
    if (gl_LocalInvocationIndex == 0u && groupCounted != 0u) atomicAdd(stats.countedBeams, uint64_t(groupCounted));
  }
}
