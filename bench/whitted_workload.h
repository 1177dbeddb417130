// The Whitted workload of docs/performance.md: every glass scene at 320x240, 1 spp, max_depth 10,
// and the rays of its trees as the CPU reference traces them (primary, shadow, reflected,
// refracted). bench/whitted_bench.cpp traces them with Embree and vitrum's traversal,
// bench/ray_query_bench.cpp with a driver's ray queries: the same rays for every comparison.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "bvh/bvh.h"
#include "cpu/reference_renderer.h"
#include "scene/scene_loader.h"
#include "stats/render_stats.h"

namespace vitrum::bench {

constexpr std::uint32_t kWhittedWidth = 320, kWhittedHeight = 240;
constexpr std::uint32_t kWhittedMaxDepth = 10;
// Relative to the source tree; the same list as bench/compare-drivers.
inline constexpr const char* kWhittedScenes[] = {
    "scenes/course/geospheres_5x5_glass.json",
    "scenes/demo.json",
    "scenes/bubble.json",
    "scenes/water_glass.json",
    "scenes/prism.json",
    "scenes/plastics_green_glass.json",
    "scenes/diamond.json",
};

// One scene of the workload: the scene at the workload's size and depth (its own spp, 1 for all
// of them), its BVH, the triangles in BVH order as the GPU reads them. Every copy of a repeated
// mesh is stored (`--no-instancing`): Embree and the driver's ray queries trace the triangle list.
struct WhittedScene {
    Scene scene;
    Bvh bvh;
    std::vector<gpu::TriangleVertices> triangles;
};

inline WhittedScene loadWhittedScene(const std::filesystem::path& file) {
    WhittedScene w;
    w.scene = loadScene(file, SceneLoadOptions{.instancing = false});
    w.scene.camera.width = kWhittedWidth;
    w.scene.camera.height = kWhittedHeight;
    w.scene.settings.maxDepth = kWhittedMaxDepth;
    w.bvh = buildSceneBvh(w.scene);
    w.triangles = packTriangleVertices(w.bvh, w.scene.triangles);
    return w;
}

// Every ray the CPU reference traces while it renders the scene (ReferenceOptions::tracedRays:
// each pixel's rays together, in the order traced; the pixels in no particular order).
inline std::vector<TracedRay> whittedRays(const WhittedScene& w) {
    std::vector<TracedRay> rays;
    RenderStats stats;
    ReferenceOptions reference;
    reference.tracedRays = &rays;
    renderReference(w.scene, w.bvh, reference, stats);
    return rays;
}

}  // namespace vitrum::bench
