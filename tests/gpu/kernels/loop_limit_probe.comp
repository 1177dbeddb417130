#version 460
// Whether the driver ends a shader's loops early, and where (tests/gpu/test_kernels.h's
// probeLoopLimit): one subgroup runs a loop of `requested` iterations and writes how many it ran.
// Mesa 22.3's lavapipe ends a shader's loops after 65,535 repeats (65,536 passes of a do-while);
// Mesa 25.0's does not.
// The loop carries a recurrence no compiler folds, so every iteration runs.
layout(local_size_x = 8) in;

layout(std430, set = 0, binding = 0) buffer Probe {
    uint requested;
    uint ran;
    uint value;
    uint unused;
};

void main() {
    uint n = requested;
    uint i = 0u;
    uint x = gl_LocalInvocationIndex + 1u;
    do {
        x = x * 1664525u + 1013904223u;
        i += 1u;
    } while (i < n);
    if (gl_LocalInvocationIndex == 0u) {
        ran = i;
        value = x;
    }
}
