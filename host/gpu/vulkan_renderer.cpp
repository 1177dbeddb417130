#include "gpu/vulkan_renderer.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <optional>

#include "common/huge_pages.h"
#include "gpu/gpu_buffer.h"
#include "gpu/gpu_layout.h"
#include "gpu/scene_fit.h"
#include "gpu/tile_buffers.h"
#include "gpu/tile_size.h"
#include "gpu/trace_kernel_cache.h"
#include "gpu/trace_pipeline.h"
#include "gpu_input/packed_scene.h"
#include "gpu_input/render_params.h"
#include "analysis/scene_features.h"

namespace vitrum {
namespace {

// The persistent kernel's dispatch: one subgroup a this many units of the tile.
constexpr std::uint32_t kUnitsPerPersistentSubgroup = 8;

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

template <class T>
std::span<const T> spanOf(const std::vector<T>& v) {
    return std::span<const T>(v.data(), v.size());
}

// gpu::kObjectMediumTexels an object: its medium's material's `attenuation` (Tf, Ni), its
// priority and its dispersion, its surface's tint, which bindings.glsl's objectMedium(),
// objectPriority(), objectDispersion() and objectTint() read.
std::vector<glm::vec4> objectMediumTexels(const PackedTables& packed) {
    static_assert(gpu::kObjectMediumTexels == 3u, "one push_back a texel below");
    std::vector<glm::vec4> texels;
    for (std::size_t object = 0; object < packed.objectMaterials.size(); ++object) {
        texels.push_back(packed.materials[packed.objectMaterials[object]].attenuation);
        texels.push_back(glm::vec4(std::bit_cast<float>(packed.objectPriorities[object]), packed.objectDispersions[object],
                                   0.0f, 0.0f));
        texels.push_back(glm::vec4(packed.objectTints[object], 0.0f));
    }
    return texels;
}

// bindings.glsl's wavelengthTexels: the count, then each wavelength sample.
std::vector<glm::vec4> wavelengthTexels(const PackedTables& packed) {
    std::vector<glm::vec4> texels{glm::vec4(std::bit_cast<float>(std::uint32_t(packed.wavelengths.size())), 0.0f, 0.0f, 0.0f)};
    for (const WavelengthSample& sample : packed.wavelengths) texels.push_back(glm::vec4(sample.weight, sample.offset));
    return texels;
}

// Every buffer trace.comp reads or writes, each at its binding (shaders/shared/trace_bindings.h).
struct TraceBuffers {
    std::vector<GpuBuffer> owned;
    std::array<const GpuBuffer*, gpu::kTraceBindingCount> bound{};

