// The parameters of one dispatch of trace.comp: a texel buffer of kRenderParamsTexels texels
// (shaders/bindings.glsl), filled by host/gpu_input/render_params.cpp. Every lane is read through
// its accessor (VITRUM_RENDER_PARAM_LANES) and written through its setter (C++): a lane has one
// meaning, and where it lives is written here only.
#ifndef VITRUM_RENDER_PARAMS_H
#define VITRUM_RENDER_PARAMS_H

#include "language.h"

VITRUM_GPU_BEGIN

VITRUM_CONST uint kRenderParamsTexels = 16u;

struct RenderParams {
    vec4 cameraFrom;         // position, focal length
    vec4 cameraX;            // the camera's axes (x_c, y_c, z_c)
    vec4 cameraY;
    vec4 cameraZ;
    vec4 background;         // constant background colour, air IOR
    uvec4 image;             // width, height, samples per pixel, columns of the sample grid
    uvec4 tile;              // origin x, origin y, width, height
    uvec4 limits;            // max depth, iteration budget
    uvec4 counts;            // lights, textures, media around the camera, media behind its surface
    uvec4 models;            // Fresnel model, background kind, texture filter, background texture
    uvec4 surfaceChecks;     // flags: touching probe, opaque contact, coincident opaque
    vec4 thresholds;         // min weight, touching distance, ray-offset region, ray offset
    uvec4 bvh;               // the root's entry, the first instance's node
    uvec4 cameraMedia;       // media around the camera, innermost last
    vec4 cameraSurface;      // the normal of the surface the camera lies on
    uvec4 cameraMediaBehind; // media behind that surface, innermost last
};

// Each lane's accessor: X(type, name, member, lane) reads p.member.lane, FLAG a uint lane as a
// bool, VECTOR a member's .xyz. C++ gets name(p) (below), GLSL name() on its `params`
// (shaders/bindings.glsl), so that a kernel never copies the struct to read a lane.
#define VITRUM_RENDER_PARAM_LANES(SCALAR, FLAG, VECTOR)                                             \
    /* The pinhole camera of the render model (../shared/docs/render-model.md): a sample at */      \
    /* image position (sx, sy) has direction normalize((sx - width/2) x_c + (height/2 - sy) y_c */  \
    /* - f z_c), z_c pointing from the target back to the camera; f = height / (2 tan(fov_y/2)). */ \
    VECTOR(cameraPosition, cameraFrom)                                                             \
    SCALAR(float, focalLength, cameraFrom, w)                                                      \
    VECTOR(cameraAxisX, cameraX)                                                                   \
    VECTOR(cameraAxisY, cameraY)                                                                   \
    VECTOR(cameraAxisZ, cameraZ)                                                                   \
    VECTOR(backgroundColour, background) /* linear RGB */                                          \
    SCALAR(float, airIor, background, w)                                                           \
    SCALAR(uint, imageWidth, image, x)                                                             \
    SCALAR(uint, imageHeight, image, y)                                                            \
    SCALAR(uint, samplesPerPixel, image, z)                                                        \
    /* columns of the stratified sample grid (render_model/sampling.h); rows = samples / columns */ \
    SCALAR(uint, sampleGridColumns, image, w)                                                      \
    SCALAR(uint, tileX, tile, x)                                                                   \
    SCALAR(uint, tileY, tile, y)                                                                   \
    SCALAR(uint, tileWidth, tile, z)                                                               \
    SCALAR(uint, tileHeight, tile, w)                                                              \
    SCALAR(uint, maxDepth, limits, x)                                                              \
    /* loop steps a SIMD group may run in one dispatch (shaders/trace.comp) */                     \
    SCALAR(uint, iterationBudget, limits, y)                                                       \
    SCALAR(uint, lightCount, counts, x)                                                            \
    SCALAR(uint, textureCount, counts, y)                                                          \
    /* how many of cameraMedia and cameraMediaBehind hold objects */                               \
    SCALAR(uint, cameraMediaCount, counts, z)                                                      \
    SCALAR(uint, cameraMediaBehindCount, counts, w)                                                \
    SCALAR(uint, fresnelModelOf, models, x) /* kFresnel* */                                        \
    SCALAR(uint, backgroundKindOf, models, y) /* kBackground* */                                   \
    SCALAR(uint, textureFilterOf, models, z) /* kFilter* */                                        \
    /* the spherical map's texture, or the cube's +x face's (then -x, +y, -y, +z, -z) */           \
    SCALAR(uint, backgroundTexture, models, w)                                                     \
    /* glass hits look for touching surfaces of other glass objects (the scene has two) */        \
    FLAG(touchingProbeOn, surfaceChecks, x)                                                        \
    /* glass may rest on an opaque surface (SceneFeatures::opaqueContactPossible) */               \
    FLAG(opaqueContactOn, surfaceChecks, y)                                                        \
    /* opaque surfaces of two objects may coincide (SceneFeatures::coincidentOpaquePossible) */    \
    FLAG(coincidentOpaqueOn, surfaceChecks, z)                                                     \
    SCALAR(float, minWeight, thresholds, x)                                                        \
    /* the distance within which surfaces touch: 1e-5 of the scene's diagonal (SceneFeatures) */   \
    SCALAR(float, touchingDistance, thresholds, y)                                                 \
    /* Waechter and Binder's ray-origin offsets scaled to the scene (render_model/ray_offset.h): */ \
    /* the radius of the region around the origin where offsets are absolute, and that offset */   \
    SCALAR(float, offsetRegion, thresholds, z)                                                     \
    SCALAR(float, offsetDistance, thresholds, w)                                                   \
    /* the root's entry (TraversalNode): node 0, or the one leaf of a small scene */               \
    SCALAR(uint, bvhRoot, bvh, x)                                                                  \
    /* the node of the first instance (gpu_types.h, "Instances"), 0 for a scene without */        \
    SCALAR(uint, firstInstanceNode, bvh, y)                                                        \
    /* the unit normal of the surface the camera lies on, 0 if none: primary rays start off it */ \
    /* on their side (analysis/camera_surface.h), cameraMedia in front, cameraMediaBehind behind */ \
    VECTOR(cameraSurfaceNormal, cameraSurface)

