// The accuracy study: every accuracy setting's price in time and its error against a ground
// truth, scene by scene, with a heat map per result and an error-against-time plot per scene.
// Writes OUT_DIR/accuracy-vs-time.md and OUT_DIR/study/ (replaced as a whole at the end, so an
// interrupted run leaves the previous study in place); `make study`.
//
//   vitrum_study OUT_DIR [--runs N] [--size WxH] [--quick] [SCENE.json ...]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

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
#include "scene/scene_names.h"
#include "study/pareto.h"
#include "study/run_count.h"
#include "study/study_settings.h"
#include "study/svg_plot.h"
#include "study/time_difference.h"

namespace vitrum::study {
namespace {

namespace fs = std::filesystem;

const char* kDefaultScenes[] = {
    "scenes/demo.json",                         // glass sphere and tinted glass block on a checkerboard
    "scenes/bubble.json",                       // air nested in glass
    "scenes/water_glass.json",                  // water in a glass: touching media, deep trees
    "scenes/course/geospheres_5x5_glass.json",  // the course's 25 glass spheres
    "scenes/glass_sphere_spherical.json",       // an environment map: where the filter matters
    "scenes/diamond.json",                      // IOR 2.42: where Schlick is visibly wrong
};

constexpr float kHeatMapFullScale = 0.05f;

struct Options {
    fs::path outDir;
    int runs = 3;
    std::uint32_t width = 128, height = 96;
    bool quick = false;
    std::vector<std::string> scenes;
};

struct Measured {
    Image image;
    double seconds = 0;  // median render time
    double compile = 0;  // GPU: pipeline creation + first dispatch of the first run
    int runs = 0;
    double spread = 0;   // interquartile range / median over the runs: one slow run does not move it
    // Against renders of the default setting taken in turns with these (GPU rows but the default's
    // own): the median of the runs' ratios, and the middle half of those ratios. The machine's
    // drift between one setting's renders and another's falls on both sides of a ratio alike.
    std::optional<double> vsDefault;
    double vsDefaultLow = 0, vsDefaultHigh = 0;
    bool vsDefaultMeasured = false;  // study/time_difference.h
    RenderStats stats;
};

struct Error {
    ImageDiff diff;
    double ssim = 1;
};

Error compare(const Image& image, const Image& reference) { return {diffImages(image, reference), meanSsim(image, reference)}; }

using RenderOnce = std::function<Image(RenderStats&)>;

// Renders `runs` times (see runsFor) with render(stats) and keeps the last image. With
// `pairedDefault`, each run is paired with a render of the default setting, the two taking turns
// as to which goes first, and vsDefault is worked out from the pairs.
Measured measure(int runs, const RenderOnce& render, const RenderOnce* pairedDefault = nullptr) {
    Measured m;
    std::vector<double> times, ratios;
    int wanted = runs;
    for (int run = 0; run < wanted; ++run) {
        double defaultSeconds = 0;
        auto renderDefault = [&] {
            RenderStats stats;
            (*pairedDefault)(stats);
            defaultSeconds = stats.seconds("render");
        };
        if (pairedDefault && run % 2 == 1) renderDefault();
        RenderStats stats;
        Image image = render(stats);
        if (pairedDefault && run % 2 == 0) renderDefault();
        if (run == 0) m.compile = stats.seconds("pipeline") + stats.seconds("compile");
        times.push_back(stats.seconds("render"));
        if (pairedDefault && defaultSeconds > 0) ratios.push_back(times.back() / defaultSeconds);
        if (run == 0) wanted = runsFor(times.back(), runs, pairedDefault != nullptr);
        m.stats = stats;
        m.image = std::move(image);
    }
    m.seconds = bench::median(times);
    m.runs = int(times.size());
    m.spread = m.seconds > 0 ? (bench::quantile(times, 0.75) - bench::quantile(times, 0.25)) / m.seconds : 0;
    if (!ratios.empty()) {
        m.vsDefault = bench::median(ratios);
        m.vsDefaultLow = bench::quantile(ratios, 0.25);
        m.vsDefaultHigh = bench::quantile(ratios, 0.75);
        m.vsDefaultMeasured = differenceMeasured(ratios);
    }
    return m;
}

// Renders on the GPU with kernels of its own, kept across its renders (gpu/trace_kernel_cache.h):
// its first render creates and compiles them (the compile column), the later ones reuse them.
RenderOnce gpuRender(VulkanDevice& device, const Scene& scene, const Bvh& bvh) {
    auto kernels = std::make_shared<TraceKernelCache>();
    return [&device, &scene, &bvh, kernels](RenderStats& stats) {
        return renderVulkan(device, scene, bvh, VulkanRenderOptions{.kernels = kernels.get()}, stats);
    };
}

Measured measureCpu(const Scene& scene, const Bvh& bvh, bool doublePrecision, int runs) {
    ReferenceOptions options;
    options.doublePrecision = doublePrecision;
    return measure(runs, [&](RenderStats& stats) { return renderReference(scene, bvh, options, stats); });
}

Image renderTruth(Scene scene, const Bvh& bvh, const RenderSettings& settings, double& seconds) {
    scene.settings = settings;
    Measured m = measureCpu(scene, bvh, true, 1);
    seconds += m.seconds;
    return std::move(m.image);
}

// Errors span 1e-7 .. 1: three significant digits.
std::string sci(double v) {
    if (v == 0) return "0";
    if (!std::isfinite(v)) return "inf";
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, v >= 0.01 ? "%.4f" : "%.2e", v);
    return buffer;
}

std::string percent(double share) { return bench::fixed(100.0 * share, share < 0.001 && share > 0 ? 3 : 1) + "%"; }

std::string psnrText(double psnr) { return std::isinf(psnr) ? "inf" : bench::fixed(psnr, 1); }

// A time against another: the ratio, and where there is one, the middle half of the ratios of
// the runs taken in turns with the default's and whether they measure a difference
// (study/time_difference.h).
struct TimeRatio {
    double ratio = 1;
    std::optional<std::pair<double, double>> middleHalf;  // of the paired runs' ratios
    bool measured = true;
};

// "+12% time" / "-30% time" / "4.1x the time", with the middle half of the paired runs' ratios
// when they do not measure a difference.
std::string timeChange(const TimeRatio& t) {
    const std::string change = t.ratio >= 2.0 ? bench::fixed(t.ratio, 1) + "x the time"
                                              : (t.ratio >= 1 ? "+" : "") + bench::fixed(100.0 * (t.ratio - 1.0), 0) + "% time";
    if (t.measured || !t.middleHalf) return change;
    return change + " (not measured: the middle half of its runs took " + bench::fixed(t.middleHalf->first, 2) + "-" +
           bench::fixed(t.middleHalf->second, 2) + "x the default's time)";
}

// "removes 80% of the error (RMSE 0.0123 -> 0.0025)"; "adds ..." when it grows.
std::string errorChange(double from, double to) {
    std::string arrow = " (RMSE " + sci(from) + " -> " + sci(to) + ")";
    if (from == 0 && to == 0) return "leaves the error at 0";
    if (std::fabs(to - from) <= 0.005 * from) return "leaves the error as it is, within 0.5%" + arrow;
    if (to <= from) return "removes " + bench::fixed(from > 0 ? 100.0 * (from - to) / from : 0.0, 0) + "% of the error" + arrow;
    return "adds error" + arrow;
}

std::string slug(const std::string& label) {
    std::string s;
    for (char c : label) {
        if (std::isalnum(static_cast<unsigned char>(c))) s += char(std::tolower(static_cast<unsigned char>(c)));
        else if (c == '.') s += 'p';
        else if (!s.empty() && s.back() != '-') s += '-';
    }
    while (!s.empty() && s.back() == '-') s.pop_back();
    return s;
}

struct Row {
    const StudySetting* setting = nullptr;
    Measured measured;
    std::optional<Error> approximation;  // against the truth at the same sample positions (1 spp rows)
    Error total;                         // against the converged truth
    std::string heatMap;                 // relative to the report
};

struct TruthChecks {
    double seconds = 0;       // CPU time spent on all truths of the scene
    double truthSeconds = 0;  // the 1-spp truth alone
    ImageDiff depth;          // kTruthDepth against kTruthCheckDepth
    ImageDiff cut;            // kTruthMinWeight against no cut-off, at kUncutCheckDepth
    ImageDiff convergedCut;   // kConvergedMinWeight against kTruthMinWeight, 1 spp
    ImageDiff sampling;       // kConvergedSamples against a quarter of them
    std::uint32_t samples = 0;
};

struct SceneStudy {
    std::string name;
    std::size_t triangles = 0;
    TruthChecks checks;
    std::vector<Row> rows;
    std::vector<std::size_t> front;
};

const Row* find(const SceneStudy& s, const std::string& label) {
    for (const Row& r : s.rows)
        if (r.setting->label == label) return &r;
    return nullptr;
}

const Row& defaultRow(const SceneStudy& s) {
    for (const Row& r : s.rows)
        if (r.setting->isDefault) return r;
    throw std::runtime_error("the study has no row with the default settings");
}

// The error a row is judged by in sentences: the approximation error where there is one.
double judgedError(const Row& r) { return r.approximation ? r.approximation->diff.rmse : r.total.diff.rmse; }

// A row's time against the default's: from the renders taken in turns where there are some (GPU
// rows), else the ratio of the two medians (the default itself, CPU rows).
TimeRatio vsDefault(const Row& r, const Row& base) {
    if (!r.measured.vsDefault) return {r.measured.seconds / base.measured.seconds, std::nullopt};
    return {*r.measured.vsDefault, std::make_pair(r.measured.vsDefaultLow, r.measured.vsDefaultHigh),
            r.measured.vsDefaultMeasured};
}

SceneStudy studyScene(VulkanDevice& device, const std::string& file, const Options& options,
                      const std::vector<StudySetting>& settings, const fs::path& studyDir) {
    Scene scene = loadScene(fs::path(VITRUM_SOURCE_DIR) / file);
    scene.camera.width = options.width;
    scene.camera.height = options.height;
    const Bvh bvh = buildSceneBvh(scene);
    SceneStudy study;
    study.name = fs::path(file).stem().string();
    study.triangles = scene.triangles.size();
    const fs::path heatDir = studyDir / study.name;
    fs::create_directories(heatDir);

    std::cerr << study.name << ": ground truth ..." << std::flush;
    TruthChecks& c = study.checks;
    const Image truth = renderTruth(scene, bvh, truthSettings(1, kTruthDepth, kTruthMinWeight), c.truthSeconds);
    c.seconds += c.truthSeconds;
    c.depth = diffImages(truth, renderTruth(scene, bvh, truthSettings(1, kTruthCheckDepth, kTruthMinWeight), c.seconds));
    c.cut = diffImages(renderTruth(scene, bvh, truthSettings(1, kUncutCheckDepth, kTruthMinWeight), c.seconds),
                       renderTruth(scene, bvh, truthSettings(1, kUncutCheckDepth, 0.0f), c.seconds));
    c.convergedCut = diffImages(renderTruth(scene, bvh, truthSettings(1, kTruthDepth, kConvergedMinWeight), c.seconds), truth);
    c.samples = options.quick ? 16 : kConvergedSamples;
    const Image converged = renderTruth(scene, bvh, truthSettings(c.samples, kTruthDepth, kConvergedMinWeight), c.seconds);
    c.sampling = diffImages(converged, renderTruth(scene, bvh, truthSettings(c.samples / 4, kTruthDepth, kConvergedMinWeight), c.seconds));
    writeImage(truth, heatDir / "truth.png");
    writeImage(converged, heatDir / "converged.png");
    std::cerr << " " << bench::fixed(c.seconds, 1) << " s\n";

    // Every GPU setting's renders take turns with renders of the default setting.
    Scene defaultScene = scene;
    const auto defaultSetting = std::find_if(settings.begin(), settings.end(), [](const StudySetting& s) { return s.isDefault; });
    if (defaultSetting == settings.end()) throw std::runtime_error("the study has no default setting");
    defaultScene.settings = defaultSetting->render;
    const RenderOnce renderDefault = gpuRender(device, defaultScene, bvh);
    for (std::size_t i = 0; i < settings.size(); ++i) {
        const StudySetting& s = settings[i];
        std::cerr << "  [" << i + 1 << "/" << settings.size() << "] " << s.label << " ..." << std::flush;
        scene.settings = s.render;
        Row row;
        row.setting = &s;
        row.measured = s.backend == Backend::Gpu
                           ? measure(options.runs, gpuRender(device, scene, bvh), s.isDefault ? nullptr : &renderDefault)
                           : measureCpu(scene, bvh, s.backend == Backend::CpuDouble, options.runs);
        const Image* reference = &converged;
        if (s.render.samplesPerPixel == 1) {
            row.approximation = compare(row.measured.image, truth);
            reference = &truth;
        }
        row.total = compare(row.measured.image, converged);
        row.heatMap = "study/" + study.name + "/" + slug(s.label) + ".png";
        writeImage(diffHeatMap(row.measured.image, *reference, kHeatMapFullScale), heatDir / (slug(s.label) + ".png"));
        std::cerr << " " << bench::fixed(row.measured.seconds, 3) << " s, RMSE " << sci(judgedError(row)) << "\n";
        study.rows.push_back(std::move(row));
    }
    // The front is the GPU's: the CPU rows are there to measure precision, not as a way to render.
    std::vector<TimeError> points;
    std::vector<std::size_t> gpuRows;
    for (std::size_t i = 0; i < study.rows.size(); ++i)
        if (study.rows[i].setting->backend == Backend::Gpu) {
            points.push_back({study.rows[i].measured.seconds, study.rows[i].total.diff.rmse});
            gpuRows.push_back(i);
        }
    for (std::size_t k : paretoFront(points)) study.front.push_back(gpuRows[k]);
    return study;
}

std::string limitsHit(const RenderStats& s) {
    std::string hit;
    auto add = [&](const char* name, std::uint64_t n) {
        if (n) hit += (hit.empty() ? "" : ", ") + std::string(name) + " " + std::to_string(n);
    };
    add("ray stack", s.rayStackOverflows);
    add("medium stack", s.mediumStackOverflows);
    add("traversal stack", s.traversalStackOverflows);
    add("loop limit", s.loopLimitSuspected);
    return hit;
}

std::string backendName(Backend b) { return b == Backend::Gpu ? "GPU float" : b == Backend::CpuFloat ? "CPU float" : "CPU double"; }

std::string sceneTable(const SceneStudy& s) {
    std::ostringstream t;
    const Row& base = defaultRow(s);
    t << "| setting | backend | time s | vs default | compile s | rays | Mrays/s | RMSE | PSNR dB | max | 8-bit changed | "
         "SSIM | total RMSE | total SSIM | heat map |\n"
      << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for (std::size_t i = 0; i < s.rows.size(); ++i) {
        const Row& r = s.rows[i];
        const bool onFront = std::find(s.front.begin(), s.front.end(), i) != s.front.end();
        const std::uint64_t rays = r.measured.stats.totalRays();
        t << "| " << (r.setting->isDefault ? "**" + r.setting->label + " (default)**" : r.setting->label)
          << (onFront ? " [front]" : "") << " | " << backendName(r.setting->backend) << " | " << bench::fixed(r.measured.seconds, 3)
          << " (" << r.measured.runs << (r.measured.runs == 1 ? " run" : " runs") << ")" << " | " << bench::fixed(vsDefault(r, base).ratio, 2) << "x | "
          << (r.setting->backend == Backend::Gpu ? bench::fixed(r.measured.compile, 2) : "-") << " | " << rays << " | "
          << bench::fixed(double(rays) / r.measured.seconds * 1e-6, 2) << " | ";
        if (r.approximation) {
            const ImageDiff& d = r.approximation->diff;
            t << sci(d.rmse) << " | " << psnrText(d.psnr) << " | " << sci(d.maxAbsError) << " | " << percent(d.shareSrgb8Changed)
              << " | " << bench::fixed(r.approximation->ssim, 5) << " | ";
        } else {
            t << "- | - | - | - | - | ";
        }
        t << sci(r.total.diff.rmse) << " | " << bench::fixed(r.total.ssim, 4) << " | [png](" << r.heatMap << ")";
        const std::string limits = limitsHit(r.measured.stats);
        if (!limits.empty()) t << " limits: " << limits;
        t << " |\n";
    }
    return t.str();
}

// Plain sentences: what each setting buys and costs on this scene, against the default.
std::string sceneSentences(const SceneStudy& s) {
    std::ostringstream t;
    const Row& base = defaultRow(s);
    const double baseTime = base.measured.seconds;
    auto line = [&](const std::string& what, const Row* r, bool total) {
        if (!r) return;
        const double from = total ? base.total.diff.rmse : judgedError(base);
        const double to = total ? r->total.diff.rmse : judgedError(*r);
        t << "- " << what << ": " << timeChange(vsDefault(*r, base)) << ", " << errorChange(from, to) << ".\n";
    };
    t << "- timing noise: the middle half of the default's " << base.measured.runs << " renders spread over "
      << bench::fixed(100.0 * base.measured.spread, 0) << "% of their median (interquartile range). Each other GPU "
      << "setting is timed against renders of the default taken in turns with its own.\n";
    const Row* d4 = find(s, "depth 4");
    if (d4) {
        const Row* d10 = find(s, "depth 10");
        t << "- depth 10 instead of 4: " << timeChange({vsDefault(*d10, base).ratio / vsDefault(*d4, base).ratio, std::nullopt, true}) << ", "
          << errorChange(judgedError(*d4), judgedError(*d10)) << ".\n";
    }
    line("depth 16 instead of 10", find(s, "depth 16"), false);
    line("depth 6 instead of 10", find(s, "depth 6"), false);
    line("exact Fresnel instead of Schlick", find(s, "Fresnel exact"), false);
    line("Schlick-exp2 instead of Schlick", find(s, "Fresnel schlick-exp2"), false);
    for (const char* spp : {"4 spp", "16 spp", "64 spp"}) line(std::string(spp) + " instead of 1 (total error)", find(s, spp), true);
    line("nearest instead of bilinear filtering", find(s, "nearest filter"), false);
    for (const char* w : {"min weight 0.001", "min weight 0.01", "min weight 0.1"}) line(std::string(w) + " instead of 0", find(s, w), false);
    if (const Row* cpu = find(s, "CPU double")) {
        const ImageDiff d = diffImages(base.measured.image, cpu->measured.image);
        t << "- float on the GPU against double on the CPU, default settings: RMSE " << sci(d.rmse) << ", max "
          << sci(d.maxAbsError) << ", " << percent(d.shareSrgb8Changed) << " of the pixels change their 8-bit value; the "
          << "CPU reference takes " << bench::fixed(cpu->measured.seconds, 3) << " s against the GPU's " << bench::fixed(baseTime, 3) << " s.\n";
    }
    if (const Row* exact = find(s, "GPU, truth settings")) {
        t << "- the GPU with the truth's settings: RMSE " << sci(exact->approximation->diff.rmse) << " (max "
          << sci(exact->approximation->diff.maxAbsError) << ") from the truth: what float precision leaves.\n";
        if (const Row* schlick = find(s, "GPU, truth settings, Schlick"))
            t << "- Schlick alone (the truth's settings, Schlick instead of exact Fresnel): RMSE "
              << sci(schlick->approximation->diff.rmse) << ", max " << sci(schlick->approximation->diff.maxAbsError) << ", "
              << percent(schlick->approximation->diff.shareSrgb8Changed) << " of the pixels change their 8-bit value.\n";
    }
    t << "- Pareto front (total error against time), fastest first: ";
    for (std::size_t k = 0; k < s.front.size(); ++k) t << (k ? "; " : "") << s.rows[s.front[k]].setting->label;
    t << ".\n";
    return t.str();
}

std::string plot(const SceneStudy& s, const std::vector<std::string>& groups) {
    PlotSpec spec;
    spec.title = s.name + ": error against the converged truth, against render time";
    spec.xLabel = "render time, s (log)";
    spec.yLabel = "RMSE against the converged truth (log)";
    spec.groups = groups;
    for (const Row& r : s.rows) {
        const int g = int(std::find(groups.begin(), groups.end(), r.setting->group) - groups.begin());
        spec.points.push_back({r.measured.seconds, r.total.diff.rmse, g, r.setting->label});
    }
    spec.front = s.front;
    return scatterSvg(spec);
}

// Across scenes: the figures the defaults are chosen by.
std::string summaryTable(const std::vector<SceneStudy>& studies) {
    std::ostringstream t;
    t << "| scene | triangles | default time s | default RMSE | depth 6: time, RMSE | depth 16: time, RMSE | "
         "exact Fresnel: time, RMSE | 4 spp: time, total RMSE (1 spp: total) | min weight 0.01: time, RMSE | "
         "Schlick alone: RMSE | GPU float vs CPU double RMSE |\n"
      << "|---|---:|---:|---:|---|---|---|---|---|---:|---:|\n";
    for (const SceneStudy& s : studies) {
        const Row& base = defaultRow(s);
        auto cell = [&](const char* label, bool total) -> std::string {
            const Row* r = find(s, label);
            if (!r) return "-";
            return bench::fixed(vsDefault(*r, base).ratio, 2) + "x, " + sci(total ? r->total.diff.rmse : judgedError(*r));
        };
        const Row* cpu = find(s, "CPU double");
        const Row* schlick = find(s, "GPU, truth settings, Schlick");
        t << "| " << s.name << " | " << s.triangles << " | " << bench::fixed(base.measured.seconds, 3) << " | " << sci(judgedError(base))
          << " | " << cell("depth 6", false) << " | " << cell("depth 16", false) << " | " << cell("Fresnel exact", false)
          << " | " << cell("4 spp", true) << " (" << sci(base.total.diff.rmse) << ") | " << cell("min weight 0.01", false)
          << " | " << (schlick ? sci(schlick->approximation->diff.rmse) : "-")
          << " | " << (cpu ? sci(diffImages(base.measured.image, cpu->measured.image).rmse) : "-") << " |\n";
    }
    return t.str();
}

std::string truthTable(const std::vector<SceneStudy>& studies) {
    std::ostringstream t;
    t << "| scene | truth s (1 spp) | all truths s | depth " << kTruthDepth << " vs " << kTruthCheckDepth
      << ": RMSE, max, 8-bit changed | cut-off " << kTruthMinWeight << " vs none (depth " << kUncutCheckDepth
      << "): RMSE, max | cut-off " << kConvergedMinWeight << " vs " << kTruthMinWeight
      << ": RMSE | samples N vs N/4: RMSE (bounds the converged image's sampling error) |\n"
      << "|---|---:|---:|---|---|---:|---:|\n";
    for (const SceneStudy& s : studies) {
        const TruthChecks& c = s.checks;
        t << "| " << s.name << " | " << bench::fixed(c.truthSeconds, 2) << " | " << bench::fixed(c.seconds, 1) << " | " << sci(c.depth.rmse)
          << ", " << sci(c.depth.maxAbsError) << ", " << percent(c.depth.shareSrgb8Changed) << " | " << sci(c.cut.rmse) << ", "
          << sci(c.cut.maxAbsError) << " | " << sci(c.convergedCut.rmse) << " | " << sci(c.sampling.rmse) << " (N = " << c.samples
          << ") |\n";
    }
    return t.str();
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--runs" && i + 1 < argc) o.runs = std::max(1, std::atoi(argv[++i]));
        else if (a == "--size" && i + 1 < argc) {
            if (std::sscanf(argv[++i], "%ux%u", &o.width, &o.height) != 2 || o.width == 0 || o.height == 0)
                throw std::runtime_error("--size must look like 128x96");
        } else if (a == "--quick") o.quick = true;
        else if (a.rfind("--", 0) == 0) throw std::runtime_error("unknown option " + a);
        else if (o.outDir.empty()) o.outDir = a;
        else o.scenes.push_back(a);
    }
    if (o.outDir.empty())
        throw std::runtime_error("usage: vitrum_study OUT_DIR [--runs N] [--size WxH] [--quick] [SCENE.json ...]");
    if (o.scenes.empty()) o.scenes.assign(std::begin(kDefaultScenes), std::end(kDefaultScenes));
    return o;
}

