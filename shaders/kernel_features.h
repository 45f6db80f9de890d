// Feature switches of the shared kernel. The trace shader defines them from
// specialisation constants, so a pipeline built for a scene compiles out
// what the scene lacks; these defaults (everything decided at run time) are
// the general pipeline's, and the CPU reference's. Each needs `constants`.
#ifndef SPECTRACE_KERNEL_FEATURES_H
#define SPECTRACE_KERNEL_FEATURES_H

#ifndef SPECTRACE_LIGHT_ENABLED
#define SPECTRACE_LIGHT_ENABLED(type) true
#endif
#ifndef SPECTRACE_SELECT_LIGHT
#define SPECTRACE_SELECT_LIGHT (constants.lightCount > 1u)
#endif
#ifndef SPECTRACE_CAMERA_TYPE
#define SPECTRACE_CAMERA_TYPE (constants.cameraType)
#endif
#ifndef SPECTRACE_AIM
#define SPECTRACE_AIM true
#endif
#ifndef SPECTRACE_EXACT_COLOUR
#define SPECTRACE_EXACT_COLOUR (constants.exactColour != 0u)
#endif
#ifndef SPECTRACE_SINGLE_CHUNK
#define SPECTRACE_SINGLE_CHUNK false  // the film may span several histogram chunks
#endif
#ifndef SPECTRACE_WEIGHTED
#define SPECTRACE_WEIGHTED (constants.weighted != 0u)  // weighted counts (device_shared.h)
#endif

// Whether the scene may hold primitives or materials of a type: a shader's
// `if` runs on lavapipe for every lane, met or not, so a type's test left in
// costs every beam that reaches the dispatch.
#ifndef SPECTRACE_PRIMITIVE_ENABLED
#define SPECTRACE_PRIMITIVE_ENABLED(type) true
#endif
#ifndef SPECTRACE_MATERIAL_ENABLED
#define SPECTRACE_MATERIAL_ENABLED(type) true
#endif
#ifndef SPECTRACE_OBJECTS
#define SPECTRACE_OBJECTS (constants.objectPrimitives > 0u)
#endif
#ifndef SPECTRACE_CAMERA_PATHS
#define SPECTRACE_CAMERA_PATHS ((constants.estimators & kEstimatorCameraPaths) != 0u)
#endif
#ifndef SPECTRACE_LIGHT_PATHS
#define SPECTRACE_LIGHT_PATHS ((constants.estimators & kEstimatorLightPaths) != 0u)
#endif
#ifndef SPECTRACE_RECORDING
#define SPECTRACE_RECORDING false  // true: note each beam's counts (BeamRecord) instead of counting them
#endif

#endif  // SPECTRACE_KERNEL_FEATURES_H
