#include "gpu_input/packed_scene.h"

#include "common/parallel.h"
#include "render_model/medium_materials.h"

#include <bit>
#include <algorithm>
#include <cmath>

namespace vitrum {
static_assert(std::uint32_t(BackgroundKind::Constant) == gpu::kBackgroundConstant &&
              std::uint32_t(BackgroundKind::Spherical) == gpu::kBackgroundSpherical &&
              std::uint32_t(BackgroundKind::Cube) == gpu::kBackgroundCube);
static_assert(std::uint32_t(TextureFilter::Bilinear) == gpu::kFilterBilinear &&
              std::uint32_t(TextureFilter::Nearest) == gpu::kFilterNearest);

namespace {
float bits(std::uint32_t value) { return std::bit_cast<float>(value); }
}  // namespace

void packVertices(const Scene& scene, const Bvh& bvh, std::span<gpu::TriangleVertices> into) {
    parallelFor(into.size(), [&](std::size_t begin, std::size_t end) {
        packTriangleVertices(bvh, scene.triangles, into.subspan(begin, end - begin), begin);
        for (std::size_t i = begin; i < end; ++i) {
            const Triangle& t = scene.triangles[bvh.triangleOrder[i]];
            into[i].v2.w = bits(traversalMark(scene.materials[t.material]));
        }
    });
}

// The kernel reads a material's model as the MaterialModel it is (gpu_types.h, "Materials").
static_assert(std::uint32_t(MaterialModel::Normal) == gpu::kMaterialNormal &&
              std::uint32_t(MaterialModel::Lambert) == gpu::kMaterialLambert &&
              std::uint32_t(MaterialModel::Phong) == gpu::kMaterialPhong &&
              std::uint32_t(MaterialModel::Glass) == gpu::kMaterialGlass &&
              std::uint32_t(MaterialModel::Mirror) == gpu::kMaterialMirror &&
              std::uint32_t(MaterialModel::ThinGlass) == gpu::kMaterialThinGlass);

PackedTables packTables(const Scene& scene) {
    PackedTables packed;
    for (const Material& m : scene.materials) {
        std::uint32_t texture = m.diffuseTexture >= 0 ? std::uint32_t(m.diffuseTexture) : gpu::kNoTexture;
        std::uint32_t coverage = hasPartialCoverage(m) ? std::uint32_t(m.coverage) : gpu::kNoTexture;
        const bool switches = hasTransmissionTexture(m);
        std::uint32_t transmission = switches ? std::uint32_t(m.transmissionTexture) : gpu::kNoTexture;
        std::uint32_t opaquePart = switches ? std::uint32_t(m.opaquePart) : 0u;
        packed.materials.push_back({
            .ambient = glm::vec4(m.ambient, bits(std::uint32_t(m.model))),
            .diffuse = glm::vec4(m.diffuse, bits(texture)),
            .specular = glm::vec4(m.specular, m.shininess),
            .attenuation = glm::vec4(m.attenuation, m.ior),
            .parts = glm::vec4(bits(coverage), bits(transmission), bits(opaquePart), 0.0f),
        });
    }
    // The kernel reads material 0 for lanes that are not at a hit (one fetch a round for all
    // lanes, shaders/trace.comp), so there is always one.
    if (packed.materials.empty()) packed.materials.push_back({});
    for (const PointLight& light : scene.lights)
        packed.lights.push_back({glm::vec4(light.position, light.inverseSquare ? 1.0f : 0.0f), glm::vec4(light.colour, 0.0f)});
    for (const Texture& texture : scene.textures) {
        packed.textures.push_back({glm::uvec4(packed.texels.size(), texture.width, texture.height, 0)});
        for (const glm::vec3& texel : texture.texels) packed.texels.push_back(glm::vec4(texel, 0.0f));
    }
    packed.objectMaterials = objectMediumMaterials(scene);
    for (std::uint32_t material : packed.objectMaterials) {
        const Material* m = material < scene.materials.size() ? &scene.materials[material] : nullptr;
        packed.objectPriorities.push_back(m ? m->priority : 0);
        // As the CPU reference takes it (cpu/reference_renderer.cpp): glass media only.
        packed.objectDispersions.push_back(m && m->model == MaterialModel::Glass ? float(cauchyB(m->ior, m->abbe)) : 0.0f);
        packed.objectTints.push_back(m && m->model == MaterialModel::Glass ? m->tint : glm::vec3(1.0f));
    }
    if (std::any_of(packed.objectDispersions.begin(), packed.objectDispersions.end(), [](float b) { return b != 0.0f; }))
        packed.wavelengths = wavelengthSamples(scene.settings.wavelengths);
    return packed;
}

PackedScene packScene(const Scene& scene, const Bvh& bvh) {
    PackedScene packed{makeTraversalNodes(bvh.nodes, bvh.instances), {}, {}, packTables(scene)};
    packed.vertices.resize(bvh.triangleOrder.size());
    packVertices(scene, bvh, packed.vertices);
    const ShadingPlan plan = planShading(scene, bvh);
    packed.shading.resize(plan.texels());
    writeShading(scene, bvh, plan, packed.shading);
    return packed;
}

}  // namespace vitrum
