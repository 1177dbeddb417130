#version 460
// The ray tree of docs/render-model.md, one pixel per invocation, for one tile of the image.
//
// lavapipe silently ends a shader's loops after 65,535 iterations of a SIMD group. So every loop
// iteration of this kernel is one small counted step (one BVH node, one leaf, one triangle, or one
// round of shading, see main), counted for the group (bvh.glsl's traverse). A dispatch runs at most
// `params.counts.w` steps per group and unit of pixels. The first dispatch of a tile gives up the
// pixels that are not done by then; the resumable build of this kernel (kResumable) restarts them
// and keeps their state between its dispatches (suspend.glsl), and the host dispatches it until
// every pixel of the tile is done. Nothing recurses. In the first dispatch, where subgroups are
// full, a lane whose pixel is done takes pending rays of the other lanes of its group
// (ray_sharing.glsl), and on a device that runs on the CPU a subgroup goes on to the tile's next
// unit of pixels when its own are done (main).
#extension GL_GOOGLE_include_directive : require
// The default build uses subgroup operations: to count the SIMD group's loop iterations
// (lanes.glsl) and to sum its statistics over each subgroup before adding them up atomically
// (statistics.glsl). The build with VITRUM_NO_SUBGROUP_OPERATIONS (trace_without_subgroups.spv.h)
// is for devices without subgroup arithmetic and ballots.

#include "shared/gpu_types.h"
#include "bindings.glsl"
#include "specialization.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// The whole state of this pixel; the resumable kernel keeps it in stateTexels[] between its
// dispatches (suspend.glsl).
TraceState st;

// Counters of this invocation, added to stats[] once at the end.
uint gPixelSteps = 0u;  // loop iterations this pixel's lane ran (was active in)
uint gNodeVisits = 0u;
uint gTraversalOverflows = 0u;

// What this round of shading (main's loop) adds to the pixel's colour: a float sum of a few
// terms, added to the fixed-point sum once at the round's end (colour_sum.glsl).
vec3 gRoundColour = vec3(0.0);

uint gTouchingInterfaces = 0u;
uint gTouchingProbes = 0u;
uint gMediumStackOverflows = 0u;

// This invocation's pixel in the image (main's tilePixel() in the tile).
uvec2 gPixel = uvec2(0u);

// This pixel's pending rays: entries 0 .. kPendingRayCapacity - 1 of its place in pendingRays
// (pendingRayIndex), the ones waiting from gBottom up to st.control.y; below gBottom, those that
// other lanes took (ray_sharing.glsl).
uint gBottom = 0u;

// Where entry `entry` of this pixel's pending rays is: entry-major, so that the deeper entries,
// which few pixels reach, lie together. In the first dispatch pending rays are the invocation's,
// kept only while it traces a unit (a pixel it gives up starts again from nothing), so the
// persistent kernel's invocations, 8 times fewer than a tile's pixels, use 8 times less memory
// and use it again unit after unit. The resumable kernel keeps them by slot, across dispatches.
// Memory matters beyond the caches: a fresh buffer's first touch of a page is a page fault,
// about 10 us on the machines of docs/performance.md; by slot, with a slot's entries together,
// a render of bubble at 640x480 took 7,000 more faults and 27% longer (docs/gpu-design.md).
uint gPendingPlace = 0u;
uint gPendingStride = 0u;
uint pendingRayIndex(uint entry) { return entry * gPendingStride + gPendingPlace; }

void placePendingRays(uint slot) {
    if (kResumable) {
        gPendingPlace = slot;
        gPendingStride = params.tile.z * params.tile.w;
    } else {
        uint invocations = gl_WorkGroupSize.x * gl_WorkGroupSize.y;
        uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
        gPendingPlace = group * invocations + gl_LocalInvocationIndex;
        gPendingStride = gl_NumWorkGroups.x * gl_NumWorkGroups.y * invocations;
    }
}

// The pending ray read this round, at its one load site (main's loop, after shading, where a lane
// that gives one of its rays to another reads it too, ray_sharing.glsl): on lavapipe every
// storage-buffer load site is a loop over the lanes each round, whether a lane loads or not.
uint gLoadIndex = 0u;
bool gLoad = false;
// This pixel's BVH traversal stack, in private memory while the kernel runs: on lavapipe that is
// cheaper than a storage buffer, whose every access loops over the lanes. A pixel suspended in
// the middle of a traversal keeps it in traversalStacks[stackBase .. stackBase + kTraversalStackSize).
uint stackBase = 0u;
uint gStack[kTraversalStackSize];

#include "bvh.glsl"
#include "ieee_vector_math.glsl"
#include "camera.glsl"
#include "optics.glsl"
#include "ray_offset.glsl"
#include "texture.glsl"
#include "background.glsl"
#include "colour_sum.glsl"

const uint kPhaseStartSample = 0u;  // make the next primary ray, or finish the pixel
const uint kPhaseTrace = 1u;        // closest-hit traversal of st.ray
const uint kPhaseNextLight = 2u;    // direct light from light st.control.z, or go on to scatter
const uint kPhaseShadow = 3u;       // any-hit traversal towards light st.control.z
const uint kPhaseScatter = 4u;      // spawn reflected / refracted rays
const uint kPhaseNextRay = 5u;      // pop a pending ray, or finish the sample
const uint kPhaseDone = 6u;

