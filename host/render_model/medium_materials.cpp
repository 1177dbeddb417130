#include "render_model/medium_materials.h"

#include <algorithm>
#include <limits>

namespace vitrum {

std::vector<std::uint32_t> objectMediumMaterials(const Scene& scene) {
    constexpr std::uint32_t kUnset = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> result(scene.objectNames.size(), kUnset);
    auto take = [&](const Triangle& t, std::uint32_t object) {
        if (object >= result.size()) result.resize(object + 1, kUnset);
        std::uint32_t& slot = result[object];
        const bool glass = scene.materials[t.material].model == MaterialModel::Glass;
        if (slot == kUnset || (glass && scene.materials[slot].model != MaterialModel::Glass)) slot = t.material;
    };
    for (std::uint32_t i = 0; i < worldTriangleCount(scene); ++i) take(scene.triangles[i], scene.triangles[i].object);
    // An instance's objects are its mesh's (Scene::Instance): each mesh's objects are found once.
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        std::vector<std::uint32_t> local(mesh.objects, kUnset);
        std::swap(result, local);
        for (std::uint32_t i = mesh.first; i < mesh.first + mesh.count; ++i) take(scene.triangles[i], scene.triangles[i].object);
        std::swap(result, local);
        for (const Instance& instance : scene.instances) {
            if (instance.mesh != m) continue;
            if (instance.firstObject + mesh.objects > result.size()) result.resize(instance.firstObject + mesh.objects, kUnset);
            std::copy(local.begin(), local.begin() + mesh.objects, result.begin() + instance.firstObject);
        }
    }
    for (std::uint32_t& slot : result)
        if (slot == kUnset) slot = 0;
    return result;
}

}  // namespace vitrum
