// CPU traversal of the flattened BVH (the same node array the GPU walks), in float or double.
// Triangle test: Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection" (JCGT 2013) on the
// stored vertices, exactly like shaders/bvh.glsl: no ray slips between triangles sharing an edge.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "shared/gpu_types.h"

namespace vitrum {

template <class Real>
struct Ray {
    glm::vec<3, Real> origin;
    glm::vec<3, Real> direction;  // need not be unit length; t is in units of it
    Real tMin = Real(0);
    Real tMax = Real(1e30);
};

template <class Real>
struct TriangleHit {
    Real t;
    Real u, v;               // barycentrics of v1 and v2
    std::uint32_t triangle;  // index in BVH order
};

struct TraversalCounters {
    std::uint64_t nodeVisits = 0;
    std::uint64_t triangleTests = 0;
};

template <class Real>
std::optional<TriangleHit<Real>> intersectTriangle(const gpu::TriangleVertices& tri, const Ray<Real>& ray);

template <class Real>
std::optional<TriangleHit<Real>> traceClosest(std::span<const gpu::BvhNode> nodes,
                                              std::span<const gpu::TriangleVertices> triangles,
                                              const Ray<Real>& ray, TraversalCounters* counters = nullptr);

// True when any triangle is hit with tMin < t < tMax (shadow rays).
template <class Real>
bool traceAny(std::span<const gpu::BvhNode> nodes, std::span<const gpu::TriangleVertices> triangles,
              const Ray<Real>& ray, TraversalCounters* counters = nullptr);

// Appends every triangle hit with tMin < t < tMax to `hits`, in traversal order. For short
// intervals: the CPU reference uses it to find surfaces touching the one a ray just hit.
template <class Real>
void traceAll(std::span<const gpu::BvhNode> nodes, std::span<const gpu::TriangleVertices> triangles,
              const Ray<Real>& ray, std::vector<TriangleHit<Real>>& hits, TraversalCounters* counters = nullptr);

}  // namespace vitrum
