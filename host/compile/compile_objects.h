#pragma once
// The scene's objects for the kernel (shaders/objects.h, transport.h):
// shapes become primitives in the camera frame, placed by their kind's unit
// (shapes/shape_type.h), each object's material a Material packed by its
// kind's unit (materials/material_type.h), and a BVH over the primitives,
// all worked out in double and rounded once.
#include "compile/compile_scene.h"
#include "scene/scene.h"

namespace spectrace {

// Fills device.primitives (in the BVH's order), bvhNodes, materials (their
// tables in device.data), and the object constants (objectPrimitives,
// maxBounces, connect). options.connect: camera connections at diffuse
// vertices (kept only when some object's material connects);
// options.bruteForceObjects: a flat tree that tests every primitive
// instead of the BVH.
// Each primitive of object i records emitterOf[i] (Primitive.emitter: 1 +
// the index in device.lights of the object's emission; 0 or absent: none).
void compileObjects(const Scene& scene, const CompileOptions& options, DeviceScene& device,
                    const std::vector<uint32_t>& emitterOf = {});

}  // namespace spectrace
