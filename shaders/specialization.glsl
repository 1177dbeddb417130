// What this build of trace.comp can simulate: Vulkan specialization constants (ids in
// shared/trace_constants.h), set by the host from the scene's analysis
// (host/gpu_input/trace_specialization.cpp) and the device (host/gpu/trace_pipeline.cpp). A feature
// that is off is constant false, so the driver's compiler removes its code; the defaults below
// are the general kernel (`--no-specialize`), which decides everything at run time.
#ifndef VITRUM_SPECIALIZATION_GLSL
#define VITRUM_SPECIALIZATION_GLSL

#include "bindings.glsl"

#include "shared/trace_constants.h"

const uint kAnyKind = 0xFFFFFFFFu;  // decided at run time from the render parameters

layout(constant_id = kConstantMaterialModels) const uint kMaterialModels = 0xFFFFFFFFu;  // bit (1 << kMaterial*) per model used
layout(constant_id = kConstantShadowRays) const bool kShadowRays = true;      // lights and Lambert / Phong materials
layout(constant_id = kConstantAbsorption) const bool kAbsorption = true;      // some glass has Tf != 0
layout(constant_id = kConstantTouchingProbe) const bool kTouchingProbe = true;   // glass objects may touch or nest
layout(constant_id = kConstantTextures) const bool kTextures = true;        // some material has map_Kd
layout(constant_id = kConstantBackgroundKind) const uint kBackgroundKind = kAnyKind;  // kBackground* or kAnyKind
layout(constant_id = kConstantFresnelModel) const uint kFresnelModel = kAnyKind;    // kFresnel* or kAnyKind
layout(constant_id = kConstantTextureFilter) const uint kTextureFilter = kAnyKind;   // kFilter* or kAnyKind
layout(constant_id = kConstantMediumStackDepth) const uint kMediumStackDepth = kMaxMediumDepth;  // 1..kMaxMediumDepth
layout(constant_id = kConstantPendingRayCapacity) const uint kPendingRayCapacity = kRayStackSize;  // 0..kRayStackSize
layout(constant_id = kConstantSingleSample) const bool kSingleSample = false;  // one sample a pixel: its centre
layout(constant_id = kConstantOpaqueContact) const bool kOpaqueContact = true;  // glass may rest on an opaque surface
layout(constant_id = kConstantCoincidentOpaque) const bool kCoincidentOpaque = true;  // opaque surfaces of two objects may coincide
layout(constant_id = kConstantMediumPriorities) const bool kMediumPriorities = true;  // glass media of different priorities
layout(constant_id = kConstantDispersion) const bool kDispersion = true;  // some glass disperses (MTL Vd)
layout(constant_id = kConstantInstancing) const bool kInstancing = true;  // the BVH has two levels (gpu_types.h, "Instances")
layout(constant_id = kConstantGlassTints) const bool kGlassTints = true;  // some glass tints what crosses its surface
layout(constant_id = kConstantCutouts) const bool kCutouts = true;  // some surface has cut-out parts (Material::cutout)
layout(constant_id = kConstantPartialCoverage) const bool kPartialCoverage = true;  // some surface is partly there (Material::coverage)
layout(constant_id = kConstantTransmissionTextures) const bool kTransmissionTextures = true;  // some glass is glass only where a texture says
// Not a scene feature but the kernel's role (shaders/suspend.glsl): the first dispatch of a tile
// runs without it and gives up the pixels that need more than one dispatch; the resumable kernel
// restarts them and suspends them between dispatches.
layout(constant_id = kConstantResumable) const bool kResumable = true;
// Not a scene feature but the device's guarantee: every subgroup is full, since the pipeline was
// created with VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT (statistics.glsl).
layout(constant_id = kConstantFullSubgroups) const bool kFullSubgroups = false;
// Not a scene feature but the device's threads: on a device that runs on the CPU, the first
// dispatch's subgroups take units of work until none is left, so that the CPU's threads share
// the work however fast each runs (trace.comp's main). Only with kFullSubgroups.
layout(constant_id = kConstantPersistentSubgroups) const bool kPersistentSubgroups = false;

bool usesMaterial(uint model) { return ((kMaterialModels >> model) & 1u) != 0u; }

uint backgroundKind() { return kBackgroundKind == kAnyKind ? backgroundKindOf() : kBackgroundKind; }
uint fresnelModel() { return kFresnelModel == kAnyKind ? fresnelModelOf() : kFresnelModel; }
uint textureFilter() { return kTextureFilter == kAnyKind ? textureFilterOf() : kTextureFilter; }

#endif
