// GPU data layout shared by the C++ host and the GLSL kernels: one definition of every buffer
// element. Everything is built from vec4/uvec4 so that std430 and C++ agree without padding;
// integers travel bit-cast in the .w of a vec4 (tinybvh's trick). The host checks sizes with
// static_assert in host/gpu/gpu_layout.h.
#ifndef VITRUM_GPU_TYPES_H
#define VITRUM_GPU_TYPES_H

#include "language.h"

VITRUM_GPU_BEGIN

// ---- BVH -----------------------------------------------------------------------------------
// A flattened binary BVH in depth-first order (pbrt-v4's LinearBVHNode): an interior node's
// first child is the next node, its second child sits at `boundsMin.w`.
//   boundsMin.xyz, boundsMax.xyz: the node's box
//   boundsMin.w (uint bits): leaf -> index of its first triangle; interior -> second child index
//   boundsMax.w (uint bits): leaf -> triangle count (1..kMaxLeafTriangles);
//                            interior -> kInteriorNodeFlag | split axis (0, 1, 2)
struct BvhNode {
    vec4 boundsMin;
    vec4 boundsMax;
};
VITRUM_CONST uint kInteriorNodeFlag = 0x80000000u;
VITRUM_CONST uint kMaxLeafTriangles = 8u;

// The same tree as the GPU traverses it (Aila and Laine, "Understanding the Efficiency of Ray
// Traversal on GPUs", 2009): only the interior nodes, each holding both children's boxes, so a
// visit reads one node (4 texels) and tests two boxes. Child 0 is BvhNode's first child, child 1
// its second; nodes keep the depth-first order of their BvhNodes (host/render/traversal_nodes.h).
//   min0.xyz, max0.xyz: child 0's box; min0.w (uint bits): child 0's entry
//   min1.xyz, max1.xyz: child 1's box; min1.w (uint bits): child 1's entry
//   max0.w (uint bits): the split axis (0, 1, 2); max1.w: 0
// An entry (also what the traversal stack holds) is an interior child's TraversalNode index, or
// for a leaf kLeafEntryFlag | first triangle << 4 | triangle count: 27 bits of first triangle,
// so the host refuses scenes of kMaxTriangles or more.
struct TraversalNode {
    vec4 min0;
    vec4 max0;
    vec4 min1;
    vec4 max1;
};
VITRUM_CONST uint kLeafEntryFlag = 0x80000000u;
VITRUM_CONST uint kMaxTriangles = (1u << 27) - 1u;
VITRUM_CONST uint kTraversalStackSize = 64u;

// ---- Triangles (in BVH leaf order) -----------------------------------------------------------
// Positions for intersection. v0.w = material index bits, v1.w = object index bits (the closed
// mesh the triangle belongs to; it encloses a medium when its material is glass), v2.w =
// kTriangleGlass bits when the material is glass (else 0), so that the traversal can tell touching
// glass surfaces without reading materials (shaders/touching.glsl).
VITRUM_CONST uint kTriangleGlass = 1u;
struct TriangleVertices {
    vec4 v0;
    vec4 v1;
    vec4 v2;
};

// Shading attributes. n0..n2 are the vertex normals (the geometric normal where the file has
// none), uv01 = (u0, v0, u1, v1), uv2 = (u2, v2, -, -).
struct TriangleShading {
    vec4 n0;
    vec4 n1;
    vec4 n2;
    vec4 uv01;
    vec4 uv2;
};

// ---- Materials ------------------------------------------------------------------------------
// Material models, numbered like the course's MTL `shader N` (docs/render-model.md).
VITRUM_CONST uint kMaterialNormal = 1u;
VITRUM_CONST uint kMaterialLambert = 2u;
VITRUM_CONST uint kMaterialPhong = 3u;  // opaque dielectric: Phong + Schlick-weighted reflection
VITRUM_CONST uint kMaterialGlass = 4u;
VITRUM_CONST uint kMaterialMirror = 6u;

VITRUM_CONST uint kNoTexture = 0xFFFFFFFFu;

