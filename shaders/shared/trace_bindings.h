// The descriptor bindings of trace.comp (set 0): shaders/bindings.glsl declares a buffer at each,
// host/gpu/trace_pipeline.cpp binds one to each.
#ifndef VITRUM_TRACE_BINDINGS_H
#define VITRUM_TRACE_BINDINGS_H

#include "language.h"

VITRUM_GPU_BEGIN
// The scene and the render parameters: read-only texel buffers, but for the textures.
VITRUM_CONST uint kBindingParams = 0u;
VITRUM_CONST uint kBindingNodes = 1u;
VITRUM_CONST uint kBindingVertices = 2u;
VITRUM_CONST uint kBindingShading = 3u;
VITRUM_CONST uint kBindingMaterials = 4u;
VITRUM_CONST uint kBindingLights = 5u;
VITRUM_CONST uint kBindingTextures = 6u;
VITRUM_CONST uint kBindingTexels = 7u;
VITRUM_CONST uint kBindingObjectMedia = 8u;
// One tile's buffers (host/gpu/tile_buffers.h) and the dispatch's counters.
VITRUM_CONST uint kBindingPixels = 9u;
VITRUM_CONST uint kBindingStates = 10u;
VITRUM_CONST uint kBindingStats = 11u;
VITRUM_CONST uint kBindingPendingRays = 12u;
VITRUM_CONST uint kBindingTraversalStacks = 13u;
// The wavelength samples of dispersion (render_model/dispersion.h): a read-only texel buffer.
VITRUM_CONST uint kBindingWavelengths = 14u;
VITRUM_CONST uint kTraceBindingCount = 15u;
VITRUM_GPU_END

#endif
