#include "render/packed_scene.h"

#include "cpu/ray_offset.h"
#include "render/medium_materials.h"
#include "render/sampling.h"

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

PackedScene packScene(const Scene& scene, const Bvh& bvh) {
    PackedScene packed;
    packed.bvh = makeTraversalNodes(bvh.nodes);
    packed.vertices = packTriangleVertices(bvh, scene.triangles);
    for (std::size_t i = 0; i < packed.vertices.size(); ++i) {
        const Triangle& t = scene.triangles[bvh.triangleOrder[i]];
        if (scene.materials[t.material].model == MaterialModel::Glass) packed.vertices[i].v2.w = bits(gpu::kTriangleGlass);
    }
    packed.shading.reserve(bvh.triangleOrder.size());
    for (std::uint32_t index : bvh.triangleOrder) {
        const Triangle& t = scene.triangles[index];
        packed.shading.push_back({
            .n0 = glm::vec4(t.normal[0], 0.0f),
            .n1 = glm::vec4(t.normal[1], 0.0f),
            .n2 = glm::vec4(t.normal[2], 0.0f),
            .uv01 = glm::vec4(t.uv[0], t.uv[1]),
            .uv2 = glm::vec4(t.uv[2], 0.0f, 0.0f),
        });
    }
    for (const Material& m : scene.materials) {
        std::uint32_t texture = m.diffuseTexture >= 0 ? std::uint32_t(m.diffuseTexture) : gpu::kNoTexture;
        packed.materials.push_back({
            .ambient = glm::vec4(m.ambient, bits(std::uint32_t(m.model))),
            .diffuse = glm::vec4(m.diffuse, bits(texture)),
            .specular = glm::vec4(m.specular, m.shininess),
            .attenuation = glm::vec4(m.attenuation, m.ior),
        });
    }
    // The kernel reads material 0 for lanes that are not at a hit (one fetch a round for all
    // lanes, shaders/trace.comp), so there is always one.
    if (packed.materials.empty()) packed.materials.push_back({});
    for (const PointLight& light : scene.lights)
        packed.lights.push_back({glm::vec4(light.position, light.inverseSquare ? 1.0f : 0.0f), glm::vec4(light.colour, 0.0f)});
    for (const Texture& texture : scene.textures) {
        packed.textures.push_back({glm::uvec4(packed.texels.size() / 3, texture.width, texture.height, 0)});
        for (const glm::vec3& texel : texture.texels) packed.texels.insert(packed.texels.end(), {texel.x, texel.y, texel.z});
    }
    packed.objectMaterials = objectMediumMaterials(scene);
    return packed;
}

gpu::RenderParams makeRenderParams(const Scene& scene, std::uint32_t rootEntry) {
    const Camera& camera = scene.camera;
    glm::vec3 z = glm::normalize(camera.from - camera.at);
    glm::vec3 x = glm::normalize(glm::cross(camera.up, z));
    glm::vec3 y = glm::cross(z, x);
    float focal = float(camera.height) / (2.0f * std::tan(glm::radians(camera.fovY) / 2.0f));
    const RenderSettings& s = scene.settings;
    gpu::RenderParams p{};
    p.cameraFrom = glm::vec4(camera.from, focal);
    p.cameraX = glm::vec4(x, 0.0f);
    p.cameraY = glm::vec4(y, 0.0f);
    p.cameraZ = glm::vec4(z, 0.0f);
    p.background = glm::vec4(scene.background.colour, scene.airIor);
    p.image = glm::uvec4(camera.width, camera.height, s.samplesPerPixel, s.maxDepth);
    p.counts = glm::uvec4(scene.lights.size(), std::uint32_t(s.fresnel), scene.textures.size(), 0);
    p.pass = glm::uvec4(0, stratifiedColumns(s.samplesPerPixel), 0, 0);
    p.tuning = glm::vec4(s.minWeight, 0.0f, 0.0f, 0.0f);
    p.environment = glm::uvec4(std::uint32_t(scene.background.kind), std::uint32_t(s.filter),
                               std::uint32_t(std::max(scene.background.map, 0)), 0);
    const RayOffsetScale offsets = rayOffsetScale(scene.triangles);  // Waechter and Binder's, scaled to the scene
    p.offsets = glm::vec4(offsets.origin, offsets.absolute, 0.0f, 0.0f);
    p.bvh = glm::uvec4(rootEntry, 0, 0, 0);
    return p;
}

}  // namespace vitrum
