#include "gpu/vulkan_renderer.h"

#include <algorithm>
#include <chrono>
#include <cstring>

#include "gpu/gpu_buffer.h"
#include "gpu/gpu_layout.h"
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

// One texel an object: its medium's material's `attenuation` (Tf, Ni), which bindings.glsl's
// objectMedium() reads.
std::vector<glm::vec4> objectMediumTexels(const PackedScene& packed) {
    std::vector<glm::vec4> texels;
    for (std::uint32_t material : packed.objectMaterials) texels.push_back(packed.materials[material].attenuation);
    return texels;
}

}  // namespace

Image renderVulkan(VulkanDevice& device, const Scene& scene, const Bvh& bvh, const VulkanRenderOptions& options,
                   RenderStats& stats) {
    if (scene.triangles.size() > gpu::kMaxTriangles)
        throw InputError("the scene has " + std::to_string(scene.triangles.size()) +
                         " triangles; the Vulkan backend traces at most " + std::to_string(gpu::kMaxTriangles));
    if (options.iterationBudget < kMinIterationBudget)
        throw InputError("an iteration budget of " + std::to_string(options.iterationBudget) +
                         " steps: a dispatch needs at least " + std::to_string(kMinIterationBudget) +
                         " for every pixel to finish");
    stats.backend = "vulkan";
    stats.device = device.name();
    stats.features = analyseScene(scene);
    const TraceSpecialization kernel =
        options.specialize ? TraceSpecialization::forScene(scene, stats.features) : TraceSpecialization::general();
    stats.kernel = kernel;

    auto start = Clock::now();
    PackedScene packed = packScene(scene, bvh);
    const std::uint32_t width = scene.camera.width;
    const std::uint32_t height = scene.camera.height;
    const std::uint32_t tileSize = tileSizeFor(device.description(), options.tileSize);
    stats.tileSize = tileSize;
    const std::uint32_t tileWidth = std::min(tileSize, width);
    const std::uint32_t tileHeight = std::min(tileSize, height);

    const gpu::RenderParams noParams{};
    GpuBuffer params = makeTexelBuffer(device, std::span<const gpu::RenderParams>(&noParams, 1), "render parameters",
                                       MemoryUse::HostShared);  // rewritten before every dispatch
    GpuBuffer nodes = makeTexelBuffer(device, spanOf(packed.bvh.nodes), "BVH nodes");
    GpuBuffer vertices = makeTexelBuffer(device, spanOf(packed.vertices), "triangle vertices");
    GpuBuffer shading = makeTexelBuffer(device, spanOf(packed.shading), "triangle normals and uvs");
    GpuBuffer materials = makeTexelBuffer(device, spanOf(packed.materials), "materials");
    GpuBuffer lights = makeTexelBuffer(device, spanOf(packed.lights), "lights");
    GpuBuffer textures = makeStorageBuffer(device, spanOf(packed.textures), "texture table");
    GpuBuffer texels = makeStorageBuffer(device, spanOf(packed.texels), "texture texels");
    const std::vector<glm::vec4> mediumTexels = objectMediumTexels(packed);
    GpuBuffer objectMedia = makeTexelBuffer(device, spanOf(mediumTexels), "object media");
    // Like the state buffers, the pixels are one tile's (a slot a pixel), copied into the image
    // as each tile is done: so the image's size is not bound by the device's buffer limits.
    const VkDeviceSize tilePixels = VkDeviceSize(tileWidth) * tileHeight;
    // The kernel writes each pixel, with its slot's status in .w (shaders/suspend.glsl); the host
    // reads the colours.
    GpuBuffer pixels(device, tilePixels * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                     "pixels of one tile", MemoryUse::Readback);
    GpuBuffer states(device, tilePixels * gpu::kTraceStateBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                     "trace state of one tile", MemoryUse::DeviceOnly);
    // The resumable kernel keeps pending rays by slot, the first dispatch by invocation (trace.comp's
    // pendingRayIndex): as many as a tile's whole workgroups have, at most.
    const auto wholeGroups = [](std::uint32_t side) { return (side + kTraceGroupSize - 1) / kTraceGroupSize; };
    const VkDeviceSize tileInvocations =
        VkDeviceSize(wholeGroups(tileWidth)) * wholeGroups(tileHeight) * kTraceGroupSize * kTraceGroupSize;
    const VkDeviceSize pendingRayBytes = tileInvocations * kernel.pendingRayCapacity * sizeof(gpu::PendingRay);
    GpuBuffer pendingRays(device, std::max<VkDeviceSize>(pendingRayBytes, 16), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          "pending rays of one tile", MemoryUse::DeviceOnly);
    GpuBuffer traversalStacks(device, tilePixels * gpu::kTraversalStackSize * sizeof(std::uint32_t),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "traversal stacks of one tile", MemoryUse::DeviceOnly);
    stats.stateBytesPerPixel = gpu::kTraceStateBytes + kernel.pendingRayCapacity * sizeof(gpu::PendingRay) +
                               gpu::kTraversalStackSize * sizeof(std::uint32_t);
    GpuBuffer counters(device, gpu::kDispatchCounterCount * sizeof(std::uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                       "statistics and work cursor");
    stats.addPhase("upload", secondsSince(start));

    start = Clock::now();
    const std::array<const GpuBuffer*, gpu::kTraceBindingCount> bound{
        &params, &nodes, &vertices, &shading, &materials, &lights, &textures,
        &texels, &objectMedia, &pixels, &states, &counters, &pendingRays, &traversalStacks};
    const StatisticsSums sums = statisticsSumsFor(device, options.statisticsSums);
    // The build without subgroup operations counts each lane's steps as a group's.
    stats.lanesPerGroup = sums == StatisticsSums::atomics ? 1u : device.subgroups().size;
    // Subgroups that go on taking work (trace.comp's main) where the device runs on the CPU:
    // lavapipe gives each of its threads a fixed share of a dispatch's workgroups, so a thread
    // that runs ahead would otherwise wait for the others at the end (docs/gpu-design.md).
    const bool persistent = options.persistentSubgroups && sums == StatisticsSums::shuffles &&
                            device.description().cpu;
    TraceKernelCache ownKernels(2);
    TraceKernelCache& kernels = options.kernels ? *options.kernels : ownKernels;
    const TraceKernelCache::Kernel firstPass = kernels.get(device, kernel, false, sums, persistent);
    firstPass.pipeline.bind(bound);
    stats.addPhase("pipeline", secondsSince(start));

    gpu::RenderParams p = makeRenderParams(scene, stats.features, packed.bvh.rootEntry, options.iterationBudget);
    const std::uint32_t tilesX = (width + tileWidth - 1) / tileWidth;
    const std::uint32_t tilesY = (height + tileHeight - 1) / tileHeight;
    auto* counterValues = counters.as<std::uint32_t>();

    // lavapipe compiles a kernel at its first dispatch: one that traces nothing (an empty tile)
    // measures the compile time alone. A kernel dispatched before (kept in `kernels`) is compiled.
    auto compile = [&](const TraceKernelCache::Kernel& k) {
        if (k.compiled) return 0.0;
        const auto compileStart = Clock::now();
        gpu::setTile(p, glm::uvec4(0u));
        std::memcpy(params.mapped(), &p, sizeof(p));
        device.submitAndWait([&](VkCommandBuffer commands) { k.pipeline.record(commands, 1, 1); });
        k.compiled = true;
        return secondsSince(compileStart);
    };
    stats.addPhase("compile", compile(firstPass));

    // Taken when a first dispatch gives up a pixel: most scenes never need it.
    const ComputePipeline* resumable = nullptr;
    double resumableSeconds = 0;
    // A tile at the image's right or bottom edge may be cut off: only the workgroups over its part
    // inside the image are dispatched.
    auto tileGroups = [&] {
        return glm::uvec2((std::min(gpu::tileWidth(p), width - gpu::tileX(p)) + kTraceGroupSize - 1) / kTraceGroupSize,
                          (std::min(gpu::tileHeight(p), height - gpu::tileY(p)) + kTraceGroupSize - 1) / kTraceGroupSize);
    };
    // One dispatch of `groups` workgroups; returns the pixels it left unfinished.
    auto run = [&](const ComputePipeline& pipeline, glm::uvec2 groups) {
        device.submitAndWait([&](VkCommandBuffer commands) { pipeline.record(commands, groups.x, groups.y); });
        ++stats.dispatches;
        stats.addDispatch(counterValues);
        return counterValues[TraceStatistic::unfinishedPixels];
    };
    auto dispatch = [&](const ComputePipeline& pipeline) {
        std::memcpy(params.mapped(), &p, sizeof(p));
        std::memset(counterValues, 0, gpu::kDispatchCounterCount * sizeof(std::uint32_t));
        return run(pipeline, tileGroups());
    };
    // The persistent kernel's subgroups take the tile's units until they are used up, or until
    // each has traced as much as lavapipe's loop limit lets it: it is dispatched again, the work
    // cursor kept, until the cursor has reached the units (a subgroup's share of a workgroup each:
    // the pipeline's subgroups are full, of the device's subgroup size), since a subgroup traces
    // every unit it takes. A subgroup that finds no unit costs a pass over the kernel's code
    // (lavapipe runs every branch, masked), so there is one subgroup a kUnitsPerPersistentSubgroup
    // units.
    auto dispatchPersistent = [&](const ComputePipeline& pipeline) {
        std::memcpy(params.mapped(), &p, sizeof(p));
        std::memset(counterValues, 0, gpu::kDispatchCounterCount * sizeof(std::uint32_t));
        const glm::uvec2 groups = tileGroups();
        const std::uint32_t units = groups.x * groups.y * (kTraceGroupSize * kTraceGroupSize / device.subgroups().size);
        const glm::uvec2 persistentGroups(
            (groups.x * groups.y + kUnitsPerPersistentSubgroup - 1) / kUnitsPerPersistentSubgroup, 1);
        std::uint32_t unfinished = 0;
        for (;;) {
            unfinished += run(pipeline, persistentGroups);
            const std::uint32_t cursor = counterValues[gpu::kWorkCursor];
            if (cursor >= units) return unfinished;
            std::memset(counterValues, 0, gpu::kDispatchCounterCount * sizeof(std::uint32_t));
            counterValues[gpu::kWorkCursor] = cursor;
        }
    };
    Image image(width, height);
    double readbackSeconds = 0;
    // The tile's pixels inside the image, from their slots (trace.comp's traceUnit) to the image.
    auto readTile = [&](glm::uvec4 tile) {
        const auto readStart = Clock::now();
        const auto* values = pixels.as<glm::vec4>();
        const std::uint32_t columns = std::min(tile.z, width - tile.x);
        const std::uint32_t rows = std::min(tile.w, height - tile.y);
        for (std::uint32_t y = 0; y < rows; ++y)
            for (std::uint32_t x = 0; x < columns; ++x)
                image.at(tile.x + x, tile.y + y) = glm::vec3(values[y * tile.z + x]);
        readbackSeconds += secondsSince(readStart);
    };
    start = Clock::now();
    for (std::uint32_t ty = 0; ty < tilesY; ++ty) {
        for (std::uint32_t tx = 0; tx < tilesX; ++tx) {
            const glm::uvec4 tile(tx * tileWidth, ty * tileHeight, tileWidth, tileHeight);
            gpu::setTile(p, tile);
            const std::uint32_t givenUp =
                persistent ? dispatchPersistent(firstPass.pipeline) : dispatch(firstPass.pipeline);
            stats.restartedPixels += givenUp;
            if (givenUp > 0 && !resumable) {
                const auto buildStart = Clock::now();
                const TraceKernelCache::Kernel k = kernels.get(device, kernel, true, sums);
                k.pipeline.bind(bound);
                compile(k);
                resumable = &k.pipeline;
                resumableSeconds = secondsSince(buildStart);
                gpu::setTile(p, tile);
            }
            for (std::uint32_t unfinished = givenUp; unfinished > 0;) unfinished = dispatch(*resumable);
            readTile(tile);
            if (options.progress) options.progress(double(ty * tilesX + tx + 1) / double(tilesX * tilesY));
        }
    }
    stats.addPhase("render", secondsSince(start) - resumableSeconds - readbackSeconds);
    if (resumable) stats.addPhase("resumable kernel", resumableSeconds);  // its pipeline and compile
    stats.addPhase("readback", readbackSeconds);
    return image;
}

}  // namespace vitrum
