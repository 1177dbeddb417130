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
    // A ray going on through a partly covered surface passes by the triangles marked
    // gpu::kTriangleCovered that it hits below this t, where it crosses the surface it started at
    // (render-model-decisions.md, "Partial coverage"); 0 for every other ray.
    Real passCoveredBelow = Real(0);
};

template <class Real>
struct TriangleHit {
    Real t;
    Real u, v;               // barycentrics of v1 and v2
    std::uint32_t triangle;  // index in BVH order
    std::uint32_t instance = gpu::kNoInstance;  // the copy of its mesh (Bvh::instances), or none
};

// Where a triangle is cut away (Material::cutout): a triangle whose vertices are marked
// gpu::kTriangleCutout | texture (gpu_types.h, "Triangles") is asked about at each of its hits,
// before the hit counts as one of any kind; where it is cut away the ray passes on, as the
// kernel's cutAway (shaders/cutout.glsl) lets it. `triangle` is in BVH order, (u, v) the hit's
// barycentrics of v1 and v2.
class Cutouts {
public:
    virtual ~Cutouts() = default;
    virtual bool cutAway(std::uint32_t triangle, std::uint32_t mark, float u, float v) const = 0;
    virtual bool cutAway(std::uint32_t triangle, std::uint32_t mark, double u, double v) const = 0;
};

// What a traversal walks: the flattened nodes (bvh.h), the triangles in BVH order and, for a
// scene with instances, the instances the top-level leaves name (Bvh::instances); where triangles
// are marked as cut out, what decides where (null: every hit counts).
struct TraversalInput {
    std::span<const gpu::BvhNode> nodes;
    std::span<const gpu::TriangleVertices> triangles;
    std::span<const gpu::GpuInstance> instances = {};
    const Cutouts* cutouts = nullptr;
};

struct TraversalCounters {
    std::uint64_t nodeVisits = 0;
    std::uint64_t triangleTests = 0;
};

template <class Real>
std::optional<TriangleHit<Real>> intersectTriangle(const gpu::TriangleVertices& tri, const Ray<Real>& ray);

// The ray in an instance's space, as both traversals move it (gpu_types.h, "Instances").
template <class Real>
Ray<Real> rayIntoInstance(const gpu::GpuInstance& instance, const Ray<Real>& ray);

// The closest hit with tMin < t < tMax; a hit in an instance has t, u, v of the mesh's triangle
// along the ray moved into the instance's space.
template <class Real>
std::optional<TriangleHit<Real>> traceClosest(const TraversalInput& bvh, const Ray<Real>& ray,
                                              TraversalCounters* counters = nullptr);

// True when any triangle is hit with tMin < t < tMax (shadow rays).
template <class Real>
bool traceAny(const TraversalInput& bvh, const Ray<Real>& ray, TraversalCounters* counters = nullptr);

// Appends every triangle hit with tMin < t < tMax to `hits`, in traversal order. For short
// intervals: the CPU reference uses it to find surfaces touching the one a ray just hit.
template <class Real>
void traceAll(const TraversalInput& bvh, const Ray<Real>& ray, std::vector<TriangleHit<Real>>& hits,
              TraversalCounters* counters = nullptr);

// The same over a tree without instances.
template <class Real>
std::optional<TriangleHit<Real>> traceClosest(std::span<const gpu::BvhNode> nodes,
                                              std::span<const gpu::TriangleVertices> triangles,
                                              const Ray<Real>& ray, TraversalCounters* counters = nullptr) {
    return traceClosest(TraversalInput{nodes, triangles}, ray, counters);
}
template <class Real>
bool traceAny(std::span<const gpu::BvhNode> nodes, std::span<const gpu::TriangleVertices> triangles,
              const Ray<Real>& ray, TraversalCounters* counters = nullptr) {
    return traceAny(TraversalInput{nodes, triangles}, ray, counters);
}
template <class Real>
void traceAll(std::span<const gpu::BvhNode> nodes, std::span<const gpu::TriangleVertices> triangles,
              const Ray<Real>& ray, std::vector<TriangleHit<Real>>& hits, TraversalCounters* counters = nullptr) {
    traceAll(TraversalInput{nodes, triangles}, ray, hits, counters);
}

}  // namespace vitrum