#ifdef __cplusplus
#define VITRUM_PARAM_SCALAR(type, name, member, lane) \
    inline type name(const RenderParams& p) { return p.member.lane; }
#define VITRUM_PARAM_FLAG(name, member, lane) \
    inline bool name(const RenderParams& p) { return p.member.lane != 0u; }
#define VITRUM_PARAM_VECTOR(name, member) \
    inline vec3 name(const RenderParams& p) { return vec3(p.member); }
VITRUM_RENDER_PARAM_LANES(VITRUM_PARAM_SCALAR, VITRUM_PARAM_FLAG, VITRUM_PARAM_VECTOR)
#undef VITRUM_PARAM_SCALAR
#undef VITRUM_PARAM_FLAG
#undef VITRUM_PARAM_VECTOR
#endif

#ifdef __cplusplus
inline void setCamera(RenderParams& p, vec3 position, float focal, vec3 x, vec3 y, vec3 z) {
    p.cameraFrom = vec4(position, focal);
    p.cameraX = vec4(x, 0.0f);
    p.cameraY = vec4(y, 0.0f);
    p.cameraZ = vec4(z, 0.0f);
}
inline void setBackground(RenderParams& p, vec3 colour, float air) { p.background = vec4(colour, air); }
inline void setImage(RenderParams& p, uint width, uint height, uint samples, uint gridColumns) {
    p.image = uvec4(width, height, samples, gridColumns);
}
inline void setTile(RenderParams& p, uvec4 originAndSize) { p.tile = originAndSize; }
inline void setLimits(RenderParams& p, uint maxDepth, uint iterationBudget) { p.limits = uvec4(maxDepth, iterationBudget, 0, 0); }
inline void setCounts(RenderParams& p, uint lights, uint textures, uint cameraMedia, uint cameraMediaBehind) {
    p.counts = uvec4(lights, textures, cameraMedia, cameraMediaBehind);
}
inline void setModels(RenderParams& p, uint fresnel, uint backgroundKind, uint filter, uint backgroundTexture) {
    p.models = uvec4(fresnel, backgroundKind, filter, backgroundTexture);
}
inline void setSurfaceChecks(RenderParams& p, bool touchingProbe, bool opaqueContact, bool coincidentOpaque) {
    p.surfaceChecks = uvec4(touchingProbe ? 1u : 0u, opaqueContact ? 1u : 0u, coincidentOpaque ? 1u : 0u, 0u);
}
inline void setThresholds(RenderParams& p, float minWeight, float touchingDistance, float offsetRegion, float offset) {
    p.thresholds = vec4(minWeight, touchingDistance, offsetRegion, offset);
}
inline void setBvhRoot(RenderParams& p, uint root, uint firstInstance = 0) { p.bvh = uvec4(root, firstInstance, 0, 0); }
#endif

VITRUM_GPU_END

#endif
