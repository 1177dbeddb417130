// A resumable BVH traversal over the flattened nodes of shared/gpu_types.h.
// The traversal's state is kept in the pixel's state `st` (trace_state.glsl) and its stack in
// gStack, so that a dispatch can stop after any step and the next one resume it (suspend.glsl).
// Its includer provides the scene's geometry (geometry_texels.glsl's nodeTexels and
// vertexTexels), `params` (bvh.x, tuning, pass.w) and the constants kShadowRays, kTouchingProbe,
// kOpaqueContact, kCoincidentOpaque, kResumable and kFullSubgroups: trace.comp's
// (bindings.glsl, specialization.glsl), or a benchmark's own (bench/trace_only).
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

// This pixel's BVH traversal stack, in private memory while the kernel runs: on lavapipe that is
// cheaper than a storage buffer, whose every access loops over the lanes.
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
}

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
    beginTraversal(st.ray.origin.xyz, st.ray.direction.xyz, 0.0, 3.0e38);
    st.phase = kPhaseTrace;
}

// One interior node of a traversal: tests both children's boxes, keeps the nearer hit child in
// `current` and pushes the farther one when both are. When neither is hit, the next entry comes
// off the stack at once; `over` when the stack is empty. The stack's top is read before the node,
// so that the two reads overlap and the next node's read waits for neither.
//
// The far child is returned in `farEntry` for the caller to write to the free slot above the
// top (as it was before the visit), and the top is raised only when it is pushed: the caller
// stores it in every iteration of its loop, in every lane (traverse below says why).
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
// (in the manner of Aila and Laine 2009), or taking a leaf off the stack. Returns true when it is
// over: the closest hit (or, for kTraverseAny, some hit) is st.traversal.closest, with its t in
// tMax and its barycentrics. With the touching probe on, a closest-hit traversal also collects
// the glass triangles within the touching distance beyond the closest hit (touching.glsl) in
// st.candidates. Returns false when the budget ran
// out first; the state is then back in `st` and a later call resumes it. A lane that is not
// tracing returns true and leaves `st` as it was.
//
// The ray and the cursor live in locals while it runs, the stack in the private array gStack
// (suspend.glsl saves it to traversalStacks[] only when the pixel is suspended mid-traversal).
// Nodes are visited depth first, near child (by the split axis) first, as
// host/bvh/bvh_traversal.cpp does, so both find the same closest triangle, ties included.
bool traverse(uint mode, bool tracing, inout uint steps, uint budget) {
    vec3 origin = st.traversal.origin;
    float tMin = st.traversal.tMin;
    vec3 direction = st.traversal.direction;
    float tMax = st.traversal.tMax;
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
    // Aila and Laine's "while-while": inner nodes until every lane of the SIMD group holds a leaf
    // (or is done), then that leaf's triangles, so that one loop iteration is one kind of work.
    // Every loop is written `if (c) do { ... } while (c)`: lavapipe tests a loop's exit at the end
    // of its body, so a `while (c)` loop runs its whole body once more than its longest lane, with
    // every lane masked off (docs/gpu-design.md: 12% of a primary-ray render), while the do-while
    // runs it as often as its longest lane, and once, masked, when no lane enters it.
    // lavapipe counts the group's iterations against its limit, not a lane's: lanes that finish
    // a loop early wait for the others. So each inner loop adds the most iterations any lane ran
    // in it, or one for a loop no lane enters, to `steps`, which stays the same in all lanes: the
    // iterations the group ran. counters.loopSteps counts those this lane ran. The outer loop runs while
    // some lane's traversal is not over, and a lane whose traversal is over waits in it.
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
        // The node loop runs while some lane of the group needs a node (the same condition in
        // every lane), and each iteration writes every lane's far child, or a 0 where the lane
        // visits no node, to the free slot above its top. On lavapipe a lane's store to a private
        // array at an index of its own is a branch a lane on the lanes' mask (store the new value
        // or the old one): with the store in every lane the branches always go the same way,
        // while a store made only by the lanes still in the loop follows which of them are, which
        // the CPU cannot predict (docs/gpu-design.md). The iterations are the ones of a loop that
        // every lane leaves for itself: as many as its longest lane's.
        bool inNodes = !over && cursor >= leafEnd;
        uint nodeSteps = 0u;  // the group's
        if (groupAny(inNodes) && steps < budget) do {
            nodeSteps += 1u;
            uint slot = min(top, kTraversalStackSize - 1u);  // the top before a push: a free slot
            uint farEntry = 0u;
            if (inNodes) {
                counters.loopSteps += 1u;
                if ((current & kLeafEntryFlag) == 0u)
                    visitInteriorNode(current, top, over, farEntry, direction, boxRay, tMin, tMax + reach);
                // A leaf, taken off the stack or just entered, is taken in the same iteration.
                if (!over && (current & kLeafEntryFlag) != 0u) {
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
        uint triangleSteps = 0u;
        if (!over && cursor < leafEnd && steps < budget) do {
            triangleSteps += 1u;
            uint triangle = cursor;
            cursor += 1u;
            TriangleVertices tri = loadTriangle(triangle);
            vec3 hit = intersectTriangle(tri, triangleRay);
            if (hit.x > tMin && hit.x < tMax + reach) {
                bool glass = floatBitsToUint(tri.v2.w) == kTriangleGlass;
                if (collectTouching && glass) {
                    bool entering = ieeeDot(direction, windingNormal(tri)) < 0.0;
                    addTouchingCandidate(touchingObjects, touchingT, floatBitsToUint(tri.v1.w), entering, hit.x,
                                         tMax + reach, counters.mediumStackOverflows);
                }
                if (collectContact && !glass &&
                    (hit.x < contact.x || (hit.x == contact.x && triangle < floatBitsToUint(contact.y))))
                    contact = vec4(hit.x, uintBitsToFloat(triangle), hit.yz);
                if (collectLeaving && !glass &&
                    (hit.x < leaving.x || (hit.x == leaving.x && triangle < floatBitsToUint(leaving.y))) &&
                    ieeeDot(direction, windingNormal(tri)) > 0.0)
                    leaving = vec4(hit.x, uintBitsToFloat(triangle), hit.yz);
                if (hit.x < tMax) {
                    tMax = hit.x;
                    closest = triangle;
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
    // Suspended: the entry in hand goes back on the stack (pushes leave it a free slot). Stored
    // in every lane, for the reason the node loop's store is (a lane that is not suspended
    // writes its free slot, and one that does not trace has no stack to keep). Only the
    // resumable kernel resumes a traversal: the first dispatch gives up a pixel whose budget ran
    // out, and its stack with it (trace.comp), so there the store would run every round for nothing.
    if (kResumable) gStack[min(top, kTraversalStackSize - 1u)] = current;
    if (!tracing) return true;
    if (!over && current != kNoEntry) top += 1u;
    // Both windows begin at the nearest hit: the opaque surface the ray leaves through first,
    // then, under glass, the nearest opaque one.
    if (collectLeaving && over && leaving.x < tMax + reach) {
        tMax = leaving.x;
        closest = floatBitsToUint(leaving.y);
        barycentrics = leaving.zw;
    } else if (collectContact && over && closestGlass && contact.x < tMax + reach) {
        tMax = contact.x;
        closest = floatBitsToUint(contact.y);
        barycentrics = contact.zw;
    }
    st.traversal.tMax = tMax;
    st.traversal.leafCursor = cursor;
    st.traversal.leafEnd = leafEnd;
    st.traversal.closest = closest;
    st.traversal.barycentrics = barycentrics;
    st.traversal.stackTop = top;
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
