// What a render reports, whichever backend made it: `--stats FILE.json` writes it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "render/scene_features.h"
#include "render/trace_specialization.h"

namespace vitrum {

struct RayCounts {
    std::uint64_t primary = 0;
    std::uint64_t shadow = 0;
    std::uint64_t reflection = 0;
    std::uint64_t refraction = 0;
    std::uint64_t total() const { return primary + shadow + reflection + refraction; }
};

// Limits that were hit. Nothing is cut silently: each is counted (docs/render-model.md).
struct LimitCounts {
    std::uint64_t depthLimit = 0;            // branches not traced because of max_depth
    std::uint64_t traversalStackOverflow = 0;
    std::uint64_t loopLimitSuspected = 0;    // GPU loops that ended without a reason of ours
    std::uint64_t rayStackOverflow = 0;      // branches dropped: pending-ray stack full
    std::uint64_t mediumStackOverflow = 0;   // media not recorded: medium stack full
    std::uint64_t weightCuts = 0;            // branches skipped by min_weight
    std::uint64_t inconsistentMedia = 0;     // rays leaving an object they were not inside
};

struct RenderStats {
    std::string backend;  // "vulkan" or "cpu"
    std::string device;
    std::vector<std::pair<std::string, double>> phaseSeconds;  // in the order they ran
    RayCounts rays;
    LimitCounts limits;
    std::uint64_t dispatches = 0;
    std::uint64_t restartedPixels = 0;  // GPU: pixels the first dispatch of their tile gave up
    std::uint64_t restartedSteps = 0;   // GPU: the loop steps those first attempts spent
    std::uint64_t nodeVisits = 0;
    std::uint64_t totalInternalReflections = 0;
    std::uint64_t absorbedEscapes = 0;
    std::uint64_t touchingInterfaces = 0;  // glass hits merged with touching surfaces of other objects
    std::uint64_t touchingProbes = 0;      // traversals around glass hits that looked for touching surfaces
    std::uint64_t maxRayDepth = 0;         // deepest ray traced (primary = 0)
    std::uint64_t maxMediumDepth = 0;      // most media one ray was inside
    std::uint64_t loopSteps = 0;          // GPU: steps of trace.comp's loop, all pixels
    std::uint64_t maxPixelLoopSteps = 0;  // GPU: most steps one pixel needed, over all its dispatches
    // GPU: the steps the SIMD groups ran (each group once, as the budget counts them), first
    // attempts included: lanes that wait for the others of their group make it larger than
    // (loopSteps + restartedSteps) / lanes a group.
    std::uint64_t groupLoopSteps = 0;
    std::uint32_t lanesPerGroup = 0;  // GPU: lanes the kernel counts a group's steps for (1: each lane its own)
    SceneFeatures features;                    // what the scene can need (both backends use it)
    std::optional<TraceSpecialization> kernel;  // GPU: what the kernel was built for
    std::uint64_t stateBytesPerPixel = 0;      // GPU: trace state and pending rays of one pixel
    std::uint32_t tileSize = 0;                // GPU: pixels a side of the tiles rendered

    void addPhase(const std::string& name, double seconds) { phaseSeconds.emplace_back(name, seconds); }
    double seconds(const std::string& phase) const;
};

nlohmann::json toJson(const RenderStats& stats);

}  // namespace vitrum
