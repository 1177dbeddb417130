// Cut-out parts of surfaces (glTF's alphaMode MASK; Material::cutout): a triangle marked
// kTriangleCutout | texture (gpu_types.h, "Triangles") is not there where that grey texture, read
// at the hit's uv as shading reads map_Kd, is below 1. bvh.glsl asks at every hit of a marked
// triangle, before the hit is a candidate of any kind, so that a ray passes such a hit by as if
// the triangle had a hole there (docs/render-model-decisions.md, "Cut-out surfaces"). The CPU
// reference's ReferenceCutouts (host/cpu/reference_renderer.cpp) does the same steps.
#ifndef VITRUM_CUTOUT_GLSL
#define VITRUM_CUTOUT_GLSL

#include "bindings.glsl"
#include "specialization.glsl"
#include "texture.glsl"

// Whether triangle `triangle` (marked `mark`) is cut away at barycentrics (u, v) of v1 and v2.
bool cutAway(uint triangle, uint mark, vec2 barycentrics) {
    return sampleMeshTexture(mark & kTriangleCutoutTexture, interpolatedUv(triangle, barycentrics)).x < 1.0;
}

#endif
