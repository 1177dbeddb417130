#include "render_model/medium_materials.h"

#include <limits>

namespace vitrum {

std::vector<std::uint32_t> objectMediumMaterials(const Scene& scene) {
    constexpr std::uint32_t kUnset = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> result(scene.objectNames.size(), kUnset);
    for (const Triangle& t : scene.triangles) {
        if (t.object >= result.size()) result.resize(t.object + 1, kUnset);
        std::uint32_t& slot = result[t.object];
        const bool glass = scene.materials[t.material].model == MaterialModel::Glass;
        if (slot == kUnset || (glass && scene.materials[slot].model != MaterialModel::Glass)) slot = t.material;
    }
    for (std::uint32_t& slot : result)
        if (slot == kUnset) slot = 0;
    return result;
}

}  // namespace vitrum
