// A resumable BVH traversal over the flattened nodes of shared/gpu_types.h: its state lives in
// `st` (trace_state.glsl) and its stack in gStack, so that a dispatch can stop after any step and
// the next one resume it (suspend.glsl). The includer provides nodeTexels and vertexTexels
// (geometry_texels.glsl), `params`, the constants kShadowRays, kTouchingProbe, kOpaqueContact,
// kCoincidentOpaque, kInstancing, kCutouts, kResumable and kFullSubgroups, and cutAway:
// trace.comp's (bindings.glsl, specialization.glsl, cutout.glsl) or a benchmark's own
// (bench/trace_only).
#ifndef VITRUM_BVH_GLSL
#define VITRUM_BVH_GLSL

const uint kNoTriangle = 0xFFFFFFFFu;

#include "trace_state.glsl"
#include "counters.glsl"
#include "lanes.glsl"
#include "ieee_vector_math.glsl"
#include "ray_box.glsl"
#include "triangle_test.glsl"
#include "touching.glsl"

const uint kTraverseClosest = 0u;  // the closest hit (and touching.glsl's candidates, when collected)
const uint kTraverseAny = 1u;      // any hit (shadow rays)

// This pixel's traversal stack, in private memory: on lavapipe every storage-buffer access is a
// loop over the lanes (docs/gpu-design.md, "Data").
uint gStack[kTraversalStackSize];

// A traversal stack entry is a node whose box the ray entered, as gpu_types.h's TraversalNode
// writes its children: an interior node's index, or a leaf's triangle range (kLeafEntryFlag), so
// that popping a leaf reads no node.
const uint kNoEntry = 0xFFFFFFFFu;

// A fresh traversal: its stack holds only the root, which traverse() takes without a push.
const uint kFreshTraversal = 0xFFFFFFFFu;

// Starts a traversal of the ray origin + t direction, tMin < t < tMax. The root is entered
// without testing its box: its children's boxes are tested (or, for a one-leaf tree, its triangles).
void beginTraversal(vec3 origin, vec3 direction, float tMin, float tMax) {
    st.traversal.origin = origin;
    st.traversal.tMin = tMin;
    st.traversal.direction = direction;
    st.traversal.tMax = tMax;
    st.traversal.stackTop = kFreshTraversal;
    st.traversal.leafCursor = 0u;
    st.traversal.leafEnd = 0u;
    st.traversal.closest = kNoTriangle;
    if (kInstancing) {
        st.traversal.instance = kNoInstance;
        st.traversal.closestInstance = kNoInstance;
    }
}

// Instances (gpu_types.h, "Instances"): a point and a direction by a 3x4 matrix's rows, with the
// operations of host/bvh/bvh_traversal.cpp's rayIntoInstance in the same order.
vec3 pointByRows(vec4 r0, vec4 r1, vec4 r2, vec3 p) {
    return vec3(ieeeDot(r0.xyz, p) + r0.w, ieeeDot(r1.xyz, p) + r1.w, ieeeDot(r2.xyz, p) + r2.w);
}
vec3 vectorByRows(vec4 r0, vec4 r1, vec4 r2, vec3 v) { return vec3(ieeeDot(r0.xyz, v), ieeeDot(r1.xyz, v), ieeeDot(r2.xyz, v)); }

GpuInstance instanceNumbered(uint instance) { return loadInstance(firstInstanceNode() + kGpuInstanceNodes * instance); }

// Whether a traversal entry enters an instance or leaves one (not the empty scene's leaf).
bool instanceEntry(uint entry) { return (entry & (kLeafEntryFlag | 15u)) == kLeafEntryFlag && entry != kLeafEntryFlag; }

