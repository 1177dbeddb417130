// The settings the accuracy study renders (docs/accuracy-vs-time.md): each accuracy setting swept
// alone from the documented defaults, a few useful combinations, and the ground truth's own
// settings.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace vitrum::study {

enum class Backend { Gpu, CpuFloat, CpuDouble };

struct StudySetting {
    std::string group;  // what is varied: "depth", "Fresnel", "samples", ...
    std::string label;  // unique within a study, e.g. "depth 4"
    RenderSettings render;
    Backend backend = Backend::Gpu;
    bool isDefault = false;
};

// The ground truth (CPU reference, double precision): exact Fresnel, bilinear, a deep tree with
// a tiny weight cut-off. Its depth and cut-off are checked against a deeper, uncut tree.
constexpr std::uint32_t kTruthDepth = 32;
constexpr std::uint32_t kTruthCheckDepth = 48;
constexpr float kTruthMinWeight = 1e-6f;
constexpr std::uint32_t kUncutCheckDepth = 16;  // an uncut tree deeper than this is too big to render
// The converged image (for the sampling error): many samples, a slightly larger cut-off for time.
constexpr std::uint32_t kConvergedSamples = 256;
constexpr float kConvergedMinWeight = 1e-4f;

inline RenderSettings truthSettings(std::uint32_t samples, std::uint32_t depth, float minWeight) {
    RenderSettings s;
    s.samplesPerPixel = samples;
    s.maxDepth = depth;
    s.fresnel = FresnelModel::Exact;
    s.minWeight = minWeight;
    s.filter = TextureFilter::Bilinear;
    return s;
}

inline std::vector<StudySetting> studySettings(bool quick) {
    const RenderSettings defaults;  // the documented defaults (scene.h, docs/render-model-decisions.md)
    std::vector<StudySetting> all;
    auto add = [&](std::string group, std::string label, RenderSettings r, Backend b = Backend::Gpu) {
        StudySetting s{std::move(group), std::move(label), r, b, false};
        s.isDefault = b == Backend::Gpu && r.samplesPerPixel == defaults.samplesPerPixel &&
                      r.maxDepth == defaults.maxDepth && r.fresnel == defaults.fresnel &&
                      r.minWeight == defaults.minWeight && r.filter == defaults.filter;
        all.push_back(std::move(s));
    };
    const std::vector<std::uint32_t> depths =
        quick ? std::vector<std::uint32_t>{1, 2, 10} : std::vector<std::uint32_t>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
    for (std::uint32_t d : depths) {
        RenderSettings r = defaults;
        r.maxDepth = d;
        add("depth", "depth " + std::to_string(d), r);
    }
    for (auto [model, name] : {std::pair{FresnelModel::Exact, "exact"}, std::pair{FresnelModel::SchlickExp2, "schlick-exp2"}}) {
        if (quick && model != FresnelModel::Exact) continue;
        RenderSettings r = defaults;
        r.fresnel = model;
        add("Fresnel", std::string("Fresnel ") + name, r);
    }
    for (std::uint32_t spp : quick ? std::vector<std::uint32_t>{4} : std::vector<std::uint32_t>{4, 16, 64}) {
        RenderSettings r = defaults;
        r.samplesPerPixel = spp;
        add("samples", std::to_string(spp) + " spp", r);
    }
    {
        RenderSettings r = defaults;
        r.filter = TextureFilter::Nearest;
        add("filter", "nearest filter", r);
    }
    for (float w : quick ? std::vector<float>{0.01f} : std::vector<float>{0.0001f, 0.001f, 0.01f, 0.03f, 0.1f}) {
        RenderSettings r = defaults;
        r.minWeight = w;
        char label[48];
        std::snprintf(label, sizeof label, "min weight %g", double(w));
        add("min weight", label, r);
    }
    add("precision", "CPU double", defaults, Backend::CpuDouble);
    if (!quick) add("precision", "CPU float", defaults, Backend::CpuFloat);
    // Combinations: more samples with a shallower or exact tree, and a cut-off.
    struct Combination {
        std::uint32_t spp, depth;
        FresnelModel fresnel;
        float minWeight;
    };
    const std::vector<Combination> combinations =
        quick ? std::vector<Combination>{{4, 10, FresnelModel::Exact, 0.0f}}
              : std::vector<Combination>{{4, 4, FresnelModel::Schlick, 0.0f},   {4, 6, FresnelModel::Exact, 0.0f},
                                         {4, 10, FresnelModel::Exact, 0.0f},    {4, 10, FresnelModel::Exact, 0.01f},
                                         {16, 6, FresnelModel::Exact, 0.0f},    {16, 10, FresnelModel::Exact, 0.01f},  {64, 6, FresnelModel::Exact, 0.01f}};
    for (const Combination& c : combinations) {
        RenderSettings r = defaults;
        r.samplesPerPixel = c.spp;
        r.maxDepth = c.depth;
        r.fresnel = c.fresnel;
        r.minWeight = c.minWeight;
        char label[96];
        std::snprintf(label, sizeof label, "%u spp, depth %u, %s", c.spp, c.depth,
                      c.fresnel == FresnelModel::Exact ? "exact" : "schlick");
        char cut[48] = "";
        if (c.minWeight > 0) std::snprintf(cut, sizeof cut, ", min weight %g", double(c.minWeight));
        add("combined", std::string(label) + cut, r);
    }
    // The truth's own settings on the GPU: what float precision alone leaves.
    add("truth settings", "GPU, truth settings", truthSettings(1, kTruthDepth, kTruthMinWeight));
    // ... and with Schlick: the Fresnel approximation's error alone, without the depth's.
    RenderSettings schlick = truthSettings(1, kTruthDepth, kTruthMinWeight);
    schlick.fresnel = FresnelModel::Schlick;
    add("truth settings", "GPU, truth settings, Schlick", schlick);
    return all;
}

}  // namespace vitrum::study
