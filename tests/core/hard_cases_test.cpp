// Hard cases on the CPU side alone (docs/hard-cases.md): watertightness of the triangle test on
// the CPU traversal, rays that never re-hit the surface they start on at any scale, degenerate
// triangles, and the scene-scaled ray offsets. The GPU halves are in tests/gpu/hard_cases_test.cpp.
#include <gtest/gtest.h>

#include "../support/test_meshes.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/bvh_traversal.h"
#include "cpu/optics.h"
#include "render_model/ray_offset.h"
#include "gpu_input/packed_scene.h"
#include "gpu_input/render_params.h"
#include "scene/scene.h"
#include "shared/gpu_types.h"

namespace vitrum {
namespace {

// Deterministic uniform numbers in [0, 1) from the shared hash (fixed seeds on every platform).
float uniform(std::uint32_t index, std::uint32_t k) {
    return gpu::hashToUnit(gpu::pcgHash(0xC0FFEEu ^ gpu::pcgHash(index * 8u + k)));
}

// A closed, outward-wound mesh as an indexed list: shared vertices have bit-identical positions
// in every triangle that uses them, as in a mesh loaded from an OBJ file.
struct Mesh {
    std::vector<glm::vec3> vertices;
    std::vector<glm::uvec3> faces;
};

// The shared test icosphere as this file's Mesh.
Mesh icosphere(int levels, float radius = 1.0f, glm::vec3 centre = glm::vec3(0.0f)) {
    testing::IndexedMesh shared = testing::icosphere(levels, radius, centre);
    return Mesh{std::move(shared.vertices), std::move(shared.faces)};
}

// A cube [-1, 1]^3 whose faces are n x n grids of quads, two triangles each, outward wound.
Mesh gridCube(int n) {
    Mesh mesh;
    std::map<std::tuple<int, int, int>, unsigned> index;  // integer lattice point -> vertex
    auto vertex = [&](int i, int j, int k) {
        auto [it, inserted] = index.try_emplace({i, j, k}, unsigned(mesh.vertices.size()));
        if (inserted) mesh.vertices.push_back(glm::vec3(2.0f * i / n - 1.0f, 2.0f * j / n - 1.0f, 2.0f * k / n - 1.0f));
        return it->second;
    };
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side <= 1; ++side)
            for (int a = 0; a < n; ++a)
                for (int b = 0; b < n; ++b) {
                    auto at = [&](int da, int db) {
                        int c[3];
                        c[axis] = side * n;
                        c[(axis + 1) % 3] = a + da;
                        c[(axis + 2) % 3] = b + db;
                        return vertex(c[0], c[1], c[2]);
                    };
                    unsigned p00 = at(0, 0), p10 = at(1, 0), p11 = at(1, 1), p01 = at(0, 1);
                    // (axis+1) x (axis+2) = +axis: counter-clockwise seen from outside on the + side.
                    if (side == 1) {
                        mesh.faces.push_back({p00, p10, p11});
                        mesh.faces.push_back({p00, p11, p01});
                    } else {
                        mesh.faces.push_back({p00, p11, p10});
                        mesh.faces.push_back({p00, p01, p11});
                    }
                }
    return mesh;
}

std::vector<Triangle> triangles(const Mesh& mesh) {
    std::vector<Triangle> result;
    for (const glm::uvec3& f : mesh.faces) {
        Triangle t{};
        for (int i = 0; i < 3; ++i) t.position[i] = mesh.vertices[f[i]];
        const glm::vec3 n = glm::normalize(glm::cross(t.position[1] - t.position[0], t.position[2] - t.position[0]));
        for (auto& vn : t.normal) vn = n;
        result.push_back(t);
    }
    return result;
}

struct Traced {
    Bvh bvh;
    std::vector<gpu::TriangleVertices> vertices;
    explicit Traced(const std::vector<Triangle>& tris)
        : bvh(buildBvh(tris)), vertices(packTriangleVertices(bvh, tris)) {}
};

// Targets on shared features: every vertex, and points on every edge (a convex combination of its
// two end points, computed in float as a renderer would).
std::vector<glm::vec3> edgeAndVertexTargets(const Mesh& mesh, int perEdge) {
    std::vector<glm::vec3> targets = mesh.vertices;
    std::map<std::pair<unsigned, unsigned>, bool> seen;
    std::uint32_t k = 0;
    for (const glm::uvec3& f : mesh.faces)
        for (int e = 0; e < 3; ++e) {
            const auto key = std::minmax(f[e], f[(e + 1) % 3]);
            if (!seen.emplace(key, true).second) continue;
            for (int i = 0; i < perEdge; ++i) {
                const float s = uniform(k++, 0);
                targets.push_back((1.0f - s) * mesh.vertices[key.first] + s * mesh.vertices[key.second]);
            }
        }
    return targets;
}

// Moller-Trumbore (1997), the test this project used before: kept here only to show that the rays
// below do find the gaps a non-watertight test leaves, i.e. that the watertightness test can fail.
bool mollerTrumboreHits(const Triangle& tri, glm::vec3 origin, glm::vec3 direction) {
    const glm::vec3 e1 = tri.position[1] - tri.position[0], e2 = tri.position[2] - tri.position[0];
    const glm::vec3 p = glm::cross(direction, e2);
    const float det = glm::dot(e1, p);
    if (det == 0.0f) return false;
    const float invDet = 1.0f / det;
    const glm::vec3 s = origin - tri.position[0];
    const float u = glm::dot(s, p) * invDet;
    if (u < 0.0f || u > 1.0f) return false;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(direction, q) * invDet;
    if (v < 0.0f || u + v > 1.0f) return false;
    return glm::dot(e2, q) * invDet > 0.0f;
}

struct LeakCount {
    std::uint64_t rays = 0;
    std::uint64_t watertightMisses = 0;
    std::uint64_t watertightMissesDouble = 0;
    std::uint64_t mollerTrumboreMisses = 0;
    std::uint64_t bruteMisses = 0;
};

// Rays from outside and from inside (the centre, slightly jittered) through every target: all
// must hit the closed mesh, on the BVH traversal and on a brute-force loop over the triangles.
LeakCount countLeaks(const Mesh& mesh, int perEdge) {
    const std::vector<Triangle> tris = triangles(mesh);
    const Traced traced(tris);
    LeakCount count;
    std::uint32_t k = 0;
    for (const glm::vec3& target : edgeAndVertexTargets(mesh, perEdge)) {
        // From outside every face plane around the target (so the ray truly crosses the surface
        // there rather than grazing a silhouette, where a miss by an ulp would be correct):
        // outwards from the centre, tilted by up to ~20 degrees.
        const glm::vec3 tilt = 0.5f * glm::vec3(uniform(k, 1) - 0.5f, uniform(k, 2) - 0.5f, uniform(k, 3) - 0.5f);
        const glm::vec3 outside = target + 2.0f * glm::normalize(glm::normalize(target) + tilt);
        const glm::vec3 inside = 0.01f * glm::vec3(uniform(k, 4) - 0.5f, uniform(k, 5) - 0.5f, uniform(k, 6) - 0.5f);
        ++k;
        for (glm::vec3 origin : {outside, inside}) {
            const glm::vec3 direction = target - origin;
            ++count.rays;
            if (!traceClosest<float>(traced.bvh.nodes, traced.vertices, Ray<float>{origin, direction}))
                ++count.watertightMisses;
            if (!traceClosest<double>(traced.bvh.nodes, traced.vertices,
                                      Ray<double>{glm::dvec3(origin), glm::dvec3(direction)}))
                ++count.watertightMissesDouble;
            bool brute = false;
            for (const auto& t : traced.vertices)
                brute = brute || intersectTriangle<float>(t, Ray<float>{origin, direction}).has_value();
            if (!brute) ++count.bruteMisses;
            bool hit = false;
            for (const Triangle& t : tris) hit = hit || mollerTrumboreHits(t, origin, direction);
            if (!hit) ++count.mollerTrumboreMisses;
        }
    }
    return count;
}

TEST(HardCaseWatertight, RaysAtSharedEdgesAndVerticesOfAClosedMeshNeverSlipThrough) {
    // An icosphere (1,280 triangles, vertices of valence 5 and 6) and a cube of 6 x 8 x 8 x 2
    // triangles (axis-aligned edges, valence 4 to 6 and the cube's corners).
    LeakCount total;
    for (const auto& [name, mesh, perEdge] :
         {std::tuple{"icosphere", icosphere(3), 3}, std::tuple{"grid cube", gridCube(8), 6}}) {
        const LeakCount c = countLeaks(mesh, perEdge);
        std::cout << name << ": " << c.rays << " rays at shared edges and vertices, misses: watertight float "
                  << c.watertightMisses << ", double " << c.watertightMissesDouble << "; Moller-Trumbore "
                  << c.mollerTrumboreMisses << " brute " << c.bruteMisses << "\n";
        EXPECT_EQ(c.watertightMisses, 0u) << name;
        EXPECT_EQ(c.watertightMissesDouble, 0u) << name;
        EXPECT_EQ(c.bruteMisses, 0u) << name;
        total.rays += c.rays;
        total.mollerTrumboreMisses += c.mollerTrumboreMisses;
    }
    EXPECT_GT(total.rays, 10000u);
    // The rays are hard enough to find the gaps of a test that is not watertight.
    EXPECT_GT(total.mollerTrumboreMisses, 0u);
}

TEST(HardCaseWatertight, IntersectionReportsBarycentricsOfV1AndV2) {
    // The contract shaders/bvh.glsl keeps: (t, u, v) with u, v the weights of v1 and v2.
    gpu::TriangleVertices tri{glm::vec4(0, 0, 0, 0), glm::vec4(4, 0, 0, 0), glm::vec4(0, 2, 0, 0)};
    for (glm::vec3 d : {glm::vec3(0, 0, -1), glm::vec3(0, 0, 1), glm::vec3(0.3f, -0.2f, -2.0f)}) {
        const glm::vec3 p(1.0f, 0.5f, 0.0f);  // weights: v1 1/4, v2 1/4, v0 1/2
        const glm::vec3 origin = p - 3.0f * d;
        const auto hit = intersectTriangle<float>(tri, Ray<float>{origin, d});
        ASSERT_TRUE(hit.has_value());
        EXPECT_NEAR(hit->t, 3.0f, 1e-6f);
        EXPECT_NEAR(hit->u, 0.25f, 1e-6f);
        EXPECT_NEAR(hit->v, 0.25f, 1e-6f);
    }
}

// ---- Self-intersection --------------------------------------------------------------------

// A glass-like closed convex mesh at a given scale and place: from the hit point of a random ray
// (interpolated from the barycentrics, as both renderers do), the reflected ray offset outwards
// must hit nothing (the mesh is convex), and the refracted ray offset inwards must not hit the
// triangle it starts on. Rays are followed like the renderer's: direction unit, tMin = 0.
template <class Real>
void expectNoSelfHits(float scale, glm::vec3 shift, std::uint32_t rays) {
    using Vec = glm::vec<3, Real>;
    Mesh mesh = icosphere(3, scale, shift);
    const std::vector<Triangle> tris = triangles(mesh);
    const Traced traced(tris);
    const RayOffsetScale offsets = rayOffsetScale(tris);
    std::uint32_t reflectedSelfHits = 0, refractedSelfHits = 0, tested = 0;
    for (std::uint32_t i = 0; i < rays; ++i) {
        const glm::vec3 from =
            shift +
            3.0f * scale * glm::normalize(glm::vec3(uniform(i, 1) - 0.5f, uniform(i, 2) - 0.5f, uniform(i, 3) - 0.5f));
        const glm::vec3 aim =
            shift + 0.9f * scale * glm::vec3(uniform(i, 4) - 0.5f, uniform(i, 5) - 0.5f, uniform(i, 6) - 0.5f);
        const Vec d = glm::normalize(Vec(aim) - Vec(from));
        const auto hit = traceClosest<Real>(traced.bvh.nodes, traced.vertices, Ray<Real>{Vec(from), d});
        if (!hit) continue;
        ++tested;
        const gpu::TriangleVertices& tv = traced.vertices[hit->triangle];
        const Vec v0(tv.v0), v1(tv.v1), v2(tv.v2);
        const Vec p = (Real(1) - hit->u - hit->v) * v0 + hit->u * v1 + hit->v * v2;
        const Vec n = glm::normalize(glm::cross(v1 - v0, v2 - v0));  // outward
        const Vec reflected = optics::reflect(d, n);
        if (traceClosest<Real>(traced.bvh.nodes, traced.vertices, Ray<Real>{offsetRayOrigin(p, n, offsets), reflected}))
            ++reflectedSelfHits;
        const auto refracted = optics::refract(d, n, Real(1) / Real(1.5));
        const auto inside = traceClosest<Real>(traced.bvh.nodes, traced.vertices,
                                               Ray<Real>{offsetRayOrigin(p, -n, offsets), *refracted});
        if (!inside || inside->triangle == hit->triangle) ++refractedSelfHits;
    }
    EXPECT_GT(tested, rays * 3 / 4);
    EXPECT_EQ(reflectedSelfHits, 0u) << "scale " << scale << " shift " << shift.x;
    EXPECT_EQ(refractedSelfHits, 0u) << "scale " << scale << " shift " << shift.x;
}

TEST(HardCaseSelfIntersection, SecondaryRaysNeverReHitTheirSurfaceAtAnyScale) {
    for (float scale : {1e-3f, 1.0f, 1e3f}) {
        expectNoSelfHits<float>(scale, glm::vec3(0.0f), 2000);
        expectNoSelfHits<double>(scale, glm::vec3(0.0f), 2000);
    }
    // Far from the origin (1e4 units): every coordinate is in the relative (256 ulps) regime.
    expectNoSelfHits<float>(1.0f, glm::vec3(1e4f, -1e4f, 1e4f), 2000);
    expectNoSelfHits<double>(1.0f, glm::vec3(1e4f, -1e4f, 1e4f), 2000);
}

TEST(HardCaseSelfIntersection, OffsetConstantsFollowTheSceneExtent) {
    // Extent E: region E / 32 (the chapter's for E = 1), offset E / 2^23 = 32 ulps of E / 32;
    // exact multiples for a power-of-two scale, within float rounding for any other; a
    // translation does not change them.
    std::vector<Triangle> unit = triangles(gridCube(1));  // [-1, 1]^3: extent 2
    for (Triangle& t : unit)
        for (glm::vec3& p : t.position) p *= 0.5f;  // extent 1
    const RayOffsetScale one = rayOffsetScale(unit);
    EXPECT_EQ(one.origin, 1.0f / 32.0f);
    EXPECT_EQ(one.absolute, 1.0f / 8388608.0f);
    // Continuous at the region's edge: the absolute offset is the relative one (32 ulps) there.
    const float edge = one.origin;
    EXPECT_EQ(std::bit_cast<float>(std::bit_cast<std::uint32_t>(edge) + 32u) - edge, one.absolute);
    for (float s : {1e-3f, 1e3f, 0.25f}) {
        std::vector<Triangle> scaled = unit;
        for (Triangle& t : scaled)
            for (glm::vec3& p : t.position) p *= s;
        const RayOffsetScale o = rayOffsetScale(scaled);
        EXPECT_FLOAT_EQ(o.origin, s / 32.0f);
        EXPECT_FLOAT_EQ(o.absolute, s / 8388608.0f);
    }
    std::vector<Triangle> moved = unit;
    for (Triangle& t : moved)
        for (glm::vec3& p : t.position) p += glm::vec3(1e4f);
    EXPECT_NEAR(rayOffsetScale(moved).origin, 1.0f / 32.0f, 1e-3f / 32.0f);  // only rounding of 1e4 + 0.5
    // Nothing to measure: the chapter's constants.
    EXPECT_EQ(rayOffsetScale(std::span<const Triangle>{}).origin, 1.0f / 32.0f);
    // The GPU gets the same numbers.
    Scene scene;
    scene.triangles = unit;
    for (Triangle& t : scene.triangles)
        for (glm::vec3& p : t.position) p *= 1e-3f;
    scene.materials.push_back(Material{});
    const gpu::RenderParams params = makeRenderParams(scene, analyseScene(scene), gpu::kLeafEntryFlag, 1000);
    EXPECT_EQ(gpu::offsetRegion(params), rayOffsetScale(scene.triangles).origin);
    EXPECT_EQ(gpu::offsetDistance(params), rayOffsetScale(scene.triangles).absolute);
}

// ---- Degenerate triangles ------------------------------------------------------------------

TEST(HardCaseDegenerate, ZeroAreaTrianglesAreNeverHit) {
    // Triangles with a repeated vertex: two edge functions are exact negatives of each other and
    // the third is exactly 0, so the determinant is exactly 0 for every ray: never hit (a hit
    // would give the renderer a zero geometric normal). Rays aimed at points of the segment.
    const glm::vec3 a(0.3f, -0.2f, 0.1f), b(1.7f, 0.4f, -0.9f);
    std::vector<gpu::TriangleVertices> tris = {{glm::vec4(a, 0), glm::vec4(a, 0), glm::vec4(b, 0)},
                                               {glm::vec4(a, 0), glm::vec4(b, 0), glm::vec4(b, 0)},
                                               {glm::vec4(a, 0), glm::vec4(a, 0), glm::vec4(a, 0)}};
    std::uint32_t hits = 0;
    for (std::uint32_t i = 0; i < 3000; ++i) {
        const float s = uniform(i, 0);
        const glm::vec3 target = (1.0f - s) * a + s * b;
        const glm::vec3 origin =
            target + 4.0f * glm::vec3(uniform(i, 1) - 0.5f, uniform(i, 2) - 0.5f, uniform(i, 3) - 0.5f);
        for (const auto& tri : tris) {
            hits += intersectTriangle<float>(tri, Ray<float>{origin, target - origin}).has_value();
            hits += intersectTriangle<double>(tri, Ray<double>{glm::dvec3(origin), glm::dvec3(target - origin)})
                        .has_value();
        }
    }
    EXPECT_EQ(hits, 0u);
}

}  // namespace
}  // namespace vitrum