int run(int argc, char** argv) {
    const Options options = parse(argc, argv);
    const auto started = std::chrono::steady_clock::now();
    const std::vector<StudySetting> settings = studySettings(options.quick);
    // Compile times are measured from an empty Mesa shader cache: each kernel the study needs is
    // compiled cold once, then found in the cache.
    const fs::path cache = fs::temp_directory_path() / ("vitrum-study-cache-" + std::to_string(::getpid()));
    fs::remove_all(cache);
    fs::create_directories(cache);
    setenv("MESA_SHADER_CACHE_DIR", cache.c_str(), 1);
    const fs::path studyDir = options.outDir / "study.partial";
    fs::remove_all(studyDir);
    fs::create_directories(studyDir);

    std::vector<SceneStudy> studies;
    std::string deviceName;
    {
        VulkanDevice device("");
        deviceName = device.name();
        for (const std::string& file : options.scenes) studies.push_back(studyScene(device, file, options, settings, studyDir));
    }
    fs::remove_all(cache);

    std::vector<std::string> groups;
    for (const StudySetting& s : settings)
        if (std::find(groups.begin(), groups.end(), s.group) == groups.end()) groups.push_back(s.group);
    for (const SceneStudy& s : studies) writeFileAtomically(studyDir / (s.name + ".svg"), plot(s, groups));
    const double minutes = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() / 60.0;

    std::ostringstream md;
    md << "# Accuracy against time\n\n"
       << "Generated by `make study` (bench/accuracy_study.cpp) on " << bench::today() << " in " << bench::fixed(minutes, 1)
       << " minutes. Machine: " << bench::machine() << "; device: " << deviceName << ".\n\n"
       << "Every scene is rendered at " << options.width << "x" << options.height
       << " with its own camera, lights and materials and the documented default settings (1 sample per pixel, "
          "`max_depth` 10, Schlick Fresnel, bilinear filtering, no weight cut-off), then with one setting changed "
          "at a time, then with a few combinations. Time is the median of at least "
       << options.runs << " renders (the tile dispatches only; renders under " << bench::fixed(kTimedSeconds, 1) << " s are repeated "
       << "until they fill about that long, up to " << kMaxRuns << " times, and renders over " << bench::fixed(kTimeOnceSeconds, 0)
       << " s are timed once; the table gives the count); compile is pipeline creation plus the first dispatch, from a Mesa shader cache that "
          "was empty when the study started (a kernel another setting already built comes from the cache). CPU rows "
          "run the reference renderer on all hardware threads. Each GPU setting's renders take turns with as many renders of the "
          "default setting, and its time against the default's (`vs default`, the sentences) is the median of those pairs' ratios: "
          "the machine's drift over the minutes between two settings falls on both alike. A difference is called measured when "
          "its pairs' ratios lean to one side of 1 so far that chance would do it less than one time in 20 (an exact "
          "two-sided sign test; at least 6 of 6 pairs, or 12 of 15), or when every pair's ratio is beyond 2x either way "
          "(a render timed once); paired settings get at least 6 pairs unless timed once. Otherwise it is called not "
          "measured, and the middle half of its pairs' ratios is given.\n\n"
       << "## Ground truth\n\n"
       << "The CPU reference in double precision with exact Fresnel and bilinear filtering, `max_depth` " << kTruthDepth
       << " and a weight cut-off of " << kTruthMinWeight << ", one sample at each pixel centre: the same sample "
          "positions as the 1-spp settings, so their error against it is the approximation alone, without sampling "
          "noise (columns RMSE to SSIM). The converged truth adds sampling: the same with "
       << kConvergedSamples << " stratified samples per pixel (cut-off " << kConvergedMinWeight
       << "); every setting's total error is measured against it (total RMSE, total SSIM, the plots). How far each "
          "truth is from its limit, measured:\n\n"
       << truthTable(studies) << "\n"
       << "The sampling error of the converged truth is at most the RMSE between N and N/4 samples (if N samples "
          "have at most half the error of N/4, the difference is at least as large as the N-sample error). Total "
          "errors closer than that to each other are not told apart by this study; the approximation errors have no "
          "sampling noise, and their floor is the depth column (light still travelling after "
       << kTruthDepth << " bounces, trapped by total internal reflection).\n\n"
       << "Measures: RMSE, PSNR (peak 1), maximum absolute error of a linear channel; the share of pixels whose "
          "8-bit sRGB PNG value changes in some channel; SSIM (Wang et al. 2004, on sRGB luma, 11x11 Gaussian window, "
          "1 = identical). Heat maps show the largest channel error per pixel, black 0 to white "
       << kHeatMapFullScale << " or more, against the 1-spp truth for 1-spp settings and against the converged truth "
          "otherwise. `[front]` marks the Pareto front of total error against time.\n\n"
       << "## Across scenes\n\nTime as a multiple of the default's; RMSE is the approximation error (against the "
          "1-spp truth) except for 4 spp, which is measured against the converged truth like the default's total "
          "error in brackets.\n\n"
       << summaryTable(studies) << "\n"
       << "What the defaults are and why: [render-model-decisions.md](render-model-decisions.md#defaults-and-what-the-study-says).\n"
       << "Dispersion's setting, the number of wavelength samples, is studied on its own scenes in "
          "[wavelengths-vs-time.md](wavelengths-vs-time.md) (`make study-wavelengths`).\n";
    for (const SceneStudy& s : studies) {
        md << "\n## " << s.name << "\n\n"
           << "![" << s.name << ": error against time](study/" << s.name << ".svg)\n\n"
           << "Truth: [1 spp](study/" << s.name << "/truth.png), [converged](study/" << s.name << "/converged.png).\n\n"
           << sceneSentences(s) << "\n"
           << sceneTable(s);
    }
    const fs::path finalDir = options.outDir / "study";
    fs::remove_all(finalDir);
    fs::rename(studyDir, finalDir);
    writeFileAtomically(options.outDir / "accuracy-vs-time.md", md.str());
    std::cerr << "wrote " << (options.outDir / "accuracy-vs-time.md") << " and " << finalDir << " in " << bench::fixed(minutes, 1)
              << " minutes\n";
    return 0;
}

}  // namespace
}  // namespace vitrum::study

int main(int argc, char** argv) {
    return vitrum::bench::guardedMain("vitrum_study", [&] { return vitrum::study::run(argc, argv); });
}