// A closest-hit traversal of st.ray, with no touching candidates yet (touching.glsl), no
// opaque surface under glass and none the ray leaves through (bvh.glsl's traverse).
void beginClosestTraversal() {
    if (kTouchingProbe) {
        st.candidates.touchingObjects = uvec4(0u);
        st.candidates.touchingT = vec4(kNoCandidate);
    }
    if (kOpaqueContact) {
        st.candidates.contact = vec4(kNoCandidate, uintBitsToFloat(kNoTriangle), 0.0, 0.0);
        st.candidates.closestIsGlass = false;
    }
    if (kCoincidentOpaque) st.candidates.leaving = vec4(kNoCandidate, uintBitsToFloat(kNoTriangle), 0.0, 0.0);
    if (kInstancing) {
        st.candidates.contactInstance = kNoInstance;
        st.candidates.leavingInstance = kNoInstance;
    }
    beginTraversal(st.ray.origin.xyz, st.ray.direction.xyz, 0.0, 3.0e38);
    st.phase = kPhaseTrace;
}

// One interior node of a traversal: tests both children's boxes, keeps the nearer hit child in
// `current` and pushes the farther one when both are. When neither is hit, the next entry comes
// off the stack at once; `over` when the stack is empty. The stack's top is read before the node,
// so that the two reads overlap.
//
// The far child is returned in `farEntry` for the caller to store to the free slot above the top
// (as it was before the visit), in every lane (traverse says why); the top is raised only when
// it is pushed.
void visitInteriorNode(inout uint current, inout uint top, inout bool over, out uint farEntry, vec3 direction,
                       BoxRay ray, float tMin, float tMax) {
    uint below = gStack[top == 0u ? 0u : top - 1u];
    TraversalNode node = loadTraversalNode(current);
    counters.nodeVisits += 2u;
    bool hit0 = hitsBox(node.min0.xyz, node.max0.xyz, ray, tMin, tMax);
    bool hit1 = hitsBox(node.min1.xyz, node.max1.xyz, ray, tMin, tMax);
    // Near child (on the ray's side of the split) and far child.
    bool negative = direction[floatBitsToUint(node.max0.w)] < 0.0;
    bool hitNear = negative ? hit1 : hit0;
    bool hitFar = negative ? hit0 : hit1;
    uint entry0 = floatBitsToUint(node.min0.w);
    uint entry1 = floatBitsToUint(node.min1.w);
    farEntry = negative ? entry0 : entry1;
    current = hitNear ? (negative ? entry1 : entry0) : below;
    if (!hitFar) {
        if (!hitNear && top == 0u) over = true;
        else if (!hitNear) top -= 1u;
        return;
    }
    if (!hitNear) {
        current = farEntry;
    } else if (top + 2u > kTraversalStackSize) {
        counters.traversalStackOverflows += 1u;  // the far child is dropped, never silently
    } else {
        top += 1u;
    }
}

