// Glass scenes built in code for the tests of the scene's analysis: closed, outward-wound boxes
// and flat grids of triangles, each a glass object of its own.
#pragma once

#include <string>

#include "scene/scene.h"

namespace vitrum {

// A closed, outward-wound glass box lo..hi as a new object.
inline void addGlassBox(Scene& scene, glm::vec3 lo, glm::vec3 hi) {
    const std::uint32_t object = std::uint32_t(scene.objectNames.size());
    scene.objectNames.push_back("box " + std::to_string(object));
    auto corner = [&](int i, int j, int k) { return glm::vec3(i ? hi.x : lo.x, j ? hi.y : lo.y, k ? hi.z : lo.z); };
    const int faces[6][4][3] = {{{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}},
                                {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},
                                {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
    for (const auto& f : faces) {
        glm::vec3 q[4];
        for (int v = 0; v < 4; ++v) q[v] = corner(f[v][0], f[v][1], f[v][2]);
        for (const auto& [b, c] : {std::pair{1, 2}, std::pair{2, 3}}) {
            Triangle t;
            t.position[0] = q[0];
            t.position[1] = q[b];
            t.position[2] = q[c];
            t.object = object;
            scene.triangles.push_back(t);
        }
    }
}

// A flat glass sheet of n x n squares, two triangles each, over [0, size]^2 in the plane z = height,
// as a new object (open: the analysis of touching surfaces does not need closed meshes).
inline void addGlassSheet(Scene& scene, int n, float size, float height) {
    const std::uint32_t object = std::uint32_t(scene.objectNames.size());
    scene.objectNames.push_back("sheet " + std::to_string(object));
    const float step = size / float(n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const glm::vec3 a(i * step, j * step, height), b((i + 1) * step, j * step, height),
                c((i + 1) * step, (j + 1) * step, height), d(i * step, (j + 1) * step, height);
            for (const auto& [p, q] : {std::pair{b, c}, std::pair{c, d}}) {
                Triangle t;
                t.position[0] = a;
                t.position[1] = p;
                t.position[2] = q;
                t.object = object;
                scene.triangles.push_back(t);
            }
        }
}

inline Scene glassScene() {
    Scene scene;
    Material glass;
    glass.model = MaterialModel::Glass;
    scene.materials.push_back(glass);
    return scene;
}

}  // namespace vitrum
