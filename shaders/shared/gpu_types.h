// GPU data layout shared by the C++ host and the GLSL kernels: one definition of every buffer
// element. Everything is built from vec4/uvec4 so that std430 and C++ agree without padding;
// integers travel bit-cast in the .w of a vec4 (tinybvh's trick). The host checks sizes with
// static_assert in host/gpu/gpu_layout.h.
#ifndef VITRUM_GPU_TYPES_H
#define VITRUM_GPU_TYPES_H

#include "language.h"
#include "render_params.h"

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
// its second; nodes keep the depth-first order of their BvhNodes (host/gpu_input/traversal_nodes.h).
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

// ---- Instances (a two-level BVH; docs/gpu-design.md, "Instancing") ----------------------------
// A scene with instances (vitrum::Scene::instances) has a top-level tree over its instances' world
// boxes first in the node array, then the world triangles' tree, then each mesh's tree (their
// triangles stored once, in the mesh's space). A top-level leaf is one instance: as a BvhNode, a
// leaf of count 0 whose first is the instance; as a traversal entry, kLeafEntryFlag | (instance +
// 1) << 4 (count 0; kLeafEntryFlag alone stays the empty scene's leaf), or for the world
// triangles' tree, that tree's root entry itself. Entering an instance moves the ray into its
// mesh's space (not normalized, so that t stays the world's) and pushes kLeaveInstanceEntry,
// whose pop moves it back. A tree's depth is bounded so that the top level's, one entry and a
// mesh's fit the stack (host/bvh/bvh_builder.cpp).
//   toObject0..2: the rows of the world-to-object matrix (xyz the linear part, w the translation)
//   toWorld0..2: the rows of the object-to-world matrix
//   info.x: the mesh tree's root, a BvhNode index (the CPU's); info.y: the traversal entry of it
//   (the GPU's); info.z: the instance's first object (its mesh's object k is first + k);
//   info.w: kIdentityInstance for the world triangles' tree (no transform, no objects added)
// Eight texels, two traversal nodes: instance i is at traversal node RenderParams bvh.y + 2 i.
struct GpuInstance {
    vec4 toObject0;
    vec4 toObject1;
    vec4 toObject2;
    vec4 toWorld0;
    vec4 toWorld1;
    vec4 toWorld2;
    uvec4 info;
    uvec4 unused;
};
VITRUM_CONST uint kNoInstance = 0xFFFFFFFFu;
VITRUM_CONST uint kIdentityInstance = 1u;
VITRUM_CONST uint kMaxInstances = (1u << 27) - 2u;
VITRUM_CONST uint kLeaveInstanceEntry = 0xFFFFFFF0u;  // kLeafEntryFlag | (kMaxInstances + 1) << 4
VITRUM_CONST uint kGpuInstanceNodes = 2u;

// ---- Triangles (in BVH leaf order) -----------------------------------------------------------
// Positions for intersection. v0.w = material index bits, v1.w = object index bits (the closed
// mesh the triangle belongs to; it encloses a medium when its material is glass), v2.w = the
// triangle's mark, so that the traversal knows what it needs without reading materials:
// kTriangleGlass where the material is glass (touching glass surfaces, shaders/touching.glsl);
// kTriangleCutout | texture where the material has cut-out parts (Material::cutout, the texture
// its index in the texture table, kTriangleCutoutTexture's bits; shaders/cutout.glsl), with
// kTriangleCovered where it is partly there (Material::coverage: a ray going on through such a
// surface passes them by near its start; shading.glsl's coverSurface); else 0.
VITRUM_CONST uint kTriangleGlass = 1u;
VITRUM_CONST uint kTriangleCutout = 0x80000000u;
VITRUM_CONST uint kTriangleCovered = 0x40000000u;
VITRUM_CONST uint kTriangleCutoutTexture = 0x3FFFFFFFu;
struct TriangleVertices {
    vec4 v0;
    vec4 v1;
    vec4 v2;
};

// Shading attributes, in one texel buffer: a texel a triangle (in BVH order), then the scene's
// distinct vertex normals of the triangles that need them, a texel each (xyz), then the corners'
// texture coordinates of the triangles whose material has a texture or cut-outs, two texels each
// (u0 v0 u1 v1, u2 v2 - -). A triangle's texel:
//   flat (its three vertex normals the same bits, e.g. the geometric normal where the file has
//   none) and untextured: xyz = that normal's float bits, w = kFlatTriangle;
//   else: xyz = the texels of its corners' normals, w = its first uv texel, or kNoCornerUvs.
// A flat triangle takes one texel and a smooth mesh's shared normals are stored once, where
// four texels a triangle held them all (docs/gpu-design.md, "Shading data by index").
struct ShadingTexel {
    uvec4 bits;
};
VITRUM_CONST uint kFlatTriangle = 0xFFFFFFFFu;
VITRUM_CONST uint kNoCornerUvs = 0xFFFFFFFEu;
VITRUM_CONST uint kCornerUvsTexels = 2u;

// ---- Materials ------------------------------------------------------------------------------
// Material models, numbered like the course's MTL `shader N` (../shared/docs/render-model.md).
VITRUM_CONST uint kMaterialNormal = 1u;
VITRUM_CONST uint kMaterialLambert = 2u;
VITRUM_CONST uint kMaterialPhong = 3u;  // opaque dielectric: Phong + Schlick-weighted reflection
VITRUM_CONST uint kMaterialGlass = 4u;
VITRUM_CONST uint kMaterialMirror = 6u;
VITRUM_CONST uint kMaterialThinGlass = 7u;  // no course number: MaterialModel::ThinGlass

