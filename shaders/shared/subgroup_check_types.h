// Buffer elements of shaders/subgroup_check.comp, the device self-check of the fast kernel's
// subgroup machinery (host/gpu/subgroup_self_check.h), and the trip counts and values it works
// on, computed the same way by the kernel and by the host that checks it. Shared by the C++ host
// and GLSL like gpu_types.h.
#ifndef VITRUM_SUBGROUP_CHECK_TYPES_H
#define VITRUM_SUBGROUP_CHECK_TYPES_H

#include "shared/gpu_types.h"

#ifdef __cplusplus
namespace vitrum::gpu {
#define VITRUM_SHARED_FUNCTION inline
#else
#define VITRUM_SHARED_FUNCTION
#endif

struct SubgroupCheckControl {
    uint cursor;  // the next unit to take: 0 before the dispatch
    uint units;
    uint fault;   // nonzero: one lane behaves as a lost invocation (tests of the fallback)
    uint unused;
};

// One a lane of a unit (unit * subgroup size + lane), 8 bytes, so that the check's buffers fit
// even the 4 KiB a test lowers the storage buffer limit to (VITRUM_MAX_BUFFER_BYTES).
struct SubgroupCheckResult {
    // Bits 24-31: the rounds its subgroup ran (the largest trip count of its lanes); 16-23: the
    // rounds in which this lane was busy (its own trip count); 0-15: the sum of its lanes' trips
    // plus one (0: never written).
    uint counts;
    uint received;  // the sum of the values the subgroup's picked lane gave each round
};

// Rounds lane `lane` of `unit` is busy: 0 to 24, so that a workgroup's subgroups run different
// numbers of rounds (a hash, not a pattern a compiler could fold).
VITRUM_SHARED_FUNCTION uint subgroupCheckHash(uint x) {
    x ^= x >> 16u;
    x *= 0x7FEB352Du;
    x ^= x >> 15u;
    x *= 0x846CA68Bu;
    x ^= x >> 16u;
    return x;
}

VITRUM_SHARED_FUNCTION uint subgroupCheckTrips(uint unit, uint lane) {
    return subgroupCheckHash(unit * 131u + lane) % 25u;
}

// What lane `lane` of `unit` gives in round `round`.
VITRUM_SHARED_FUNCTION uint subgroupCheckValue(uint unit, uint lane, uint round) {
    return subgroupCheckHash(unit * 7919u + lane * 31u + round) & 0xFFFFu;
}

#undef VITRUM_SHARED_FUNCTION
#ifdef __cplusplus
}  // namespace vitrum::gpu
#endif
#endif