// A pending ray in the buffer. On lavapipe each member moved is a loop over the 8 lanes, with a
// branch on each lane's mask: with a medium stack of one, the ray's one medium travels in its
// weight's unused .w (a child's weight.w is 0, and media beyond the first are 0), so that three
// members are moved instead of four.
void storePendingRay(uint index, PendingRay r) {
    if (kMediumStackDepth > 1u) {
        pendingRays[index] = r;
        return;
    }
    pendingRays[index].origin = r.origin;
    pendingRays[index].direction = r.direction;
    pendingRays[index].weight = vec4(r.weight.xyz, uintBitsToFloat(r.media.x));
}

PendingRay readPendingRay(uint index) {
    if (kMediumStackDepth > 1u) return pendingRays[index];
    PendingRay r;
    r.origin = pendingRays[index].origin;
    r.direction = pendingRays[index].direction;
    vec4 weight = pendingRays[index].weight;
    r.weight = vec4(weight.xyz, 0.0);
    r.media = uvec4(floatBitsToUint(weight.w), 0u, 0u, 0u);
    return r;
}

// The pending ray at `index` goes on as st.ray: read at the round's end (main).
void loadPendingRay(uint index) {
    gLoadIndex = index;
    gLoad = true;
    st.control.x = kPhaseTrace;  // beginRay, once the ray is read, begins its traversal
}

#include "ray_sharing.glsl"

uint gPrimaryRays = 0u;
uint gShadowRays = 0u;
uint gReflectionRays = 0u;
uint gRefractionRays = 0u;
uint gDepthLimitHits = 0u;
uint gRayStackOverflows = 0u;
uint gWeightCuts = 0u;
uint gTotalInternalReflections = 0u;
uint gAbsorbedEscapes = 0u;
uint gInconsistentMedia = 0u;
uint gMaxRayDepth = 0u;
uint gMaxMediumDepth = 0u;

uint rayDepth(PendingRay r) { return floatBitsToUint(r.origin.w); }
uint mediaCount(PendingRay r) { return floatBitsToUint(r.direction.w); }
uint hitMaterial() { return floatBitsToUint(st.hitNormal.w); }
uint hitObject() { return floatBitsToUint(st.hitGeometricNormal.w); }
uint materialModel(GpuMaterial m) { return floatBitsToUint(m.ambient.w); }

// IOR of the medium inside the innermost of `count` objects in `media`, or of the scene's air.
float ior(uvec4 media, uint count) {
    if (!usesMaterial(kMaterialGlass) || count == 0u) return params.background.w;
    return objectMedium(media[count - 1u]).w;
}

// IOR of the medium a ray is in.
float mediumIor(PendingRay r) { return ior(r.media, mediaCount(r)); }

vec3 mediumAttenuation(PendingRay r) {
    if (!kAbsorption) return vec3(0.0);
    uint count = mediaCount(r);
    return count == 0u ? vec3(0.0) : objectMedium(r.media[count - 1u]).xyz;
}

// A closest-hit traversal of st.ray, with no touching candidates yet (touching.glsl), no
// opaque surface under glass and none the ray leaves through (bvh.glsl's traverse).
void beginClosestTraversal() {
    if (kTouchingProbe) {
        st.touching = uvec4(0u);
        st.probe = vec4(kNoCandidate);
    }
    if (kOpaqueContact) {
        st.hitPosition = vec4(kNoCandidate, uintBitsToFloat(kNoTriangle), 0.0, 0.0);
        st.hitNormal.x = 0.0;
    }
    if (kCoincidentOpaque) st.hitGeometricNormal = vec4(kNoCandidate, uintBitsToFloat(kNoTriangle), 0.0, 0.0);
    beginTraversal(st.ray.origin.xyz, st.ray.direction.xyz, 0.0, 3.0e38);
    st.control.x = kPhaseTrace;
}

// The work of a dispatch comes in units: where subgroups are full, a unit is a subgroup's share
// of an 8x8 block of the tile's part inside the image; elsewhere a workgroup traces its own block
// and there is one unit, its own.
//
// Which unit: lavapipe splits a dispatch's workgroups, in order, into one run of consecutive
// workgroups a thread (Mesa's lp_cs_tpool), so a thread whose run covers the glass works on while
// the other waits. Where subgroups are full, each subgroup instead takes the dispatch's next unit
// from a counter: the threads take turns through the tile, each near the other, and a unit is the
// same pixels whichever thread takes it (so are the images and statistics). The persistent
// kernel's subgroups go on taking units (main), so that a thread that is ahead takes more of them.
uvec2 tileBlocks() {
    uvec2 inside = min(params.tile.zw, params.image.xy - min(params.tile.xy, params.image.xy));
    return (inside + gl_WorkGroupSize.xy - 1u) / gl_WorkGroupSize.xy;
}

uint tileUnits() {
#ifndef VITRUM_NO_SUBGROUP_OPERATIONS
    if (kFullSubgroups) {
        uvec2 blocks = tileBlocks();
        return blocks.x * blocks.y * gl_NumSubgroups;
    }
#endif
    return 1u;
}

// The dispatch's next unit (the same in every lane).
uint takeUnit() {
#ifndef VITRUM_NO_SUBGROUP_OPERATIONS
    if (kFullSubgroups) {
        uint unit = 0u;
        if (firstLane()) unit = atomicAdd(stats[kWorkCursor], 1u);
        return fromFirstLane(unit);
    }
#endif
    return 0u;
}

