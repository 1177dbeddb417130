// The state of the pixel an invocation traces: the ray of its tree being traced or shaded, the
// traversal under way, the hit being shaded, and the pixel's progress. The resumable kernel keeps
// it between dispatches (suspend.glsl packs it into kTraceStateTexels texels).
#ifndef VITRUM_TRACE_STATE_GLSL
#define VITRUM_TRACE_STATE_GLSL

#include "shared/gpu_types.h"
#include "colour_sum.glsl"

// A BVH traversal of the ray origin + t direction, tMin < t < tMax (bvh.glsl).
struct Traversal {
    vec3 origin;
    float tMin;
    vec3 direction;
    float tMax;          // the nearest hit so far
    uint leafCursor;     // the next triangle of the leaf being tested, up to leafEnd
    uint leafEnd;
    uint closest;        // the nearest hit's triangle, or kNoTriangle
    uint stackTop;       // entries on the traversal stack (gStack), or kFreshTraversal
    vec2 barycentrics;   // the nearest hit's
    // The instance whose mesh the traversal is in (its ray moved there: gpu_types.h, "Instances"),
    // and the nearest hit's, or kNoInstance (the world); origin and direction stay the world's.
    uint instance;
    uint closestInstance;
};

// What a closest-hit traversal collects beyond its nearest hit (bvh.glsl's traverse).
struct Candidates {
    uvec4 touchingObjects;  // glass surfaces of other objects: object | entering << 31 (touching.glsl)
    vec4 touchingT;         // and the nearest t of each
    vec4 contact;           // the nearest opaque hit under glass: t, triangle (bits), barycentrics
    vec4 leaving;           // the nearest opaque surface the ray leaves through: the same
    bool closestIsGlass;    // the nearest hit so far is glass
    uint contactInstance;   // the instance of `contact`'s triangle, and of `leaving`'s
    uint leavingInstance;
};

// The hit being shaded.
struct Hit {
    vec3 position;
    float t;
    vec3 shadingNormal;
    uint material;
    vec3 geometricNormal;
    uint object;            // the closed mesh hit (gpu_types.h's TriangleVertices)
    vec2 uv;                // texture coordinates
};

struct TraceState {
    PendingRay ray;         // the ray traced or shaded
    Traversal traversal;
    Candidates candidates;
    Hit hit;
    uvec4 touching;         // surfaces of other objects touching a glass hit: object | entering
                            // << 31 in .xyz, how many in .w (shading.glsl's finishTrace)
    float farthestTouching; // the farthest of them along the ray: transmitted rays start beyond it
    vec3 shadowLight;       // the direct light the pending shadow ray adds if it is unoccluded
    ColourSum colour;       // the pixel's samples so far
    uint samplesDone;
    uint phase;             // kPhase*
    uint pendingRays;       // the top of the pixel's pending rays (pending_rays.glsl)
    uint light;             // the light whose direct term is next (kPhaseNextLight, kPhaseShadow)
    uint steps;             // loop steps the pixel has run, over all its dispatches
};

// The whole state of this pixel.
TraceState st;

const uint kPhaseStartSample = 0u;  // make the next primary ray, or finish the pixel
const uint kPhaseTrace = 1u;        // closest-hit traversal of st.ray
const uint kPhaseNextLight = 2u;    // direct light from light st.light, or go on to scatter
const uint kPhaseShadow = 3u;       // any-hit traversal towards light st.light
const uint kPhaseScatter = 4u;      // spawn reflected / refracted rays
const uint kPhaseNextRay = 5u;      // pop a pending ray, or finish the sample
const uint kPhaseDone = 6u;

// origin.w: the depth in its low 8 bits; above them, with dispersion, the ray's wavelength
// (media.glsl's wavelengthCode).
uint rayDepth(PendingRay r) { return floatBitsToUint(r.origin.w) & 0xFFu; }
uint mediaCount(PendingRay r) { return floatBitsToUint(r.direction.w); }
uint materialModel(GpuMaterial m) { return floatBitsToUint(m.ambient.w); }

#endif
