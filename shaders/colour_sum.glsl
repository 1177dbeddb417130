// A pixel's colour as a sum that does not depend on the order of its terms: 64-bit fixed point
// per channel, 32 bits of them below the binary point, kept as two uint words (no 64-bit integer
// feature needed).
//
// Why: lanes of a SIMD group trace one another's pending rays (ray_sharing.glsl), so the rays
// of a pixel finish in an order that depends on its neighbours and on the step budget. Float sums
// would then round differently from run to run of the same scene in another configuration;
// integer sums are the same in any order, so the image is bit for bit the same whichever lane
// traced which ray, and whether the pixel was suspended or not. What a lane adds is one round of
// shading's float sum (trace.comp's traceUnit: a round is a unit of one ray, the same whichever
// lane runs it), truncated to a multiple of 2^-32: below any visible difference, and finer than
// float's own rounding for every value above 2^-8. A term is clamped to [0, 2^32) and a sum past
// 2^32 stays at the largest value; a negative or NaN term, which no valid scene makes, adds 0
// (docs/render-model-decisions.md).
#ifndef VITRUM_COLOUR_SUM_GLSL
#define VITRUM_COLOUR_SUM_GLSL

const float kColourSumLimit = 4294967040.0;  // the largest float below 2^32

// A sum of colours: each channel a 64-bit number, its low and high words.
struct ColourSum {
    uvec3 low;
    uvec3 high;
};

const ColourSum kNoColour = ColourSum(uvec3(0u), uvec3(0u));

// sum += add; a sum past 2^64 - 1 saturates.
void addColourSums(inout ColourSum sum, ColourSum add) {
    uvec3 carry, wrapA, wrapB;
    uvec3 sumLow = uaddCarry(sum.low, add.low, carry);
    uvec3 sumHigh = uaddCarry(sum.high, add.high, wrapA);
    sumHigh = uaddCarry(sumHigh, carry, wrapB);
    bvec3 saturated = notEqual(wrapA | wrapB, uvec3(0u));
    sum.low = mix(sumLow, uvec3(0xFFFFFFFFu), saturated);
    sum.high = mix(sumHigh, uvec3(0xFFFFFFFFu), saturated);
}

// Adds a colour (float) to the sum.
void addColour(inout ColourSum sum, vec3 colour) {
    // NaN compares false: it becomes 0 as a negative term does.
    vec3 c = mix(vec3(0.0), min(colour, vec3(kColourSumLimit)), greaterThan(colour, vec3(0.0)));
    uvec3 whole = uvec3(c);                                   // c >= 0: truncation is floor
    uvec3 fraction = uvec3((c - vec3(whole)) * 4294967296.0);  // exact: c - floor(c) and * 2^32
    addColourSums(sum, ColourSum(fraction, whole));
}

vec3 colourOfSum(ColourSum sum) { return vec3(sum.high) + vec3(sum.low) * (1.0 / 4294967296.0); }

#endif
