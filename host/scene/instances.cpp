#include "scene/instances.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/gtc/matrix_access.hpp>

namespace vitrum {

Instance makeInstance(std::uint32_t mesh, std::uint32_t firstObject, const glm::mat4& objectToWorld) {
    const glm::dmat4 m(objectToWorld);
    const double det = glm::determinant(glm::dmat3(m));
    if (!(std::isfinite(det) && det != 0.0))
        throw std::invalid_argument("an instance's transform must be finite and invertible");
    const glm::dmat4 inverse = glm::inverse(m);
    Instance instance{mesh, firstObject, objectToWorld, glm::mat4(inverse)};
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r)
            if (!std::isfinite(instance.worldToObject[c][r]))
                throw std::invalid_argument("an instance's transform must be finite and invertible");
    // The bottom row stays exactly (0, 0, 0, 1): both backends read the top three rows only.
    instance.worldToObject = glm::row(instance.worldToObject, 3, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    return instance;
}

std::uint32_t makeMesh(Scene& scene, std::size_t firstTriangle, std::size_t firstObject,
                       std::vector<std::string>& objectNames) {
    Mesh mesh{std::uint32_t(firstTriangle), std::uint32_t(scene.triangles.size() - firstTriangle),
              std::uint32_t(scene.objectNames.size() - firstObject)};
    for (std::size_t i = firstTriangle; i < scene.triangles.size(); ++i)
        scene.triangles[i].object -= std::uint32_t(firstObject);
    objectNames.assign(scene.objectNames.begin() + std::ptrdiff_t(firstObject), scene.objectNames.end());
    scene.objectNames.resize(firstObject);
    scene.meshes.push_back(mesh);
    return std::uint32_t(scene.meshes.size() - 1);
}

void putMeshesLast(Scene& scene) {
    std::vector<bool> inMesh(scene.triangles.size(), false);
    for (const Mesh& mesh : scene.meshes) std::fill_n(inMesh.begin() + mesh.first, mesh.count, true);
    const std::size_t world = std::size_t(std::count(inMesh.begin(), inMesh.end(), false));
    bool last = true;
    std::uint32_t next = std::uint32_t(world);
    for (const Mesh& mesh : scene.meshes) {
        last = last && mesh.first == next;
        next += mesh.count;
    }
    if (last) return;
    std::vector<Triangle> ordered;
    ordered.reserve(scene.triangles.size());
    for (std::size_t i = 0; i < scene.triangles.size(); ++i)
        if (!inMesh[i]) ordered.push_back(scene.triangles[i]);
    for (Mesh& mesh : scene.meshes) {
        const std::uint32_t first = std::uint32_t(ordered.size());
        ordered.insert(ordered.end(), scene.triangles.begin() + mesh.first, scene.triangles.begin() + mesh.first + mesh.count);
        mesh.first = first;
    }
    scene.triangles = std::move(ordered);
}

FloatBox meshBox(const Scene& scene, const Mesh& mesh) {
    FloatBox box{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest())};
    for (std::uint32_t i = mesh.first; i < mesh.first + mesh.count; ++i)
        for (const glm::vec3& p : scene.triangles[i].position) {
            box.min = glm::min(box.min, p);
            box.max = glm::max(box.max, p);
        }
    return box;
}

std::vector<FloatBox> meshBoxes(const Scene& scene) {
    std::vector<FloatBox> boxes;
    for (const Mesh& mesh : scene.meshes) boxes.push_back(meshBox(scene, mesh));
    return boxes;
}

FloatBox instanceBox(const Instance& instance, std::span<const FloatBox> meshParts) {
    const glm::dmat4 m(instance.objectToWorld);
    glm::dmat3 extentMatrix(m);  // a box's half extent moves through |M|
    for (int c = 0; c < 3; ++c) extentMatrix[c] = glm::abs(extentMatrix[c]);
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
    for (const FloatBox& part : meshParts) {
        const glm::dvec3 centre = 0.5 * (glm::dvec3(part.min) + glm::dvec3(part.max));
        const glm::dvec3 halfExtent = 0.5 * (glm::dvec3(part.max) - glm::dvec3(part.min));
        const glm::dvec3 movedCentre = glm::dvec3(m * glm::dvec4(centre, 1.0));
        const glm::dvec3 movedExtent = extentMatrix * halfExtent;
        lo = glm::min(lo, movedCentre - movedExtent);
        hi = glm::max(hi, movedCentre + movedExtent);
    }
    // The ray reaches the mesh through a float transform whose rounding moves its hits by a few
    // ulps of the box's largest coordinate (docs/gpu-design.md, "Instancing"): the box is grown by
    // 2^-18 of it, far beyond that.
    const double reach = std::ldexp(std::max(glm::length(lo), glm::length(hi)), -18);
    FloatBox box;
    for (int a = 0; a < 3; ++a) {
        box.min[a] = std::nextafter(float(lo[a] - reach), -std::numeric_limits<float>::infinity());
        box.max[a] = std::nextafter(float(hi[a] + reach), std::numeric_limits<float>::infinity());
    }
    return box;
}

FloatBox worldBox(const Scene& scene) {
    FloatBox box{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest())};
    for (std::uint32_t i = 0; i < worldTriangleCount(scene); ++i)
        for (const glm::vec3& p : scene.triangles[i].position) {
            box.min = glm::min(box.min, p);
            box.max = glm::max(box.max, p);
        }
    const std::vector<FloatBox> meshes = meshBoxes(scene);
    for (const Instance& instance : scene.instances) {
        const FloatBox b = instanceBox(instance, meshes[instance.mesh]);
        box.min = glm::min(box.min, b.min);
        box.max = glm::max(box.max, b.max);
    }
    return box;
}

Scene flattened(const Scene& scene) {
    Scene flat = scene;
    flat.triangles = placedTriangles(scene, [](const Instance&) { return true; });
    flat.meshes.clear();
    flat.instances.clear();
    return flat;
}

std::uint64_t placedTriangleCount(const Scene& scene) {
    std::uint64_t placed = worldTriangleCount(scene);
    for (const Instance& instance : scene.instances) placed += scene.meshes[instance.mesh].count;
    return placed;
}

std::vector<Triangle> placedTriangles(const Scene& scene, const std::function<bool(const Instance&)>& keep) {
    std::vector<Triangle> placed(scene.triangles.begin(), scene.triangles.begin() + worldTriangleCount(scene));
    for (const Instance& instance : scene.instances) {
        if (!keep(instance)) continue;
        const Mesh& mesh = scene.meshes[instance.mesh];
        const glm::mat4& m = instance.objectToWorld;
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
        const bool mirrored = glm::determinant(glm::mat3(m)) < 0.0f;  // keep the winding outward-facing
        for (std::uint32_t i = mesh.first; i < mesh.first + mesh.count; ++i) {
            const Triangle& t = scene.triangles[i];
            Triangle w = t;
            w.object = instance.firstObject + t.object;
            for (int k = 0; k < 3; ++k) {
                const int from = mirrored && k > 0 ? 3 - k : k;
                w.position[k] = glm::vec3(m * glm::vec4(t.position[from], 1.0f));
                w.normal[k] = glm::normalize(normalMatrix * t.normal[from]);
                w.uv[k] = t.uv[from];
            }
            placed.push_back(w);
        }
    }
    return placed;
}

}  // namespace vitrum
