#version 450
// The baseline kernel of docs/performance.md (plain_primary.glsl) on uniform texel buffers.
#extension GL_GOOGLE_include_directive : require
#define PLAIN_TEXEL_BUFFERS
#include "plain_primary.glsl"