// This invocation's pixel in `unit`, relative to the tile. A block is walked in Morton order, so
// that the 8 lanes of a lavapipe SIMD group cover 4x2 pixels rather than a row of 8: nearer pixels
// send nearer rays, which visit more of the same BVH nodes, and the group's loops run fewer
// iterations (docs/gpu-design.md).
uvec2 tilePixel(uint unit) {
    uvec2 block = gl_WorkGroupID.xy;
    uint i = gl_LocalInvocationIndex;
#ifndef VITRUM_NO_SUBGROUP_OPERATIONS
    if (kFullSubgroups) {
        uint blockIndex = unit / gl_NumSubgroups;
        uint blocksX = tileBlocks().x;
        block = uvec2(blockIndex % blocksX, blockIndex / blocksX);
        i = (unit % gl_NumSubgroups) * gl_SubgroupSize + gl_SubgroupInvocationID;
    }
#endif
    uvec2 inBlock = uvec2((i & 1u) | ((i >> 1u) & 2u) | ((i >> 2u) & 4u), ((i >> 1u) & 1u) | ((i >> 2u) & 2u) | ((i >> 3u) & 4u));
    return block * gl_WorkGroupSize.xy + inBlock;
}

void startPrimaryRay() {
    uvec2 pixel = gPixel;
    uint pixelIndex = pixel.y * params.image.x + pixel.x;
    uint k = st.colourLow.w;
    vec2 position = vec2(pixel) + sampleOffsetInPixel(pixelIndex, k, params.image.z, params.pass.y);
    vec3 d = cameraRayDirection(position);
    // Off the surface the camera lies on (a normal of 0 where none), on the ray's side, with that
    // side's media (host/render/camera_surface.h: primaryRayOrigin).
    vec3 n = params.cameraSurface.xyz;
    bool behind = ieeeDot(d, n) < 0.0;
    st.ray.origin = vec4(offsetRayOrigin(params.cameraFrom.xyz, behind ? -n : n), uintBitsToFloat(0u));
    uint media = behind ? params.pass.z : params.pass.x;
    st.ray.direction = vec4(d, uintBitsToFloat(usesMaterial(kMaterialGlass) ? media : 0u));
    st.ray.weight = vec4(1.0);
    st.ray.media = behind ? params.cameraMediaBehind : params.cameraMedia;  // innermost last
    st.control.y = 0u;
    if (params.image.w == 0u) {
        // max_depth 0: not even the primary ray is traced (render model); the sample is black.
        gDepthLimitHits += 1u;
        st.control.x = kPhaseNextRay;
        return;
    }
    gPrimaryRays += 1u;
    beginClosestTraversal();
}

// The closest-hit traversal of st.ray is over: record the hit (triangle `tri`, material `m`, both
// read by main) or take the background.
void finishTrace(TriangleVertices tri, GpuMaterial m) {
    uint triangle = st.traversal.z;
    // Beer-Lambert over the segment just travelled (render model: "Media: the IOR stack").
    vec3 mu = mediumAttenuation(st.ray);
    if (triangle == kNoTriangle) {
        vec3 escaped = st.ray.weight.xyz * backgroundRadiance(st.ray.direction.xyz);
        if (any(greaterThan(mu, vec3(0.0)))) {
            // Only an open mesh lets a ray leave the scene inside an absorbing medium.
            escaped *= vec3(equal(mu, vec3(0.0)));
            gAbsorbedEscapes += 1u;
        }
        gRoundColour += escaped;
        st.control.x = kPhaseNextRay;
        return;
    }
    float t = st.traceDirection.w;
    if (kAbsorption) st.ray.weight.xyz *= beerLambert(mu, t);  // exp(-0 t) is 1 only for finite t: not folded

    mat3 normals = loadVertexNormals(triangle);
    vec2 bary = st.hitUv.zw;
    float w0 = 1.0 - bary.x - bary.y;
    vec3 edgeCross = windingNormal(tri);
    float crossLength = ieeeLength(edgeCross);
    vec3 interpolated = w0 * normals[0] + bary.x * normals[1] + bary.y * normals[2];
    float normalLength = ieeeLength(interpolated);
    bool shadingValid = normalLength > 0.0 && !isinf(normalLength);
    // A triangle whose corners are collinear has no geometric normal but can still be hit by
    // rounding: fall back to the shading normal, else to facing the ray (hard-cases.md).
    vec3 geometricNormal = crossLength > 0.0 && !isinf(crossLength)
                               ? edgeCross / crossLength
                               : (shadingValid ? interpolated / normalLength : -st.ray.direction.xyz);
    vec3 shadingNormal = shadingValid ? interpolated / normalLength : geometricNormal;
    // The hit point from the barycentrics, not origin + t d: it lies on the triangle to within
    // rounding (Waechter and Binder).
    vec3 position = w0 * tri.v0.xyz + bary.x * tri.v1.xyz + bary.y * tri.v2.xyz;
    st.hitPosition = vec4(position, t);
    st.hitNormal = vec4(shadingNormal, tri.v0.w);
    st.hitGeometricNormal = vec4(geometricNormal, tri.v1.w);
    if (kTextures) {  // only texture lookups read them
        vec2 uv0, uv1, uv2;
        loadCornerUvs(triangle, uv0, uv1, uv2);
        st.hitUv.xy = w0 * uv0 + bary.x * uv1 + bary.y * uv2;
    }

    uint model = materialModel(m);
    if (usesMaterial(kMaterialGlass) && model == kMaterialGlass) {
        // Touching objects (lecture, "Problematic Cases"): the other glass surfaces within the
        // touching distance of this hit along the ray, which the traversal collected.
        float farthest = t;
        uvec4 touching = uvec4(0u);
        if (kTouchingProbe && params.tuning.z != 0.0) {
            gTouchingProbes += 1u;
            touching = selectTouching(st.touching, st.probe, t + params.tuning.y, hitObject(), farthest);
        }
        st.touching = touching;
        st.probe.x = farthest;
        st.control.x = kPhaseScatter;
        return;
    }
    // Opaque: both normals face the incoming ray.
    vec3 d = st.ray.direction.xyz;
    if (ieeeDot(geometricNormal, d) > 0.0) st.hitGeometricNormal.xyz = -geometricNormal;
    if (ieeeDot(shadingNormal, d) > 0.0) st.hitNormal.xyz = -shadingNormal;
    if (usesMaterial(kMaterialNormal) && model == kMaterialNormal) {
        gRoundColour += st.ray.weight.xyz * (0.5 * st.hitNormal.xyz + 0.5);
        st.control.x = kPhaseNextRay;
        return;
    }
    st.control.z = 0u;
    st.control.x = usesMaterial(kMaterialMirror) && model == kMaterialMirror ? kPhaseScatter : kPhaseNextLight;
}

