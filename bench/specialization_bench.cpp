// The specialized kernel against the general one, scene by scene, on the Vulkan device (lavapipe
// by default): render time (median of several runs, the two kernels taking turns), the time to
// create the pipeline and compile it at the first dispatch with an empty and with a warm Mesa
// shader cache, the per-pixel state, and the work the specialized kernel skips. Writes a Markdown
// report (docs/specialization.md); `make bench-specialization`.
//
//   vitrum_bench_specialization OUT.md [RUNS] [WIDTH HEIGHT]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>
#include <vector>

#include <unistd.h>

#include "bench_support.h"
#include "bvh/bvh.h"
#include "gpu/vulkan_device.h"
#include "gpu/vulkan_renderer.h"
#include "scene/scene_loader.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

const char* kScenes[] = {
    "scenes/course/geospheres_5x5.json",        // Lambert only, constant background
    "scenes/lambert_spheres.json",              // Lambert and opaque dielectric
    "scenes/course/cornell_box2.json",          // the course's Cornell box with one glass sphere
    "scenes/course/geospheres_5x5_glass.json",  // 25 separate glass spheres
    "scenes/demo.json",                         // glass and tinted glass apart, plastic
    "scenes/touching_cubes.json",               // glass touching glass
    "scenes/bubble.json",                       // an air bubble nested in glass
    "scenes/water_glass.json",                  // water in a glass
    "scenes/glass_sphere_spherical.json",       // an environment map
};

// One kernel's measurements on one scene.
struct Measured {
    double coldCompile = 0;            // pipeline creation + first dispatch, empty shader cache
    std::vector<double> warmCompiles;  // the same with the cache the cold runs filled, a run each
    std::vector<double> renders;       // tile dispatches only, a run each
    RenderStats stats;
    Image image;
};

// Both kernels on one scene. The warm renders take turns (the general kernel first in even runs,
// the specialized one in odd runs), so that the machine's drift over the runs falls on both alike,
// and the speed-up is the median of each run's pair.
struct Compared {
    Measured general, special;
    std::vector<double> speedUps;  // a run each: general render / specialized render
};

Measured& kernel(Compared& c, bool specialize) { return specialize ? c.special : c.general; }

Compared compare(const Scene& scene, const Bvh& bvh, int runs, const fs::path& cacheRoot) {
    // A shader cache of its own, empty at first: Mesa reads MESA_SHADER_CACHE_DIR when the device
    // is made, and writes the cache out when it is destroyed. The two kernels are different
    // shaders to it, so each one's first render finds nothing of its own there.
    const fs::path cache = cacheRoot / scene.source.stem();
    fs::remove_all(cache);
    fs::create_directories(cache);
    setenv("MESA_SHADER_CACHE_DIR", cache.c_str(), 1);
    auto render = [&](VulkanDevice& device, bool specialize, Measured& m) {
        VulkanRenderOptions options;
        options.specialize = specialize;
        RenderStats stats;
        m.image = renderVulkan(device, scene, bvh, options, stats);
        m.stats = stats;
        return stats;
    };
    Compared c;
    for (bool specialize : {false, true}) {
        VulkanDevice device("");
        const RenderStats stats = render(device, specialize, kernel(c, specialize));
        kernel(c, specialize).coldCompile = stats.seconds("pipeline") + stats.seconds("compile");
    }
    VulkanDevice device("");
    for (int run = 0; run < runs; ++run) {
        for (bool specialize : {run % 2 == 1, run % 2 == 0}) {
            Measured& m = kernel(c, specialize);
            const RenderStats stats = render(device, specialize, m);
            m.warmCompiles.push_back(stats.seconds("pipeline") + stats.seconds("compile"));
            m.renders.push_back(stats.seconds("render"));
        }
        c.speedUps.push_back(c.general.renders.back() / c.special.renders.back());
    }
    return c;
}

