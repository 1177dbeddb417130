#include "stats/render_stats.h"

#include <nlohmann/json.hpp>

namespace vitrum {

double RenderStats::seconds(const std::string& phase) const {
    for (const auto& [name, s] : phaseSeconds)
        if (name == phase) return s;
    return 0.0;
}

nlohmann::json toJson(const RenderStats& stats) {
    nlohmann::json phases = nlohmann::json::object();
    for (const auto& [name, s] : stats.phaseSeconds) phases[name] = s;
    const bool gpu = stats.backend == "vulkan";
    nlohmann::json result = {
        {"backend", stats.backend},
        {"device", stats.device},
        {"seconds", phases},
        {"features", toJson(stats.features)},
    };
    addToJson(stats, gpu, result);
    if (gpu) {
        result["lanes_per_group"] = stats.lanesPerGroup;
        result["dispatches"] = stats.dispatches;
        result["restarted_pixels"] = stats.restartedPixels;
    }
    if (stats.kernel) {
        result["kernel"] = toJson(*stats.kernel);
        result["kernel"]["state_bytes_per_pixel"] = stats.stateBytesPerPixel;
        result["kernel"]["tile_size"] = stats.tileSize;
        result["device_bytes"] = {{"scene", stats.sceneBytes}, {"tile", stats.tileBytes}};
    }
    return result;
}

}  // namespace vitrum