vec3 diffuseColour(GpuMaterial m) {
    uint texture = floatBitsToUint(m.diffuse.w);
    return !kTextures || texture == kNoTexture ? m.diffuse.xyz
                                 : sampleTexture(texture, vec2(st.hitUv.x, 1.0 - st.hitUv.y), true, true);
}

// The visibility-weighted part of light `index` at the hit: m_d max(0, n.l) (+ Phong's
// m_s max(0, l_r.v)^Ns), times the light's colour and fall-off.
vec3 directLight(GpuMaterial m, GpuLight light) {
    vec3 p = st.hitPosition.xyz;
    vec3 n = st.hitNormal.xyz;
    vec3 toLight = light.position.xyz - p;
    float distanceSquared = ieeeDot(toLight, toLight);
    vec3 l = toLight / sqrt(distanceSquared);  // as the CPU reference divides
    vec3 colour = light.colour.xyz;
    if (light.position.w != 0.0) colour /= distanceSquared;
    vec3 result = diffuseColour(m) * max(0.0, ieeeDot(n, l));
    if (usesMaterial(kMaterialPhong) && materialModel(m) == kMaterialPhong) {
        vec3 lr = 2.0 * ieeeDot(n, l) * n - l;
        float c = max(0.0, ieeeDot(lr, -st.ray.direction.xyz));
        float ns = m.specular.w;
        float highlight = c > 0.0 ? pow(c, ns) : (ns == 0.0 ? 1.0 : 0.0);
        result += m.specular.xyz * highlight;
    }
    return colour * result;
}

// Lambert and Phong: ambient from every light, then one shadow ray per light whose direct term
// is not zero; the shadow ray carries that term (st.probe.yzw) to finishShadow.
void nextLight(GpuMaterial m) {
    uint index = st.control.z;
    if (!kShadowRays || index >= params.counts.x) {
        st.control.x = usesMaterial(kMaterialPhong) && materialModel(m) == kMaterialPhong ? kPhaseScatter : kPhaseNextRay;
        return;
    }
    GpuLight light = loadLight(index);
    gRoundColour += st.ray.weight.xyz * light.colour.xyz * m.ambient.xyz;
    vec3 direct = directLight(m, light);
    if (all(equal(direct, vec3(0.0)))) {
        st.control.z = index + 1u;
        return;
    }
    vec3 origin = offsetRayOrigin(st.hitPosition.xyz, st.hitGeometricNormal.xyz);
    gShadowRays += 1u;
    st.probe.yzw = direct;
    beginTraversal(origin, light.position.xyz - origin, 0.0, 1.0);
    st.control.x = kPhaseShadow;
}

void finishShadow() {
    if (st.traversal.z == kNoTriangle) gRoundColour += st.ray.weight.xyz * st.probe.yzw;
    st.control.z += 1u;
    st.control.x = kPhaseNextLight;
}

// Whether a child of st.ray at `depth` with path weight `weight` is traced; a limit that stops
// it is counted.
bool admitChild(uint depth, vec3 weight) {
    if (depth >= params.image.w) {
        gDepthLimitHits += 1u;
        return false;
    }
    if (all(lessThan(weight, vec3(params.tuning.x)))) {
        gWeightCuts += 1u;
        return false;
    }
    return true;
}

PendingRay childRay(vec3 origin, vec3 direction, vec3 weight, uvec4 media, uint count, uint depth) {
    PendingRay r;
    r.origin = vec4(origin, uintBitsToFloat(depth));
    r.direction = vec4(direction, uintBitsToFloat(count));
    r.weight = vec4(weight, 0.0);
    r.media = media;
    return r;
}

