// A scene with instances built in code (issue 50; docs/gpu-design.md, "Instancing"): a Lambert
// floor in the world, and two meshes placed twice each: an absorbing glass box, once moved and
// once turned and stretched, and a chiral glass tetrahedron (its edges all of different lengths),
// once moved and once mirrored, so that a mirroring instance's winding matters.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/instances.h"
#include "scene/scene.h"
#include "scenes_in_code.h"

namespace vitrum::testing {

// Appends `triangles` (objects numbered from 0) as a mesh; returns its index.
inline std::uint32_t addMesh(Scene& scene, const std::vector<Triangle>& triangles, const std::string& name) {
    const std::size_t first = scene.triangles.size(), firstObject = scene.objectNames.size();
    scene.objectNames.push_back(name);
    for (Triangle t : triangles) {
        t.object = std::uint32_t(firstObject);
        scene.triangles.push_back(t);
    }
    std::vector<std::string> names;
    return makeMesh(scene, first, firstObject, names);
}

inline void place(Scene& scene, std::uint32_t mesh, const glm::mat4& objectToWorld, const std::string& name) {
    scene.instances.push_back(makeInstance(mesh, std::uint32_t(scene.objectNames.size()), objectToWorld));
    scene.objectNames.push_back(name);
}

// A closed tetrahedron, outward wound, with six edges of different lengths.
inline std::vector<Triangle> chiralTetrahedron(std::uint32_t material) {
    const glm::vec3 p[4] = {{0.0f, 0.0f, 0.0f}, {0.9f, 0.0f, 0.0f}, {0.2f, 0.7f, 0.0f}, {0.3f, 0.25f, 0.8f}};
    const glm::vec3 centre = (p[0] + p[1] + p[2] + p[3]) / 4.0f;
    std::vector<Triangle> triangles;
    const int faces[4][3] = {{0, 1, 2}, {0, 1, 3}, {1, 2, 3}, {0, 2, 3}};
    for (const auto& f : faces) {
        glm::vec3 a = p[f[0]], b = p[f[1]], c = p[f[2]];
        if (glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - centre) < 0.0f) std::swap(b, c);
        triangles.push_back(makeTriangle(a, b, c, material, 0));
    }
    return triangles;
}

// Width x height pixels; the camera above and in front, the light high on the left.
inline Scene instancedScene(std::uint32_t width = 64, std::uint32_t height = 48) {
    Scene scene;
    scene.camera = {.from = {0.5f, -6.0f, 3.0f}, .at = {0.2f, 0.0f, 0.4f}, .up = {0, 0, 1}, .fovY = 40.0f,
                    .width = width, .height = height};
    scene.background.colour = glm::vec3(0.3f, 0.5f, 0.8f);
    scene.lights.push_back({.position = {-3, -4, 6}, .colour = glm::vec3(0.9f)});
    scene.settings.fresnel = FresnelModel::Exact;
    scene.materials.push_back(makeMaterial(MaterialModel::Lambert, glm::vec3(0.1f), glm::vec3(0.7f, 0.6f, 0.5f)));
    Material glass = makeMaterial(MaterialModel::Glass, glm::vec3(0.0f), glm::vec3(0.0f));
    glass.attenuation = glm::vec3(0.1f, 0.3f, 0.6f);
    scene.materials.push_back(glass);
    scene.objectNames.push_back("floor");
    addBox(scene, {-4, -4, -0.2f}, {4, 4, 0}, 0, 0);

    Scene box;  // the mesh's triangles, in its own space
    addBox(box, {-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}, 1, 0);
    const std::uint32_t boxMesh = addMesh(scene, box.triangles, "box");
    const std::uint32_t tetraMesh = addMesh(scene, chiralTetrahedron(1), "tetrahedron");
    const glm::mat4 identity(1.0f);
    place(scene, boxMesh, glm::translate(identity, {-1.2f, 0.3f, 0.5f}), "box moved");
    place(scene, boxMesh,
          glm::scale(glm::rotate(glm::translate(identity, {0.4f, 1.2f, 0.6f}), glm::radians(30.0f), {0, 0, 1}),
                     {0.6f, 1.2f, 1.2f}),
          "box turned and stretched");
    place(scene, tetraMesh, glm::translate(identity, {1.1f, -0.6f, 0.0f}), "tetrahedron moved");
    place(scene, tetraMesh, glm::scale(glm::translate(identity, {0.2f, -1.3f, 0.0f}), {-1.0f, 1.0f, 1.0f}),
          "tetrahedron mirrored");
    return scene;
}

// Every position of an instanced scene (world triangles, instances, camera, lights) times
// `scale` plus `shift`, absorption scaled by 1 / scale: the same image.
inline Scene movedInstancedScene(Scene scene, float scale, glm::vec3 shift) {
    for (std::uint32_t i = 0; i < worldTriangleCount(scene); ++i)
        for (glm::vec3& p : scene.triangles[i].position) p = p * scale + shift;
    const glm::mat4 move = glm::scale(glm::translate(glm::mat4(1.0f), shift), glm::vec3(scale));
    for (Instance& instance : scene.instances)
        instance = makeInstance(instance.mesh, instance.firstObject, move * instance.objectToWorld);
    scene.camera.from = scene.camera.from * scale + shift;
    scene.camera.at = scene.camera.at * scale + shift;
    for (PointLight& l : scene.lights) l.position = l.position * scale + shift;
    for (Material& m : scene.materials) m.attenuation /= scale;
    return scene;
}

}  // namespace vitrum::testing
