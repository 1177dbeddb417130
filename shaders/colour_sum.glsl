// A pixel's colour as a sum that does not depend on the order of its terms: 64-bit fixed point
// per channel, 32 bits of them below the binary point, kept as two uint words (no 64-bit integer
// feature needed). Lanes trace one another's rays (ray_sharing.glsl), so a pixel's rays finish in
// an order that depends on its neighbours and the budget; integer sums keep the image the same
// bit for bit (docs/gpu-design.md, "The ray tree"). A term is one round of shading's float sum,
// truncated to a multiple of 2^-32 and clamped to [0, 2^32); a sum saturates; a negative or NaN
// term adds 0 (docs/render-model-decisions.md, "Pixel sanitising (GPU)").
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

// With dispersion a term may be negative in a channel, where a wavelength sample's weight lies
// outside sRGB's gamut (render-model-decisions.md, "Dispersion"): the sum is then a signed 64-bit
// number in two's complement, a negative term subtracted; a NaN term adds 0.
void addSignedColour(inout ColourSum sum, vec3 colour) {
    vec3 magnitude = mix(vec3(0.0), min(abs(colour), vec3(kColourSumLimit)), equal(colour, colour));
    uvec3 whole = uvec3(magnitude);
    uvec3 fraction = uvec3((magnitude - vec3(whole)) * 4294967296.0);
    uvec3 carry, borrow;
    uvec3 addedLow = uaddCarry(sum.low, fraction, carry);
    uvec3 addedHigh = sum.high + whole + carry;
    uvec3 subtractedLow = usubBorrow(sum.low, fraction, borrow);
    uvec3 subtractedHigh = sum.high - whole - borrow;
    bvec3 negative = lessThan(colour, vec3(0.0));
    sum.low = mix(addedLow, subtractedLow, negative);
    sum.high = mix(addedHigh, subtractedHigh, negative);
}

// sum += add for signed sums: two's complement wraps, it does not saturate.
void addSignedColourSums(inout ColourSum sum, ColourSum add) {
    uvec3 carry;
    sum.low = uaddCarry(sum.low, add.low, carry);
    sum.high = sum.high + add.high + carry;
}

vec3 colourOfSignedSum(ColourSum sum) {
    bvec3 negative = greaterThanEqual(sum.high, uvec3(0x80000000u));
    uvec3 carry;
    uvec3 negatedLow = uaddCarry(~sum.low, uvec3(1u), carry);
    uvec3 negatedHigh = ~sum.high + carry;
    vec3 magnitude = colourOfSum(ColourSum(mix(sum.low, negatedLow, negative), mix(sum.high, negatedHigh, negative)));
    return mix(magnitude, -magnitude, negative);
}

#endif