// Runs the traversal begun by beginTraversal while the SIMD group has run fewer than `budget`
// steps, in the lanes where `tracing`; every lane of the subgroup calls it, and stays in its outer
// loop until the group's last traversal is over, so that groupMax may read every lane (lanes.glsl).
// `steps` is the group's count, the same in all its lanes on entry and on return. Each loop
// iteration is one step: a triangle test, an interior node whose two children's boxes it tests
// (Aila and Laine 2009), or taking a leaf off the stack. Returns true when it is over: the
// closest hit (or, for kTraverseAny, some hit) is st.traversal.closest, with its t in tMax and its
// barycentrics; with the touching probe on, st.candidates holds the glass triangles within the
// touching distance beyond it (touching.glsl). Returns false when the budget ran out first; the
// state is then back in `st` and a later call resumes it. A lane that is not tracing returns true
// and leaves `st` as it was.
//
// Nodes are visited depth first, near child (by the split axis) first, as
// host/bvh/bvh_traversal.cpp does, so both find the same closest triangle, ties included.
bool traverse(uint mode, bool tracing, inout uint steps, uint budget) {
    vec3 origin = st.traversal.origin;
    float tMin = st.traversal.tMin;
    vec3 direction = st.traversal.direction;
    float tMax = st.traversal.tMax;
    // In an instance's mesh (resumed there), the ray in its space and its objects' first. Only
    // the resumable kernel resumes a traversal (trace.comp): every other begins outside instances.
    uint instance = kInstancing && kResumable ? st.traversal.instance : kNoInstance;
    uint closestInstance = st.traversal.closestInstance;
    uint contactInstance = st.candidates.contactInstance;
    uint leavingInstance = st.candidates.leavingInstance;
    uint firstObject = 0u;
    if (kInstancing && instance != kNoInstance) {
        GpuInstance entered = instanceNumbered(instance);
        origin = pointByRows(entered.toObject0, entered.toObject1, entered.toObject2, st.traversal.origin);
        direction = vectorByRows(entered.toObject0, entered.toObject1, entered.toObject2, st.traversal.direction);
        firstObject = entered.info.z;
    }
    BoxRay boxRay = makeBoxRay(origin, direction);
    TriangleRay triangleRay = makeTriangleRay(origin, direction);
    uint cursor = st.traversal.leafCursor;
    uint leafEnd = st.traversal.leafEnd;
    uint closest = st.traversal.closest;
    vec2 barycentrics = st.traversal.barycentrics;
    uint top = st.traversal.stackTop;
    bool collectTouching = kTouchingProbe && mode == kTraverseClosest && touchingProbeOn();
    // Glass resting on an opaque surface (render-model-decisions.md, "Glass on an opaque
    // surface"): the nearest opaque triangle hit below the nearest hit so far plus e (ties: the
    // lower index), which the CPU reference's probe beyond a glass hit finds too, and whether the
    // nearest hit so far is glass. When the traversal is over and an opaque hit lies within e
    // beyond a glass one, the opaque one is the hit (st.candidates.contact, closestIsGlass).
    bool collectContact = kOpaqueContact && mode == kTraverseClosest && opaqueContactOn();
    // Coincident opaque surfaces (render-model-decisions.md): the nearest opaque triangle hit from
    // behind (the ray leaves through it) below the nearest hit so far plus e, ties as above. When
    // the traversal is over and it lies within e of the nearest hit, it is the hit
    // (st.candidates.leaving).
    bool collectLeaving = kCoincidentOpaque && mode == kTraverseClosest && coincidentOpaqueOn();
    // A ray going on through a partly covered surface passes by the partly covered triangles it
    // meets before st.ray.weight.w, where it crosses the surface it started at (coverSurface).
    float passCovered = kPartialCoverage && mode == kTraverseClosest ? st.ray.weight.w : 0.0;
    // Boxes and candidates are tested up to tMax + reach.
    float reach = collectTouching || collectContact || collectLeaving ? touchingDistance() : 0.0;
    uvec4 touchingObjects = st.candidates.touchingObjects;
    vec4 touchingT = st.candidates.touchingT;
    vec4 contact = st.candidates.contact;
    vec4 leaving = st.candidates.leaving;
    bool closestGlass = st.candidates.closestIsGlass;
    uint current = kNoEntry;  // the entry to visit next, taken off the stack or kept from a visit
    if (top == kFreshTraversal) {
        top = 0u;
        current = bvhRoot();
    }
    bool over = !tracing;
    // Aila and Laine's "while-while": nodes until every lane holds a leaf (or is done), then that
    // leaf's triangles. Every loop is `if (c) do { ... } while (c)`, which lavapipe runs no more
    // often than its longest lane (docs/gpu-design.md, "One loop, bounded, resumable"). `steps`
    // gets each inner loop's group iterations (one where no lane enters), counters.loopSteps this
    // lane's; a lane whose traversal is over waits in the outer loop until every lane's is.
    if (groupAny(!over) && steps < budget) do {
        steps += 1u;
        if (!over) counters.loopSteps += 1u;
        // After a leaf (or on resuming between nodes), the next entry comes off the stack.
        if (!over && current == kNoEntry && cursor >= leafEnd) {
            if (top == 0u) over = true;
            else {
                top -= 1u;
                current = gStack[top];
            }
        }
        // Runs while some lane needs a node (as many iterations as its longest lane), and every
        // iteration stores every lane's far child (0 where it visits none) above its top: lavapipe
        // branches on the lanes' mask for each lane of a private-array store, and stored in every
        // lane those branches always go the same way (docs/gpu-design.md, "The node loop in every
        // lane").
        bool inNodes = !over && cursor >= leafEnd && !(kInstancing && instanceEntry(current));
        uint nodeSteps = 0u;  // the group's
        if (groupAny(inNodes) && steps < budget) do {
            nodeSteps += 1u;
            uint slot = min(top, kTraversalStackSize - 1u);  // the top before a push: a free slot
            uint farEntry = 0u;
            if (inNodes) {
                counters.loopSteps += 1u;
                if ((current & kLeafEntryFlag) == 0u)
                    visitInteriorNode(current, top, over, farEntry, direction, boxRay, tMin, tMax + reach);
                // An instance's entry (entering a copy or leaving one) ends the lane's node loop,
                // and the code after the loop moves the ray: in the loop, its texel reads and the
                // rays' set-up would run, masked, in every iteration (docs/gpu-design.md,
                // "Instances crossed outside the node loop").
                if (kInstancing && !over && instanceEntry(current)) inNodes = false;
                // A leaf, taken off the stack or just entered, is taken in the same iteration.
                else if (!over && current != kNoEntry && (current & kLeafEntryFlag) != 0u) {
                    cursor = (current & ~kLeafEntryFlag) >> 4;
                    leafEnd = cursor + (current & 15u);
                    current = kNoEntry;
                    inNodes = false;
                }
                if (over) inNodes = false;
            }
            gStack[slot] = farEntry;
        } while (groupAny(inNodes) && steps + nodeSteps < budget);
        steps += max(nodeSteps, 1u);  // a loop no lane enters runs its body once, masked
        // An instance's entry moves the ray into its mesh's space, below an entry that moves it
        // back when it comes off the stack (gpu_types.h, "Instances"); the mesh's root is taken
        // next, at once where it is a leaf. Not bound by the budget, so that a suspended
        // traversal never holds an instance's entry.
        if (kInstancing && !over && instanceEntry(current)) {
            bool leaving = current == kLeaveInstanceEntry;
            instance = leaving ? kNoInstance : ((current & ~kLeafEntryFlag) >> 4) - 1u;
            current = kNoEntry;
            origin = st.traversal.origin;
            direction = st.traversal.direction;
            firstObject = 0u;
            if (!leaving && top + 2u > kTraversalStackSize) {
                counters.traversalStackOverflows += 1u;  // the instance is passed by, never silently
                instance = kNoInstance;
            } else if (!leaving) {
                GpuInstance entered = instanceNumbered(instance);
                origin = pointByRows(entered.toObject0, entered.toObject1, entered.toObject2, origin);
                direction = vectorByRows(entered.toObject0, entered.toObject1, entered.toObject2, direction);
                firstObject = entered.info.z;
                gStack[top] = kLeaveInstanceEntry;
                top += 1u;
                current = entered.info.y;
                if ((current & kLeafEntryFlag) != 0u) {
                    cursor = (current & ~kLeafEntryFlag) >> 4;
                    leafEnd = cursor + (current & 15u);
                    current = kNoEntry;
                }
            }
            boxRay = makeBoxRay(origin, direction);
            triangleRay = makeTriangleRay(origin, direction);
        }
        uint triangleSteps = 0u;
        if (!over && cursor < leafEnd && steps < budget) do {
            triangleSteps += 1u;
            uint triangle = cursor;
            cursor += 1u;
            TriangleVertices tri = loadTriangle(triangle);
            vec3 hit = intersectTriangle(tri, triangleRay);
            bool candidate = hit.x > tMin && hit.x < tMax + reach;
            // A hit in a cut-out part is no hit of any kind (cutout.glsl).
            uint mark = floatBitsToUint(tri.v2.w);
            if (kCutouts && candidate && (mark & kTriangleCutout) != 0u) candidate = !cutAway(triangle, mark, hit.yz);
            if (kPartialCoverage && candidate && hit.x < passCovered && (mark & kTriangleCovered) != 0u) candidate = false;
            if (candidate) {
                bool glass = mark == kTriangleGlass;
                if (collectTouching && glass) {
                    bool entering = ieeeDot(direction, windingNormal(tri)) < 0.0;
                    addTouchingCandidate(touchingObjects, touchingT, floatBitsToUint(tri.v1.w) + firstObject, entering, hit.x,
                                         tMax + reach, counters.mediumStackOverflows);
                }
                if (collectContact && !glass &&
                    (hit.x < contact.x || (hit.x == contact.x && triangle < floatBitsToUint(contact.y)))) {
                    contact = vec4(hit.x, uintBitsToFloat(triangle), hit.yz);
                    contactInstance = instance;
                }
                if (collectLeaving && !glass &&
                    (hit.x < leaving.x || (hit.x == leaving.x && triangle < floatBitsToUint(leaving.y))) &&
                    ieeeDot(direction, windingNormal(tri)) > 0.0) {
                    leaving = vec4(hit.x, uintBitsToFloat(triangle), hit.yz);
                    leavingInstance = instance;
                }
                if (hit.x < tMax) {
                    tMax = hit.x;
                    closest = triangle;
                    closestInstance = instance;
                    barycentrics = hit.yz;
                    closestGlass = glass;
                    if (kShadowRays && mode == kTraverseAny) {
                        over = true;
                        break;
                    }
                }
            }
        } while (cursor < leafEnd && steps + triangleSteps < budget);
        counters.loopSteps += triangleSteps;
        steps += max(groupMax(triangleSteps), 1u);
    } while (groupAny(!over) && steps < budget);
    // Suspended: the entry in hand goes back on the stack (pushes leave it a free slot), stored in
    // every lane as the node loop's store is (a lane not suspended writes only its free slot).
    // Only the resumable kernel resumes a traversal; the first dispatch gives up such a pixel.
    if (kResumable) gStack[min(top, kTraversalStackSize - 1u)] = current;
    if (!tracing) return true;
    if (!over && current != kNoEntry) top += 1u;
    // Both windows begin at the nearest hit: the opaque surface the ray leaves through first,
    // then, under glass, the nearest opaque one.
    if (collectLeaving && over && leaving.x < tMax + reach) {
        tMax = leaving.x;
        closest = floatBitsToUint(leaving.y);
        closestInstance = leavingInstance;
        barycentrics = leaving.zw;
    } else if (collectContact && over && closestGlass && contact.x < tMax + reach) {
        tMax = contact.x;
        closest = floatBitsToUint(contact.y);
        closestInstance = contactInstance;
        barycentrics = contact.zw;
    }
    st.traversal.tMax = tMax;
    st.traversal.leafCursor = cursor;
    st.traversal.leafEnd = leafEnd;
    st.traversal.closest = closest;
    st.traversal.barycentrics = barycentrics;
    st.traversal.stackTop = top;
    if (kInstancing) {
        st.traversal.instance = instance;
        st.traversal.closestInstance = closestInstance;
        st.candidates.contactInstance = contactInstance;
        st.candidates.leavingInstance = leavingInstance;
    }
    if (collectTouching) {
        st.candidates.touchingObjects = touchingObjects;
        st.candidates.touchingT = touchingT;
    }
    if (collectContact) {
        st.candidates.contact = contact;
        st.candidates.closestIsGlass = closestGlass;
    }
    if (collectLeaving) st.candidates.leaving = leaving;
    return over;
}

#endif
