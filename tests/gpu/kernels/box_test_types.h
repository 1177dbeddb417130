// Buffer elements of tests/gpu/kernels/box_test.comp, the kernel that runs the traversal's ray/box test
// (shaders/ray_box.glsl) on single cases. Shared by the C++ host and GLSL like gpu_types.h.
#ifndef VITRUM_BOX_TEST_TYPES_H
#define VITRUM_BOX_TEST_TYPES_H

#include "shared/gpu_types.h"

#ifdef __cplusplus
namespace vitrum::gpu {
#endif

struct BoxCase {
    vec4 boxMin;     // .xyz; .w = tMin
    vec4 boxMax;     // .xyz; .w = tMax
    vec4 origin;     // .xyz; .w unused
    vec4 direction;  // .xyz (the kernel takes 1 / direction, as the traversal does); .w unused
};

struct BoxResult {
    uvec4 hit;  // .x = hitsBox(...) ? 1 : 0
};

VITRUM_CONST uint kBoxTestGroupSize = 64u;  // local_size_x of box_test.comp

#ifdef __cplusplus
}  // namespace vitrum::gpu
#endif
#endif
