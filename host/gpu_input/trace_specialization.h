// The specialization constants of shaders/trace.comp (shaders/specialization.glsl): what one
// build of the kernel can simulate. `forScene` turns the scene's analysis into a kernel without
// the code the scene cannot need and with stacks sized to what it can reach; `general()` is the
// kernel that decides everything at run time (`vitrum render --no-specialize`). Both give the
// same image for every scene whose meshes are closed and consistently wound (docs/specialization.md).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "analysis/scene_features.h"
#include "scene/scene.h"
#include "shared/trace_constants.h"

namespace vitrum {

using TraceKernelConstants = std::array<std::uint32_t, gpu::kTraceConstantCount>;

struct TraceSpecialization {
    static constexpr std::uint32_t kAnyKind = 0xFFFFFFFFu;  // decided at run time

    bool specialized = false;
    std::uint32_t materialModels = 0xFFFFFFFFu;  // bit (1 << model) per material model compiled in
    bool shadowRays = true;
    bool absorption = true;
    bool touchingProbe = true;
    bool opaqueContact = true;  // glass may rest on an opaque surface (SceneFeatures::opaqueContactPossible)
    bool coincidentOpaque = true;  // opaque surfaces of two objects may coincide (coincidentOpaquePossible)
    bool mediumPriorities = true;  // glass media of different priorities (SceneFeatures::mediumPriorities)
    bool dispersion = true;        // some glass disperses (SceneFeatures::dispersion)
    bool glassTints = true;        // some glass tints what crosses its surface (SceneFeatures::glassTints)
    bool cutouts = true;           // some surface has cut-out parts (SceneFeatures::cutouts)
    bool partialCoverage = true;   // some surface is partly there (SceneFeatures::partialCoverage)
    bool transmissionTextures = true;  // some glass is glass in parts (SceneFeatures::transmissionTextures)
    bool instancing = true;        // the scene has instances: a two-level BVH (Scene::instances)
    bool textures = true;
    std::uint32_t backgroundKind = kAnyKind;  // BackgroundKind or kAnyKind
    std::uint32_t fresnelModel = kAnyKind;    // FresnelModel or kAnyKind
    std::uint32_t textureFilter = kAnyKind;   // TextureFilter or kAnyKind
    std::uint32_t mediumStackDepth;           // media one ray can be inside
    std::uint32_t pendingRayCapacity;         // pending rays a pixel
    bool singleSample = false;                // one sample a pixel: no jitter code

    static TraceSpecialization general();
    static TraceSpecialization forScene(const Scene& scene, const SceneFeatures& features);

    // All of trace.comp's specialization constants by id (shaders/shared/trace_constants.h): the
    // scene's set, the kernel's role and device's left 0 (host/gpu/trace_pipeline.cpp sets them).
    TraceKernelConstants constants() const;
    std::vector<std::string> describe() const;  // one line a setting, for `vitrum info`
};

nlohmann::json toJson(const TraceSpecialization& specialization);

}  // namespace vitrum
