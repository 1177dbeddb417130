// The CPU reference renderer: ../shared/docs/render-model.md written as plainly as possible.
// Recursive, multithreaded over rows, in float (to hold the GPU to it) or double (ground truth).
// Built with -ffp-contract=off so that float results are not changed by FMA contraction.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/bvh_traversal.h"
#include "image/image.h"
#include "stats/render_stats.h"
#include "scene/scene.h"

namespace vitrum {

// A ray the reference traced, kept so that a benchmark can trace the same rays with another
// traversal (bench/whitted_bench.cpp).
struct TracedRay {
    glm::vec3 origin;
    float tMin;
    glm::vec3 direction;  // not unit for shadow rays: o + t d reaches the light at t = 1
    float tMax;
    bool anyHit;  // a shadow ray (any hit in (tMin, tMax)); otherwise the closest hit is wanted
    std::uint32_t pixel;  // whose ray tree it belongs to: y * width + x
};

// Where the reference finds what a ray hits, if not in vitrum's BVH: another traversal of the same
// triangles, for a benchmark (bench/embree_renderer.cpp). Rays are float; hits name triangles by
// their index in the BVH's order (Bvh::triangleOrder), as traceClosest's do. Scenes without
// instances (Scene::instances) or cut-out surfaces (Material::cutout) only: rendering refuses the
// others.
class RayIntersector {
public:
    virtual ~RayIntersector() = default;
    virtual std::optional<TriangleHit<float>> closest(const Ray<float>& ray) const = 0;
    virtual bool any(const Ray<float>& ray) const = 0;  // a hit with tMin < t < tMax
    virtual void all(const Ray<float>& ray, std::vector<TriangleHit<float>>& hits) const = 0;  // appends each
};

struct ReferenceOptions {
    bool doublePrecision = false;
    unsigned threads = 0;  // 0: all hardware threads
    std::function<void(double)> progress;  // fraction done: 0 as tracing begins, then by rows, one call at a time
    // When set, every primary, shadow, reflected and refracted ray is appended (touching probes
    // are not rays of the tree and are left out): the pixels in no particular order, each
    // pixel's rays together and in the order they were traced.
    std::vector<TracedRay>* tracedRays = nullptr;
    // When set (float only), rays are traced by it instead of the BVH's nodes, which may then be
    // empty: only Bvh::triangleOrder is read.
    const RayIntersector* intersector = nullptr;
    // The scene's analysis, when the caller has made it already; null: the render makes it.
    const SceneFeatures* features = nullptr;
};

// Renders scene.camera with scene.settings. `bvh` was built over scene.triangles.
Image renderReference(const Scene& scene, const Bvh& bvh, const ReferenceOptions& options, RenderStats& stats);

}  // namespace vitrum
