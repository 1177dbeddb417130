// The parameters of one dispatch of trace.comp: a texel buffer of kRenderParamsTexels texels
// (shaders/bindings.glsl), filled by host/gpu_input/render_params.cpp. Every lane is read through
// its accessor below (both languages) and written through its setter (C++): a lane has one
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
    uvec4 bvh;               // the root's entry
    uvec4 cameraMedia;       // media around the camera, innermost last
    vec4 cameraSurface;      // the normal of the surface the camera lies on
    uvec4 cameraMediaBehind; // media behind that surface, innermost last
};

#ifdef __cplusplus
#define VITRUM_PARAMS const RenderParams&
#define VITRUM_INLINE inline
#else
#define VITRUM_PARAMS RenderParams
#define VITRUM_INLINE
#endif

// The pinhole camera of the render model (../shared/docs/render-model.md): a sample at image
// position (sx, sy) has direction normalize((sx - width/2) x_c + (height/2 - sy) y_c - f z_c),
// z_c pointing from the target back to the camera.
VITRUM_INLINE vec3 cameraPosition(VITRUM_PARAMS p) { return vec3(p.cameraFrom); }
// f = height / (2 tan(fov_y / 2)), in pixels.
VITRUM_INLINE float focalLength(VITRUM_PARAMS p) { return p.cameraFrom.w; }
VITRUM_INLINE vec3 cameraAxisX(VITRUM_PARAMS p) { return vec3(p.cameraX); }
VITRUM_INLINE vec3 cameraAxisY(VITRUM_PARAMS p) { return vec3(p.cameraY); }
VITRUM_INLINE vec3 cameraAxisZ(VITRUM_PARAMS p) { return vec3(p.cameraZ); }
VITRUM_INLINE vec3 backgroundColour(VITRUM_PARAMS p) { return vec3(p.background); }  // linear RGB
VITRUM_INLINE float airIor(VITRUM_PARAMS p) { return p.background.w; }
VITRUM_INLINE uint imageWidth(VITRUM_PARAMS p) { return p.image.x; }
VITRUM_INLINE uint imageHeight(VITRUM_PARAMS p) { return p.image.y; }
VITRUM_INLINE uint samplesPerPixel(VITRUM_PARAMS p) { return p.image.z; }
// Columns of the stratified sample grid (render_model/sampling.h); rows = samples / columns.
VITRUM_INLINE uint sampleGridColumns(VITRUM_PARAMS p) { return p.image.w; }
VITRUM_INLINE uint tileX(VITRUM_PARAMS p) { return p.tile.x; }
VITRUM_INLINE uint tileY(VITRUM_PARAMS p) { return p.tile.y; }
VITRUM_INLINE uint tileWidth(VITRUM_PARAMS p) { return p.tile.z; }
VITRUM_INLINE uint tileHeight(VITRUM_PARAMS p) { return p.tile.w; }
VITRUM_INLINE uint maxDepth(VITRUM_PARAMS p) { return p.limits.x; }
// Loop steps a SIMD group may run in one dispatch (shaders/trace.comp).
VITRUM_INLINE uint iterationBudget(VITRUM_PARAMS p) { return p.limits.y; }
VITRUM_INLINE uint lightCount(VITRUM_PARAMS p) { return p.counts.x; }
VITRUM_INLINE uint textureCount(VITRUM_PARAMS p) { return p.counts.y; }
// How many of cameraMedia and cameraMediaBehind hold objects.
VITRUM_INLINE uint cameraMediaCount(VITRUM_PARAMS p) { return p.counts.z; }
VITRUM_INLINE uint cameraMediaBehindCount(VITRUM_PARAMS p) { return p.counts.w; }
VITRUM_INLINE uint fresnelModelOf(VITRUM_PARAMS p) { return p.models.x; }      // kFresnel*
VITRUM_INLINE uint backgroundKindOf(VITRUM_PARAMS p) { return p.models.y; }    // kBackground*
VITRUM_INLINE uint textureFilterOf(VITRUM_PARAMS p) { return p.models.z; }     // kFilter*
// The spherical map's texture, or the cube's +x face's (then -x, +y, -y, +z, -z).
VITRUM_INLINE uint backgroundTexture(VITRUM_PARAMS p) { return p.models.w; }
// Whether glass hits look for touching surfaces of other glass objects (the scene has two).
VITRUM_INLINE bool touchingProbeOn(VITRUM_PARAMS p) { return p.surfaceChecks.x != 0u; }
// Whether glass may rest on an opaque surface (SceneFeatures::opaqueContactPossible).
VITRUM_INLINE bool opaqueContactOn(VITRUM_PARAMS p) { return p.surfaceChecks.y != 0u; }
// Whether opaque surfaces of two objects may coincide (SceneFeatures::coincidentOpaquePossible).
VITRUM_INLINE bool coincidentOpaqueOn(VITRUM_PARAMS p) { return p.surfaceChecks.z != 0u; }
VITRUM_INLINE float minWeight(VITRUM_PARAMS p) { return p.thresholds.x; }
// The distance within which surfaces touch: 1e-5 of the scene's diagonal (SceneFeatures).
VITRUM_INLINE float touchingDistance(VITRUM_PARAMS p) { return p.thresholds.y; }
// Waechter and Binder's ray-origin offsets scaled to the scene (host/render_model/ray_offset.h): the
// radius of the region around the origin where offsets are absolute, and that offset.
VITRUM_INLINE float offsetRegion(VITRUM_PARAMS p) { return p.thresholds.z; }
VITRUM_INLINE float offsetDistance(VITRUM_PARAMS p) { return p.thresholds.w; }
// The root's entry (TraversalNode): node 0, or the one leaf of a scene of at most
// kMaxLeafTriangles triangles.
VITRUM_INLINE uint bvhRoot(VITRUM_PARAMS p) { return p.bvh.x; }
// The unit normal of the surface the camera lies on, 0 if none: primary rays start off it on their
// side (host/analysis/camera_surface.h), with cameraMedia in front and cameraMediaBehind behind.
VITRUM_INLINE vec3 cameraSurfaceNormal(VITRUM_PARAMS p) { return vec3(p.cameraSurface); }

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
inline void setBvhRoot(RenderParams& p, uint root) { p.bvh = uvec4(root, 0, 0, 0); }
#endif

VITRUM_GPU_END

#endif
