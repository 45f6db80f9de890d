// Buffer layouts and binding indices shared by C++ and GLSL, so the two can
// never drift apart (nvpro-samples' host_device.h pattern). Scalar block
// layout on the GLSL side; static_asserts pin the C++ sizes.
#ifndef SPECTRACE_DEVICE_SHARED_H
#define SPECTRACE_DEVICE_SHARED_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
namespace spectrace::device {
using uint = uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
#define SPECTRACE_CONSTANT constexpr
#define SPECTRACE_LAYOUT_FN constexpr
#else
#define SPECTRACE_CONSTANT const
#define SPECTRACE_LAYOUT_FN
#endif

// Descriptor bindings, one typed list per pipeline (set 0). C++ gets an
// enum, GLSL constants; kTraceBindings and its twins below are each
// pipeline's one table, which the host turns into both the descriptor set
// layout and the checks that every slot was written.
#ifdef __cplusplus
#define START_BINDING(name) enum name : uint32_t {
#define END_BINDING() }
#else
#define START_BINDING(name) const uint
#define END_BINDING()
#endif

START_BINDING(TraceBinding)
  kBindingTraceConstants = 0,  // a uniform buffer
  kBindingLights = 1,
  kBindingSpectralIntervals = 2,
  kBindingHistogram = 3,    // array of kMaxHistogramChunks
  kBindingBeamRecords = 4,  // only written with kSpecRecordBeams
  kBindingCmfTable = 5,     // vec3 per node, for exact colour
  kBindingTraceStats = 6,   // TraceStats
  kBindingAliasColumns = 7, // AliasColumn: the light choice's, then each light's spectral table's
  // The same four tables as uniform buffers, read instead of the storage
  // buffers above when kSpecUniformTables is 1 (host/backend/uniform_tables.h).
  kBindingLightsUniform = 8,
  kBindingSpectralIntervalsUniform = 9,
  kBindingCmfTableUniform = 10,
  kBindingAliasColumnsUniform = 11,
  // Scene objects (transport.h): what a beam can hit between light and camera.
  kBindingPrimitives = 12,   // Primitive, in the BVH's leaf order
  kBindingBvhNodes = 13,     // BvhNode, depth first, the root at 0
  kBindingMaterials = 14,    // Material
  kBindingSceneData = 15,    // the scene data: 32-bit words, offset-addressed (below)
  // The first three as uniform buffers, read instead when kSpecUniformObjects
  // is 1 (host/backend/uniform_tables.h: small scenes, such as a prism).
  kBindingPrimitivesUniform = 16,
  kBindingBvhNodesUniform = 17,
  kBindingMaterialsUniform = 18
END_BINDING();
START_BINDING(ResolveBinding)
  kBindingResolveConstants = 0,
  kBindingBinWeights = 1,
  kBindingResolvedPixels = 2,
  kBindingResolveHistogram = 3  // array of kMaxHistogramChunks
END_BINDING();
START_BINDING(RngCheckBinding)
  kBindingRngWords = 0
END_BINDING();
START_BINDING(CeilingBinding)  // the bench's ceiling kernel (shaders/ceiling.comp)
  kBindingCeilingCdf = 0,      // float CDF of the spectrum, one entry per node
  kBindingCeilingHistogram = 1 // uint per pixel-bin
END_BINDING();

// The resolve pass sums this many bins per loop iteration, written out in
// resolve.comp (llvmpipe stops a loop after 65535 iterations).
SPECTRACE_CONSTANT uint kResolveBinsPerIteration = 4u;

// Histograms larger than maxStorageBufferRange are split into up to this many
// buffers, each holding whole pixels. A fixed array indexed through a switch
// works without non-uniform descriptor indexing (lavapipe lacks it).
SPECTRACE_CONSTANT uint kMaxHistogramChunks = 8;

// Light types (spectrace::LightType, at the end of this file, takes its
// values from these). One kernel unit per type in shaders/lights/<type>.h,
// one host unit in host/lights/<type>_light.cpp.
SPECTRACE_CONSTANT uint kLightPoint = 0;
SPECTRACE_CONSTANT uint kLightSpot = 1;
SPECTRACE_CONSTANT uint kLightDisk = 2;
SPECTRACE_CONSTANT uint kLightRect = 3;
SPECTRACE_CONSTANT uint kLightLaser = 4;
SPECTRACE_CONSTANT uint kLightPhotometric = 5;
SPECTRACE_CONSTANT uint kLightObject = 6;  // an object's "emission": its surface, Lambertian
SPECTRACE_CONSTANT uint kLightTypeCount = 7;
SPECTRACE_CONSTANT uint kAllLightTypes = (1u << kLightTypeCount) - 1u;  // a bit per type

// Camera models (what stands before the sensor): one kernel unit per model
// in shaders/cameras/<model>.h, one host unit in host/camera/<model>_camera.cpp.
SPECTRACE_CONSTANT uint kCameraBareSensor = 0;
SPECTRACE_CONSTANT uint kCameraPinhole = 1;
SPECTRACE_CONSTANT uint kCameraThinLens = 2;
SPECTRACE_CONSTANT uint kCameraLensSystem = 3;
// A lens system's table in the scene data (shaders/cameras/lens_system.h):
// its surface count, then this many words a surface.
SPECTRACE_CONSTANT uint kLensSurfaceWords = 9u;
SPECTRACE_CONSTANT uint kCameraTypeAtRunTime = 0xFFFFFFFFu;  // kSpecCameraType: read constants.cameraType

// Specialisation constant ids. Every pipeline has the workgroup size; the
// trace pipeline's others fix scene features (the defaults, in
// trace_beams.comp, are the general pipeline's: decide at run time):
// a bit per light type present; whether to choose among lights; the camera
// model (kCamera*, or kCameraTypeAtRunTime); exact colour off (0) / on (1) /
// run time (2); no light aimed (0) / some (1) / run time (2).
START_BINDING(SpecConstantId)
  kSpecWorkgroupSize = 0,
  kSpecRecordBeams = 1,  // 1: write each beam's (pixel, bin) to the beam records instead of counting it
  kSpecLightTypes = 2,
  kSpecSelectLight = 3,
  kSpecCameraType = 4,
  kSpecExactColour = 5,
  kSpecAim = 6,
  kSpecHistogramChunks = 7,  // histogram buffers in use; kMaxHistogramChunks + 1: decided at run time
  kSpecCountBeams = 8,       // 0: every weight is one unit, so the host sums the bins instead
  kSpecProfileStage = 9,     // bench only (shaders/profile.h): kProfileStageFull runs the whole kernel
  kSpecUniformTables = 10,   // 1: read the tables from their uniform buffers (0: the storage buffers)
  // Element counts of the uniform tables' arrays (1 when unused).
  kSpecUniformLights = 11,
  kSpecUniformIntervals = 12,
  kSpecUniformCmfNodes = 13,
  kSpecUniformAliasColumns = 14,
  kSpecObjects = 15,         // 0: no scene objects (transport compiled out); 1: some; 2: run time
  kSpecCameraPaths = 16,     // 0: no camera paths (camera_path.h compiled out); 1: camera paths; 2: run time
  kSpecPrimitiveTypes = 17,  // a bit per primitive type present (kAllPrimitiveTypes: run time)
  kSpecMaterialTypes = 18,   // a bit per material type present (kAllMaterialTypes: run time)
  kSpecUniformObjects = 19,  // 1: read primitives, BVH nodes and materials from their uniform buffers
  // Element counts of the uniform object tables' arrays (1 when unused).
  kSpecUniformPrimitives = 20,
  kSpecUniformBvhNodes = 21,
  kSpecUniformMaterials = 22
END_BINDING();
// Stages of the bench's cost profile (shaders/profile.h), each adding one
// part of the kernel to the one before.
START_BINDING(ProfileStage)
  kProfileStagePhilox = 0,     // the beam's two Philox blocks
  kProfileStageLight = 1,      // + light choice and its record
  kProfileStageWavelength = 2, // + wavelength and its bin
  kProfileStageEmission = 3,   // + origin and direction (unaimed)
  kProfileStageSensor = 4,     // + sensor intersection
  kProfileStageCounting = 5,   // + the bin's counter (exact colour off)
  kProfileStageColour = 6,     // + exact colour
  kProfileStageFull = 7,       // the whole kernel: + aiming and weights
  // Scenes with objects (light paths): after the emission stage,
  kProfileStageObjectsFirstHit = 8,      // the kernel's emission and its first object hit, nothing counted
  kProfileStageObjectsNoConnection = 9   // the whole kernel without camera connections (constants.connect = 0)
END_BINDING();
// A beam record of a beam that missed the sensor.
SPECTRACE_CONSTANT uint kBeamMissed = 0xFFFFFFFFu;

// Weighted counts. An aimed beam carries weight ratio r (its emission
// density over its sampling density, divided by the light's largest such
// ratio; the light-selection CDF carries the rest), and a camera connection
// its own (which grows as 1 / distance^2). When every ratio is 1 (no aimed
// area light, no connections) a film counts plain hits: one unit per beam
// in 64-bit counters. Otherwise the film is weighted, and each of its
// counters is 128 bits (two 64-bit words, low first) in units of 2^-63 of
// a full-weight beam: a counted beam adds r * 2^63 to its bin, exactly when
// r >= 2^-39 (r * 2^63 is then an integer in float) and rounded
// stochastically (unbiased) below. Rounding adds at most 1/4 unit^2 of
// variance per count, under 1% of the count's own r^2 for any r > 5 * 2^-63
// (5e-19), so no weight a scene of any size can give loses precision in
// practice (a 64-bit counter in units of 2^-24 rounded a 25 um pinhole's
// connections at 1 m, worth 0.004 units, to 0 or 1). A counter holds 2^65
// full-weight beams; words add with carry, so the sum stays exact and
// independent of order.
SPECTRACE_CONSTANT uint64_t kWeightUnitsFractional = 9223372036854775808ul;  // 2^63
// One weighted count or counter: x * 2^63 in two words.
struct WideCount {
  uint64_t low;
  uint64_t high;
};

// Philox counter blocks: each gives four 32-bit words per beam. Light choice
// has its own block, so single-light scenes draw two blocks, not three.
SPECTRACE_CONSTANT uint kRngBlockSpectral = 0;   // interval (64 bit), position in interval, spare (rounding)
SPECTRACE_CONSTANT uint kRngBlockGeometry = 1;   // origin u, origin v, direction u, direction v
SPECTRACE_CONSTANT uint kRngBlockLight = 2;      // light (64 bit), (spare), (spare)
// Transport: bounce b (the b-th surface a beam meets, from 0) draws block
// kRngBlockBounce + 2b (choice, direction u, direction v, spare) and, for a
// camera connection, kRngBlockBounce + 2b + 1 (aperture u, aperture v,
// rounding, spare): keyed on (seed, beam, bounce), as every block is.
SPECTRACE_CONSTANT uint kRngBlockBounce = 3;
// A photometric light's direction (lights/photometric.h) is drawn by
// rejection inside its patch: try t draws block kRngBlockPhotometricTry + t
// (C u, gamma u, acceptance word, spare), far above any bounce's blocks.
SPECTRACE_CONSTANT uint kRngBlockPhotometricTry = 0x40000000u;
// An emitting object's beam (lights/object.h) takes its point on the chosen
// primitive from one more block (point u, point v, side, spare).
SPECTRACE_CONSTANT uint kRngBlockEmitterPoint = 0x60000000u;
// A beam that reaches a lens system's sensor is kept with the probability
// its surfaces transmit (Fresnel): block kRngBlockLensTransmission (choice,
// spares). A beam meets the camera once.
SPECTRACE_CONSTANT uint kRngBlockLensTransmission = 0x70000000u;
// Camera paths (camera_path.h), keyed on (seed, path index, block) like
// beams, in blocks far above any bounce's: the start (pixel u, v, aperture
// u, v), the wavelength (interval (64 bit), position, rounding), the light
// (64 bit, as kRngBlockLight), and per vertex v the blocks
// kRngBlockCameraVertex + 2v (choice, direction u, direction v, rounding)
// and + 2v + 1 (light point u, v, rounding, spare). The pixel rounds
// (camera_path.h: cameraPathCell) key kRngBlockCameraRound on (seed,
// round index).
SPECTRACE_CONSTANT uint kRngBlockCameraStart = 0x80000000u;
SPECTRACE_CONSTANT uint kRngBlockCameraSpectral = 0x80000001u;
SPECTRACE_CONSTANT uint kRngBlockCameraLight = 0x80000002u;
SPECTRACE_CONSTANT uint kRngBlockCameraRound = 0x80000003u;
SPECTRACE_CONSTANT uint kRngBlockCameraVertex = 0x80000010u;
// A camera path's point on an emitting object at vertex v (alias (64 bit),
// point u, point v): block kRngBlockCameraEmitterPoint + v.
SPECTRACE_CONSTANT uint kRngBlockCameraEmitterPoint = 0xA0000000u;

// The estimators a render runs (TraceConstants.estimators): each path index
// traces a light path (a beam from a light, counted at the camera and
// through camera connections) and/or a camera path (from a pixel, through
// the objects, to the lights). With both, each path of light is counted by
// exactly one of them (camera_path.h says which).
SPECTRACE_CONSTANT uint kEstimatorLightPaths = 1u;
// The most wavelengths a path carries (shaders/wavelengths.h); k is a power
// of two up to it.
SPECTRACE_CONSTANT uint kMaxWavelengthsPerPath = 4u;
SPECTRACE_CONSTANT uint kEstimatorCameraPaths = 2u;

// Scene objects. Shapes (spectrace::ShapeType, at the end of this file; one
// host unit per kind in host/shapes/<kind>_shape.cpp) become primitives in
// the camera frame (metres, single precision, built on the host in double):
// a mesh one triangle per face, the others one primitive each. One kernel
// unit per primitive in shaders/shapes/<primitive>.h.
SPECTRACE_CONSTANT uint kPrimitiveTriangle = 0;  // a: vertex 0, b: vertex 1 - vertex 0, c: vertex 2 - vertex 0
SPECTRACE_CONSTANT uint kPrimitiveRect = 1;      // a: centre, b, c: half edges (b x c along the normal)
SPECTRACE_CONSTANT uint kPrimitiveDisk = 2;      // a: centre, b: unit normal, c.x: radius^2
SPECTRACE_CONSTANT uint kPrimitiveSphere = 3;    // a: centre, b.x: radius, b.y: radius^2
SPECTRACE_CONSTANT uint kPrimitiveTypeCount = 4;
SPECTRACE_CONSTANT uint kAllPrimitiveTypes = (1u << kPrimitiveTypeCount) - 1u;  // a bit per type
struct Primitive {
  vec3 a;
  uint type;
  vec3 b;
  uint material;  // index into the materials
  vec3 c;
  uint emitter;   // 1 + the index of the light it emits as (an emitting object's), else 0
};
// A node of the BVH, four wide (128 bytes): the boxes of up to four
// children side by side, so that one read tests them all (four lanes of one
// vector operation on the CPU) and a child the ray misses is never read.
// Built on the host from a binary tree (host/compile/wide_bvh.h), bounds
// rounded outwards to float from double. Slot k: count[k] > 0 is a leaf of
// the primitives [child[k], child[k] + count[k]); count[k] == 0 is the
// interior node child[k], or an empty slot where child[k] == 0 (the root is
// nobody's child).
struct BvhNode {
  vec4 minX;
  vec4 maxX;
  vec4 minY;
  vec4 maxY;
  vec4 minZ;
  vec4 maxZ;
  uvec4 child;
  uvec4 count;
};
// A BvhNode as the Vulkan trace reads it (64 bytes, half a BvhNode's
// words: lavapipe loads a storage buffer lane by lane, a pass over the
// lanes for each word). Each axis has a grid of step 2^e from an integer
// base; a child's box is the grid cells (base + its byte) * 2^e that hold
// its float box, so it is never smaller, and unpacking is exact integer and
// power-of-two arithmetic on any device (shaders/packed_bvh_node.h; packed
// by host/compile/packed_bvh.h). Slot k: boxes' byte k.
struct PackedBvhNode {
  uvec4 grid;     // x, y, z: each axis's base (int32 bits); w: bytes 0-2, each axis's e + 127
  uvec4 boxesXY;  // minX, maxX, minY, maxY: each child's steps above the base
  uvec4 boxesZ;   // minZ, maxZ; z, w zero
  uvec4 entries;  // child[k] << kBvhCountBits | count[k]
};
// The binary builder's depth limit (nodes on a root-to-leaf path); a wide
// tree made from it is no deeper.
SPECTRACE_CONSTANT uint kBvhMaxDepth = 32u;
// Traversal's fixed stack: a wide node pushes at most four children and
// pops one, so a walk down kBvhMaxDepth levels holds at most 3 per level
// plus one.
SPECTRACE_CONSTANT uint kBvhStackSize = 97u;
SPECTRACE_CONSTANT uint kBvhMaxLeafPrimitives = 8u;
// The traversal stack keeps a slot's child and count in one word, child <<
// kBvhCountBits | count (one scratch array fewer for each lane on
// lavapipe), so leaves hold fewer than 2^kBvhCountBits primitives and
// node and primitive indices stay below kBvhMaxIndex.
SPECTRACE_CONSTANT uint kBvhCountBits = 4u;
SPECTRACE_CONSTANT uint kBvhMaxIndex = 1u << (32u - kBvhCountBits);

// The scene data: one buffer of 32-bit words where a unit (a light, camera
// or material type) keeps parameters and tables of any length, addressed by
// offsets its own record holds, read through readSceneWord (a float as its
// bits, readSceneFloat), so a new table needs no binding of its own. Built by
// SceneData::append (host/device_data/scene_data.h). The
// materials' reflectance tables are its first tables.

// A photometric light's scene data (host/lights/photometric_light.cpp,
// shaders/lights/photometric.h), from LightRecord.dataFirst: the C count nC,
// the gamma count nG, the patch alias table's bits, the most rejection tries;
// then nC C angles and nG gamma angles in turns (ascending; C from 0 to 1),
// nC x nG intensities (candela over the table's lumens: sr^-1, C major),
// (nC - 1) x (nG - 1) patch envelopes (at least the patch's largest
// intensity x sin(gamma)), and the patch alias columns, four words each
// (threshold low, high, alias, 0). Patch k is C interval k / (nG - 1) and
// gamma interval k % (nG - 1).
SPECTRACE_CONSTANT uint kPhotometricHeaderWords = 4u;

// An emitting object's scene data (host/lights/object_light.cpp): a header
// (primitive count, alias bits, two-sided, total area in m^2 as a float),
// the alias columns over its
// primitives by area, four words each (threshold low, high, alias, 0), then
// its primitives in the camera frame, kPrimitiveWords each (Primitive's
// layout), the same float values the BVH's copies hold.
SPECTRACE_CONSTANT uint kObjectEmitterHeaderWords = 4u;
SPECTRACE_CONSTANT uint kPrimitiveWords = 12u;

// Material kinds (spectrace::MaterialType, at the end of this file, takes
// its values from these). One kernel unit per kind in
// shaders/materials/<kind>.h, one host unit in
// host/materials/<kind>_material.cpp.
SPECTRACE_CONSTANT uint kMaterialAbsorber = 0;
SPECTRACE_CONSTANT uint kMaterialDiffuse = 1;
SPECTRACE_CONSTANT uint kMaterialMirror = 2;
SPECTRACE_CONSTANT uint kMaterialDielectric = 3;
SPECTRACE_CONSTANT uint kMaterialTypeCount = 4;
SPECTRACE_CONSTANT uint kAllMaterialTypes = (1u << kMaterialTypeCount) - 1u;  // a bit per type
// A material. Reflectance (diffuse, mirror): linear between nodes
// readSceneFloat(reflectanceFirst + i) at lambda0 + i / nodesPerNm, holding
// its end values outside. Dielectric: n^2 = 1 + sum B_i l^2 / (l^2 - C_i), l in micrometres
// (a constant ior n is B = (n^2 - 1, 0, 0), C = 0).
struct Material {
  uint type;
  uint reflectanceFirst;
  uint reflectanceCount;   // >= 1
  float reflectanceLambda0;
  float reflectanceNodesPerNm;
  vec3 sellmeierB;
  vec3 sellmeierC;         // micrometres^2
  uint padding0;
};

// One light, in the camera frame (metres, single precision). Built on the
// host from the scene in double precision.
struct LightRecord {
  uint64_t selectCdfLow;  // P(light) = (next light's value, or 2^64, - this) / 2^64,
                          // drawn through the alias columns (AliasColumn)
  uint type;
  uint spectralFirst;     // first SpectralInterval of this light
  uint spectralCount;     // number of intervals (>= 1)
  float param0;           // spot: 1 - cos(half angle); disk/laser: radius; rect: width
  float param1;           // rect: height
  uint spectralAliasFirst;  // first AliasColumn of the spectral table (2^spectralAliasBits columns)
  vec3 position;          // point/spot/laser origin, disk/rect centre
  vec3 axis;              // spot/laser direction, disk/rect normal
  vec3 tangent;           // with bitangent, completes an orthonormal frame
  vec3 bitangent;
  // Aimed sampling (host/lights/light_shared.h has the derivations).
  uint aimed;             // 0: analog emission; 1: only towards the camera's target sphere
  float aimSpread;        // point/spot: 1 - cos(half angle) of the cone about aimAxis holding
                          // the target; laser: radius of the disk of origins that can reach it
  float aimAccept;        // spot: sin^2(spot half angle); laser: radius^2 (the light's own emission)
  float aimWeightScale;   // disk/rect: 1 / the light's largest weight, so ratios are <= 1
  vec3 aimAxis;           // point/spot: cone axis; laser: (centre of the origin disk in (tangent, bitangent), 0)
  vec3 aimTangent;        // point/spot: completes the cone's frame
  vec3 aimBitangent;
  uint spectralAliasBits;
  // The type's own parameters and tables beyond param0/param1, in the scene
  // data (words [dataFirst, dataFirst + dataWords)); 0, 0: none.
  uint dataFirst;
  uint dataWords;
  // Camera paths: (this light's traced power / the sampled power) / its
  // probability of being chosen, the factor that makes a camera path's count
  // through this light unbiased in the film's units (camera_path.h).
  float cameraPathWeight;
  float padding1;
};

// One interval of a light's piecewise-linear SPD, restricted to the
// spectrum range and trimmed to its support.
struct SpectralInterval {
  uint64_t cdfLow;   // P(interval) = (next cdfLow, or 2^64 after the light's last, - this) / 2^64,
                     // drawn through the light's alias columns (AliasColumn)
  float lambda0;     // nm
  float width;       // nm (0 for a Dirac line)
  float slope;       // (f1 - f0) / (f1 + f0), in [-1, 1]
  float padding0;
};

// One column of an alias table (host/spectrum/alias_table.h): a 64-bit
// uniform u whose top `bits` select this column draws the column's own
// entry when (u << bits) < threshold, else `alias`. Each entry's
// probability is exactly its integer CDF width / 2^64.
struct AliasColumn {
  uint64_t threshold;
  uint alias;
  uint padding0;
};

// Exact colour: each counted beam also adds its own x̄, ȳ, z̄ (the CMF at
// its wavelength) to three per-pixel counters, in fixed point with this many
// units per CMF unit, rounded stochastically (unbiased). Range: a hit adds at
// most 2.1 * 2^20 + 1 < 2^22 (the largest CMF value is z̄10's 2.02), so a
// uint64 counter holds 2^42 = 4.4e12 hits in one pixel; the quantum, 2^-20
// of a CMF unit, adds rounding noise far below the Monte Carlo noise.
SPECTRACE_CONSTANT float kColourFixedPointScale = 1048576.0f;  // 2^20
// A weighted film's colour sums are wide counters in its bins' units
// (kWeightUnitsFractional per CMF unit times the weight ratio), exact as
// its bins are.
SPECTRACE_LAYOUT_FN float colourUnitsPerCmf(bool weighted) { return weighted ? 9.2233720e18f : kColourFixedPointScale; }

// Scene-wide constants of the trace pass. Each stored pixel owns countersPerPixel
// 64-bit counters (countersPerPixelOf, below).
// The stored bins are bins [binOffset, binOffset + bins) of the spectrum's
// totalBins: those the scene's lights can reach (a trimmed spectrum).
struct TraceConstants {
  vec2 sensorHalfSize;      // metres
  vec2 pixelsPerMetre;
  uint pixelsX;
  uint pixelsY;
  uint bins;                // stored bins
  uint lightCount;
  float lambdaMin;          // nm, of the full spectrum
  float binsPerNm;
  uint cameraType;          // kCamera*: the camera model (shaders/camera.h)
  float cameraFrontZ;       // metres: a counted beam comes from beyond this plane (the
                            // model's entrance; 0: the sensor), where the camera's body ends
  uint pixelsPerChunk;      // histogram chunk size in whole pixels
  uint countersPerPixel;    // countersPerPixelOf(bins, the film's channel set)
  uint exactColour;         // 1: accumulate per-beam CMF values
  uint cmfCount;            // nodes of the CMF table
  float cmfLambdaMin;       // nm of node 0
  float cmfNodesPerNm;      // 1 / node spacing
  uint binOffset;           // first stored bin of the full spectrum
  uint totalBins;           // bins of the full spectrum
  vec3 aimCentre;           // sphere holding every point a counted beam passes: the
  float aimRadius;          // camera model's entrance (metres)
  uint weighted;            // 1: weighted counts in 128-bit counters (kWeightUnitsFractional)
  // The stored pixels: the rectangle of columns [windowX0, windowX0 +
  // windowWidth) and rows [windowY0, windowY0 + windowHeight) that beams can
  // reach (the whole sensor unless the host proves less); the histogram
  // holds these pixels only, row-major.
  uint windowX0;
  uint windowY0;
  uint windowWidth;
  uint windowHeight;
  uint lightAliasBits;      // the light choice's alias columns: 2^lightAliasBits, from column 0
  uint64_t seed;
  // Scene objects (transport.h). objectPrimitives 0: nothing between the
  // lights and the camera.
  uint objectPrimitives;
  uint maxBounces;          // surfaces a beam may scatter from before it is dropped
  uint connect;             // 1: connect diffuse vertices to the camera (light tracing)
  vec4 cameraParams;        // the camera model's own constants (shaders/cameras/<model>.h)
  uint cameraDataFirst;     // its tables in the scene data, if it has any
  uint estimators;          // kEstimator* bits
  // Camera paths: the stored window's sensor area times the aperture's
  // area over the aperture distance squared (m^2; camera_path.h).
  float cameraPathScale;
  uint wavelengthsPerPath;  // k: the wavelengths a beam or camera path carries (wavelengths.h)
  // > 0: the BVH is one leaf of the primitives [0, bvhRootLeaf) under the
  // root (compile/wide_bvh.h: rootLeafCount), and walks start at it.
  uint bvhRootLeaf;
};

// The film's channels, defined only here: each stored pixel owns
// countersPerPixel 64-bit words, the counters of each channel the film
// stores in channel order, each counter one word (plain hit counts) or two
// (a weighted film: low word, high word; kWeightUnitsFractional). A film's
// channel set has bit c for channel c, and kFilmWideCounters when weighted.
// host/film (FilmLayout::channels, SpectralHistogram::channel) and the
// kernel both read the layout from these.
SPECTRACE_CONSTANT uint kFilmChannelBins = 0u;           // a count per stored bin (always stored)
SPECTRACE_CONSTANT uint kFilmChannelColour = 1u;         // X, Y, Z sums of each beam's CMFs (exact colour)
SPECTRACE_CONSTANT uint kFilmChannelSquaredWeight = 2u;  // the sum of squared weights (weighted films)
SPECTRACE_CONSTANT uint kFilmChannelCount = 3u;
SPECTRACE_CONSTANT uint kFilmWideCounters = 0x80000000u;  // channel-set bit: two words per counter
// Counters per pixel of channel `channel` of a film storing `bins` bins.
SPECTRACE_LAYOUT_FN uint filmChannelCounters(uint channel, uint bins) {
  return channel == kFilmChannelBins ? bins : (channel == kFilmChannelColour ? 3u : 1u);
}
SPECTRACE_LAYOUT_FN bool filmStoresChannel(uint channelSet, uint channel) { return ((channelSet >> channel) & 1u) != 0u; }
// 64-bit words per counter.
SPECTRACE_LAYOUT_FN uint filmCounterWords(uint channelSet) { return (channelSet & kFilmWideCounters) != 0u ? 2u : 1u; }
// The first word of `channel` in a pixel's words (for a channel not
// stored: where it would go).
SPECTRACE_LAYOUT_FN uint filmChannelOffset(uint channel, uint bins, uint channelSet) {
  uint offset = 0u;
  for (uint c = 0u; c < channel; ++c)
    if (filmStoresChannel(channelSet, c)) offset += filmChannelCounters(c, bins);
  return offset * filmCounterWords(channelSet);
}
SPECTRACE_LAYOUT_FN uint filmChannelSetOf(bool exactColour, bool weighted) {
  return (1u << kFilmChannelBins) | (exactColour ? 1u << kFilmChannelColour : 0u) |
         (weighted ? (1u << kFilmChannelSquaredWeight) | kFilmWideCounters : 0u);
}
SPECTRACE_LAYOUT_FN uint countersPerPixelOf(uint bins, uint channelSet) {
  return filmChannelOffset(kFilmChannelCount, bins, channelSet);
}
// The kernel's two fixed offsets (bins come first, colour follows them).
SPECTRACE_LAYOUT_FN uint colourCounterOffset(uint bins, bool weighted) { return weighted ? 2u * bins : bins; }
SPECTRACE_LAYOUT_FN uint squaredWeightCounterOffset(uint bins, bool exactColour) {
  return filmChannelOffset(kFilmChannelSquaredWeight, bins, filmChannelSetOf(exactColour, true));
}

// Totals of the trace pass, besides the histogram.
struct TraceStats {
  uint64_t countedBeams;  // beams that were counted (hit the sensor with weight > 0)
};

// What the record mode writes per beam.
struct BeamRecord {
  uint pixel;   // kBeamMissed for a beam that was not counted
  uint bin;
  uint ratioBits;  // the float bits of its weight ratio (1.0 in a plain film)
  uint contributions;  // counts the beam made (camera connections add one each); pixel, bin
                       // and units are its last one's
};

// Per-dispatch push constants of the trace pass.
struct TracePush {
  uint64_t beamBase;   // index of the first beam of this dispatch
  uint beamCount;      // beams in this dispatch
  uint beamsPerRow;    // invocations per row of the 2D dispatch
};

struct ResolveConstants {
  uint pixelCount;
  uint bins;
  uint pixelsPerChunk;
  uint countersPerPixel;
  uint exactColour;          // 1: XYZ from the per-beam colour counters
  uint squaredWeightOffset;  // of the squared-weight counter in a pixel's; 0: none (never first)
  float irradiancePerCount;  // W/m^2 carried by one count (per bin)
  float xyzPerColourUnit;    // 683 * (irradiance per full-weight beam) / colourUnitsPerCmf
  uint weighted;             // 1: two words per counter (kFilmWideCounters)
  vec3 xyzToRgbRow0;         // linear sRGB = rows . XYZ
  vec3 xyzToRgbRow1;
  vec3 xyzToRgbRow2;
};

// Resolve output: one per pixel, with the pixel's exact sums, so the host
// needs no download of the film for the error estimate and the summary.
struct ResolvedPixel {
  vec3 rgb;          // linear sRGB
  vec3 xyz;          // CIE XYZ, Y in lux
  float irradiance;  // W/m^2 over all bins
  uint padding0;
  // The pixel's exact sums as counters (WideCount; high words 0 unless the
  // film is weighted): the sum of its bin counters, its squared-weight
  // counter (0 unless weighted) and its largest bin counter.
  WideCount totalCount;
  WideCount squaredWeightCount;
  WideCount largestCount;
};

// Per-dispatch push constants of the resolve pass: a slice of pixels, so the
// output buffer never exceeds maxStorageBufferRange.
struct ResolvePush {
  uint firstPixel;
  uint pixelCount;
};

struct RngCheckPush {
  uint64_t seed;
  uint64_t firstIndex;
  uint count;
  uint block;
};

// The bench's ceiling kernel (shaders/ceiling.comp, host/backend/ceiling.cpp):
// a disk light facing a bare sensor at z = 0, no exactness work.
struct CeilingPush {
  uint beamBase;        // first beam's index (32 bit: the hash's input)
  uint beamCount;
  uint beamsPerRow;     // invocations per row of the 2D dispatch
  uint cdfCount;        // CDF nodes, lambdaMin + i * nmPerNode
  float lambdaMin;
  float nmPerNode;
  float binsPerNm;
  uint bins;
  float diskRadius;     // metres, centred on the axis
  float diskDistance;   // from the sensor
  float sensorHalfSize; // square sensor
  float pixelsPerMetre;
  uint pixels;          // per side
  uint padding0;
};

#ifdef __cplusplus
// Each pipeline's binding list: the one table its descriptor set layout
// is built from (host/backend), beside the typed enums above.
struct BindingSlot {
  uint32_t binding;
  uint32_t count;  // > 1: an array of storage buffers
  bool uniform = false;  // a uniform buffer, not a storage buffer
};
inline constexpr BindingSlot kTraceBindings[] = {
    {kBindingTraceConstants, 1, true},
    {kBindingLights, 1},
    {kBindingSpectralIntervals, 1},
    {kBindingHistogram, kMaxHistogramChunks},
    {kBindingBeamRecords, 1},
    {kBindingCmfTable, 1},
    {kBindingTraceStats, 1},
    {kBindingAliasColumns, 1},
    {kBindingLightsUniform, 1, true},
    {kBindingSpectralIntervalsUniform, 1, true},
    {kBindingCmfTableUniform, 1, true},
    {kBindingAliasColumnsUniform, 1, true},
    {kBindingPrimitives, 1},
    {kBindingBvhNodes, 1},
    {kBindingMaterials, 1},
    {kBindingSceneData, 1},
    {kBindingPrimitivesUniform, 1, true},
    {kBindingBvhNodesUniform, 1, true},
    {kBindingMaterialsUniform, 1, true}};
// Every device has at least 12 uniform buffers a stage (the Vulkan
// minimum of maxPerStageDescriptorUniformBuffers), so this layout needs no
// query.
static_assert([] {
  uint32_t uniformBuffers = 0;
  for (const BindingSlot& slot : kTraceBindings) uniformBuffers += slot.uniform ? slot.count : 0u;
  return uniformBuffers <= 12u;
}());
inline constexpr BindingSlot kCeilingBindings[] = {{kBindingCeilingCdf, 1}, {kBindingCeilingHistogram, 1}};
inline constexpr BindingSlot kResolveBindings[] = {{kBindingResolveConstants, 1},
                                                   {kBindingBinWeights, 1},
                                                   {kBindingResolvedPixels, 1},
                                                   {kBindingResolveHistogram, kMaxHistogramChunks}};
inline constexpr BindingSlot kRngCheckBindings[] = {{kBindingRngWords, 1}};

static_assert(sizeof(LightRecord) == 152);
static_assert(kBvhMaxLeafPrimitives < (1u << kBvhCountBits));
static_assert(sizeof(SpectralInterval) == 24);
static_assert(sizeof(TraceConstants) == 176);
static_assert(offsetof(TraceConstants, cameraParams) == 140);
static_assert(offsetof(TraceConstants, cameraDataFirst) == 156);
static_assert(sizeof(Primitive) == 48 && sizeof(Primitive) == 4 * kPrimitiveWords);
static_assert(sizeof(BvhNode) == 128);
static_assert(sizeof(PackedBvhNode) == 64);
static_assert(sizeof(Material) == 48);
static_assert(sizeof(TraceStats) == 8);
static_assert(sizeof(BeamRecord) == 16);
static_assert(sizeof(TracePush) == 16);
static_assert(sizeof(ResolveConstants) == 72);
static_assert(sizeof(ResolvedPixel) == 80);
static_assert(offsetof(ResolvedPixel, totalCount) == 32);
static_assert(sizeof(RngCheckPush) == 24);
static_assert(sizeof(CeilingPush) == 56);
static_assert(sizeof(ResolvePush) == 8);
// The channels' names in state files and messages.
inline constexpr const char* kFilmChannelNames[kFilmChannelCount] = {"counts", "colour_sums", "squared_weight_sums"};
static_assert(colourCounterOffset(7, false) == filmChannelOffset(kFilmChannelColour, 7, filmChannelSetOf(true, false)) &&
                  colourCounterOffset(7, true) == filmChannelOffset(kFilmChannelColour, 7, filmChannelSetOf(true, true)),
              "the kernel's colour offset is the channel list's");
static_assert(countersPerPixelOf(7, filmChannelSetOf(true, true)) == 22 &&
              countersPerPixelOf(7, filmChannelSetOf(false, false)) == 7);
}  // namespace spectrace::device

namespace spectrace {
// The light types on the host, numbered as the kernel numbers them.
enum class LightType : uint32_t {
  Point = device::kLightPoint,
  Spot = device::kLightSpot,
  Disk = device::kLightDisk,
  Rect = device::kLightRect,
  Laser = device::kLightLaser,
  Photometric = device::kLightPhotometric,
  Object = device::kLightObject,
};
static_assert(uint32_t(LightType::Object) + 1 == device::kLightTypeCount, "light types are numbered 0.. without gaps");
// The material kinds on the host, numbered as the kernel numbers them.
enum class MaterialType : uint32_t {
  Absorber = device::kMaterialAbsorber,
  Diffuse = device::kMaterialDiffuse,
  Mirror = device::kMaterialMirror,
  Dielectric = device::kMaterialDielectric,
};
// The shape kinds on the host, numbered as host/shapes/shape_types.cpp lists
// their units. The kernel sees only the primitives each unit emits
// (kPrimitive*): it is here so that a new kind and the primitive it needs
// are one file's lines.
enum class ShapeType : uint32_t { Rect, Disk, Sphere, Mesh };
}  // namespace spectrace
#endif

#endif  // SPECTRACE_DEVICE_SHARED_H