    GpuBuffer& add(std::uint32_t binding, GpuBuffer buffer) {
        owned.push_back(std::move(buffer));
        bound[binding] = &owned.back();
        return owned.back();
    }
};

// The scene, uploaded once; the render parameters, rewritten before every dispatch; the
// statistics and work cursor, zeroed before and read after it; and the tile's buffers
// (gpu/tile_buffers.h), the pixels among them copied into the image as each tile is done, so that
// the image's size is bound by no buffer limit.
// The arrays a triangle are written into their buffers (packed_scene.h); `rootEntry` is where
// the traversal begins.
TraceBuffers makeBuffers(VulkanDevice& device, const Scene& scene, const Bvh& bvh, const ShadingPlan& shading,
                         glm::uvec2 tile, std::uint32_t pendingRayCapacity, const PhaseCallback& progress,
                         std::uint32_t& rootEntry) {
    TraceBuffers b;
    b.owned.reserve(gpu::kTraceBindingCount);  // `bound` points into it
    const gpu::RenderParams noParams{};
    b.add(gpu::kBindingParams, makeTexelBuffer(device, std::span<const gpu::RenderParams>(&noParams, 1),
                                               "render parameters", MemoryUse::HostShared));
    // The three a triangle (by far the largest), a third each; renderVulkan reported 0 before packing.
    auto uploaded = [&](double fraction) {
        if (progress) progress("uploading the scene", fraction);
    };
    rootEntry = traversalRootEntry(bvh.nodes, bvh.instances);
    b.add(gpu::kBindingNodes,
          makeTexelBufferWritten<gpu::TraversalNode>(
              device, traversalNodeCount(bvh.nodes, bvh.instances), "BVH nodes",
              [&](std::span<gpu::TraversalNode> into) { writeTraversalNodes(bvh.nodes, into, bvh.instances); }));
    uploaded(1.0 / 3.0);
    const std::size_t triangles = bvh.triangleOrder.size();
    b.add(gpu::kBindingVertices, makeTexelBufferWritten<gpu::TriangleVertices>(
                                     device, triangles, "triangle vertices",
                                     [&](std::span<gpu::TriangleVertices> into) { packVertices(scene, bvh, into); }));
    uploaded(2.0 / 3.0);
    b.add(gpu::kBindingShading,
          makeTexelBufferWritten<gpu::ShadingTexel>(
              device, shading.texels(), "triangle normals and uvs",
              [&](std::span<gpu::ShadingTexel> into) { writeShading(scene, bvh, shading, into); }));
    uploaded(1.0);
    const PackedTables packed = packTables(scene);
    b.add(gpu::kBindingMaterials, makeTexelBuffer(device, spanOf(packed.materials), "materials"));
    b.add(gpu::kBindingLights, makeTexelBuffer(device, spanOf(packed.lights), "lights"));
    b.add(gpu::kBindingTextures, makeTexelBuffer(device, spanOf(packed.textures), "texture table"));
    b.add(gpu::kBindingTexels, makeTexelBuffer(device, spanOf(packed.texels), "texture texels"));
    b.add(gpu::kBindingObjectMedia, makeTexelBuffer(device, spanOf(objectMediumTexels(packed)), "object media"));
    b.add(gpu::kBindingWavelengths, makeTexelBuffer(device, spanOf(wavelengthTexels(packed)), "wavelength samples"));
    for (const TileBuffer& buffer : kTileBuffers) {
        const VkDeviceSize bytes = std::max<VkDeviceSize>(tileBufferBytes(buffer, tile, pendingRayCapacity), 16);
        b.add(buffer.binding, GpuBuffer(device, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, buffer.what, buffer.memory));
    }
    b.add(gpu::kBindingStats, GpuBuffer(device, gpu::kDispatchCounterCount * sizeof(std::uint32_t),
                                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "statistics and work cursor"));
    return b;
}

// Trace state, pending rays and traversal stack of one pixel (the tile's buffers but its pixels).
std::uint64_t stateBytesPerPixel(std::uint32_t pendingRayCapacity) {
    std::uint64_t bytes = 0;
    for (const TileBuffer& buffer : kTileBuffers)
        if (buffer.binding != gpu::kBindingPixels)
            bytes += tileBufferBytesPerPixel(buffer, pendingRayCapacity);
    return bytes;
}

// Renders the image tile by tile: each tile's first dispatch, then the resumable kernel until no
// pixel of the tile is left (shaders/suspend.glsl), then the tile's pixels into the image.
class TileLoop {
public:
    TileLoop(VulkanDevice& device, const TraceBuffers& buffers, gpu::RenderParams params,
             const TraceSpecialization& kernel, StatisticsSums sums, bool persistent, TraceKernelCache& kernels,
             RenderStats& stats)
        : device_(device),
          buffers_(buffers),
          params_(params),
          kernel_(kernel),
          sums_(sums),
          persistent_(persistent),
          kernels_(kernels),
          stats_(stats),
          counters_(buffers.bound[gpu::kBindingStats]->as<std::uint32_t>()),
          width_(gpu::imageWidth(params)),
          height_(gpu::imageHeight(params)) {}

    // lavapipe compiles a kernel at its first dispatch: one that traces nothing (an empty tile)
    // measures the compile time alone. A kernel dispatched before (kept in `kernels`) is compiled.
    double compile(const TraceKernelCache::Kernel& k) {
        if (k.compiled) return 0.0;
        const auto start = Clock::now();
        gpu::setTile(params_, glm::uvec4(0u));
        writeParams();
        device_.submitAndWait([&](VkCommandBuffer commands) { k.pipeline.record(commands, 1, 1); });
        k.compiled = true;
        return secondsSince(start);
    }

    // Renders the tiles `schedule` hands out until it has none left, each into the schedule.
    void render(const ComputePipeline& firstPass, const TileGrid& grid, TileSchedule& schedule) {
        const auto start = Clock::now();
        while (const std::optional<std::uint32_t> index = schedule.next()) {
            const glm::uvec4 tile = grid.rect(*index);
            gpu::setTile(params_, tile);
            const std::uint32_t givenUp = persistent_ ? dispatchPersistent(firstPass) : dispatch(firstPass);
            stats_.restartedPixels += givenUp;
            if (givenUp > 0 && !resumable_) {
                const auto buildStart = Clock::now();
                const TraceKernelCache::Kernel k = kernels_.get(device_, kernel_, true, sums_);
                k.pipeline.bind(buffers_.bound);
                compile(k);
                resumable_ = &k.pipeline;
                resumableSeconds_ = secondsSince(buildStart);
                gpu::setTile(params_, tile);
            }
            for (std::uint32_t unfinished = givenUp; unfinished > 0;) unfinished = dispatch(*resumable_);
            schedule.finished(*index, readTile(tile, grid.pixelsInside(*index)));
        }
        stats_.addPhase("render", secondsSince(start) - resumableSeconds_ - readbackSeconds_);
        if (resumable_) stats_.addPhase("resumable kernel", resumableSeconds_);  // its pipeline and compile
        stats_.addPhase("readback", readbackSeconds_);
    }

private:
    void writeParams() { std::memcpy(buffers_.bound[gpu::kBindingParams]->mapped(), &params_, sizeof(params_)); }

