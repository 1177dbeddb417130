#include "gpu_input/shading_texels.h"

#include <array>
#include <atomic>
#include <bit>

#include "common/parallel.h"

namespace vitrum {
namespace {

glm::uvec3 bitsOf(const glm::vec3& v) {
    return {std::bit_cast<std::uint32_t>(v.x), std::bit_cast<std::uint32_t>(v.y), std::bit_cast<std::uint32_t>(v.z)};
}

// Distinct normals by their exact bits: an open-addressing table of indices into `normals`
// (linear probing, kept at most half full).
class NormalIndex {
public:
    explicit NormalIndex(std::vector<glm::vec3>& normals) : normals_(normals), slots_(1024, kEmpty) {
        recent_.fill(kEmpty);
    }

    std::uint32_t operator()(const glm::vec3& normal) {
        const glm::uvec3 key = bitsOf(normal);
        const std::size_t h = hash(key);
        // Triangles near each other in a mesh share normals: a small table of recent ones
        // answers most lookups without touching the big one (a 20M-triangle smooth mesh's 60M
        // corners took 5 s without it).
        std::uint32_t& recent = recent_[h % kRecent];
        if (recent != kEmpty && bitsOf(normals_[recent]) == key) return recent;
        for (std::size_t slot = h & (slots_.size() - 1);; slot = (slot + 1) & (slots_.size() - 1)) {
            const std::uint32_t index = slots_[slot];
            if (index == kEmpty) {
                slots_[slot] = std::uint32_t(normals_.size());
                normals_.push_back(normal);
                if (2 * normals_.size() > slots_.size()) grow();
                return recent = std::uint32_t(normals_.size() - 1);
            }
            if (bitsOf(normals_[index]) == key) return recent = index;
        }
    }

private:
    static constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;
    static constexpr std::size_t kRecent = 4093;  // a prime: the hash's low bits also pick the slot

    static std::size_t hash(const glm::uvec3& key) {
        std::uint64_t h = key.x * 0x9E3779B97F4A7C15ull;
        h = (h ^ key.y) * 0xC2B2AE3D27D4EB4Full;
        h = (h ^ key.z) * 0x165667B19E3779F9ull;
        return std::size_t(h ^ (h >> 29));
    }

    void grow() {
        std::vector<std::uint32_t> slots(2 * slots_.size(), kEmpty);
        for (std::uint32_t index = 0; index < normals_.size(); ++index) {
            std::size_t slot = hash(bitsOf(normals_[index])) & (slots.size() - 1);
            while (slots[slot] != kEmpty) slot = (slot + 1) & (slots.size() - 1);
            slots[slot] = index;
        }
        slots_ = std::move(slots);
    }

    std::vector<glm::vec3>& normals_;
    std::vector<std::uint32_t> slots_;
    std::array<std::uint32_t, kRecent> recent_;
};

// Whether texture lookups read the triangle's uvs: its material's map_Kd, its cut-outs in the
// traversal, its partial coverage, or its transmission texture and its opaque part's map_Kd.
bool textured(const Scene& scene, const Triangle& t) {
    const Material& m = scene.materials[t.material];
    return m.diffuseTexture >= 0 || hasCutouts(m) || hasPartialCoverage(m) || hasTransmissionTexture(m);
}

}  // namespace

bool isFlat(const Triangle& t) {
    return bitsOf(t.normal[0]) == bitsOf(t.normal[1]) && bitsOf(t.normal[0]) == bitsOf(t.normal[2]);
}

ShadingPlan planShading(const Scene& scene, const Bvh& bvh) {
    ShadingPlan plan;
    plan.triangles = bvh.triangleOrder.size();
    std::atomic<bool> anyIndexed = false, anyTextured = false;
    parallelFor(plan.triangles, [&](std::size_t begin, std::size_t end) {
        bool indexed = false, withTexture = false;
        for (std::size_t i = begin; i < end && !(indexed && withTexture); ++i) {
            const Triangle& t = scene.triangles[i];
            withTexture = withTexture || textured(scene, t);
            indexed = indexed || withTexture || !isFlat(t);
        }
        if (indexed) anyIndexed = true;
        if (withTexture) anyTextured = true;
    });
    if (!anyIndexed) return plan;
    // In the scene's order, which reads the triangles in the order they lie in memory and meets a
    // mesh's shared normals close together.
    plan.cornerNormals.assign(3 * plan.triangles, 0u);
    if (anyTextured) plan.uvTexels.assign(plan.triangles, gpu::kNoCornerUvs);
    NormalIndex index(plan.normals);
    for (std::size_t i = 0; i < plan.triangles; ++i) {
        const Triangle& t = scene.triangles[i];
        const bool withTexture = textured(scene, t);
        if (!withTexture && isFlat(t)) continue;
        for (int corner = 0; corner < 3; ++corner) plan.cornerNormals[3 * i + corner] = index(t.normal[corner]);
        if (withTexture) plan.uvTexels[i] = std::uint32_t(plan.texturedTriangles++);
    }
    // The uv texels follow the normals': their indices become texels.
    const std::uint32_t uvBase = std::uint32_t(plan.triangles + plan.normals.size());
    for (std::uint32_t& first : plan.uvTexels)
        if (first != gpu::kNoCornerUvs) first = uvBase + gpu::kCornerUvsTexels * first;
    return plan;
}

void writeShading(const Scene& scene, const Bvh& bvh, const ShadingPlan& plan, std::span<gpu::ShadingTexel> into) {
    const std::uint32_t normalBase = std::uint32_t(plan.triangles);
    parallelFor(plan.triangles, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const std::size_t j = bvh.triangleOrder[i];  // the plan's index: the scene's order
            const Triangle& t = scene.triangles[j];
            const std::uint32_t uvs = plan.uvTexels.empty() ? gpu::kNoCornerUvs : plan.uvTexels[j];
            if (uvs == gpu::kNoCornerUvs && isFlat(t)) {
                into[i].bits = glm::uvec4(bitsOf(t.normal[0]), gpu::kFlatTriangle);
                continue;
            }
            into[i].bits = glm::uvec4(normalBase + plan.cornerNormals[3 * j], normalBase + plan.cornerNormals[3 * j + 1],
                                      normalBase + plan.cornerNormals[3 * j + 2], uvs);
            if (uvs != gpu::kNoCornerUvs) {
                const auto texel = [](float a, float b, float c, float d) {
                    return gpu::ShadingTexel{glm::uvec4(std::bit_cast<std::uint32_t>(a), std::bit_cast<std::uint32_t>(b),
                                                        std::bit_cast<std::uint32_t>(c), std::bit_cast<std::uint32_t>(d))};
                };
                into[uvs] = texel(t.uv[0].x, t.uv[0].y, t.uv[1].x, t.uv[1].y);
                into[uvs + 1] = texel(t.uv[2].x, t.uv[2].y, 0.0f, 0.0f);
            }
        }
    });
    for (std::size_t k = 0; k < plan.normals.size(); ++k)
        into[normalBase + k].bits = glm::uvec4(bitsOf(plan.normals[k]), 0u);
}

}  // namespace vitrum
