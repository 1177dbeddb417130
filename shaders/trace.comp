#version 460
// The ray tree of ../shared/docs/render-model.md, one pixel per invocation, for one tile of the image.
//
// lavapipe silently ends a SIMD group's loops after 65,535 iterations, so every loop iteration is
// one counted step (a BVH node, a leaf, a triangle, or a round of shading) and a dispatch runs at
// most iterationBudget() of them per group and unit of pixels. The first dispatch gives up
// the pixels not done by then; the resumable build (kResumable, suspend.glsl) restarts them and
// keeps their state until the tile is done (docs/gpu-design.md, "One loop, bounded, resumable").
// Idle lanes take their group's pending rays (ray_sharing.glsl); on a CPU device a subgroup goes
// on to the tile's next unit (main, schedule.glsl).
#extension GL_GOOGLE_include_directive : require
// Subgroup operations count the group's iterations (lanes.glsl) and sum the statistics
// (statistics.glsl); VITRUM_NO_SUBGROUP_OPERATIONS builds trace_without_subgroups.spv.h for
// devices without subgroup arithmetic and ballots.

layout(local_size_x = 8, local_size_y = 8) in;

#include "schedule.glsl"
#include "trace_state.glsl"
#include "statistics.glsl"
#include "cutout.glsl"  // cutAway, which bvh.glsl calls
#include "bvh.glsl"
#include "pending_rays.glsl"
#include "ray_sharing.glsl"
#include "ray_tree.glsl"
#include "shading.glsl"
#include "colour_sum.glsl"
#include "suspend.glsl"

// Starts a unit: everything traceUnit's loop counts or carries for a pixel starts afresh, each
// module's state by its own reset, so a persistent subgroup's units count as separate ones would.
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
    uvec2 pixel = uvec2(tileX(), tileY()) + local;
    // A pixel inside the tile and the image, and (resumable kernel) not done yet. An invocation
    // without one returns at once, except with kFullSubgroups, where shuffles read every lane:
    // it then runs no step and counts nothing.
    bool hasPixel = local.x < tileWidth() && local.y < tileHeight() && pixel.x < imageWidth() && pixel.y < imageHeight();
    if (!hasPixel && !kFullSubgroups) return 0u;
    uint slot = local.y * tileWidth() + local.x;
    placePendingRays(slot);
    if (!kResumable) {
        if (hasPixel) startPixel();
    } else {
        hasPixel = hasPixel && resumeState(slot);
        if (!hasPixel && !kFullSubgroups) return 0u;
    }
    if (!hasPixel) st.phase = kPhaseDone;

    // lavapipe runs both sides of every branch, masked, so an iteration costs its whole body: one
    // round runs one traversal, then every shading phase due up to the next traversal, so a ray
    // costs one round of shading, not one per phase. `steps` counts the group's iterations, as the
    // driver's limit does, the same in all lanes here; the loop is a do-while, as bvh.glsl's are
    // (docs/gpu-design.md, "One loop, bounded, resumable").
    uint budget = iterationBudget();
    uint steps = 0u;
    if (st.phase == kPhaseStartSample) startSample(pixel);
    // Runs while some lane's pixel is not done; a lane that is done waits in it, so that every
    // lane reaches the groupMax calls. A traversal the budget stopped ends the loop.
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
                if (kTransmissionTextures) material = shownMaterial(material, st.traversal.closest, st.traversal.barycentrics);
            }
            GpuMaterial m = loadMaterial(material);
            if (phase == kPhaseShadow) finishShadow();
            else if (phase == kPhaseTrace) finishTrace(tri, material, m);
            if (st.phase == kPhaseNextLight) nextLight(m);  // may begin a shadow traversal
            if (spawnsRays() && st.phase == kPhaseScatter) scatter(m);
            if (st.phase == kPhaseNextRay) nextRay();  // begins a traversal or ends the sample
            // With kSingleSample that was the pixel's only sample, so the round holds no camera
            // code: lavapipe runs every phase's code in every round.
            if (st.phase == kPhaseStartSample) {
                if (kSingleSample) st.phase = kPhaseDone;
                else startSample(pixel);
            }
            if (kDispersion) addSignedColour(st.colour, gRoundColour);
            else addColour(st.colour, gRoundColour);
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
                if (kDispersion) startWaitingWavelength();
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
        vec3 sum = kDispersion ? colourOfSignedSum(st.colour) : colourOfSum(st.colour);
        pixels[slot] = slotPixel(done, sum / float(samplesPerPixel()));
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
    // The group's steps, once a group: its lanes' largest, since a lane that finished early stopped
    // counting (docs/gpu-design.md, "Statistics": how full the SIMD groups were).
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
    // Every unit runs with the same budget, whichever subgroup takes it, so it gives up the same
    // pixels and counts the same in every kernel; a subgroup takes another unit only while the
    // driver's limit still holds a whole budget more.
    do {
        uint unit = takeUnit();
        if (unit >= units) break;
        startUnit();
        iterations += traceUnit(unit, total, totalMaxima) + kUnitIterationsBeyondSteps;
    } while (kPersistent && iterations + iterationBudget() + kUnitIterationsBeyondSteps <= kDriverLoopIterations);
    addStatistics(total, totalMaxima);
}
