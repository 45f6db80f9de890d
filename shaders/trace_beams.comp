#version 460
// The trace shader for light paths alone (trace_shader.glsl): camera paths
// compiled out, which lavapipe compiles in a fraction of the time the whole
// kernel takes. trace_camera_paths.comp is the same text with them.
#extension GL_GOOGLE_include_directive : require
#include "trace_shader.glsl"
