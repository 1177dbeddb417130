// The host's view of the shared GPU layout: the sizes std430 gives each struct, checked here.
#pragma once

#include "shared/gpu_types.h"

namespace vitrum::gpu {
static_assert(sizeof(BvhNode) == 32);
static_assert(sizeof(TraversalNode) == 64);
static_assert(sizeof(TriangleVertices) == 48);
static_assert(sizeof(ShadingTexel) == 16);
static_assert(sizeof(GpuMaterial) == 80);
static_assert(sizeof(TextureInfo) == 16);
static_assert(sizeof(GpuLight) == 32);
static_assert(sizeof(RenderParams) == 256);
static_assert(sizeof(TraversalNode) == 16 * kTraversalNodeTexels);
static_assert(sizeof(GpuInstance) == 16 * kGpuInstanceTexels && kGpuInstanceTexels == kGpuInstanceNodes * kTraversalNodeTexels);
static_assert(kLeaveInstanceEntry == (kLeafEntryFlag | (kMaxInstances + 1u) << 4));
static_assert(sizeof(RenderParams) == 16 * kRenderParamsTexels, "bindings.glsl's loadRenderParams reads every field");
static_assert(sizeof(TriangleVertices) == 16 * kTriangleVerticesTexels);
static_assert(sizeof(GpuMaterial) == 16 * kGpuMaterialTexels);
static_assert(sizeof(GpuLight) == 16 * kGpuLightTexels);
}  // namespace vitrum::gpu

namespace vitrum::gpu {
static_assert(sizeof(PendingRay) == 64);
static_assert(kMaxMediumDepth == 4, "trace.comp's medium stack code is unrolled for 4 entries");
}  // namespace vitrum::gpu
