// CPU traversal of the flat BVH, mirroring shaders/bvh.glsl: Moller-Trumbore with the same
// operations in the same order, a slab test per node, and a depth-first stack that visits the
// child on the ray's near side of the split first.
#include "bvh/bvh_traversal.h"

#include <bit>
#include <cassert>
#include <cmath>
#include <limits>

namespace vitrum {
namespace {

template <class Real>
using Vec3 = glm::vec<3, Real>;

template <class Real>
Vec3<Real> toReal(const glm::vec4& v) {
    return Vec3<Real>(Real(v.x), Real(v.y), Real(v.z));
}

// Rounding in the slab distances could make a box look missed by a ray that still hits a
// triangle on its face; widening the exit by 1 + 2 gamma(3) makes the test conservative (pbrt-v4,
// "Robust Ray-Bounds Intersections", after Ize 2013).
template <class Real>
constexpr Real kFarScale = Real(1) + Real(2) * (Real(3) * std::numeric_limits<Real>::epsilon() * Real(0.5)) /
                                         (Real(1) - Real(3) * std::numeric_limits<Real>::epsilon() * Real(0.5));

// Slab test of the box against the ray segment [tMin, tMax] (Kay and Kajiya 1986). A NaN slab
// distance comes from 0 * inf: the ray runs inside the plane of a face. The axis is then skipped,
// so the box is entered exactly when the origin lies within the slab, whatever the sign of the
// zero.
template <class Real>
bool hitsBox(const gpu::BvhNode& node, const Vec3<Real>& origin, const Vec3<Real>& inverseDirection, Real tMin,
             Real tMax) {
    Real enter = tMin;
    Real leave = tMax;
    for (int a = 0; a < 3; ++a) {
        const Real t0 = (Real(node.boundsMin[a]) - origin[a]) * inverseDirection[a];
        const Real t1 = (Real(node.boundsMax[a]) - origin[a]) * inverseDirection[a];
        // NaN: the direction component is 0 and the origin lies on a face plane, so inside the
        // closed slab; this axis does not constrain the segment.
        if (std::isnan(t0) || std::isnan(t1)) continue;
        const Real nearT = t0 < t1 ? t0 : t1;
        const Real farT = t0 < t1 ? t1 : t0;
        if (nearT > enter) enter = nearT;
        if (farT * kFarScale<Real> < leave) leave = farT * kFarScale<Real>;
    }
    return enter <= leave;
}

// Walks the tree, calling onLeaf(first, count, tMax&) for every leaf whose box the ray enters
// before the current tMax; onLeaf returns true to stop the traversal.
template <class Real, class OnLeaf>
void traverse(std::span<const gpu::BvhNode> nodes, const Ray<Real>& ray, Real& tMax, TraversalCounters* counters,
              OnLeaf&& onLeaf) {
    if (nodes.empty()) return;
    const Vec3<Real> inverseDirection = Real(1) / ray.direction;  // 1/0 -> inf on purpose
    std::uint32_t stack[gpu::kTraversalStackSize];
    std::uint32_t size = 0;
    stack[size++] = 0;
    while (size > 0) {
        const std::uint32_t index = stack[--size];
        const gpu::BvhNode& node = nodes[index];
        if (counters) counters->nodeVisits += 1;
        if (!hitsBox(node, ray.origin, inverseDirection, ray.tMin, tMax)) continue;
        const std::uint32_t link = std::bit_cast<std::uint32_t>(node.boundsMin.w);
        const std::uint32_t meta = std::bit_cast<std::uint32_t>(node.boundsMax.w);
        if ((meta & gpu::kInteriorNodeFlag) == 0) {
            if (onLeaf(link, meta, tMax)) return;
            continue;
        }
        // The builder bounds the depth so that this cannot overflow (bvh_builder.cpp).
        assert(size + 2 <= gpu::kTraversalStackSize);
        if (size + 2 > gpu::kTraversalStackSize) continue;
        // Near child on top: if the ray goes towards -axis the second child (upper side) is nearer.
        const bool negative = ray.direction[meta & 3u] < Real(0);
        stack[size++] = negative ? index + 1 : link;
        stack[size++] = negative ? link : index + 1;
    }
}

}  // namespace

template <class Real>
std::optional<TriangleHit<Real>> intersectTriangle(const gpu::TriangleVertices& tri, const Ray<Real>& ray) {
    // Moller-Trumbore, exactly the operation order of shaders/bvh.glsl.
    const Vec3<Real> v0 = toReal<Real>(tri.v0);
    const Vec3<Real> e1 = toReal<Real>(tri.v1) - v0;
    const Vec3<Real> e2 = toReal<Real>(tri.v2) - v0;
    const Vec3<Real> p = glm::cross(ray.direction, e2);
    const Real det = glm::dot(e1, p);
    if (det == Real(0)) return std::nullopt;
    const Real invDet = Real(1) / det;
    const Vec3<Real> s = ray.origin - v0;
    const Real u = glm::dot(s, p) * invDet;
    if (u < Real(0) || u > Real(1)) return std::nullopt;
    const Vec3<Real> q = glm::cross(s, e1);
    const Real v = glm::dot(ray.direction, q) * invDet;
    if (v < Real(0) || u + v > Real(1)) return std::nullopt;
    const Real t = glm::dot(e2, q) * invDet;
    if (!(t > ray.tMin && t < ray.tMax)) return std::nullopt;
    return TriangleHit<Real>{t, u, v, 0};
}

template <class Real>
std::optional<TriangleHit<Real>> traceClosest(std::span<const gpu::BvhNode> nodes,
                                              std::span<const gpu::TriangleVertices> triangles,
                                              const Ray<Real>& ray, TraversalCounters* counters) {
    std::optional<TriangleHit<Real>> closest;
    Real tMax = ray.tMax;
    Ray<Real> probe = ray;
    traverse(nodes, ray, tMax, counters, [&](std::uint32_t first, std::uint32_t count, Real& currentMax) {
        probe.tMax = currentMax;
        for (std::uint32_t i = first; i < first + count; ++i) {
            if (counters) counters->triangleTests += 1;
            // tMax shrinks to the closest t: a later hit must be strictly nearer to replace it.
            if (auto hit = intersectTriangle(triangles[i], probe)) {
                hit->triangle = i;
                closest = hit;
                probe.tMax = hit->t;
            }
        }
        currentMax = probe.tMax;
        return false;
    });
    return closest;
}

template <class Real>
bool traceAny(std::span<const gpu::BvhNode> nodes, std::span<const gpu::TriangleVertices> triangles,
              const Ray<Real>& ray, TraversalCounters* counters) {
    bool found = false;
    Real tMax = ray.tMax;
    traverse(nodes, ray, tMax, counters, [&](std::uint32_t first, std::uint32_t count, Real&) {
        for (std::uint32_t i = first; i < first + count; ++i) {
            if (counters) counters->triangleTests += 1;
            if (intersectTriangle(triangles[i], ray)) {
                found = true;
                return true;
            }
        }
        return false;
    });
    return found;
}

template <class Real>
void traceAll(std::span<const gpu::BvhNode> nodes, std::span<const gpu::TriangleVertices> triangles,
              const Ray<Real>& ray, std::vector<TriangleHit<Real>>& hits, TraversalCounters* counters) {
    Real tMax = ray.tMax;
    traverse(nodes, ray, tMax, counters, [&](std::uint32_t first, std::uint32_t count, Real&) {
        for (std::uint32_t i = first; i < first + count; ++i) {
            if (counters) counters->triangleTests += 1;
            if (auto hit = intersectTriangle(triangles[i], ray)) {
                hit->triangle = i;
                hits.push_back(*hit);
            }
        }
        return false;
    });
}

template std::optional<TriangleHit<float>> intersectTriangle(const gpu::TriangleVertices&, const Ray<float>&);
template std::optional<TriangleHit<double>> intersectTriangle(const gpu::TriangleVertices&, const Ray<double>&);
template std::optional<TriangleHit<float>> traceClosest(std::span<const gpu::BvhNode>,
                                                        std::span<const gpu::TriangleVertices>, const Ray<float>&,
                                                        TraversalCounters*);
template std::optional<TriangleHit<double>> traceClosest(std::span<const gpu::BvhNode>,
                                                         std::span<const gpu::TriangleVertices>, const Ray<double>&,
                                                         TraversalCounters*);
template bool traceAny(std::span<const gpu::BvhNode>, std::span<const gpu::TriangleVertices>, const Ray<float>&,
                       TraversalCounters*);
template bool traceAny(std::span<const gpu::BvhNode>, std::span<const gpu::TriangleVertices>, const Ray<double>&,
                       TraversalCounters*);
template void traceAll(std::span<const gpu::BvhNode>, std::span<const gpu::TriangleVertices>, const Ray<float>&,
                       std::vector<TriangleHit<float>>&, TraversalCounters*);
template void traceAll(std::span<const gpu::BvhNode>, std::span<const gpu::TriangleVertices>, const Ray<double>&,
                       std::vector<TriangleHit<double>>&, TraversalCounters*);
}  // namespace vitrum
