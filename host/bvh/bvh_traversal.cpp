// CPU traversal of the flat BVH, mirroring shaders/bvh.glsl: the watertight triangle test with the same
// operations in the same order, a slab test per node, and a depth-first stack that visits the
// child on the ray's near side of the split first.
#include "bvh/bvh_traversal.h"

#include <bit>
#include <cassert>
#include <cmath>
#include <limits>
#include <utility>

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

}  // namespace

// The ray in an instance's space (gpu_types.h, "Instances"): the direction is not normalized, so
// that t is the world's. The same operations in the same order as shaders/bvh.glsl's
// rayIntoInstance: ((r.x x + r.y y) + r.z z) + r.w for a point, without r.w for a direction.
template <class Real>
Ray<Real> rayIntoInstance(const gpu::GpuInstance& instance, const Ray<Real>& ray) {
    const glm::vec4* rows[3] = {&instance.toObject0, &instance.toObject1, &instance.toObject2};
    Ray<Real> local = ray;
    for (int a = 0; a < 3; ++a) {
        const Vec3<Real> r = toReal<Real>(*rows[a]);
        local.origin[a] = r.x * ray.origin.x + r.y * ray.origin.y + r.z * ray.origin.z + Real(rows[a]->w);
        local.direction[a] = r.x * ray.direction.x + r.y * ray.direction.y + r.z * ray.direction.z;
    }
    return local;
}

