// Buffer elements of tests/gpu/kernels/optics_test.comp, the kernel that runs the GLSL optics functions
// (shaders/optics.glsl) on single cases so tests can hold them to the lecture's numbers. Shared by
// the C++ host and GLSL like gpu_types.h: all vec4, so std430 and C++ agree without padding.
#ifndef VITRUM_OPTICS_TEST_TYPES_H
#define VITRUM_OPTICS_TEST_TYPES_H

#include "shared/gpu_types.h"

#ifdef __cplusplus
namespace vitrum::gpu {
#endif

// One evaluation of every optics function at one interface. Conventions as in optics.glsl: `d`
// is the unit incoming direction, `n` the unit normal on the incoming side (d.n <= 0), the ray
// goes from IOR n1 into IOR n2.
struct OpticsCase {
    vec4 direction;    // .xyz = d; .w = unused
    vec4 normal;       // .xyz = n; .w = unused
    vec4 media;        // x = n1, y = n2, z = Beer-Lambert segment length t, w = unused
    vec4 attenuation;  // .xyz = Beer-Lambert mu per channel; .w = unused
};

struct OpticsResult {
    vec4 reflected;    // .xyz = reflectDirection(d, n); .w = schlickF0(n1, n2)
    vec4 refracted;    // .xyz = refractDirection(d, n, n1 / n2, cos2t), (0, 0, 0) at total internal
                       // reflection; .w = cos2t = cosSquaredTransmitted(d, n, n1 / n2)
    vec4 reflectance;  // fresnelReflectance for x = kFresnelSchlick, y = kFresnelExact,
                       // z = kFresnelSchlickExp2; w = eta = n1 / n2 as the device divided
    vec4 beer;         // .xyz = beerLambert(mu, t); .w = unused
};

VITRUM_CONST uint kOpticsTestGroupSize = 64u;  // local_size_x of optics_test.comp

#ifdef __cplusplus
}  // namespace vitrum::gpu
#endif
#endif
