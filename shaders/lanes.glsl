// What the lanes of a subgroup (lavapipe: the 8 lanes of a SIMD group, run in lock step) know of
// one another. The build with VITRUM_NO_SUBGROUP_OPERATIONS is for devices without subgroup arithmetic
// and ballots; there each lane answers for itself.
#ifndef VITRUM_LANES_GLSL
#define VITRUM_LANES_GLSL

#ifndef VITRUM_NO_SUBGROUP_OPERATIONS
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#endif

// The largest `value` of the active lanes.
uint groupMax(uint value) {
#ifdef VITRUM_NO_SUBGROUP_OPERATIONS
    return value;
#else
    return subgroupMax(value);
#endif
}

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
