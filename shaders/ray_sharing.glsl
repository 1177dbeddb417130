// Lanes whose pixel is done take pending rays from the other lanes of their subgroup, since a
// SIMD group runs until its last lane is done (docs/gpu-design.md, "Rays, not pixels, for the idle
// lanes"). A pending ray (a refraction whose reflection went first) is a whole ray tree: once a
// round, one idle lane takes the bottom pending ray of the lane with the most (of those that read
// no ray of their own that round), traces its tree, and hands its colour sum and steps back to
// the lane whose pixel it is (its owner). Rays the taker pushes meanwhile, of the same owner, can
// be taken in turn. Everything moves between lanes by shuffles (handOver says why).
//
// Nothing of the image or the statistics depends on who traces a ray: the colour is a sum in
// fixed point (colour_sum.glsl); a taken ray's pending rays start at its index in its owner's
// stack, so the capacity cuts the same refractions; its counters are summed with all the others;
// its steps go back to its owner. Only group_loop_steps depends on it, which is the point.
//
// Only the first dispatch shares (the resumable kernel's state holds no owner), and only where
// subgroups are full. A group cut by the budget after some lane took a ray gives up all its
// pixels, finished or not: a taken tree may be unfinished, or counted by a lane whose own pixel
// is done.
#ifndef VITRUM_RAY_SHARING_GLSL
#define VITRUM_RAY_SHARING_GLSL

#include "trace_state.glsl"
#include "counters.glsl"
#include "pending_rays.glsl"
#include "colour_sum.glsl"
#include "specialization.glsl"
#include "lanes.glsl"

#ifdef VITRUM_NO_SUBGROUP_OPERATIONS
const bool kRaySharing = false;
#else
const bool kRaySharing = kFullSubgroups && !kResumable && kPendingRayCapacity > 0u;
#endif

bool gTaken = false;     // this lane traces (or has traced) a tree taken from its owner gOwner
uint gOwner = 0u;
// This lane's own pixel's colour sum and steps, kept while it traces a taken tree.
ColourSum gOwnColour = kNoColour;
uint gOwnSteps = 0u;
bool gGroupTook = false;  // some lane of the group took a ray: the same in every lane
// The lane that gives a pending ray this round, plus one (0: none), the same in every lane. The
// giver reads the ray at the round's one load site (trace.comp's traceUnit, where the lanes read
// their own next rays), and handOver passes it to the taker by a shuffle.
uint gGiver = 0u;
bool gGives = false;     // this lane gives the ray it reads this round
bool gReceives = false;  // this lane takes the ray given this round

// A unit's lanes start with nothing taken or given.
void resetRaySharing() {
    gTaken = false;
    gOwner = 0u;
    gOwnColour = kNoColour;
    gOwnSteps = 0u;
    gGroupTook = false;
    gGiver = 0u;
    gGives = false;
    gReceives = false;
}

#ifndef VITRUM_NO_SUBGROUP_OPERATIONS
// Serves one idle lane a round (more gained little: docs/gpu-design.md, "Rays, not pixels, for the
// idle lanes"); called once a round by every lane of the subgroup, after shading.
// `canTake`: the lane has a slot of its own for the pending rays of a taken tree (it has a pixel).
void shareRays(bool canTake) {
    uint self = gl_SubgroupInvocationID;
    bool idle = st.phase == kPhaseDone;
    // The lane served this round: one done with a taken tree first (its owner waits for it),
    // else any idle one.
    uint servedKey = idle && (gTaken || canTake) ? (gTaken ? 0x100u : 0u) | (self + 1u) : 0u;
    uint served = groupMax(servedKey);
    // The lane to take from: the most pending rays (of the lowest lane among equals), of those
    // that read no ray of their own this round (the given ray is read where theirs would be).
    uint available = idle || gLoad ? 0u : st.pendingRays - gBottom;
    uint best = groupMax(available > 0u ? (available << 8u) | (255u - self) : 0u);
    if (served == 0u) return;
    uint taker = (served & 0xFFu) - 1u;

    if ((served & 0x100u) != 0u) {
        // Hand the taken tree's colour and steps back to its owner.
        ColourSum colour = ColourSum(subgroupShuffle(st.colour.low, taker), subgroupShuffle(st.colour.high, taker));
        uint steps = subgroupShuffle(counters.loopSteps, taker);
        uint owner = subgroupShuffle(gOwner, taker);
        if (self == owner) {
            if (gTaken) {  // the owner is tracing a taken tree itself (maybe this one's)
                if (kDispersion) addSignedColourSums(gOwnColour, colour);
                else addColourSums(gOwnColour, colour);
                gOwnSteps += steps;
            } else {
                if (kDispersion) addSignedColourSums(st.colour, colour);
                else addColourSums(st.colour, colour);
                counters.loopSteps += steps;
            }
        }
        if (self == taker) {
            st.colour = gOwnColour;
            counters.loopSteps = gOwnSteps;
            gTaken = false;
        }
    }

    if (best == 0u) return;
    uint donor = 255u - (best & 0xFFu);
    uint bottom = subgroupShuffle(gBottom, donor);
    uint owner = subgroupShuffle(gTaken ? gOwner : self, donor);
    gGroupTook = true;
    gGiver = donor + 1u;
    if (self == donor) {
        gLoadIndex = pendingRayIndex(gBottom);
        gGives = true;
        gBottom += 1u;
    }
    if (self == taker) {
        gOwnColour = st.colour;
        gOwnSteps = counters.loopSteps;
        st.colour = kNoColour;
        counters.loopSteps = 0u;
        gTaken = true;
        gOwner = owner;
        // Its tree's pending rays go where its owner's would have: the same capacity is left.
        st.pendingRays = bottom;
        gBottom = bottom;
        gReceives = true;
        st.phase = kPhaseTrace;  // beginRay, once the ray is handed over, begins its traversal
    }
}

// Hands the ray the giver read (`loaded`, in the giver's lane) to the taker, by shuffles: reading
// memory another invocation wrote would need a barrier, which Mesa 25.0's lavapipe runs as a
// workgroup's (docs/gpu-design.md, "Two drivers"). Called once a round by every lane, after the
// round's read of pending rays.
void handOver(inout PendingRay loaded) {
    if (gGiver == 0u) return;
    uint giver = gGiver - 1u;
    PendingRay given;
    given.origin = subgroupShuffle(loaded.origin, giver);
    given.direction = subgroupShuffle(loaded.direction, giver);
    given.weight = subgroupShuffle(loaded.weight, giver);
    given.media = kMediumStackDepth > 1u ? subgroupShuffle(loaded.media, giver)
                                         : uvec4(subgroupShuffle(loaded.media.x, giver), 0u, 0u, 0u);
    if (gReceives) loaded = given;
    gGiver = 0u;
}
#endif

#endif