// The medium stack, written without loops: every loop iteration counts against lavapipe's limit.
// Removes the innermost entry of `object` (normally the top); a ray leaving an object it is not
// inside (an open or badly wound mesh) keeps its stack, and that is counted.
// The innermost place of `object` in the stack, or `count` where the ray is not inside it.
uint innermostMedium(uvec4 media, uint count, uint object) {
    uint found = count;
    if (count > 0u && media[0] == object) found = 0u;
    if (kMediumStackDepth > 1u && count > 1u && media[1] == object) found = 1u;
    if (kMediumStackDepth > 2u && count > 2u && media[2] == object) found = 2u;
    if (kMediumStackDepth > 3u && count > 3u && media[3] == object) found = 3u;
    return found;
}

void leaveMedium(inout uvec4 media, inout uint count, uint object) {
    uint found = innermostMedium(media, count, object);
    if (found == count) {
        gInconsistentMedia += 1u;
        return;
    }
    if (kMediumStackDepth > 1u && found <= 0u && 1u < count) media[0] = media[1];
    if (kMediumStackDepth > 2u && found <= 1u && 2u < count) media[1] = media[2];
    if (kMediumStackDepth > 3u && found <= 2u && 3u < count) media[2] = media[3];
    count -= 1u;
}

// Entering an object the ray is already inside keeps the stack, and is counted, as leaving one
// it is not inside: a closed mesh cannot be entered twice (where rounding lost a crossing it can
// seem so), and the stack never holds an object twice, so the nesting bounds its depth.
void enterMedium(inout uvec4 media, inout uint count, uint object) {
    if (innermostMedium(media, count, object) != count) {
        gInconsistentMedia += 1u;
        return;
    }
    if (count >= kMediumStackDepth) {
        gMediumStackOverflows += 1u;
        return;
    }
    media[count] = object;
    count += 1u;
}

// Glass: the ray enters or leaves object k, decided by the geometric normal of the consistently
// wound mesh; the medium stack says what is on the other side. Surfaces of other glass objects
// touching the hit (st.touching) make one interface with it: the ray leaves, then enters, so
// glass touching glass is glass -> glass (lecture: P2 is 1.5 -> 1.5, never 1.5 -> 1 -> 1.5).
// Returns whether the ray enters the hit object; `media` and `count` become the stack beyond.
bool crossGlass(inout uvec4 media, inout uint count) {
    bool entering = ieeeDot(st.ray.direction.xyz, st.hitGeometricNormal.xyz) < 0.0;
    uint touchingCount = kTouchingProbe ? st.touching.w : 0u;
    if (touchingCount > 0u) gTouchingInterfaces += 1u;
    // Leaving first ...
    if (!entering) leaveMedium(media, count, hitObject());
    if (touchingCount > 0u && (st.touching.x & 0x80000000u) == 0u) leaveMedium(media, count, st.touching.x);
    if (touchingCount > 1u && (st.touching.y & 0x80000000u) == 0u) leaveMedium(media, count, st.touching.y);
    if (touchingCount > 2u && (st.touching.z & 0x80000000u) == 0u) leaveMedium(media, count, st.touching.z);
    // ... then entering.
    if (entering) enterMedium(media, count, hitObject());
    if (touchingCount > 0u && (st.touching.x & 0x80000000u) != 0u) enterMedium(media, count, st.touching.x & 0x7FFFFFFFu);
    if (touchingCount > 1u && (st.touching.y & 0x80000000u) != 0u) enterMedium(media, count, st.touching.y & 0x7FFFFFFFu);
    if (touchingCount > 2u && (st.touching.z & 0x80000000u) != 0u) enterMedium(media, count, st.touching.z & 0x7FFFFFFFu);
    gMaxMediumDepth = max(gMaxMediumDepth, count);
    return entering;
}

// Whether any material of this build spawns reflected or refracted rays.
bool spawnsRays() {
    return usesMaterial(kMaterialPhong) || usesMaterial(kMaterialMirror) || usesMaterial(kMaterialGlass);
}

void beginRay() {
    gMaxRayDepth = max(gMaxRayDepth, rayDepth(st.ray));
    beginClosestTraversal();
}