    void zeroCounters() { std::memset(counters_, 0, gpu::kDispatchCounterCount * sizeof(std::uint32_t)); }

    // A tile at the image's right or bottom edge may be cut off: only the workgroups over its part
    // inside the image are dispatched.
    glm::uvec2 tileGroups() const {
        const std::uint32_t columns = std::min(gpu::tileWidth(params_), width_ - gpu::tileX(params_));
        const std::uint32_t rows = std::min(gpu::tileHeight(params_), height_ - gpu::tileY(params_));
        return glm::uvec2((columns + kTraceGroupSize - 1) / kTraceGroupSize, (rows + kTraceGroupSize - 1) / kTraceGroupSize);
    }

    // One dispatch of `groups` workgroups; returns the pixels it left unfinished.
    std::uint32_t run(const ComputePipeline& pipeline, glm::uvec2 groups) {
        device_.submitAndWait([&](VkCommandBuffer commands) { pipeline.record(commands, groups.x, groups.y); });
        ++stats_.dispatches;
        stats_.addDispatch(counters_);
        return counters_[TraceStatistic::unfinishedPixels];
    }

    std::uint32_t dispatch(const ComputePipeline& pipeline) {
        writeParams();
        zeroCounters();
        return run(pipeline, tileGroups());
    }

    // The persistent kernel's subgroups take the tile's units until they are used up, or until
    // each has traced as much as lavapipe's loop limit lets it: it is dispatched again, the work
    // cursor kept, until the cursor has reached the units (a subgroup's share of a workgroup each:
    // the pipeline's subgroups are full, of the device's subgroup size), since a subgroup traces
    // every unit it takes. A subgroup that finds no unit costs a pass over the kernel's code
    // (lavapipe runs every branch, masked), so there is one subgroup a kUnitsPerPersistentSubgroup
    // units.
    std::uint32_t dispatchPersistent(const ComputePipeline& pipeline) {
        writeParams();
        zeroCounters();
        const glm::uvec2 groups = tileGroups();
        const std::uint32_t units = groups.x * groups.y * (kTraceGroupSize * kTraceGroupSize / device_.subgroups().size);
        const glm::uvec2 persistentGroups(
            (groups.x * groups.y + kUnitsPerPersistentSubgroup - 1) / kUnitsPerPersistentSubgroup, 1);
        std::uint32_t unfinished = 0;
        for (;;) {
            unfinished += run(pipeline, persistentGroups);
            const std::uint32_t cursor = counters_[gpu::kWorkCursor];
            if (cursor >= units) return unfinished;
            zeroCounters();
            counters_[gpu::kWorkCursor] = cursor;
        }
    }

    // The tile's pixels inside the image, from their slots (trace.comp's traceUnit).
    Image readTile(glm::uvec4 tile, glm::uvec2 inside) {
        const auto start = Clock::now();
        const auto* values = buffers_.bound[gpu::kBindingPixels]->as<glm::vec4>();
        Image pixels(inside.x, inside.y);
        for (std::uint32_t y = 0; y < inside.y; ++y)
            for (std::uint32_t x = 0; x < inside.x; ++x) pixels.at(x, y) = glm::vec3(values[y * tile.z + x]);
        readbackSeconds_ += secondsSince(start);
        return pixels;
    }

