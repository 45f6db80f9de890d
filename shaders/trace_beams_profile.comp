#version 460
// trace_beams.comp with the bench's cost profile (shaders/profile.h) in
// place of the whole kernel; never used to render.
#extension GL_GOOGLE_include_directive : require
#define SPECTRACE_WITH_PROFILE
#include "trace_shader.glsl"
