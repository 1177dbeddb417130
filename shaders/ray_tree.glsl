// The order of a pixel's rays: its samples' primary rays, then each ray tree depth first, the
// pending rays last in first out.
#ifndef VITRUM_RAY_TREE_GLSL
#define VITRUM_RAY_TREE_GLSL

#include "trace_state.glsl"
#include "counters.glsl"
#include "pending_rays.glsl"
#include "ray_sharing.glsl"
#include "cutout.glsl"  // cutAway, which bvh.glsl calls
#include "bvh.glsl"
#include "camera.glsl"
#include "ray_offset.glsl"
#include "media.glsl"
#include "ieee_vector_math.glsl"

void beginRay() {
    counters.maxRayDepth = max(counters.maxRayDepth, rayDepth(st.ray));
    beginClosestTraversal();
}

// The next sample's primary ray through `pixel`.
void startPrimaryRay(uvec2 pixel) {
    uint pixelIndex = pixel.y * imageWidth() + pixel.x;
    uint k = st.samplesDone;
    vec2 position = vec2(pixel) + sampleOffsetInPixel(pixelIndex, k, samplesPerPixel(), sampleGridColumns());
    vec3 d = cameraRayDirection(position);
    // Off the surface the camera lies on (a normal of 0 where none), on the ray's side, with that
    // side's media (host/analysis/camera_surface.h: primaryRayOrigin).
    vec3 n = cameraSurfaceNormal();
    bool behind = ieeeDot(d, n) < 0.0;
    st.ray.origin = vec4(offsetRayOrigin(cameraPosition(), behind ? -n : n), uintBitsToFloat(0u));
    uint media = behind ? cameraMediaBehindCount() : cameraMediaCount();
    st.ray.direction = vec4(d, uintBitsToFloat(usesMaterial(kMaterialGlass) ? media : 0u));
    st.ray.weight = vec4(1.0, 1.0, 1.0, 0.0);  // .w: no partly covered surface to pass by
    st.ray.media = behind ? params.cameraMediaBehind : params.cameraMedia;  // innermost last
    st.ray.weight.xyz *= skippedTransmittance(st.ray, cameraPosition());
    st.pendingRays = 0u;
    if (maxDepth() == 0u) {
        // max_depth 0: not even the primary ray is traced (render model); the sample is black.
        counters.depthLimitHits += 1u;
        st.phase = kPhaseNextRay;
        return;
    }
    counters.primaryRays += 1u;
    beginClosestTraversal();
}

void nextRay() {
    if (kPendingRayCapacity == 0u || st.pendingRays == gBottom) {
        if (kRaySharing && gTaken) {
            st.phase = kPhaseDone;  // the taken tree is done: ray_sharing.glsl hands it back
            return;
        }
        st.pendingRays = 0u;
        gBottom = 0u;
        st.samplesDone += 1u;
        st.phase = kPhaseStartSample;
        return;
    }
    st.pendingRays -= 1u;
    loadPendingRay(pendingRayIndex(st.pendingRays));
}

// The next sample's primary ray, or the end of the pixel.
void startSample(uvec2 pixel) {
    if (st.samplesDone >= samplesPerPixel()) st.phase = kPhaseDone;
    else startPrimaryRay(pixel);  // begins a traversal, or (max_depth 0) goes to kPhaseNextRay
}

// A pixel's first dispatch.
void startPixel() {
    st.colour = kNoColour;
    st.samplesDone = 0u;
    st.phase = kPhaseStartSample;
    st.pendingRays = 0u;
    st.light = 0u;
    st.steps = 0u;
}

#endif
