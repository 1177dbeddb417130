// What this build of trace.comp can simulate: Vulkan specialization constants, set by the host
// from the scene's analysis (host/gpu/trace_specialization.cpp, same constant ids). A feature
// that is off is constant false, so the driver's compiler removes its code; the defaults below
// are the general kernel (`--no-specialize`), which decides everything at run time.
#ifndef VITRUM_SPECIALIZATION_GLSL
#define VITRUM_SPECIALIZATION_GLSL

const uint kAnyKind = 0xFFFFFFFFu;  // decided at run time from the render parameters

layout(constant_id = 0) const uint kMaterialModels = 0xFFFFFFFFu;  // bit (1 << kMaterial*) per model used
layout(constant_id = 1) const bool kShadowRays = true;      // lights and Lambert / Phong materials
layout(constant_id = 2) const bool kAbsorption = true;      // some glass has Tf != 0
layout(constant_id = 3) const bool kTouchingProbe = true;   // glass objects may touch or nest
layout(constant_id = 4) const bool kTextures = true;        // some material has map_Kd
layout(constant_id = 5) const uint kBackgroundKind = kAnyKind;  // kBackground* or kAnyKind
layout(constant_id = 6) const uint kFresnelModel = kAnyKind;    // kFresnel* or kAnyKind
layout(constant_id = 7) const uint kTextureFilter = kAnyKind;   // kFilter* or kAnyKind
layout(constant_id = 8) const uint kMediumStackDepth = kMaxMediumDepth;  // 1..kMaxMediumDepth
layout(constant_id = 9) const uint kPendingRayCapacity = kRayStackSize;  // 0..kRayStackSize
layout(constant_id = 10) const bool kSingleSample = false;  // one sample a pixel: its centre
layout(constant_id = 11) const bool kOpaqueContact = true;  // glass may rest on an opaque surface
layout(constant_id = 12) const bool kCoincidentOpaque = true;  // opaque surfaces of two objects may coincide
// Not a scene feature but the kernel's role (shaders/suspend.glsl): the first dispatch of a tile
// runs without it and gives up the pixels that need more than one dispatch; the resumable kernel
// restarts them and suspends them between dispatches.
layout(constant_id = 13) const bool kResumable = true;
// Not a scene feature but the device's guarantee: every subgroup is full, since the pipeline was
// created with VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT (statistics.glsl).
layout(constant_id = 14) const bool kFullSubgroups = false;
// Not a scene feature but the device's threads: on a device that runs on the CPU, the first
// dispatch's subgroups take units of work until none is left, so that the CPU's threads share
// the work however fast each runs (trace.comp's main). Only with kFullSubgroups.
layout(constant_id = 15) const bool kPersistentSubgroups = false;

bool usesMaterial(uint model) { return ((kMaterialModels >> model) & 1u) != 0u; }

uint backgroundKind() { return kBackgroundKind == kAnyKind ? params.environment.x : kBackgroundKind; }
uint fresnelModel() { return kFresnelModel == kAnyKind ? params.counts.y : kFresnelModel; }
uint textureFilter() { return kTextureFilter == kAnyKind ? params.environment.y : kTextureFilter; }

#endif
