// The benchmarks' generated mesh: a bumpy height field of any size, with geometric normals.
#pragma once

#include <cmath>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vitrum::bench {

// A height field of n x n quads (2 n^2 triangles) with bumps at several scales: a mesh whose
// triangles are all different, like a scanned surface.
inline std::vector<Triangle> terrain(int n) {
    auto height = [](float x, float y) {
        return 0.3f * std::sin(3.1f * x) * std::cos(2.3f * y) + 0.05f * std::sin(41.0f * x + 17.0f * y);
    };
    std::vector<Triangle> triangles;
    triangles.reserve(std::size_t(2) * n * n);
    auto vertex = [&](int i, int j) {
        const float x = float(i) / float(n) * 4.0f - 2.0f, y = float(j) / float(n) * 4.0f - 2.0f;
        return glm::vec3(x, y, height(x, y));
    };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const glm::vec3 a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1), d = vertex(i, j + 1);
            for (const auto& [p, q, r] : {std::tuple{a, b, c}, std::tuple{a, c, d}}) {
                Triangle t;
                t.position[0] = p;
                t.position[1] = q;
                t.position[2] = r;
                const glm::vec3 n = glm::normalize(glm::cross(q - p, r - p));
                t.normal[0] = t.normal[1] = t.normal[2] = n;
                triangles.push_back(t);
            }
        }
    return triangles;
}

}  // namespace vitrum::bench
