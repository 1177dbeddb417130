#version 450
// The baseline kernel of docs/performance.md (plain_primary.glsl) on storage buffers.
#extension GL_GOOGLE_include_directive : require
#include "plain_primary.glsl"
