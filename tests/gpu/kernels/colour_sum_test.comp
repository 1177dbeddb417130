#version 460
// Test kernel for shaders/colour_sum.glsl: one invocation adds one ColourSumCase's terms, in
// order, to its starting sum, unsigned or signed as the case says.
#extension GL_GOOGLE_include_directive : require

#include "shared/gpu_types.h"
#include "colour_sum_test_types.h"
#include "colour_sum.glsl"

layout(local_size_x = kColourSumTestGroupSize) in;

layout(std430, binding = 0) readonly buffer Cases { ColourSumCase cases[]; };
layout(std430, binding = 1) writeonly buffer Results { ColourSumResult results[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    // The last group may run past the end; both buffers hold exactly the cases.
    if (i >= uint(cases.length()) || i >= uint(results.length())) return;
    ColourSumCase c = cases[i];
    ColourSum sum = ColourSum(c.startLow.xyz, c.startHigh.xyz);
    uint terms = min(c.startLow.w, 4u);
    bool signedSum = (c.startHigh.w & kColourSumSigned) != 0u;
    if ((c.startHigh.w & kColourSumDoubleStart) != 0u) addSignedColourSums(sum, sum);
    for (uint t = 0u; t < terms; ++t) {
        if (signedSum) addSignedColour(sum, c.terms[t].xyz);
        else addColour(sum, c.terms[t].xyz);
    }
    results[i].low = uvec4(sum.low, 0u);
    results[i].high = uvec4(sum.high, 0u);
    results[i].colour = vec4(signedSum ? colourOfSignedSum(sum) : colourOfSum(sum), 0.0);
}
