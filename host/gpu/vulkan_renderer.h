// The Vulkan backend: uploads a packed scene, then renders the image tile by tile. Each tile is
// dispatched again and again, each dispatch bounded to `iterationBudget` steps per SIMD group, until
// every pixel of the tile has finished its ray tree (shaders/trace.comp explains why).
#pragma once

#include <cstdint>
#include <functional>

#include "analysis/scene_features.h"
#include "bvh/bvh.h"
#include "common/progress.h"
#include "gpu/tile_schedule.h"
#include "gpu/trace_pipeline.h"
#include "gpu/vulkan_device.h"
#include "image/image.h"
#include "stats/render_stats.h"
#include "scene/scene.h"

namespace vitrum {

class TraceKernelCache;

// The smallest iteration budget with which every dispatch moves each SIMD group on (a node
// visited, a triangle tested or a traversal finished and shaded): the triangle loop of a
// traversal resumed inside a leaf starts after three counted steps (the round's, the traversal
// loop's and the skipped node loop's), so with fewer a pixel could stop before it again and again
// and never finish.
inline constexpr std::uint32_t kMinIterationBudget = 4;

struct VulkanRenderOptions {
    // Loop steps per SIMD group and dispatch: lavapipe ends a shader's loops after 65,535
    // iterations of the group, and the kernel counts those (trace.comp) but for the few after its
    // last counted step; three quarters of the limit leave room for those and for drivers that
    // count differently. Larger values (tests only) let the limit show.
    std::uint32_t iterationBudget = 49152;
    // Pixels a side; 0: the device's default (gpu/tile_size.h: 256 on lavapipe, as large as
    // memory allows on a GPU). A pixel's buffers take 0.5-1.5 KiB.
    std::uint32_t tileSize = 0;
    // Build the kernel for what the scene needs (gpu_input/trace_specialization.h); false: the
    // general kernel, which decides everything at run time (same image, more code to run).
    bool specialize = true;
    // How the kernel adds up its statistics: this way, or the nearest way before it that the
    // device can run (gpu/trace_pipeline.h's statisticsSumsFor). The same numbers every way.
    StatisticsSums statisticsSums = StatisticsSums::shuffles;
    // On a device that runs on the CPU, with shuffles: the first dispatch's subgroups take units
    // of work until none is left, so that the CPU's threads share the work however fast each runs.
    // The same image and statistics either way (but the dispatches).
    bool persistentSubgroups = true;
    // Kernels kept from earlier renders on this device (gpu/trace_kernel_cache.h): each is created
    // and compiled once. Null: this render creates its own and drops them at the end.
    TraceKernelCache* kernels = nullptr;
    // The scene's analysis (analysis/scene_features.h), when the caller has made it already (the
    // render command makes it alongside the BVH build). Null: the render makes it.
    const SceneFeatures* features = nullptr;
    // "analysing the scene" (0, then 1), "uploading the scene" by its buffers, then "rendering"
    // from 0 as tracing begins, by tiles.
    PhaseCallback progress;
};

// Renders every tile of the image into one image.
Image renderVulkan(VulkanDevice& device, const Scene& scene, const Bvh& bvh, const VulkanRenderOptions& options,
                   RenderStats& stats);

// Renders the tiles `schedule` hands out (of tileGridFor's grid), each into the schedule.
void renderVulkanTiles(VulkanDevice& device, const Scene& scene, const Bvh& bvh, const VulkanRenderOptions& options,
                       TileSchedule& schedule, RenderStats& stats);

// The tiles of the scene's image on this device with these options (options.tileSize, or the
// device's default).
TileGrid tileGridFor(const VulkanDevice& device, const Scene& scene, const VulkanRenderOptions& options);

}  // namespace vitrum
