// The accuracy study's dispersion setting (docs/accuracy-vs-time.md, "Wavelength samples"): each
// dispersive scene rendered on the GPU with 1, 3, 8, 16 and 32 wavelength samples
// (render-model-decisions.md, "Dispersion"), against the CPU reference in double precision with 64
// samples and otherwise the same settings (the scene's depth, Fresnel and filter, one sample at
// each pixel centre): the error that sampling the spectrum leaves, and what the samples cost. The
// settings take turns, run by run, so that the machine's drift falls on all alike; times are
// medians of the render phase. Writes OUT_DIR/wavelengths-vs-time.md and
// OUT_DIR/study/wavelengths-SCENE.svg.
//
//   vitrum_wavelength_study OUT_DIR [--runs N] [--size WxH] [SCENE.json ...]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_support.h"
#include "bvh/bvh.h"
#include "common/atomic_file.h"
#include "cpu/reference_renderer.h"
#include "gpu/trace_kernel_cache.h"
#include "gpu/vulkan_device.h"
#include "gpu/vulkan_renderer.h"
#include "image/image_diff.h"
#include "image/ssim.h"
#include "scene/scene_loader.h"
#include "study/svg_plot.h"

namespace vitrum::study {
namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kTruthWavelengths = 64;
const std::vector<std::uint32_t> kWavelengths = {1, 3, 8, 16, 32};
const char* const kDefaultScenes[] = {"scenes/dispersive_prism.json", "scenes/diamond_fire.json"};

struct Options {
    fs::path outDir;
    int runs = 5;
    std::uint32_t width = 160, height = 120;
    std::vector<std::string> scenes;
};

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--runs" && i + 1 < argc) o.runs = std::max(1, std::stoi(argv[++i]));
        else if (a == "--size" && i + 1 < argc) {
            if (std::sscanf(argv[++i], "%ux%u", &o.width, &o.height) != 2) throw std::runtime_error("--size expects WxH");
        } else if (o.outDir.empty()) o.outDir = a;
        else o.scenes.push_back(a);
    }
    if (o.outDir.empty()) throw std::runtime_error("usage: vitrum_wavelength_study OUT_DIR [--runs N] [--size WxH] [SCENE.json ...]");
    if (o.scenes.empty()) o.scenes.assign(std::begin(kDefaultScenes), std::end(kDefaultScenes));
    return o;
}

struct Row {
    std::uint32_t wavelengths = 0;
    std::vector<double> seconds;
    Image image;
    ImageDiff diff;
    double ssim = 1;
};

std::string sci(double v) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, v >= 0.01 ? "%.4f" : "%.2e", v);
    return buffer;
}

int run(int argc, char** argv) {
    const Options options = parse(argc, argv);
    const auto started = std::chrono::steady_clock::now();
    fs::create_directories(options.outDir / "study");
    VulkanDevice device("");
    std::ostringstream sections;
    for (const std::string& file : options.scenes) {
        Scene scene = loadScene(fs::path(VITRUM_SOURCE_DIR) / file);
        scene.camera.width = options.width;
        scene.camera.height = options.height;
        scene.settings.samplesPerPixel = 1;
        const Bvh bvh = buildSceneBvh(scene);
        const std::string name = fs::path(file).stem().string();
        std::cerr << name << ": truth (CPU double, " << kTruthWavelengths << " wavelength samples)\n";
        Scene truthScene = scene;
        truthScene.settings.wavelengths = kTruthWavelengths;
        RenderStats truthStats;
        ReferenceOptions reference;
        reference.doublePrecision = true;
        const Image truth = renderReference(truthScene, bvh, reference, truthStats);
        // One kernel for every count (the count is a buffer, not a constant), kept across renders.
        TraceKernelCache kernels;
        std::vector<Row> rows;
        for (std::uint32_t n : kWavelengths) rows.push_back({.wavelengths = n});
        for (int r = 0; r < options.runs + 1; ++r) {  // run 0 compiles: not timed
            for (Row& row : rows) {
                Scene s = scene;
                s.settings.wavelengths = row.wavelengths;
                RenderStats stats;
                row.image = renderVulkan(device, s, bvh, VulkanRenderOptions{.kernels = &kernels}, stats);
                if (r > 0) row.seconds.push_back(stats.seconds("render"));
            }
        }
        PlotSpec plot{.title = name + ": wavelength samples, error against time",
                      .xLabel = "render time (s)",
                      .yLabel = "RMSE against 64 samples (CPU double)",
                      .groups = {"wavelength samples"}};
        std::ostringstream table;
        table << "| wavelength samples | render (s, median) | vs 8 | RMSE | max abs error | pixels over 0.05 | SSIM |\n"
              << "|---:|---:|---:|---:|---:|---:|---:|\n";
        const double eight = bench::median(std::find_if(rows.begin(), rows.end(), [](const Row& r) { return r.wavelengths == 8; })->seconds);
        for (Row& row : rows) {
            row.diff = diffImages(row.image, truth);
            row.ssim = meanSsim(row.image, truth);
            const double seconds = bench::median(row.seconds);
            table << "| " << row.wavelengths << (row.wavelengths == 8 ? " (default)" : "") << " | " << bench::fixed(seconds, 3)
                  << " | " << bench::fixed(seconds / eight, 2) << "x | " << sci(row.diff.rmse) << " | "
                  << sci(row.diff.maxAbsError) << " | " << bench::fixed(100.0 * row.diff.shareOver005, 2) << "% | "
                  << bench::fixed(row.ssim, 4) << " |\n";
            plot.points.push_back({.x = seconds, .y = row.diff.rmse, .group = 0, .label = std::to_string(row.wavelengths)});
            plot.front.push_back(plot.points.size() - 1);
        }
        writeFileAtomically(options.outDir / "study" / ("wavelengths-" + name + ".svg"), scatterSvg(plot));
        sections << "\n## " << name << "\n\n![" << name << ": error against time](study/wavelengths-" << name << ".svg)\n\n"
                 << "Truth: " << bench::fixed(truthStats.seconds("render"), 1) << " s on the CPU.\n\n"
                 << table.str();
    }
    const double minutes = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() / 60.0;
    std::ostringstream md;
    md << "# Wavelength samples against time\n\n"
       << "Generated by `make study-wavelengths` (bench/wavelength_study.cpp) on " << bench::today() << " in "
       << bench::fixed(minutes, 1) << " minutes. Machine: " << bench::machine() << "; device: " << device.name() << ".\n\n"
       << "The accuracy study's setting for dispersion (render-model-decisions.md, \"Dispersion\"): each scene with a "
          "dispersive glass at " << options.width << "x" << options.height
       << ", one sample at each pixel centre, its own depth and Fresnel model, rendered on the GPU with each number of "
          "wavelength samples, against the CPU reference in double precision with "
       << kTruthWavelengths
       << " samples and otherwise the same settings: the error is what sampling the spectrum leaves (and float "
          "against double, far smaller). Times are the median render phase of "
       << options.runs
       << " renders, the settings taking turns run by run, after a first render that compiles (one kernel for every "
          "count: the count is a buffer, not a constant). Measures as in [accuracy-vs-time.md](accuracy-vs-time.md).\n"
       << sections.str();
    writeFileAtomically(options.outDir / "wavelengths-vs-time.md", md.str());
    std::cerr << "wrote " << (options.outDir / "wavelengths-vs-time.md") << "\n";
    return 0;
}

}  // namespace
}  // namespace vitrum::study

int main(int argc, char** argv) {
    return vitrum::bench::guardedMain("vitrum_wavelength_study", [&] { return vitrum::study::run(argc, argv); });
}
