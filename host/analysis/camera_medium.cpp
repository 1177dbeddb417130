#include "analysis/camera_medium.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <string>

#include "common/error.h"
#include "analysis/double_box.h"
#include "shared/gpu_types.h"

namespace vitrum {

double windingNumber(const std::vector<const Triangle*>& triangles, const glm::dvec3& point) {
    double solidAngle = 0.0;
    for (const Triangle* t : triangles) {
        // Van Oosterom and Strackee (1983): tan(omega / 2) = [a b c] / (|a||b||c| + (a.b)|c| +
        // (a.c)|b| + (b.c)|a|), positive where the triangle turns counterclockwise seen from the point.
        const glm::dvec3 a = glm::dvec3(t->position[0]) - point;
        const glm::dvec3 b = glm::dvec3(t->position[1]) - point;
        const glm::dvec3 c = glm::dvec3(t->position[2]) - point;
        const double la = glm::length(a);
        const double lb = glm::length(b);
        const double lc = glm::length(c);
        const double numerator = glm::dot(a, glm::cross(b, c));
        const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
        solidAngle += 2.0 * std::atan2(numerator, denominator);
    }
    return solidAngle / (4.0 * std::numbers::pi);
}

std::vector<std::uint32_t> cameraMedia(std::span<const Triangle> triangles, const std::vector<Material>& materials,
                                       const std::set<std::uint32_t>& open, const glm::dvec3& point) {
    std::map<std::uint32_t, std::vector<const Triangle*>> glassTriangles;
    for (const Triangle& t : triangles)
        if (materials[t.material].model == MaterialModel::Glass && !open.count(t.object))
            glassTriangles[t.object].push_back(&t);
    struct Around {
        double volume;
        std::uint32_t object;
    };
    std::vector<Around> around;
    for (const auto& [object, triangles] : glassTriangles) {
        if (windingNumber(triangles, point) <= 0.5) continue;
        DoubleBox box;
        for (const Triangle* t : triangles)
            for (const glm::vec3& p : t->position) box.grow(glm::dvec3(p));
        const glm::dvec3 size = box.max - box.min;
        around.push_back({size.x * size.y * size.z, object});
    }
    // Outermost first: the larger box, then the lower object index.
    std::sort(around.begin(), around.end(), [](const Around& x, const Around& y) {
        return x.volume != y.volume ? x.volume > y.volume : x.object < y.object;
    });
    if (around.size() > gpu::kMaxMediumDepth) {
        warn("the camera is inside " + std::to_string(around.size()) +
             " glass objects; primary rays start inside the " + std::to_string(gpu::kMaxMediumDepth) +
             " innermost (the GPU's medium stack), as if the others were air");
        around.erase(around.begin(), around.end() - gpu::kMaxMediumDepth);
    }
    std::vector<std::uint32_t> media;
    for (const Around& a : around) media.push_back(a.object);
    return media;
}

}  // namespace vitrum
