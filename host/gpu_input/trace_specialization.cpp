#include "gpu_input/trace_specialization.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "scene/scene_names.h"
#include "shared/gpu_types.h"

namespace vitrum {

TraceSpecialization TraceSpecialization::general() {
    TraceSpecialization s;
    s.mediumStackDepth = gpu::kMaxMediumDepth;
    s.pendingRayCapacity = gpu::kRayStackSize;
    return s;
}

TraceSpecialization TraceSpecialization::forScene(const Scene& scene, const SceneFeatures& f) {
    TraceSpecialization s;
    s.specialized = true;
    s.materialModels = f.materialModels;
    s.shadowRays = f.shadowRays;
    s.absorption = f.absorbingMedia;
    s.touchingProbe = f.touchingMediaPossible;
    s.opaqueContact = f.opaqueContactPossible;
    s.coincidentOpaque = f.coincidentOpaquePossible;
    s.mediumPriorities = f.mediumPriorities;
    s.dispersion = f.dispersion;
    s.glassTints = f.glassTints;
    s.cutouts = f.cutouts;
    s.partialCoverage = f.partialCoverage;
    s.transmissionTextures = f.transmissionTextures;
    s.instancing = !scene.instances.empty();
    s.textures = f.textures;
    s.backgroundKind = std::uint32_t(f.background);
    s.fresnelModel = std::uint32_t(scene.settings.fresnel);
    s.textureFilter = std::uint32_t(scene.settings.filter);
    // The kernel's loops over these stacks are unrolled up to the general sizes; at least one
    // entry each keeps the unused code well-formed (it is never reached).
    s.mediumStackDepth = std::max(1u, f.mediumStackDepth);
    s.pendingRayCapacity = f.rayStackDepth;
    s.singleSample = scene.settings.samplesPerPixel == 1;
    return s;
}

TraceKernelConstants TraceSpecialization::constants() const {
    TraceKernelConstants c{};
    c[gpu::kConstantMaterialModels] = materialModels;
    c[gpu::kConstantShadowRays] = shadowRays ? 1u : 0u;
    c[gpu::kConstantAbsorption] = absorption ? 1u : 0u;
    c[gpu::kConstantTouchingProbe] = touchingProbe ? 1u : 0u;
    c[gpu::kConstantTextures] = textures ? 1u : 0u;
    c[gpu::kConstantBackgroundKind] = backgroundKind;
    c[gpu::kConstantFresnelModel] = fresnelModel;
    c[gpu::kConstantTextureFilter] = textureFilter;
    c[gpu::kConstantMediumStackDepth] = mediumStackDepth;
    c[gpu::kConstantPendingRayCapacity] = pendingRayCapacity;
    c[gpu::kConstantSingleSample] = singleSample ? 1u : 0u;
    c[gpu::kConstantOpaqueContact] = opaqueContact ? 1u : 0u;
    c[gpu::kConstantCoincidentOpaque] = coincidentOpaque ? 1u : 0u;
    c[gpu::kConstantMediumPriorities] = mediumPriorities ? 1u : 0u;
    c[gpu::kConstantDispersion] = dispersion ? 1u : 0u;
    c[gpu::kConstantInstancing] = instancing ? 1u : 0u;
    c[gpu::kConstantGlassTints] = glassTints ? 1u : 0u;
    c[gpu::kConstantCutouts] = cutouts ? 1u : 0u;
    c[gpu::kConstantPartialCoverage] = partialCoverage ? 1u : 0u;
    c[gpu::kConstantTransmissionTextures] = transmissionTextures ? 1u : 0u;
    return c;
}

namespace {

// The name of a constant that is a kind (background, Fresnel model, filter), or "any".
template <class Kind>
std::string kindName(std::uint32_t kind, const char* (*name)(Kind)) {
    return kind == TraceSpecialization::kAnyKind ? "any (run time)" : name(Kind(kind));
}

std::string modelList(std::uint32_t mask) {
    if (mask == 0xFFFFFFFFu) return "all";
    std::string list;
    for (const std::string& name : materialModelNames(mask)) list += (list.empty() ? "" : ", ") + name;
    return list.empty() ? "none" : list;
}

}  // namespace

std::vector<std::string> TraceSpecialization::describe() const {
    auto onOff = [](bool b) { return b ? "compiled in" : "removed"; };
    return {
        std::string("kernel: ") + (specialized ? "specialized for this scene" : "general"),
        "material models: " + modelList(materialModels),
        std::string("shadow rays: ") + onOff(shadowRays),
        std::string("Beer-Lambert absorption: ") + onOff(absorption),
        std::string("touching probe: ") + onOff(touchingProbe),
        std::string("glass on opaque surfaces: ") + onOff(opaqueContact),
        std::string("coincident opaque surfaces: ") + onOff(coincidentOpaque),
        std::string("overlapping media by priority: ") + onOff(mediumPriorities),
        std::string("dispersion: ") + onOff(dispersion),
        std::string("glass tints: ") + onOff(glassTints),
        std::string("cut-out surfaces: ") + onOff(cutouts),
        std::string("partly covered surfaces: ") + onOff(partialCoverage),
        std::string("transmission textures: ") + onOff(transmissionTextures),
        std::string("instancing: ") + onOff(instancing),
        std::string("textures: ") + onOff(textures),
        "background: " + kindName(backgroundKind, backgroundKindName),
        "fresnel: " + kindName(fresnelModel, fresnelModelName),
        "filter: " + kindName(textureFilter, textureFilterName),
        "medium stack: " + std::to_string(mediumStackDepth) + " media a ray",
        "pending-ray stack: " + std::to_string(pendingRayCapacity) + " rays a pixel",
        std::string("samples: ") + (singleSample ? "one a pixel (no jitter)" : "any (run time)"),
    };
}

nlohmann::json toJson(const TraceSpecialization& s) {
    return {
        {"specialized", s.specialized},
        {"material_models", modelList(s.materialModels)},
        {"shadow_rays", s.shadowRays},
        {"absorption", s.absorption},
        {"touching_probe", s.touchingProbe},
        {"opaque_contact", s.opaqueContact},
        {"coincident_opaque", s.coincidentOpaque},
        {"medium_priorities", s.mediumPriorities},
        {"dispersion", s.dispersion},
        {"glass_tints", s.glassTints},
        {"cutouts", s.cutouts},
        {"partial_coverage", s.partialCoverage},
        {"transmission_textures", s.transmissionTextures},
        {"instancing", s.instancing},
        {"textures", s.textures},
        {"background", kindName(s.backgroundKind, backgroundKindName)},
        {"fresnel", kindName(s.fresnelModel, fresnelModelName)},
        {"filter", kindName(s.textureFilter, textureFilterName)},
        {"medium_stack_depth", s.mediumStackDepth},
        {"pending_ray_capacity", s.pendingRayCapacity},
        {"single_sample", s.singleSample},
    };
}

}  // namespace vitrum