namespace {

// Walks the tree from node `root`, calling onLeaf(first, count, tMax&, ray, instance) for every
// leaf whose box the ray enters before the current tMax, with the ray in the space of the
// instance the leaf is in (kNoInstance: the world); onLeaf returns true to stop the traversal,
// and so does this. A leaf of count 0 is an instance: its mesh's tree is walked at once, depth
// first, as the GPU's traversal does.
template <class Real, class OnLeaf>
bool traverseFrom(std::span<const gpu::BvhNode> nodes, std::span<const gpu::GpuInstance> instances,
                  std::uint32_t root, const Ray<Real>& ray, std::uint32_t instance, Real& tMax,
                  TraversalCounters* counters, OnLeaf& onLeaf) {
    const Vec3<Real> inverseDirection = Real(1) / ray.direction;  // 1/0 -> inf on purpose
    std::uint32_t stack[gpu::kTraversalStackSize];
    std::uint32_t size = 0;
    stack[size++] = root;
    while (size > 0) {
        const std::uint32_t index = stack[--size];
        const gpu::BvhNode& node = nodes[index];
        if (counters) counters->nodeVisits += 1;
        if (!hitsBox(node, ray.origin, inverseDirection, ray.tMin, tMax)) continue;
        const std::uint32_t link = std::bit_cast<std::uint32_t>(node.boundsMin.w);
        const std::uint32_t meta = std::bit_cast<std::uint32_t>(node.boundsMax.w);
        if ((meta & gpu::kInteriorNodeFlag) == 0) {
            if (meta == 0 && !instances.empty()) {
                const gpu::GpuInstance& entered = instances[link];
                const bool identity = entered.info.w == gpu::kIdentityInstance;
                const Ray<Real> local = identity ? ray : rayIntoInstance(entered, ray);
                if (traverseFrom(nodes, instances, entered.info.x, local, identity ? gpu::kNoInstance : link, tMax,
                                 counters, onLeaf))
                    return true;
                continue;
            }
            if (onLeaf(link, meta, tMax, ray, instance)) return true;
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
    return false;
}

// Whether the ray passes a hit of triangle i by: it lies in a cut-out part of it
// (TraversalInput::cutouts), or the triangle is partly covered and the ray goes on through such a
// surface and has not passed it yet (Ray::passCoveredBelow).
template <class Real>
bool passedBy(const TraversalInput& bvh, const Ray<Real>& ray, std::uint32_t i, const TriangleHit<Real>& hit) {
    const std::uint32_t mark = std::bit_cast<std::uint32_t>(bvh.triangles[i].v2.w);
    if ((mark & gpu::kTriangleCovered) != 0 && hit.t < ray.passCoveredBelow) return true;
    return bvh.cutouts && (mark & gpu::kTriangleCutout) != 0 && bvh.cutouts->cutAway(i, mark, hit.u, hit.v);
}

template <class Real, class OnLeaf>
void traverse(const TraversalInput& bvh, const Ray<Real>& ray, Real& tMax, TraversalCounters* counters,
              OnLeaf&& onLeaf) {
    if (bvh.nodes.empty()) return;
    traverseFrom(bvh.nodes, bvh.instances, 0u, ray, gpu::kNoInstance, tMax, counters, onLeaf);
}

}  // namespace

template <class Real>
std::optional<TriangleHit<Real>> intersectTriangle(const gpu::TriangleVertices& tri, const Ray<Real>& ray) {
    // Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection" (JCGT 2013), without back-face
    // culling, exactly the operation order of shaders/bvh.glsl. The vertices are moved into a frame
    // where the ray starts at the origin and runs along +z (a shear), so the three edge functions
    // are 2D cross products of the transformed vertices. An edge shared by two triangles gives the
    // same two vertices to both, hence exactly opposite edge functions: a ray can never pass
    // between them. A zero edge function counts as inside, so a ray exactly on an edge or a vertex
    // hits every triangle around it (the paper's double-precision re-evaluation of zeros, which
    // would pick one, is left out: it is not needed for watertightness and GLSL has no double here).
    const Vec3<Real>& d = ray.direction;
    // kz: the dimension where |d| is largest (first one on ties); kx, ky follow it cyclically,
    // swapped when d[kz] < 0 to keep the triangles' winding.
    int kz = 0;
    if (std::fabs(d.y) > std::fabs(d[kz])) kz = 1;
    if (std::fabs(d.z) > std::fabs(d[kz])) kz = 2;
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    if (d[kz] < Real(0)) std::swap(kx, ky);
    // Shear constants: multiplications by 1 / d[kz], as the GLSL does them.
    const Real sz = Real(1) / d[kz];
    const Real sx = d[kx] * sz;
    const Real sy = d[ky] * sz;
    const Vec3<Real> a = toReal<Real>(tri.v0) - ray.origin;
    const Vec3<Real> b = toReal<Real>(tri.v1) - ray.origin;
    const Vec3<Real> c = toReal<Real>(tri.v2) - ray.origin;
    const Real ax = a[kx] - sx * a[kz];
    const Real ay = a[ky] - sy * a[kz];
    const Real bx = b[kx] - sx * b[kz];
    const Real by = b[ky] - sy * b[kz];
    const Real cx = c[kx] - sx * c[kz];
    const Real cy = c[ky] - sy * c[kz];
    // Scaled barycentrics: u0 of v0 (edge v1 v2), u1 of v1, u2 of v2.
    const Real u0 = cx * by - cy * bx;
    const Real u1 = ax * cy - ay * cx;
    const Real u2 = bx * ay - by * ax;
    if ((u0 < Real(0) || u1 < Real(0) || u2 < Real(0)) && (u0 > Real(0) || u1 > Real(0) || u2 > Real(0)))
        return std::nullopt;
    const Real det = u0 + u1 + u2;
    if (det == Real(0)) return std::nullopt;  // degenerate triangle, or the ray lies in its plane
    const Real scaledT = u0 * (sz * a[kz]) + u1 * (sz * b[kz]) + u2 * (sz * c[kz]);
    const Real invDet = Real(1) / det;
    const Real t = scaledT * invDet;
    if (!(t > ray.tMin && t < ray.tMax)) return std::nullopt;
    return TriangleHit<Real>{t, u1 * invDet, u2 * invDet, 0};
}

template <class Real>
std::optional<TriangleHit<Real>> traceClosest(const TraversalInput& bvh, const Ray<Real>& ray,
                                              TraversalCounters* counters) {
    std::optional<TriangleHit<Real>> closest;
    Real tMax = ray.tMax;
    traverse(bvh, ray, tMax, counters,
             [&](std::uint32_t first, std::uint32_t count, Real& currentMax, const Ray<Real>& local, std::uint32_t instance) {
                 Ray<Real> probe = local;
                 probe.tMax = currentMax;
                 for (std::uint32_t i = first; i < first + count; ++i) {
                     if (counters) counters->triangleTests += 1;
                     // tMax shrinks to the closest t: a later hit must be strictly nearer to replace it.
                     if (auto hit = intersectTriangle(bvh.triangles[i], probe); hit && !passedBy(bvh, probe, i, *hit)) {
                         hit->triangle = i;
                         hit->instance = instance;
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
bool traceAny(const TraversalInput& bvh, const Ray<Real>& ray, TraversalCounters* counters) {
    bool found = false;
    Real tMax = ray.tMax;
    traverse(bvh, ray, tMax, counters,
             [&](std::uint32_t first, std::uint32_t count, Real&, const Ray<Real>& local, std::uint32_t) {
                 for (std::uint32_t i = first; i < first + count; ++i) {
                     if (counters) counters->triangleTests += 1;
                     if (auto hit = intersectTriangle(bvh.triangles[i], local); hit && !passedBy(bvh, local, i, *hit)) {
                         found = true;
                         return true;
                     }
                 }
                 return false;
             });
    return found;
}

template <class Real>
void traceAll(const TraversalInput& bvh, const Ray<Real>& ray, std::vector<TriangleHit<Real>>& hits,
              TraversalCounters* counters) {
    Real tMax = ray.tMax;
    traverse(bvh, ray, tMax, counters,
             [&](std::uint32_t first, std::uint32_t count, Real&, const Ray<Real>& local, std::uint32_t instance) {
                 for (std::uint32_t i = first; i < first + count; ++i) {
                     if (counters) counters->triangleTests += 1;
                     if (auto hit = intersectTriangle(bvh.triangles[i], local); hit && !passedBy(bvh, local, i, *hit)) {
                         hit->triangle = i;
                         hit->instance = instance;
                         hits.push_back(*hit);
                     }
                 }
                 return false;
             });
}

template std::optional<TriangleHit<float>> intersectTriangle(const gpu::TriangleVertices&, const Ray<float>&);
template std::optional<TriangleHit<double>> intersectTriangle(const gpu::TriangleVertices&, const Ray<double>&);
#define VITRUM_TRAVERSAL_FOR(Real)                                                                                 \
    template std::optional<TriangleHit<Real>> traceClosest(const TraversalInput&, const Ray<Real>&,               \
                                                           TraversalCounters*);                                   \
    template bool traceAny(const TraversalInput&, const Ray<Real>&, TraversalCounters*);                          \
    template void traceAll(const TraversalInput&, const Ray<Real>&, std::vector<TriangleHit<Real>>&,              \
                           TraversalCounters*);                                                                   \
    template Ray<Real> rayIntoInstance(const gpu::GpuInstance&, const Ray<Real>&);
VITRUM_TRAVERSAL_FOR(float)
VITRUM_TRAVERSAL_FOR(double)
#undef VITRUM_TRAVERSAL_FOR
}  // namespace vitrum