// All colours linear RGB.
//   ambient.w  (uint bits) = model (kMaterial*)
//   diffuse.w  (uint bits) = index into the texture table or kNoTexture
//   specular.w = Phong exponent Ns
//   attenuation.xyz = Beer-Lambert mu per channel (Tf), attenuation.w = IOR (Ni)
struct GpuMaterial {
    vec4 ambient;
    vec4 diffuse;
    vec4 specular;
    vec4 attenuation;
};

// A texture is a run of texels in the texel buffer (linear RGB, three packed floats a texel).
//   x = first texel, y = width, z = height, w = unused
struct TextureInfo {
    uvec4 offsetAndSize;
};

// ---- Lights ---------------------------------------------------------------------------------
// position.w = 1 for inverse-square fall-off, 0 for none (the course's default).
struct GpuLight {
    vec4 position;
    vec4 colour;
};

// ---- Fresnel models -------------------------------------------------------------------------
VITRUM_CONST uint kFresnelSchlick = 0u;
VITRUM_CONST uint kFresnelExact = 1u;
VITRUM_CONST uint kFresnelSchlickExp2 = 2u;

// ---- Texel buffers -------------------------------------------------------------------------------
// The scene's read-only data are bound as storage texel buffers of 16-byte uvec4 texels
// (shaders/bindings.glsl): a struct is this many consecutive texels (gpu_layout.h checks them
// against the struct sizes). An object's medium is one texel: its material's `attenuation` (Tf, Ni).
VITRUM_CONST uint kTraversalNodeTexels = 4u;
VITRUM_CONST uint kRenderParamsTexels = 16u;
VITRUM_CONST uint kTraceStateTexels = 16u;  // a storage buffer of uvec4s (shaders/suspend.glsl)
VITRUM_CONST uint kTriangleVerticesTexels = 3u;
VITRUM_CONST uint kTriangleShadingTexels = 5u;
VITRUM_CONST uint kGpuMaterialTexels = 4u;
VITRUM_CONST uint kGpuLightTexels = 2u;

// ---- Per-render parameters (a texel buffer of kRenderParamsTexels, see bindings.glsl) -----------
// The pinhole camera of docs/render-model.md: a sample at image position (sx, sy) has direction
// normalize((sx - width/2) * cameraX + (height/2 - sy) * cameraY - focalLength * cameraZ).
struct RenderParams {
    vec4 cameraFrom;   // .w = focal length f = height / (2 tan(fov_y / 2)), in pixels
    vec4 cameraX;      // .xyz = x_c
    vec4 cameraY;      // .xyz = y_c
    vec4 cameraZ;      // .xyz = z_c (points from the target back to the camera)
    vec4 background;   // .xyz = constant background colour; .w = air IOR
    uvec4 image;       // width, height, samples per pixel, max depth
    uvec4 counts;      // light count, fresnel model, texture count, iteration budget per SIMD group and dispatch
    uvec4 tile;        // tile origin x, tile origin y, tile width, tile height
    uvec4 pass;        // x = media around the camera (cameraMedia); y = columns of the stratified
                       // sample grid (rows = spp / columns); z = media of cameraMediaBehind; w = 1
                       // when opaque surfaces of two objects may coincide
                       // (SceneFeatures::coincidentOpaquePossible), else 0
    vec4 tuning;       // x = min weight, y = distance within which surfaces touch (1e-5 x scene
                       // diagonal), z = 1 when the scene has two or more glass objects (so
                       // surfaces of different objects can touch), else 0; w = 1 when glass may
                       // rest on an opaque surface (SceneFeatures::opaqueContactPossible), else 0
    uvec4 environment; // x = background kind (kBackground*), y = filter (kFilter*), z = texture of
                       // the spherical map or of the cube's +x face (then -x, +y, -y, +z, -z)
    vec4 offsets;      // ray-origin offsets (Waechter and Binder) scaled to the scene: x = radius of
                       // the region around the origin where offsets are absolute, y = that offset
    uvec4 bvh;         // x = the root's entry (see TraversalNode): node 0, or the one leaf of a
                       // scene of at most kMaxLeafTriangles triangles
    uvec4 cameraMedia; // the objects whose media the camera is inside, innermost last: every
                       // primary ray's medium stack (host/render/camera_medium.h); pass.x of them
    vec4 cameraSurface;       // .xyz = unit normal of the surface the camera lies on, 0 if none:
                              // primary rays start off it on their side (host/render/camera_surface.h)
    uvec4 cameraMediaBehind;  // the media of primary rays that go against that normal; pass.z of them
};

