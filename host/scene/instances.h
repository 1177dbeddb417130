// Instancing (issue 50; docs/gpu-design.md, "Instancing"): placing a mesh stored once, and the
// world boxes its copies fill, which the top-level BVH and the scene's analysis use.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vitrum {

// An instance of `mesh` whose objects begin at `firstObject`. Throws std::invalid_argument where
// the transform is singular or not finite.
Instance makeInstance(std::uint32_t mesh, std::uint32_t firstObject, const glm::mat4& objectToWorld);

// Makes the triangles appended to the scene since `firstTriangle` a new mesh, its objects numbered
// from 0, and moves the object names appended since `firstObject` into `objectNames` (each
// instance adds its own); returns the mesh's index. putMeshesLast then puts the world first.
std::uint32_t makeMesh(Scene& scene, std::size_t firstTriangle, std::size_t firstObject,
                       std::vector<std::string>& objectNames);

// Moves every mesh's triangles after the world's (Scene::triangles' order), keeping both orders;
// loaders call it once they have made their meshes.
void putMeshesLast(Scene& scene);

struct FloatBox {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
};

// A mesh's box in its own space, and each mesh's.
FloatBox meshBox(const Scene& scene, const Mesh& mesh);
std::vector<FloatBox> meshBoxes(const Scene& scene);

// The world box of an instance whose mesh lies within the union of `meshParts` (boxes in the
// mesh's space: its box, or boxes of its tree that hold every triangle): each part moved to the
// world in double, their union rounded outwards, so that it holds every triangle of the copy as a
// float transform of the ray finds it. Parts fit a turned copy more tightly than one box does.
FloatBox instanceBox(const Instance& instance, std::span<const FloatBox> meshParts);
inline FloatBox instanceBox(const Instance& instance, const FloatBox& meshBox) {
    return instanceBox(instance, std::span(&meshBox, 1));
}

// The box of everything in the world: the world triangles and every instance's box; min > max
// where the scene is empty.
FloatBox worldBox(const Scene& scene);

// The same scene with every instance's triangles moved to the world, as a loader would place the
// mesh with the instance's transform (each instance's objects its own): what instancing saves,
// and what tests compare an instanced render with.
Scene flattened(const Scene& scene);
// The triangles the scene places in the world: its world's and every copy's (what instancing saves
// storing, and what the analysis compares up to kFlatAnalysisTriangles).
std::uint64_t placedTriangleCount(const Scene& scene);
// The world's triangles, then those of each instance for which keep(instance) is true, moved to
// the world as flattened() moves them.
std::vector<Triangle> placedTriangles(const Scene& scene, const std::function<bool(const Instance&)>& keep);

}  // namespace vitrum
