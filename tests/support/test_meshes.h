// Closed meshes built in code for tests: indexed, so shared vertices have bit-identical positions
// in every triangle that uses them, as in a mesh loaded from an OBJ file.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace vitrum::testing {

struct IndexedMesh {
    std::vector<glm::vec3> vertices;
    std::vector<glm::vec3> directions;  // each vertex's unit direction from the centre (smooth normals)
    std::vector<glm::uvec3> faces;      // outward wound (counter-clockwise seen from outside)
};

// Icosahedron subdivided `levels` times (20 * 4^levels triangles), on the unit sphere (positions
// computed in double and rounded once), scaled by `radius` and moved to `centre` in float.
inline IndexedMesh icosphere(int levels, float radius = 1.0f, glm::vec3 centre = glm::vec3(0.0f)) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<glm::dvec3> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    for (glm::dvec3& p : v) p = glm::normalize(p);
    std::vector<glm::uvec3> f = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                 {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<unsigned, unsigned>, unsigned> midpoints;
        auto midpoint = [&](unsigned a, unsigned b) {
            auto [it, inserted] = midpoints.try_emplace(std::minmax(a, b), unsigned(v.size()));
            if (inserted) v.push_back(glm::normalize(v[a] + v[b]));
            return it->second;
        };
        std::vector<glm::uvec3> next;
        for (const glm::uvec3& tri : f) {
            const unsigned ab = midpoint(tri.x, tri.y), bc = midpoint(tri.y, tri.z), ca = midpoint(tri.z, tri.x);
            next.insert(next.end(), {{tri.x, ab, ca}, {tri.y, bc, ab}, {tri.z, ca, bc}, {ab, bc, ca}});
        }
        f = std::move(next);
    }
    IndexedMesh mesh;
    for (const glm::dvec3& p : v) {
        mesh.vertices.push_back(glm::vec3(p) * radius + centre);
        mesh.directions.push_back(glm::vec3(p));
    }
    mesh.faces = std::move(f);
    return mesh;
}

}  // namespace vitrum::testing
