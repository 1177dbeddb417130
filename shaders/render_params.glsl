// The lanes of the includer's `params` (a RenderParams) by name: the accessors of
// shared/render_params.h, reading the global so that no call copies the struct.
#ifndef VITRUM_RENDER_PARAMS_GLSL
#define VITRUM_RENDER_PARAMS_GLSL

#include "shared/render_params.h"

#define VITRUM_PARAM_SCALAR(type, name, member, lane) type name() { return params.member.lane; }
#define VITRUM_PARAM_FLAG(name, member, lane) bool name() { return params.member.lane != 0u; }
#define VITRUM_PARAM_VECTOR(name, member) vec3 name() { return params.member.xyz; }
VITRUM_RENDER_PARAM_LANES(VITRUM_PARAM_SCALAR, VITRUM_PARAM_FLAG, VITRUM_PARAM_VECTOR)
#undef VITRUM_PARAM_SCALAR
#undef VITRUM_PARAM_FLAG
#undef VITRUM_PARAM_VECTOR

#endif
