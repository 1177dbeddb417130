// What the lanes of a subgroup (lavapipe: the 8 lanes of a SIMD group, run in lock step) know of
// one another. The build with VITRUM_NO_SUBGROUP_OPERATIONS is for devices without subgroup arithmetic
// and ballots; there each lane answers for itself. The includer declares kFullSubgroups: trace.comp
// as a specialization constant (specialization.glsl), the self-check kernel as true.
#ifndef VITRUM_LANES_GLSL
#define VITRUM_LANES_GLSL

#ifndef VITRUM_NO_SUBGROUP_OPERATIONS
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_shuffle : require
#endif

// The largest `value` of the active lanes. lavapipe's subgroupMax is a loop over the lanes with a
// branch each, so where subgroups are full (kFullSubgroups) a butterfly of shuffles does it
// (docs/gpu-design.md, "Group maxima by shuffles"). A shuffle reads another lane: there every lane
// of the subgroup must call this (trace.comp's traceUnit and bvh.glsl keep them together).
uint groupMax(uint value) {
#ifdef VITRUM_NO_SUBGROUP_OPERATIONS
    return value;
#else
    if (!kFullSubgroups) return subgroupMax(value);
    // Written out, not a loop (lavapipe would count its iterations against its limit), for up to
    // 128 lanes: gl_SubgroupSize is a compile-time constant to the driver, so extra rounds fold away.
    if (gl_SubgroupSize > 1u) value = max(value, subgroupShuffleXor(value, 1u));
    if (gl_SubgroupSize > 2u) value = max(value, subgroupShuffleXor(value, 2u));
    if (gl_SubgroupSize > 4u) value = max(value, subgroupShuffleXor(value, 4u));
    if (gl_SubgroupSize > 8u) value = max(value, subgroupShuffleXor(value, 8u));
    if (gl_SubgroupSize > 16u) value = max(value, subgroupShuffleXor(value, 16u));
    if (gl_SubgroupSize > 32u) value = max(value, subgroupShuffleXor(value, 32u));
    if (gl_SubgroupSize > 64u) value = max(value, subgroupShuffleXor(value, 64u));
    return value;
#endif
}

// Whether `value` holds in some active lane (as groupMax: every lane where subgroups are full).
bool groupAny(bool value) { return groupMax(value ? 1u : 0u) != 0u; }

// Whether this is the one active lane that speaks for its subgroup.
bool firstLane() {
#ifdef VITRUM_NO_SUBGROUP_OPERATIONS
    return true;
#else
    return subgroupElect();
#endif
}

// `value` as the lowest active lane has it.
uint fromFirstLane(uint value) {
#ifdef VITRUM_NO_SUBGROUP_OPERATIONS
    return value;
#else
    return subgroupBroadcastFirst(value);
#endif
}

#endif