int run(int argc, char** argv) {
    if (argc < 2) {
        std::cerr << "usage: vitrum_bench_specialization OUT.md [RUNS] [WIDTH HEIGHT]\n";
        return 2;
    }
    const fs::path out = argv[1];
    const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
    const std::uint32_t width = argc > 4 ? std::uint32_t(std::atoi(argv[3])) : 320;
    const std::uint32_t height = argc > 4 ? std::uint32_t(std::atoi(argv[4])) : 240;
    const fs::path cacheRoot = fs::temp_directory_path() / ("vitrum-bench-cache-" + std::to_string(::getpid()));

    std::ostringstream rows, work;
    std::string deviceName;
    std::uint32_t tileSize = 0;  // the device's default
    for (const char* file : kScenes) {
        Scene scene = loadScene(fs::path(VITRUM_SOURCE_DIR) / file);
        scene.camera.width = width;
        scene.camera.height = height;
        Bvh bvh = buildSceneBvh(scene);
        std::cerr << file << ": " << std::flush;
        const Compared c = compare(scene, bvh, runs, cacheRoot);
        const Measured& general = c.general;
        const Measured& special = c.special;
        deviceName = general.stats.device;
        tileSize = special.stats.tileSize;
        const bool identical =
            general.image.pixels.size() == special.image.pixels.size() &&
            std::memcmp(general.image.pixels.data(), special.image.pixels.data(),
                        general.image.pixels.size() * sizeof(glm::vec3)) == 0;
        const double speedUp = bench::median(c.speedUps);
        std::cerr << bench::fixed(speedUp, 2) << "x\n";
        const TraceSpecialization& k = *special.stats.kernel;
        const std::string name = fs::path(file).stem().string();
        rows << "| " << name << " | " << bench::fixed(bench::median(general.renders), 3) << " | "
             << bench::fixed(bench::median(special.renders), 3) << " | **" << bench::fixed(speedUp, 2) << "x** | "
             << bench::fixed(bench::quantile(c.speedUps, 0.25), 2) << "-" << bench::fixed(bench::quantile(c.speedUps, 0.75), 2)
             << "x | " << bench::fixed(general.coldCompile, 2) << " | " << bench::fixed(special.coldCompile, 2) << " | "
             << bench::fixed(bench::median(general.warmCompiles), 3) << " | "
             << bench::fixed(bench::median(special.warmCompiles), 3) << " | " << (identical ? "yes" : "**no**") << " |\n";
        const double tilePixels = double(std::min(tileSize, width)) * std::min(tileSize, height);
        work << "| " << name << " | " << special.stats.totalRays() << " | " << k.mediumStackDepth << " | "
             << k.pendingRayCapacity << " | " << general.stats.stateBytesPerPixel << " -> "
             << special.stats.stateBytesPerPixel << " | "
             << bench::fixed(double(general.stats.stateBytesPerPixel - special.stats.stateBytesPerPixel) * tilePixels /
                                 (1024.0 * 1024.0),
                             1)
             << " | " << general.stats.touchingProbes - special.stats.touchingProbes << " | "
             << (k.shadowRays ? "" : "shadow rays, ") << (k.absorption ? "" : "absorption, ")
             << (k.touchingProbe ? "" : "touching surfaces, ") << (k.opaqueContact ? "" : "glass on opaque surfaces, ")
             << (k.coincidentOpaque ? "" : "coincident opaque surfaces, ") << (k.textures ? "" : "textures, ")
             << (k.materialModels >> std::uint32_t(MaterialModel::Glass) & 1u ? "" : "glass, ")
             << (k.materialModels >> std::uint32_t(MaterialModel::ThinGlass) & 1u ? "" : "thin glass, ")
             << (k.mediumPriorities ? "" : "priorities, ") << (k.dispersion ? "" : "dispersion, ")
             << (k.glassTints ? "" : "glass tints, ") << (k.cutouts ? "" : "cut-outs, ")
             << (k.instancing ? "" : "instancing, ") << "other backgrounds |\n";
    }
    fs::remove_all(cacheRoot);

    std::ofstream report(out);
    report << "# Specialized kernels: what they save\n\n"
           << "Generated by `make bench-specialization` (bench/specialization_bench.cpp) on " << bench::today() << ".\n"
           << "Machine: " << bench::machine() << "; device: "
           << deviceName << ".\n"
           << "Each scene at " << width << "x" << height << ", 1 sample per pixel, its own max_depth and Fresnel model. "
           << "Render time is the median of " << runs
           << " renders (tile dispatches only, the compile excluded), the two kernels taking turns; the speed-up is "
              "the median of the runs' ratios (general over specialized, each run's pair rendered one after the other), "
              "with the middle half of those ratios beside it, so that the machine's drift falls on both kernels alike. "
              "Compile time is pipeline creation plus the first dispatch (lavapipe compiles there) of an empty tile, with "
              "an empty Mesa shader cache (cold, once) and with the cache the cold runs filled (warm, the median of the "
              "runs). Ratios come from one run of this program.\n\n"
           << "What the kernels are and why they give the same image: [gpu-design.md](gpu-design.md#specialized-kernels).\n\n"
           << "| scene | general render s | specialized render s | speed-up | middle half | general compile s (cold) | "
              "specialized compile s (cold) | general compile s (warm cache) | specialized compile s (warm cache) | "
              "same image, bit for bit |\n"
           << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n"
           << rows.str() << "\n"
           << "## Work skipped\n\n"
           << "Rays traced are the same for both kernels (the tests check it); the specialized kernel's stacks are "
              "sized to what the scene can reach, its code lacks what the scene cannot need, and it looks for no touching "
              "surfaces where no two glass objects' boxes overlap. State is the trace state, the traversal stack "
              "and the pending rays of one pixel; a tile is "
           << tileSize << "x" << tileSize << " pixels (the device's default), clipped to the image.\n\n"
           << "| scene | rays | medium stack | pending-ray stack | state bytes a pixel | state MiB a tile saved | "
              "glass hits not examined for touching | code removed |\n"
           << "|---|---:|---:|---:|---:|---:|---:|---|\n"
           << work.str();
    std::cerr << "wrote " << out << "\n";
    return 0;
}

}  // namespace
}  // namespace vitrum

int main(int argc, char** argv) {
    return vitrum::bench::guardedMain("vitrum_bench_specialization", [&] { return vitrum::run(argc, argv); });
}
