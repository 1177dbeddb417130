// The specialization constant ids of trace.comp: shaders/specialization.glsl declares a constant
// at each, host/gpu_input/trace_specialization.cpp and host/gpu/trace_pipeline.cpp set them.
#ifndef VITRUM_TRACE_CONSTANTS_H
#define VITRUM_TRACE_CONSTANTS_H

#include "language.h"

VITRUM_GPU_BEGIN
// What the scene needs (TraceSpecialization).
VITRUM_CONST uint kConstantMaterialModels = 0u;
VITRUM_CONST uint kConstantShadowRays = 1u;
VITRUM_CONST uint kConstantAbsorption = 2u;
VITRUM_CONST uint kConstantTouchingProbe = 3u;
VITRUM_CONST uint kConstantTextures = 4u;
VITRUM_CONST uint kConstantBackgroundKind = 5u;
VITRUM_CONST uint kConstantFresnelModel = 6u;
VITRUM_CONST uint kConstantTextureFilter = 7u;
VITRUM_CONST uint kConstantMediumStackDepth = 8u;
VITRUM_CONST uint kConstantPendingRayCapacity = 9u;
VITRUM_CONST uint kConstantSingleSample = 10u;
VITRUM_CONST uint kConstantOpaqueContact = 11u;
VITRUM_CONST uint kConstantCoincidentOpaque = 12u;
VITRUM_CONST uint kConstantMediumPriorities = 13u;
// The kernel's role and the device's guarantees (host/gpu/trace_pipeline.cpp).
VITRUM_CONST uint kConstantResumable = 14u;
VITRUM_CONST uint kConstantFullSubgroups = 15u;
VITRUM_CONST uint kConstantPersistentSubgroups = 16u;
// A scene feature, numbered after the others.
VITRUM_CONST uint kConstantDispersion = 17u;
VITRUM_CONST uint kConstantInstancing = 18u;
VITRUM_CONST uint kConstantGlassTints = 19u;
VITRUM_CONST uint kConstantCutouts = 20u;
VITRUM_CONST uint kConstantPartialCoverage = 21u;
VITRUM_CONST uint kConstantTransmissionTextures = 22u;
VITRUM_CONST uint kTraceConstantCount = 23u;
VITRUM_GPU_END

#endif