    VulkanDevice& device_;
    const TraceBuffers& buffers_;
    gpu::RenderParams params_;
    const TraceSpecialization& kernel_;
    StatisticsSums sums_;
    bool persistent_;
    TraceKernelCache& kernels_;
    RenderStats& stats_;
    std::uint32_t* counters_;
    std::uint32_t width_, height_;
    // Taken when a first dispatch gives up a pixel: most scenes never need it.
    const ComputePipeline* resumable_ = nullptr;
    double resumableSeconds_ = 0;
    double readbackSeconds_ = 0;
};

}  // namespace

void renderVulkanTiles(VulkanDevice& device, const Scene& scene, const Bvh& bvh, const VulkanRenderOptions& options,
                       TileSchedule& schedule, RenderStats& stats) {
    if (scene.triangles.size() > gpu::kMaxTriangles)
        throw InputError("the scene has " + std::to_string(scene.triangles.size()) +
                         " triangles; the Vulkan backend traces at most " + std::to_string(gpu::kMaxTriangles));
    if (options.iterationBudget < kMinIterationBudget)
        throw InputError("an iteration budget of " + std::to_string(options.iterationBudget) +
                         " steps: a dispatch needs at least " + std::to_string(kMinIterationBudget) +
                         " for every pixel to finish");
    stats.backend = "vulkan";
    stats.device = device.name();
    if (options.features) {
        stats.features = *options.features;
    } else {
        const auto analysisStart = Clock::now();
        if (options.progress) options.progress("analysing the scene", 0.0);
        stats.features = analyseScene(scene);
        if (options.progress) options.progress("analysing the scene", 1.0);
        stats.addPhase("analysis", secondsSince(analysisStart));
    }
    const TraceSpecialization kernel =
        options.specialize ? TraceSpecialization::forScene(scene, stats.features) : TraceSpecialization::general();
    stats.kernel = kernel;

    // From the buffers to the last tile, Mesa takes and frees tens of MB of heap (its pipeline
    // creation most), and the tiles' buffers are its memory: in huge pages on a device that runs on
    // the CPU, where the page faults are the process's own (common/huge_pages.h).
    std::optional<HugePageHeap> window;
    if (device.description().cpu) window.emplace();
    auto start = Clock::now();
    if (options.progress) options.progress("uploading the scene", 0.0);
    const TileGrid grid = tileGridFor(device, scene, options);
    stats.tileSize = tileSizeFor(device.description(), options.tileSize);
    std::uint32_t rootEntry = gpu::kLeafEntryFlag;
    // The shading plan's indices (up to 16 bytes a triangle) are let go once the buffers hold them.
    const TraceBuffers buffers = [&] {
        const ShadingPlan shading = planShading(scene, bvh);
        checkSceneFitsDevice(device, scene.triangles.size(), sceneGeometry(bvh, shading), &scene, options.tileSize);
        return makeBuffers(device, scene, bvh, shading, grid.tile, kernel.pendingRayCapacity, options.progress, rootEntry);
    }();
    stats.stateBytesPerPixel = stateBytesPerPixel(kernel.pendingRayCapacity);
    for (std::uint32_t binding = 0; binding < gpu::kTraceBindingCount; ++binding) {
        const bool perTile = std::any_of(kTileBuffers.begin(), kTileBuffers.end(),
                                         [&](const TileBuffer& b) { return b.binding == binding; });
        (perTile ? stats.tileBytes : stats.sceneBytes) += buffers.bound[binding]->size();
    }
    stats.addPhase("upload", secondsSince(start));

    start = Clock::now();
    const StatisticsSums sums = statisticsSumsFor(device, options.statisticsSums);
    // The build without subgroup operations counts each lane's steps as a group's.
    stats.lanesPerGroup = sums == StatisticsSums::atomics ? 1u : device.subgroups().size;
    // Subgroups that go on taking work (trace.comp's main) where the device runs on the CPU:
    // lavapipe gives each of its threads a fixed share of a dispatch's workgroups, so a thread
    // that runs ahead would otherwise wait for the others at the end (docs/gpu-design.md).
    const bool persistent = options.persistentSubgroups && sums == StatisticsSums::shuffles && device.description().cpu;
    TraceKernelCache ownKernels(2);
    TraceKernelCache& kernels = options.kernels ? *options.kernels : ownKernels;
    const TraceKernelCache::Kernel firstPass = kernels.get(device, kernel, false, sums, persistent);
    firstPass.pipeline.bind(buffers.bound);
    stats.addPhase("pipeline", secondsSince(start));

    TileLoop loop(device, buffers, makeRenderParams(scene, stats.features, rootEntry, options.iterationBudget,
                                                   firstInstanceNode(bvh.nodes)),
                  kernel, sums, persistent, kernels, stats);
    stats.addPhase("compile", loop.compile(firstPass));
    if (options.progress) options.progress("rendering", 0.0);
    loop.render(firstPass.pipeline, grid, schedule);
}

TileGrid tileGridFor(const VulkanDevice& device, const Scene& scene, const VulkanRenderOptions& options) {
    const std::uint32_t side = tileSizeFor(device.description(), options.tileSize);
    return TileGrid{scene.camera.width, scene.camera.height,
                    glm::uvec2(std::min(side, scene.camera.width), std::min(side, scene.camera.height))};
}

Image renderVulkan(VulkanDevice& device, const Scene& scene, const Bvh& bvh, const VulkanRenderOptions& options,
                   RenderStats& stats) {
    LocalTiles tiles(tileGridFor(device, scene, options), [&](double fraction) {
        if (options.progress) options.progress("rendering", fraction);
    });
    renderVulkanTiles(device, scene, bvh, options, tiles, stats);
    return std::move(tiles.image());
}

}  // namespace vitrum
