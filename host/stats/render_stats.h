// What a render reports, whichever backend made it: `--stats FILE.json` writes it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "analysis/scene_features.h"
#include "stats/trace_counts.h"
#include "gpu_input/trace_specialization.h"

namespace vitrum {

// The counters (TraceCounts) and what else a render reports.
struct RenderStats : TraceCounts {
    std::string backend;  // "vulkan" or "cpu"
    std::string device;
    std::vector<std::pair<std::string, double>> phaseSeconds;  // in the order they ran
    std::uint64_t dispatches = 0;
    std::uint64_t restartedPixels = 0;  // GPU: pixels the first dispatch of their tile gave up
    std::uint32_t lanesPerGroup = 0;  // GPU: lanes the kernel counts a group's steps for (1: each lane its own)
    SceneFeatures features;                    // what the scene can need (both backends use it)
    std::optional<TraceSpecialization> kernel;  // GPU: what the kernel was built for
    std::uint64_t stateBytesPerPixel = 0;      // GPU: trace state and pending rays of one pixel
    std::uint32_t tileSize = 0;                // GPU: pixels a side of the tiles rendered
    // GPU: bytes of the device buffers: the scene's (geometry, materials, textures, parameters,
    // statistics) and the tile's (trace state, pending rays, stacks and pixels of one tile).
    std::uint64_t sceneBytes = 0, tileBytes = 0;

    void addPhase(const std::string& name, double seconds) { phaseSeconds.emplace_back(name, seconds); }
    double seconds(const std::string& phase) const;
};

nlohmann::json toJson(const RenderStats& stats);

}  // namespace vitrum