// Numbered like vitrum::BackgroundKind and vitrum::TextureFilter.
VITRUM_CONST uint kBackgroundConstant = 0u;
VITRUM_CONST uint kBackgroundSpherical = 1u;
VITRUM_CONST uint kBackgroundCube = 2u;
VITRUM_CONST uint kFilterBilinear = 0u;
VITRUM_CONST uint kFilterNearest = 1u;

// ---- Per-invocation trace state (storage buffers, one entry per pixel of a tile) ---------------
// lavapipe stops any shader loop after 65,535 iterations, silently. trace.comp therefore runs
// at most `iteration budget` counted steps per dispatch; a pixel that is not finished keeps its
// whole state in these buffers and the next dispatch resumes it (docs/gpu-design.md).
VITRUM_CONST uint kRayStackSize = 16u;    // most pending rays of the depth-first ray tree
VITRUM_CONST uint kMaxMediumDepth = 4u;   // most media a ray can be inside at once (trace.comp unrolls for 4)

// A ray of the tree with everything needed to continue it later.
struct PendingRay {
    vec4 origin;     // .w = depth (uint bits)
    vec4 direction;  // unit; .w = number of media on the stack (uint bits)
    vec4 weight;     // .xyz = product of the path factors (R, 1 - R, Beer-Lambert, m_s)
    uvec4 media;     // object indices of the media the ray is inside, innermost last
};

// The pending rays of a pixel are not part of its TraceState: they live in their own buffer,
// `capacity` entries a pixel (the specialized kernel's kPendingRayCapacity, sized to what the
// scene can reach), read and written in place, so suspending a pixel never copies them. Nor is
// its BVH traversal stack (kTraversalStackSize uints a pixel, in a buffer of its own): the kernel
// keeps it in private memory and saves only the entries in use, only when a pixel is suspended in
// the middle of a traversal. On lavapipe every storage-buffer access is a loop over the 8 lanes.
struct TraceState {
    PendingRay ray;                      // the ray being traced (or shaded)
    vec4 traceOrigin;                    // the ray of the current traversal; .w = tMin
    vec4 traceDirection;                 // .w = closest t so far (the traversal's tMax)
    vec4 hitPosition;                    // .w = hit t of `ray`. During a closest-hit traversal
                                         // that looks for glass on opaque surfaces: the nearest
                                         // opaque hit's t, triangle (bits) and barycentrics
    vec4 hitNormal;                      // shading normal, .w = material (uint bits). During such
                                         // a traversal: .x = 1 when the nearest hit is glass
    vec4 hitGeometricNormal;             // .w = object (uint bits)
    vec4 hitUv;                          // .xy = texture coordinates, .zw = barycentrics
    uvec4 colourLow;                     // the pixel's colour so far, summed over its samples in
                                         // fixed point (shaders/colour_sum.glsl): .xyz = low
                                         // words; .w = samples done
    uvec4 colourHigh;                    // .xyz = high words
    uvec4 control;                       // phase, pending rays, current light, traversal stack entries
    uvec4 traversal;                     // leaf cursor, leaf end, closest triangle, pixel's steps
    uvec4 touching;                      // other objects' glass surfaces at the hit: object | entering
                                         // << 31, up to 3; .w = how many. During a closest-hit
                                         // traversal: touching.glsl's candidate objects
    vec4 probe;                          // .x = farthest touching surface's t; .yzw = the direct
                                         // light a pending shadow ray adds if unoccluded. During a
                                         // closest-hit traversal: the candidates' t
};

// ---- Sampling -------------------------------------------------------------------------------
// The integer hash both backends use for jitter, so that their samples are bit-identical:
// PCG's output permutation (Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 2020).
#ifdef __cplusplus
inline
#endif
uint pcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A uniform float in [0, 1) from the top 24 bits of a hash: exact in float on every backend.
#ifdef __cplusplus
inline
#endif
float hashToUnit(uint h) {
    return float(h >> 8u) * (1.0f / 16777216.0f);
}

VITRUM_GPU_END
#endif
