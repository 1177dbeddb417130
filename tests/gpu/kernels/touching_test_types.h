// Buffer elements of tests/gpu/kernels/touching_test.comp, the kernel that runs the touching-surface
// functions of shaders/touching.glsl on single sequences of crossings, as a closest-hit traversal
// would hand them over. Shared by the C++ host and GLSL like gpu_types.h: all vec4.
#ifndef VITRUM_TOUCHING_TEST_TYPES_H
#define VITRUM_TOUCHING_TEST_TYPES_H

#include "shared/gpu_types.h"

#ifdef __cplusplus
namespace vitrum::gpu {
#endif

VITRUM_CONST uint kTouchingTestCrossings = 8u;

// Up to 8 glass crossings in the order the traversal finds them, each passed to
// addTouchingCandidate under its limit (the nearest hit before it, plus the touching distance),
// then selectTouching for the hit.
struct TouchingCase {
    uvec4 objects0;  // crossings 0-3: object | entering << 31
    uvec4 objects1;  // crossings 4-7
    vec4 t0;         // their t
    vec4 t1;
    vec4 limit0;     // the limit each was found under
    vec4 limit1;
    uvec4 control;   // x = how many crossings (0..8), y = the hit's object
    vec4 hit;        // x = the hit's limit (its t plus the touching distance), y = its t
};

struct TouchingResult {
    uvec4 touching;  // selectTouching: object | entering << 31 for up to 3, .w = how many
    vec4 farthest;   // .x = the farthest surface's t (the hit's when none); .yzw = 0
    uvec4 counts;    // .x = medium_stack_overflow counted; .yzw = 0
};

VITRUM_CONST uint kTouchingTestGroupSize = 64u;  // local_size_x of touching_test.comp

#ifdef __cplusplus
}  // namespace vitrum::gpu
#endif
#endif
