#include "render/scene_features.h"

#include <set>

namespace vitrum {

SceneFeatures analyseScene(const Scene& scene) {
    SceneFeatures f;
    std::set<std::uint32_t> used;
    for (const Triangle& t : scene.triangles) used.insert(t.material);
    std::set<std::uint32_t> glassObjects;
    for (const Triangle& t : scene.triangles)
        if (scene.materials[t.material].model == MaterialModel::Glass) glassObjects.insert(t.object);
    for (std::uint32_t index : used) {
        const Material& m = scene.materials[index];
        switch (m.model) {
            case MaterialModel::Glass:
                f.glass = f.reflection = true;
                if (m.attenuation != glm::vec3(0.0f)) f.absorbingMedia = true;
                break;
            case MaterialModel::Mirror: f.reflection = true; break;
            case MaterialModel::Phong: f.reflection = true; [[fallthrough]];
            case MaterialModel::Lambert:
                if (!scene.lights.empty()) f.shadowRays = true;
                if (m.diffuseTexture >= 0) f.textures = true;
                break;
            case MaterialModel::Normal: break;
        }
    }
    f.glassObjects = std::uint32_t(glassObjects.size());
    f.touchingMediaPossible = f.glassObjects >= 2;
    f.background = scene.background.kind;
    f.usefulDepth = f.reflection ? scene.settings.maxDepth : std::min<std::uint32_t>(1, scene.settings.maxDepth);
    return f;
}

std::vector<std::string> SceneFeatures::describe() const {
    auto yesNo = [](bool b) { return b ? "yes" : "no"; };
    const char* backgrounds[] = {"constant", "spherical map", "cube map"};
    return {
        std::string("glass (refraction, medium stack): ") + yesNo(glass) + ", " + std::to_string(glassObjects) +
            " objects",
        std::string("absorbing media (Beer-Lambert): ") + yesNo(absorbingMedia),
        std::string("touching or nested media possible: ") + yesNo(touchingMediaPossible),
        std::string("reflected rays: ") + yesNo(reflection),
        std::string("shadow rays: ") + yesNo(shadowRays),
        std::string("textures: ") + yesNo(textures),
        std::string("background: ") + backgrounds[int(background)],
        "useful ray-tree depth: " + std::to_string(usefulDepth),
    };
}

}  // namespace vitrum