// The hit's children. The one traced next goes on at once as st.ray: the reflection (of a
// mirror, a Phong surface with Schlick's weight, or glass), or through an index-matched glass
// interface the same ray with the new medium stack. Only a glass hit's refraction, whose
// reflection goes first, waits in the pending-ray stack. So the kernel has one place that stores
// a pending ray: on lavapipe each store costs a loop over the lanes every round, whether a lane
// stores or not. The order is the one of pushing both and popping the reflection at once.
//
// lavapipe runs the code of every material in every round, masked, so the materials share one
// reflection: its IOR lookup, Fresnel term, direction and origin are worked out once, from the
// normals on the incoming ray's side (an opaque hit's were turned so by finishTrace).
void scatter(GpuMaterial m) {
    uint model = materialModel(m);
    bool glass = usesMaterial(kMaterialGlass) && model == kMaterialGlass;
    bool mirror = usesMaterial(kMaterialMirror) && model == kMaterialMirror;
    vec3 d = st.ray.direction.xyz;
    vec3 w = st.ray.weight.xyz;
    uint depth = rayDepth(st.ray);
    vec3 p = st.hitPosition.xyz;
    vec3 facing = st.hitGeometricNormal.xyz;
    vec3 n = st.hitNormal.xyz;
    float n1 = mediumIor(st.ray);
    float n2 = m.attenuation.w;
    uvec4 media = st.ray.media;
    uint count = mediaCount(st.ray);
    vec3 through = p;  // where a transmitted ray starts: beyond every surface of the interface
    if (usesMaterial(kMaterialGlass) && glass) {
        bool entering = crossGlass(media, count);
        if (!entering) n1 = m.attenuation.w;
        if (!entering || (kTouchingProbe && st.touching.w > 0u)) n2 = ior(media, count);
        if (!entering) facing = -facing;
        if (!entering) n = -n;
        if (ieeeDot(n, d) >= 0.0) n = facing;  // a shading normal on the wrong side: use the true one
        if (kTouchingProbe && st.touching.w > 0u) through = st.ray.origin.xyz + st.probe.x * d;
    }
    // Index-matched glass: no optical interface; the same ray goes on with the new stack.
    bool matched = glass && n1 == n2;
    float eta = n1 / n2;
    float cosI = -ieeeDot(d, n);
    float cos2t = cosSquaredTransmitted(d, n, eta);
    float r = fresnelReflectance(glass ? fresnelModel() : kFresnelSchlick, n1, n2, cosI, cos2t);
    if (glass && !matched && cos2t < 0.0) gTotalInternalReflections += 1u;
    vec3 transmittedOrigin = offsetRayOrigin(through, -facing);
    // Each child passes the depth and weight limits (or is counted).
    if (usesMaterial(kMaterialGlass) && glass && !matched && cos2t >= 0.0 && admitChild(depth + 1u, w * (1.0 - r))) {
        if (st.control.y >= kPendingRayCapacity) {
            gRayStackOverflows += 1u;  // the refraction is dropped, never silently
        } else {
            PendingRay refracted = childRay(transmittedOrigin, refractDirection(d, n, eta, cos2t), w * (1.0 - r), media,
                                            count, depth + 1u);
            storePendingRay(pendingRayIndex(st.control.y), refracted);
            st.control.y += 1u;
            gRefractionRays += 1u;
        }
    }
    PendingRay next = matched ? childRay(transmittedOrigin, d, w, media, count, depth)
                              : childRay(offsetRayOrigin(p, facing), reflectDirection(d, n), mirror ? w * m.specular.xyz : w * r,
                                         st.ray.media, mediaCount(st.ray), depth + 1u);
    // An index-matched continuation is the same ray going on at its own depth, not a new branch:
    // neither max_depth nor min_weight stops it (as on the CPU).
    if (matched || admitChild(rayDepth(next), next.weight.xyz)) {
        if (!matched) gReflectionRays += 1u;
        st.ray = next;
        beginRay();
    } else {
        st.control.x = kPhaseNextRay;
    }
}

void nextRay() {
    if (kPendingRayCapacity == 0u || st.control.y == gBottom) {
        if (kRaySharing && gTaken) {
            st.control.x = kPhaseDone;  // the taken tree is done: ray_sharing.glsl hands it back
            return;
        }
        st.control.y = 0u;
        gBottom = 0u;
        st.colourLow.w += 1u;
        st.control.x = kPhaseStartSample;
        return;
    }
    st.control.y -= 1u;
    loadPendingRay(pendingRayIndex(st.control.y));
}

// The next sample's primary ray, or the end of the pixel.
void startSample() {
    if (st.colourLow.w >= params.image.z) st.control.x = kPhaseDone;
    else startPrimaryRay();  // begins a traversal, or (max_depth 0) goes to kPhaseNextRay
}

// A pixel's first dispatch.
void startPixel() {
    st.colourLow = uvec4(0u);
    st.colourHigh = uvec4(0u);
    st.control = uvec4(kPhaseStartSample, 0u, 0u, 0u);
    st.traversal.w = 0u;
}

#include "suspend.glsl"

#include "statistics.glsl"

// main() fills StatisticSums and the maxima by position, in the order of gpu_types.h's kStat*
// indices: if that order changes, this stops the build until main() follows it.
const bool kStatOrderAsFilled =
    kStatPrimaryRays == 0u && kStatShadowRays == 1u && kStatReflectionRays == 2u && kStatRefractionRays == 3u &&
    kStatUnfinishedPixels == 4u && kStatLoopLimitSuspected == 5u && kStatTraversalStackOverflow == 6u &&
    kStatDepthLimitHits == 7u && kStatNodeVisits == 8u && kStatTraversalSteps == 9u && kStatRayStackOverflow == 10u &&
    kStatMediumStackOverflow == 11u && kStatWeightCuts == 12u && kStatTotalInternalReflections == 13u &&
    kStatAbsorbedEscapes == 14u && kStatTouchingInterfaces == 15u && kStatInconsistentMedia == 16u &&
    kStatTouchingProbes == 17u && kStatRestartedSteps == 18u && kStatGroupSteps == 19u && kStatFirstMax == 20u &&
    kStatMaxPixelSteps == 20u && kStatMaxRayDepth == 21u && kStatMaxMediumDepth == 22u && kStatCount == 23u;
const uint kStatOrderCheck[kStatOrderAsFilled ? 1 : -1] = uint[](0u);