VITRUM_CONST uint kNoTexture = 0xFFFFFFFFu;

// All colours linear RGB.
//   ambient.w  (uint bits) = model (kMaterial*)
//   diffuse.w  (uint bits) = index into the texture table or kNoTexture
//   specular.w = Phong exponent Ns
//   attenuation.xyz = Beer-Lambert mu per channel (Tf), attenuation.w = IOR (Ni)
//   parts.x (uint bits) = the texture of the share of the surface that is there
//                         (Material::coverage, hasPartialCoverage) or kNoTexture
//   parts.y (uint bits) = the texture of where a glass is glass (Material::transmissionTexture,
//                         hasTransmissionTexture) or kNoTexture; parts.z (uint bits) = the
//                         material it is elsewhere (Material::opaquePart); w unused
struct GpuMaterial {
    vec4 ambient;
    vec4 diffuse;
    vec4 specular;
    vec4 attenuation;
    vec4 parts;
};

// A texture is a run of texels in the texture texel buffer, one 16-byte texel a texture texel
// (linear RGB in xyz, w unused), so that one imageLoad reads it (docs/gpu-design.md, "Texture
// texels as texel loads").
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

// ---- Shadow rays ----------------------------------------------------------------------------
// A light's shadow ray is traced only where its unshadowed direct term reaches the smallest normal
// float in some channel: a term below it is a denormal, which a device may flush to 0 (Vulkan
// leaves that to the implementation; lavapipe flushes some), so that the rays traced, and their
// count, would depend on the device (render-model-decisions.md, "Skipped").
VITRUM_CONST float kLeastShadowedTerm = 1.17549435e-38;  // FLT_MIN

// ---- Fresnel models -------------------------------------------------------------------------
VITRUM_CONST uint kFresnelSchlick = 0u;
VITRUM_CONST uint kFresnelExact = 1u;
VITRUM_CONST uint kFresnelSchlickExp2 = 2u;

// ---- Texel buffers -------------------------------------------------------------------------------
// The scene's read-only data are bound as storage texel buffers of 16-byte uvec4 texels
// (shaders/bindings.glsl): a struct is this many consecutive texels (gpu_layout.h checks them
// against the struct sizes). An object's medium is three texels: its material's `attenuation` (Tf,
// Ni); its priority (int bits in x; render-model-decisions.md, "Overlapping media by priority")
// and Cauchy B (y); its surface's tint (xyz; "Glass tint").
VITRUM_CONST uint kTraversalNodeTexels = 4u;
VITRUM_CONST uint kGpuInstanceTexels = 8u;
VITRUM_CONST uint kTraceStateTexels = 16u;  // a pixel's saved state (shaders/suspend.glsl)
VITRUM_CONST uint kTriangleVerticesTexels = 3u;
VITRUM_CONST uint kGpuMaterialTexels = 5u;
VITRUM_CONST uint kGpuLightTexels = 2u;
VITRUM_CONST uint kObjectMediumTexels = 3u;

// Numbered like vitrum::BackgroundKind and vitrum::TextureFilter.
VITRUM_CONST uint kBackgroundConstant = 0u;
VITRUM_CONST uint kBackgroundSpherical = 1u;
VITRUM_CONST uint kBackgroundCube = 2u;
VITRUM_CONST uint kFilterBilinear = 0u;
VITRUM_CONST uint kFilterNearest = 1u;

// ---- Per-invocation trace state (storage buffers, one entry per pixel of a tile) ---------------
// lavapipe stops any shader loop after 65,535 iterations, silently. trace.comp therefore runs
// at most `iteration budget` counted steps per dispatch; a pixel that is not finished keeps its
// whole state in these buffers and the next dispatch resumes it (docs/gpu-design.md, "One loop,
// bounded, resumable").
VITRUM_CONST uint kRayStackSize = 16u;    // most pending rays of the depth-first ray tree
VITRUM_CONST uint kMaxMediumDepth = 4u;   // most media a ray can be inside at once (trace.comp unrolls for 4)

// A ray of the tree with everything needed to continue it later.
struct PendingRay {
    vec4 origin;     // .w = depth (uint bits)
    vec4 direction;  // unit; .w = number of media on the stack (uint bits)
    vec4 weight;     // .xyz = product of the path factors (R, 1 - R, Beer-Lambert, m_s); .w = the t
                     // below which a ray going on through a partly covered surface passes such
                     // surfaces by (shaders/shading.glsl's coverSurface), else 0
    uvec4 media;     // object indices of the media the ray is inside, innermost last
};

// A pixel's state (shaders/trace_state.glsl), saved between the resumable kernel's dispatches
// as kTraceStateTexels texels (shaders/suspend.glsl). Its pending rays are not part of it: they
// live in their own buffer, `capacity` entries a pixel (the specialized kernel's
// kPendingRayCapacity, sized to what the scene can reach), read and written in place, so
// suspending a pixel never copies them. Nor is its BVH traversal stack (kTraversalStackSize uints
// a pixel, in a buffer of its own): the kernel keeps it in private memory and saves only the
// entries in use, only when a pixel is suspended in the middle of a traversal.
VITRUM_CONST uint kTraceStateBytes = 16u * kTraceStateTexels;

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
