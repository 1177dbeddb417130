#version 460
// The ray tree of ../shared/docs/render-model.md, one pixel per invocation, for one tile of the image.
//
// lavapipe silently ends a shader's loops after 65,535 iterations of a SIMD group. So every loop
// iteration of this kernel is one small counted step (one BVH node, one leaf, one triangle, or one
// round of shading, see main), counted for the group (bvh.glsl's traverse). A dispatch runs at most
// `iterationBudget(params)` steps per group and unit of pixels. The first dispatch of a tile gives up the
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

layout(local_size_x = 8, local_size_y = 8) in;

#include "schedule.glsl"
#include "trace_state.glsl"
#include "statistics.glsl"
#include "bvh.glsl"
#include "pending_rays.glsl"
#include "ray_sharing.glsl"
#include "ray_tree.glsl"
#include "shading.glsl"
#include "colour_sum.glsl"
#include "suspend.glsl"

// Starts a unit: everything traceUnit's loop counts or carries for a pixel starts afresh, each
// module's state by its own reset (the tests compare the persistent kernel's statistics with
// those of one unit an invocation).
void startUnit() {
    counters = noCounters();
    gRoundColour = vec3(0.0);
    resetPendingRays();
    resetRaySharing();
}

// Traces the pixels of `unit` and adds what they counted to `total` and `totalMaxima`. Returns
// the steps the SIMD group ran (the same in every lane).
uint traceUnit(uint unit, inout StatisticSums total, inout uvec3 totalMaxima) {
    uvec2 local = tilePixel(unit);
    uvec2 pixel = uvec2(tileX(params), tileY(params)) + local;
    // An invocation has a pixel to trace when it is inside the tile and the image and (in the
    // resumable kernel) the pixel is not done yet. One without returns at once, except where the
    // statistics are summed by shuffles (kFullSubgroups, statistics.glsl), which read every lane:
    // it then runs no step and counts nothing.
    bool hasPixel = local.x < tileWidth(params) && local.y < tileHeight(params) && pixel.x < imageWidth(params) && pixel.y < imageHeight(params);
    if (!hasPixel && !kFullSubgroups) return 0u;
    uint slot = local.y * tileWidth(params) + local.x;
    placePendingRays(slot);
    if (!kResumable) {
        if (hasPixel) startPixel();
    } else {
        hasPixel = hasPixel && resumeState(slot);
        if (!hasPixel && !kFullSubgroups) return 0u;
    }
    if (!hasPixel) st.phase = kPhaseDone;

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
    uint budget = iterationBudget(params);
    uint steps = 0u;
    if (st.phase == kPhaseStartSample) startSample(pixel);
    // The loop runs while some lane of the group has a pixel that is not done; a lane that is
    // done waits in it, as the traversal's lanes do (bvh.glsl), so that every lane reaches the
    // groupMax calls. A lane whose traversal the budget stopped goes no further: the loop ends.
    bool working = st.phase != kPhaseDone;
    bool busy = working;
    if (groupAny(busy) && steps < budget) do {
        steps += 1u;
        if (working) counters.loopSteps += 1u;
        uint phase = st.phase;
        bool traced = traverse(kShadowRays && phase == kPhaseShadow ? kTraverseAny : kTraverseClosest,
                               phase == kPhaseTrace || phase == kPhaseShadow, steps, budget);
        if (traced && working) {
            // The hit's triangle and material, each read once a round (only lanes at a hit use
            // them): a closest hit's, or the one whose shadow ray just ended or whose lights or
            // scattering go on from an earlier round.
            TriangleVertices tri = TriangleVertices(vec4(0.0), vec4(0.0), vec4(0.0));
            bool atEarlierHit = phase == kPhaseShadow || phase == kPhaseNextLight || phase == kPhaseScatter;
            uint material = atEarlierHit ? st.hit.material : 0u;
            if (phase == kPhaseTrace && st.traversal.closest != kNoTriangle) {
                tri = loadTriangle(st.traversal.closest);
                material = floatBitsToUint(tri.v0.w);
            }
            GpuMaterial m = loadMaterial(material);
            if (phase == kPhaseShadow) finishShadow();
            else if (phase == kPhaseTrace) finishTrace(tri, m);
            if (st.phase == kPhaseNextLight) nextLight(m);  // may begin a shadow traversal
            if (spawnsRays() && st.phase == kPhaseScatter) scatter(m);
            if (st.phase == kPhaseNextRay) nextRay();  // begins a traversal or ends the sample
            // A sample has ended here: with one sample a pixel (kSingleSample) that was the
            // pixel's only one, and the round needs no camera code (main starts the first sample
            // before the loop): the code of every phase runs in every round on lavapipe.
            if (st.phase == kPhaseStartSample) {
                if (kSingleSample) st.phase = kPhaseDone;
                else startSample(pixel);
            }
            addColour(st.colour, gRoundColour);
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
        working = st.phase != kPhaseDone;
        busy = working || gTaken;  // a lane done with a taken tree waits to hand it back
    } while (groupAny(busy) && steps < budget);

    // A group cut by the budget after some lane took a ray gives up all its pixels
    // (ray_sharing.glsl); then all the steps a lane ran are restarted steps.
    bool givenUpGroup = kRaySharing && gGroupTook && groupAny(busy);
    if (gTaken) counters.loopSteps += gOwnSteps;
    st.steps += counters.loopSteps;
    bool done = st.phase == kPhaseDone && !givenUpGroup;
    if (hasPixel) {
        pixels[slot] = slotPixel(done, colourOfSum(st.colour) / float(samplesPerPixel(params)));
        if (kResumable) suspendState(slot, !done);
    }

    // A pixel the first dispatch gives up is traced again from its start: what it counted so far
    // would count twice, so only its steps are counted, as restarted steps. A loop that stopped
    // short of both the end and the budget was stopped by the driver: count it, never hide it.
    bool counted = kResumable || done;
    TraceCounters c = counters;
    c.maxPixelLoopSteps = done ? st.steps : 0u;
    if (!counted) {
        c = noCounters();
        c.restartedSteps = counters.loopSteps;
    }
    if (!done) {
        c.unfinishedPixels = 1u;
        c.loopLimitSuspected = steps < budget ? 1u : 0u;
    }
    if (!hasPixel) c = noCounters();
    // The group's steps, once a group: a lane that finished early stopped counting, so the
    // group's count is its lanes' largest. Against the lanes' own steps it says how full the SIMD
    // groups were (docs/gpu-design.md).
    uint groupSteps = groupMax(steps);
    c.groupLoopSteps = firstLane() ? groupSteps : 0u;
    addSums(total, sumsOf(c));
    totalMaxima = max(totalMaxima, maximaOf(c));
    return groupSteps;
}


void main() {
    params = loadRenderParams();
    StatisticSums total = kNoStatistics;
    uvec3 totalMaxima = uvec3(0u);
    uint units = tileUnits();
    uint iterations = 0u;  // lavapipe's count for this subgroup, bounded from above
    // Every unit runs with the same budget (iterationBudget(params)), whichever subgroup takes it and
    // whatever it traced before: so a unit gives up the same pixels, and counts the same, in
    // every kernel. A subgroup takes another unit only while the driver's limit still holds a
    // whole budget more.
    do {
        uint unit = takeUnit();
        if (unit >= units) break;
        startUnit();
        iterations += traceUnit(unit, total, totalMaxima) + kUnitIterationsBeyondSteps;
    } while (kPersistent && iterations + iterationBudget(params) + kUnitIterationsBeyondSteps <= kDriverLoopIterations);
    addStatistics(total, totalMaxima);
}