// Starts a unit in the persistent kernel: everything main's loop counts or carries for a unit's
// pixel is as it was when the invocation began (their declarations' values). The tests compare
// the persistent kernel's statistics with one unit an invocation's: a counter left out here would
// count twice.
void startUnit() {
    gPixelSteps = 0u;
    gNodeVisits = 0u;
    gTraversalOverflows = 0u;
    gRoundColour = vec3(0.0);
    gTouchingInterfaces = 0u;
    gTouchingProbes = 0u;
    gMediumStackOverflows = 0u;
    gBottom = 0u;
    gLoadIndex = 0u;
    gLoad = false;
    gGiver = 0u;
    gGives = false;
    gReceives = false;
    gTaken = false;
    gOwner = 0u;
    gOwnLow = uvec4(0u);
    gOwnHigh = uvec4(0u);
    gOwnSteps = 0u;
    gGroupTook = false;
    gPrimaryRays = 0u;
    gShadowRays = 0u;
    gReflectionRays = 0u;
    gRefractionRays = 0u;
    gDepthLimitHits = 0u;
    gRayStackOverflows = 0u;
    gWeightCuts = 0u;
    gTotalInternalReflections = 0u;
    gAbsorbedEscapes = 0u;
    gInconsistentMedia = 0u;
    gMaxRayDepth = 0u;
    gMaxMediumDepth = 0u;
}

// Traces the pixels of `unit` and adds what they counted to `total` and `totalMaxima`. Returns
// the steps the SIMD group ran (the same in every lane).
uint traceUnit(uint unit, inout StatisticSums total, inout uvec3 totalMaxima) {
    uvec2 local = tilePixel(unit);
    uvec2 pixel = params.tile.xy + local;
    gPixel = pixel;
    // An invocation has a pixel to trace when it is inside the tile and the image and (in the
    // resumable kernel) the pixel is not done yet. One without returns at once, except where the
    // statistics are summed by shuffles (kFullSubgroups, statistics.glsl), which read every lane:
    // it then runs no step and counts nothing.
    bool hasPixel = local.x < params.tile.z && local.y < params.tile.w && pixel.x < params.image.x && pixel.y < params.image.y;
    if (!hasPixel && !kFullSubgroups) return 0u;
    uint slot = local.y * params.tile.z + local.x;
    placePendingRays(slot);
    stackBase = slot * kTraversalStackSize;
    if (!kResumable) {
        if (hasPixel) startPixel();
    } else {
        hasPixel = hasPixel && resumeState(slot);
        if (!hasPixel && !kFullSubgroups) return 0u;
    }
    if (!hasPixel) st.control.x = kPhaseDone;

    // lavapipe runs 8 invocations in lock step and executes both sides of every branch under a
    // mask, so a loop iteration costs its whole body, whatever phase each pixel is in. One
    // iteration therefore runs one traversal (a loop of its own that walks only the BVH) and then
    // takes the pixel through every shading phase that is due, in the order they follow each
    // other, up to the start of the next traversal: each ray of the tree costs one iteration of
    // shading code, not one per phase. Every loop counts against one budget of steps below
    // lavapipe's 65,535 iterations, which it counts for the SIMD group, not the lane: `steps` is
    // the group's count, the same in all its lanes at the top of this loop. The loop is a
    // do-while, as bvh.glsl's are: a while loop would run its body once more with every lane
    // masked off.
    uint budget = params.counts.w;
    uint steps = 0u;
    if (st.control.x == kPhaseStartSample) startSample();
    // The loop runs while some lane of the group has a pixel that is not done; a lane that is
    // done waits in it, as the traversal's lanes do (bvh.glsl), so that every lane reaches the
    // groupMax calls. A lane whose traversal the budget stopped goes no further: the loop ends.
    bool working = st.control.x != kPhaseDone;
    bool busy = working;
    if (groupAny(busy) && steps < budget) do {
        steps += 1u;
        if (working) gPixelSteps += 1u;
        uint phase = st.control.x;
        bool traced = traverse(kShadowRays && phase == kPhaseShadow ? kTraverseAny : kTraverseClosest,
                               phase == kPhaseTrace || phase == kPhaseShadow, steps, budget);
        if (traced && working) {
            // The hit's triangle and material, each read once a round (only lanes at a hit use
            // them): a closest hit's, or the one whose shadow ray just ended or whose lights or
            // scattering go on from an earlier round.
            TriangleVertices tri = TriangleVertices(vec4(0.0), vec4(0.0), vec4(0.0));
            bool atEarlierHit = phase == kPhaseShadow || phase == kPhaseNextLight || phase == kPhaseScatter;
            uint material = atEarlierHit ? hitMaterial() : 0u;
            if (phase == kPhaseTrace && st.traversal.z != kNoTriangle) {
                tri = loadTriangle(st.traversal.z);
                material = floatBitsToUint(tri.v0.w);
            }
            GpuMaterial m = loadMaterial(material);
            if (phase == kPhaseShadow) finishShadow();
            else if (phase == kPhaseTrace) finishTrace(tri, m);
            if (st.control.x == kPhaseNextLight) nextLight(m);  // may begin a shadow traversal
            if (spawnsRays() && st.control.x == kPhaseScatter) scatter(m);
            if (st.control.x == kPhaseNextRay) nextRay();  // begins a traversal or ends the sample
            // A sample has ended here: with one sample a pixel (kSingleSample) that was the
            // pixel's only one, and the round needs no camera code (main starts the first sample
            // before the loop): the code of every phase runs in every round on lavapipe.
            if (st.control.x == kPhaseStartSample) {
                if (kSingleSample) st.control.x = kPhaseDone;
                else startSample();
            }
            addColour(st.colourLow, st.colourHigh, gRoundColour);
            gRoundColour = vec3(0.0);
        }
#ifndef VITRUM_NO_SUBGROUP_OPERATIONS
        if (kRaySharing) shareRays(hasPixel);
#endif
        if (kPendingRayCapacity > 0u) {
            // The round's one read of a pending ray: the lane's own next one, or the one it gives
            // to a lane that takes it (ray_sharing.glsl).
            PendingRay loaded = st.ray;
            if (gLoad || (kRaySharing && gGives)) loaded = readPendingRay(gLoadIndex);
#ifndef VITRUM_NO_SUBGROUP_OPERATIONS
            if (kRaySharing) handOver(loaded);
#endif
            if (gLoad || (kRaySharing && gReceives)) {
                st.ray = loaded;
                beginRay();
            }
            gLoad = false;
            gGives = false;
            gReceives = false;
        }
        working = st.control.x != kPhaseDone;
        busy = working || gTaken;  // a lane done with a taken tree waits to hand it back
    } while (groupAny(busy) && steps < budget);

    // A group cut by the budget after some lane took a ray gives up all its pixels
    // (ray_sharing.glsl); then all the steps a lane ran are restarted steps.
    bool givenUpGroup = kRaySharing && gGroupTook && groupAny(busy);
    if (gTaken) gPixelSteps += gOwnSteps;
    st.traversal.w += gPixelSteps;
    bool done = st.control.x == kPhaseDone && !givenUpGroup;
    if (hasPixel) {
        pixels[slot] = slotPixel(done, colourOfSum(st.colourLow, st.colourHigh) / float(params.image.z));
        if (kResumable) suspendState(slot, !done);
    }

    // A pixel the first dispatch gives up is traced again from its start: what it counted so far
    // would count twice, so only its steps are counted, as restarted steps. A loop that stopped
    // short of both the end and the budget was stopped by the driver: count it, never hide it.
    bool counted = kResumable || done;
    StatisticSums sums;
    sums.v0 = uvec4(gPrimaryRays, gShadowRays, gReflectionRays, gRefractionRays);
    sums.v1 = uvec4(0u, 0u, gTraversalOverflows, gDepthLimitHits);
    sums.v2 = uvec4(gNodeVisits, gPixelSteps, gRayStackOverflows, gMediumStackOverflows);
    sums.v3 = uvec4(gWeightCuts, gTotalInternalReflections, gAbsorbedEscapes, gTouchingInterfaces);
    sums.v4 = uvec4(gInconsistentMedia, gTouchingProbes, 0u, 0u);
    uvec3 maxima = uvec3(done ? st.traversal.w : 0u, gMaxRayDepth, gMaxMediumDepth);
    if (!counted) {
        sums = StatisticSums(uvec4(0u), uvec4(0u), uvec4(0u), uvec4(0u), uvec4(0u, 0u, gPixelSteps, 0u));  // kStatRestartedSteps
        maxima = uvec3(0u);
    }
    if (!done) sums.v1.xy = uvec2(1u, steps < budget ? 1u : 0u);  // kStatUnfinishedPixels, kStatLoopLimitSuspected
    if (!hasPixel) {
        sums = kNoStatistics;
        maxima = uvec3(0u);
    }
    // The group's steps, once a group (kStatGroupSteps): a lane that finished early stopped
    // counting, so the group's count is its lanes' largest. Against the lanes' own steps it says
    // how full the SIMD groups were (docs/gpu-design.md).
    uint groupSteps = groupMax(steps);
    sums.v4.w = firstLane() ? groupSteps : 0u;
    addSums(total, sums);
    totalMaxima = max(totalMaxima, maxima);
    return groupSteps;
}

