#include "analysis/camera_surface.h"

#include <cmath>

namespace vitrum {
namespace {

// The point of triangle abc closest to p (Ericson, Real-Time Collision Detection, 5.1.5).
glm::dvec3 closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return a;
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const double denominator = 1.0 / (va + vb + vc);
    return a + ab * (vb * denominator) + ac * (vc * denominator);
}

}  // namespace

CameraSurface cameraSurface(std::span<const Triangle> triangles, const glm::vec3& from, const RayOffsetScale& scale) {
    const glm::dvec3 camera(from);
    // No offset along a unit normal is longer than this: a triangle whose box is farther from the
    // camera is not tested further (a scene of a million triangles is passed over in milliseconds).
    const double reach = glm::length(glm::dvec3(offsetRayOrigin(from, glm::vec3(1.0f), scale)) - camera);
    CameraSurface surface;
    for (const Triangle& t : triangles) {
        const glm::dvec3 a(t.position[0]), b(t.position[1]), c(t.position[2]);
        const glm::dvec3 lo = glm::min(a, glm::min(b, c)) - reach, hi = glm::max(a, glm::max(b, c)) + reach;
        if (glm::any(glm::lessThan(camera, lo)) || glm::any(glm::greaterThan(camera, hi))) continue;
        const glm::dvec3 cross = glm::cross(b - a, c - a);
        const double area = glm::length(cross);
        if (!(area > 0.0) || !std::isfinite(area)) continue;  // no plane: the renderers never hit it
        const glm::vec3 normal(cross / area);
        const double offset = glm::length(glm::dvec3(offsetRayOrigin(from, normal, scale)) - camera);
        if (glm::length(closestPointOnTriangle(camera, a, b, c) - camera) > offset) continue;
        if (surface.triangles == 0)
            surface.normal = normal;
        else if (std::fabs(glm::dot(glm::dvec3(surface.normal), glm::dvec3(normal))) < 1.0 - 1e-6)
            surface.otherPlanes = true;
        surface.triangles += 1;
    }
    return surface;
}

}  // namespace vitrum
