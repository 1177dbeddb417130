#include "render/render_stats.h"

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
    nlohmann::json result = {
        {"backend", stats.backend},
        {"device", stats.device},
        {"seconds", phases},
        {"rays",
         {{"primary", stats.rays.primary},
          {"shadow", stats.rays.shadow},
          {"reflection", stats.rays.reflection},
          {"refraction", stats.rays.refraction},
          {"total", stats.rays.total()}}},
        {"limits",
         {{"depth_limit", stats.limits.depthLimit},
          {"traversal_stack_overflow", stats.limits.traversalStackOverflow},
          {"loop_limit_suspected", stats.limits.loopLimitSuspected},
          {"ray_stack_overflow", stats.limits.rayStackOverflow},
          {"medium_stack_overflow", stats.limits.mediumStackOverflow},
          {"weight_cuts", stats.limits.weightCuts},
          {"inconsistent_media", stats.limits.inconsistentMedia}}},
        {"touching_interfaces", stats.touchingInterfaces},
        {"touching_probes", stats.touchingProbes},
        {"max_ray_depth", stats.maxRayDepth},
        {"max_medium_depth", stats.maxMediumDepth},
        {"total_internal_reflections", stats.totalInternalReflections},
        {"absorbed_escapes", stats.absorbedEscapes},
        {"loop_steps", stats.loopSteps},
        {"max_pixel_loop_steps", stats.maxPixelLoopSteps},
        {"group_loop_steps", stats.groupLoopSteps},
        {"lanes_per_group", stats.lanesPerGroup},
        {"dispatches", stats.dispatches},
        {"restarted_pixels", stats.restartedPixels},
        {"restarted_steps", stats.restartedSteps},
        {"node_visits", stats.nodeVisits},
        {"features", toJson(stats.features)},
    };
    if (stats.kernel) {
        result["kernel"] = toJson(*stats.kernel);
        result["kernel"]["state_bytes_per_pixel"] = stats.stateBytesPerPixel;
        result["kernel"]["tile_size"] = stats.tileSize;
    }
    return result;
}

}  // namespace vitrum
