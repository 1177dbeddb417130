// `vitrum render SCENE -o OUT [options]`
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <future>
#include <new>
#include <iostream>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/arguments.h"
#include "app/commands.h"
#include "analysis/scene_features.h"
#include "app/render_options.h"
#include "bvh/bvh.h"
#include "common/atomic_file.h"
#include "common/byte_size.h"
#include "common/error.h"
#include "common/huge_pages.h"
#include "common/progress.h"
#include "cpu/reference_renderer.h"
#include "distributed/distributed_render.h"
#include "distributed/launch.h"
#include "distributed/mpi_job.h"
#include "gpu/gpu_buffer.h"
#include "gpu/scene_fit.h"
#include "gpu/tile_buffers.h"
#include "gpu/tile_size.h"
#include "gpu/vulkan_device.h"
#include "gpu/vulkan_renderer.h"
#include "image/image.h"
#include "image/pixel_limit.h"
#include "scene/scene_fingerprint.h"
#include "scene/scene_loader.h"
#include "shared/gpu_types.h"

namespace vitrum {
namespace {

// Said before a render whose work (pixels x samples x depth) is far beyond the usual (a 16384 x
// 16384 image at 4096 samples was accepted without a word, and took about 15 hours): its size, and
// a lower bound on its time at the fastest rate lavapipe traces primary rays alone here
// (docs/performance.md, about 20 Mrays/s).
std::string largeRenderNote(const Scene& scene) {
    constexpr double kLargeWork = 1e10;
    constexpr double kFastestRaysPerSecond = 20e6;
    const Camera& c = scene.camera;
    const RenderSettings& s = scene.settings;
    const double primary = double(c.width) * c.height * s.samplesPerPixel;
    if (primary * std::max(s.maxDepth, 1u) < kLargeWork) return "";
    const double seconds = primary / kFastestRaysPerSecond;
    char time[64];
    if (seconds < 90.0) std::snprintf(time, sizeof(time), "a minute");
    else if (seconds < 3600.0) std::snprintf(time, sizeof(time), "%.0f minutes", seconds / 60.0);
    else std::snprintf(time, sizeof(time), "%.1f hours", seconds / 3600.0);
    char text[320];
    std::snprintf(text, sizeof(text),
                  "a large render: %.3g primary rays (%u x %u pixels x %u samples), each a tree of up to %u levels; "
                  "at 20 Mrays/s, lavapipe's fastest for primary rays alone, it takes at least %s",
                  primary, c.width, c.height, s.samplesPerPixel, s.maxDepth, time);
    return text;
}

// What each rank of an MPI job takes of its host, before its device is opened
// (distributed/launch.h); the progress bar and warnings are rank 0's alone.
void joinJob(MpiJob& job, RenderCommand& command) {
    if (command.backend != Backend::Vulkan && job.size() > 1)
        throw InputError("--backend cpu renders in one process; run it without mpirun, or with -np 1");
    shareCpuThreads(job.localSize());
    if (command.backend == Backend::Vulkan && command.device.empty())
        command.device = deviceForLocalRank(VulkanDevice::listDevices(), job.localRank());
    if (job.rank() != 0) {
        setenv("VITRUM_PROGRESS", "0", 1);
        silenceWarnings();
    } else {
        // mpirun passes stderr through a pipe: rank 0 draws its bar unless told not to.
        setenv("VITRUM_PROGRESS", "1", 0);
    }
}

// The ranks agree on one grid of tiles (the smallest tile any rank's device takes) and check that
// they loaded the same scene: a host with other copies of the files would render its tiles of
// another image.
void agreeOnTheImage(MpiJob& job, const VulkanDevice& device, const Scene& scene, const std::string& scenePath,
                     VulkanRenderOptions& options) {
    options.tileSize = job.smallest(tileSizeFor(device.description(), options.tileSize));
    const std::vector<std::uint64_t> prints = job.allGather(sceneFingerprint(scene));
    if (prints[std::size_t(job.rank())] != prints[0])
        throw InputError(scenePath + " loaded here is not the scene rank 0 loaded: every rank must read the same "
                                     "files (docs/distributed.md)");
}

void printDistributed(const DistributedReport& report) {
    std::printf("ranks: %zu, tiles", report.ranks.size());
    for (const RankReport& r : report.ranks)
        std::printf("%s%llu", r.rank == 0 ? " " : " + ", (unsigned long long)r.tiles);
    std::printf(" of %llu; %s sent, %.3f s assembling on rank 0\n", (unsigned long long)report.tiles,
                describeBytes(report.bytesSent).c_str(), report.assembleSeconds);
}

nlohmann::json toJson(const DistributedReport& report) {
    nlohmann::json ranks = nlohmann::json::array();
    for (const RankReport& r : report.ranks)
        ranks.push_back({{"rank", r.rank}, {"host", r.host}, {"device", r.device}, {"tiles", r.tiles},
                         {"render_seconds", r.renderSeconds}});
    return {{"ranks", ranks}, {"tiles", report.tiles}, {"bytes_sent", report.bytesSent},
            {"assemble_seconds", report.assembleSeconds}};
}

}  // namespace

int renderCommand(int argc, char** argv, int first, MpiJob* job) {
    if (wantsHelp(argc, argv, first)) {
        std::cout << renderHelp();
        return 0;
    }
    RenderCommand command = parseRenderCommand(argc, argv, first);
    if (job) joinJob(*job, command);
    const bool writes = !job || job->rank() == 0;  // in a job, rank 0 writes the image
    if (writes) checkOutputs(command);
    using Clock = std::chrono::steady_clock;
    auto start = Clock::now();

    // The device comes first, so that a scene too large for it is refused before any long work:
    // a texture by its header, before it is decoded; the rest before the BVH build.
    std::optional<VulkanDevice> device;
    TexelLimit texelLimit;
    if (command.backend == Backend::Vulkan) {
        const HugePageHeap window;  // the driver's loading and self-check (common/huge_pages.h)
        device.emplace(command.device);
        const BufferLimit limit = bufferLimit(*device, BufferKind::Texel);
        texelLimit = {limit.bytes, describeBufferLimit(*device, BufferKind::Texel)};
    }
    const double deviceSeconds = std::chrono::duration<double>(Clock::now() - start).count();

    auto loadStart = Clock::now();
    PhaseProgress phases;  // loading and building a big model take seconds (issue 52)
    SceneLoadOptions loadOptions{texelLimit, phases.callback()};
    loadOptions.camera = command.camera;
    loadOptions.variant = command.variant;
    loadOptions.instancing = command.instancing;
    if (device)
        loadOptions.checkTriangles = [&](std::size_t triangles) {
            checkSceneFitsDevice(*device, triangles, sceneGeometryAtLeast(triangles), nullptr, command.gpu.tileSize);
        };
    Scene scene = loadScene(command.scenePath, loadOptions);
    if (writes) checkOutputsSpareTheScenesImages(command, scene);
    applyOverrides(command, scene, texelLimit);
    if (const std::string note = largeRenderNote(scene); !note.empty()) warn(note);
    const double loadSeconds = std::chrono::duration<double>(Clock::now() - loadStart).count();
    if (job && device) agreeOnTheImage(*job, *device, scene, command.scenePath, command.gpu);
    if (device)
        checkSceneFitsDevice(*device, scene.triangles.size(), sceneGeometryAtLeast(scene.triangles.size()), &scene,
                             command.gpu.tileSize);

    RenderStats stats;
    DistributedReport distributed;
    stats.addPhase("load", loadSeconds);
    Image image;
    Bvh bvh;
    try {
        // The scene's analysis reads only the triangles, as the BVH build does: the two run side by
        // side (each took seconds on a 3M-triangle model, issue 52).
        std::future<std::pair<SceneFeatures, double>> analysis = std::async(std::launch::async, [&] {
            const auto analysisStart = Clock::now();
            SceneFeatures features = analyseScene(scene);
            return std::pair(std::move(features), std::chrono::duration<double>(Clock::now() - analysisStart).count());
        });
        bvh = buildSceneBvh(scene, [&](double fraction) { phases.update("building the BVH", fraction); });
        phases.finish();
        stats.addPhase("bvh", bvh.stats.buildSeconds);
        const auto [features, analysisSeconds] = analysis.get();
        stats.addPhase("analysis", analysisSeconds);
        if (const std::string open = openGlassWarning(scene, features); !open.empty()) warn(open);
        command.gpu.features = &features;
        // The renderers report "rendering" from 0 as they begin to trace, after their analysis and
        // upload (the Vulkan one reports those phases too).
        if (command.backend == Backend::Vulkan) {
            stats.addPhase("device", deviceSeconds);
            command.gpu.progress = phases.callback();
            if (job) image = renderDistributed(*job, *device, scene, bvh, command.gpu, stats, distributed);
            else image = renderVulkan(*device, scene, bvh, command.gpu, stats);
            if (device->validationMessages() > 0)
                throw std::runtime_error(std::to_string(device->validationMessages()) +
                                         " Vulkan validation messages (see above)");
        } else {
            ReferenceOptions options{.doublePrecision = command.doublePrecision,
                                     .threads = command.threads,
                                     .progress = [&](double fraction) { phases.update("rendering", fraction); },
                                     .features = &features};
            image = renderReference(scene, bvh, options, stats);
        }
    } catch (const std::bad_alloc&) {
        throw InputError(command.scenePath + ": not enough memory to render it (" + std::to_string(scene.triangles.size()) +
                         " triangles, " + std::to_string(scene.camera.width) + " x " +
                         std::to_string(scene.camera.height) + " pixels)");
    }
    if (!writes) return 0;
    auto writeStart = Clock::now();
    writeImage(image, command.outputPath);
    stats.addPhase("write", std::chrono::duration<double>(Clock::now() - writeStart).count());

    double renderSeconds = stats.seconds("render");
    double totalSeconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::printf("device: %s (%s)\n", stats.device.c_str(), stats.backend.c_str());
    std::printf("image: %ux%u, %u spp, max depth %u -> %s\n", scene.camera.width, scene.camera.height,
                scene.settings.samplesPerPixel, scene.settings.maxDepth, command.outputPath.c_str());
    if (stats.kernel)
        std::printf("kernel: %s (medium stack %u, pending rays %u), compiled in %.3f s\n",
                    stats.kernel->specialized ? "specialized for the scene" : "general", stats.kernel->mediumStackDepth,
                    stats.kernel->pendingRayCapacity, stats.seconds("pipeline") + stats.seconds("compile"));
    if (stats.restartedPixels > 0)
        std::printf("resumable kernel: %llu pixels needed more than one dispatch, restarted (%.3f s to build it)\n",
                    (unsigned long long)stats.restartedPixels, stats.seconds("resumable kernel"));
    std::printf("time: %.3f s rendering, %.3f s in all\n", renderSeconds, totalSeconds);
    std::printf("rays: %llu (%.2f Mrays/s): %llu primary, %llu shadow, %llu reflection, %llu refraction",
                (unsigned long long)stats.totalRays(),
                renderSeconds > 0 ? double(stats.totalRays()) / renderSeconds * 1e-6 : 0.0,
                (unsigned long long)stats.primaryRays, (unsigned long long)stats.shadowRays,
                (unsigned long long)stats.reflectionRays, (unsigned long long)stats.refractionRays);
    if (stats.passThroughRays > 0)
        std::printf(", %llu through partly covered surfaces", (unsigned long long)stats.passThroughRays);
    std::printf("\n");
    if (job) printDistributed(distributed);
    if (stats.loopLimitSuspected || stats.traversalStackOverflows || stats.rayStackOverflows ||
        stats.mediumStackOverflows)
        std::fprintf(stderr, "vitrum: warning: limits hit: see --stats (loop limit %llu, traversal stack %llu, "
                             "ray stack %llu, medium stack %llu)\n",
                     (unsigned long long)stats.loopLimitSuspected,
                     (unsigned long long)stats.traversalStackOverflows,
                     (unsigned long long)stats.rayStackOverflows,
                     (unsigned long long)stats.mediumStackOverflows);
    if (!command.statsPath.empty()) {
        nlohmann::json json = toJson(stats);
        json["scene"] = command.scenePath;
        json["image"] = {{"width", scene.camera.width}, {"height", scene.camera.height}};
        json["settings"] = {{"spp", scene.settings.samplesPerPixel},
                            {"max_depth", scene.settings.maxDepth},
                            {"min_weight", scene.settings.minWeight},
                            {"fresnel", int(scene.settings.fresnel)}};
        json["triangles"] = scene.triangles.size();
        if (!scene.instances.empty()) json["instances"] = scene.instances.size();
        if (job) json["distributed"] = toJson(distributed);
        writeFileAtomically(command.statsPath, json.dump(2) + "\n");
    }
    return 0;
}

}  // namespace vitrum
