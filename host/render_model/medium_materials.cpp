#include "render_model/medium_materials.h"

#include <algorithm>
#include <limits>

namespace vitrum {

namespace {

constexpr std::uint32_t kUnset = std::numeric_limits<std::uint32_t>::max();

// Takes triangle t into its object's slot: an object's medium is the material of its first glass
// triangle, else of its first triangle.
void take(const Scene& scene, const Triangle& t, std::vector<std::uint32_t>& slots) {
    if (t.object >= slots.size()) slots.resize(t.object + 1, kUnset);
    std::uint32_t& slot = slots[t.object];
    const bool glass = scene.materials[t.material].model == MaterialModel::Glass;
    if (slot == kUnset || (glass && scene.materials[slot].model != MaterialModel::Glass)) slot = t.material;
}

}  // namespace

std::vector<std::uint32_t> objectMediumMaterials(const Scene& scene) {
    std::vector<std::uint32_t> result(scene.objectNames.size(), kUnset);
    for (std::uint32_t i = 0; i < worldTriangleCount(scene); ++i) take(scene, scene.triangles[i], result);
    // An instance's objects are its mesh's (Scene::Instance): each mesh's are found once.
    std::vector<std::vector<std::uint32_t>> meshes;
    for (const Mesh& mesh : scene.meshes) {
        std::vector<std::uint32_t>& local = meshes.emplace_back(mesh.objects, kUnset);
        for (std::uint32_t i = mesh.first; i < mesh.first + mesh.count; ++i) take(scene, scene.triangles[i], local);
    }
    for (const Instance& instance : scene.instances) {
        const std::vector<std::uint32_t>& local = meshes[instance.mesh];
        if (instance.firstObject + local.size() > result.size()) result.resize(instance.firstObject + local.size(), kUnset);
        std::copy(local.begin(), local.end(), result.begin() + instance.firstObject);
    }
    for (std::uint32_t& slot : result)
        if (slot == kUnset) slot = 0;
    return result;
}

}  // namespace vitrum
