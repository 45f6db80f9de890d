#version 460
// The trace shader with camera paths (trace_shader.glsl, shaders/camera_path.h),
// for scenes whose estimators include them.
#extension GL_GOOGLE_include_directive : require
#define SPECTRACE_WITH_CAMERA_PATHS
#include "trace_shader.glsl"