// The persistent kernel: the first dispatch's, where subgroups are full, on a device that runs
// on the CPU (host/gpu/vulkan_renderer.cpp). Its subgroups take units until none is left or the
// driver's loop limit could not hold another unit's budget.
#ifndef VITRUM_NO_SUBGROUP_OPERATIONS
const bool kPersistent = kPersistentSubgroups && kFullSubgroups && !kResumable;
#else
const bool kPersistent = false;
#endif

// lavapipe counts a subgroup's loop iterations over all the units it traces: their steps, at
// most about 20 more a unit that the count misses (docs/gpu-design.md), the loop over the units
// and, once, the statistics' loops. A unit is counted for 64 beyond its steps, and the limit is
// kept 256 below lavapipe's.
const uint kUnitIterationsBeyondSteps = 64u;
const uint kDriverLoopIterations = 65535u - 256u;

void main() {
    params = loadRenderParams();
    StatisticSums total = kNoStatistics;
    uvec3 totalMaxima = uvec3(0u);
    uint units = tileUnits();
    uint iterations = 0u;  // lavapipe's count for this subgroup, bounded from above
    // Every unit runs with the same budget (params.counts.w), whichever subgroup takes it and
    // whatever it traced before: so a unit gives up the same pixels, and counts the same, in
    // every kernel. A subgroup takes another unit only while the driver's limit still holds a
    // whole budget more.
    do {
        uint unit = takeUnit();
        if (unit >= units) break;
        if (kPersistent) startUnit();
        iterations += traceUnit(unit, total, totalMaxima) + kUnitIterationsBeyondSteps;
    } while (kPersistent && iterations + params.counts.w + kUnitIterationsBeyondSteps <= kDriverLoopIterations);
    addStatistics(total, totalMaxima);
}
