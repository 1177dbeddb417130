// Primary rays: the pinhole camera and the stratified jitter of ../shared/docs/render-model.md,
// written to give the same sample positions as host/render_model/sampling.h, bit for bit.
#ifndef VITRUM_CAMERA_GLSL
#define VITRUM_CAMERA_GLSL

#include "bindings.glsl"
#include "specialization.glsl"

#include "ieee_vector_math.glsl"

// Position of sample k of n inside its pixel, in [0, 1)^2: the pixel centre for one sample,
// otherwise a jittered point in cell (k % columns, k / columns) of a columns x (n / columns) grid.
vec2 sampleOffsetInPixel(uint pixelIndex, uint k, uint n, uint columns) {
    if (kSingleSample || n == 1u) return vec2(0.5);
    uint seed = pixelIndex * 2654435761u;
    float jx = hashToUnit(pcgHash(seed ^ pcgHash(2u * k)));
    float jy = hashToUnit(pcgHash(seed ^ pcgHash(2u * k + 1u)));
    uint rows = n / columns;
    return vec2((float(k % columns) + jx) / float(columns), (float(k / columns) + jy) / float(rows));
}

vec3 cameraRayDirection(vec2 imagePosition) {
    float halfWidth = 0.5 * float(imageWidth());
    float halfHeight = 0.5 * float(imageHeight());
    vec3 d = (imagePosition.x - halfWidth) * cameraAxisX() + (halfHeight - imagePosition.y) * cameraAxisY() -
             focalLength() * cameraAxisZ();
    return ieeeNormalize(d);
}

#endif
