// Buffer elements of tests/gpu/kernels/colour_sum_test.comp, the kernel that adds colours to a fixed-point
// sum (shaders/colour_sum.glsl) for single cases. Shared by the C++ host and GLSL like gpu_types.h.
#ifndef VITRUM_COLOUR_SUM_TEST_TYPES_H
#define VITRUM_COLOUR_SUM_TEST_TYPES_H

#include "shared/gpu_types.h"

#ifdef __cplusplus
namespace vitrum::gpu {
#endif

struct ColourSumCase {
    uvec4 startLow;   // the sum to start from: .xyz = low words, .w = how many terms follow (0..4)
    uvec4 startHigh;  // .xyz = high words; .w = kColourSumSigned: signed sums (addSignedColour),
                      // | kColourSumDoubleStart: first the start added to itself (addSignedColourSums)
    vec4 terms[4];    // .xyz = colours added in this order; .w unused
};

struct ColourSumResult {
    uvec4 low;    // .xyz
    uvec4 high;   // .xyz
    vec4 colour;  // .xyz = colourOfSum, or colourOfSignedSum for a signed case
};

VITRUM_CONST uint kColourSumSigned = 1u;
VITRUM_CONST uint kColourSumDoubleStart = 2u;

VITRUM_CONST uint kColourSumTestGroupSize = 64u;  // local_size_x of colour_sum_test.comp

#ifdef __cplusplus
}  // namespace vitrum::gpu
#endif
#endif
