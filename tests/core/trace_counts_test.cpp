// The statistics list (shaders/shared/trace_statistics.h) as the host reads and reports it.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "stats/render_stats.h"
#include "stats/trace_counts.h"

namespace vitrum {
namespace {

TEST(TraceCounts, ADispatchBufferIsReadByIndexSumsAddAndMaximaTakeTheLarger) {
    std::uint32_t buffer[gpu::kDispatchCounterCount] = {};
    buffer[TraceStatistic::primaryRays] = 7;
    buffer[TraceStatistic::depthLimitHits] = 3;
    buffer[TraceStatistic::maxRayDepth] = 5;
    buffer[gpu::kWorkCursor] = 99;  // not a statistic
    TraceCounts counts;
    counts.addDispatch(buffer);
    buffer[TraceStatistic::maxRayDepth] = 2;
    counts.addDispatch(buffer);
    EXPECT_EQ(counts.primaryRays, 14u);
    EXPECT_EQ(counts.depthLimitHits, 6u);
    EXPECT_EQ(counts.maxRayDepth, 5u);
    EXPECT_EQ(counts.totalRays(), 14u);

    TraceCounts more;
    more.shadowRays = 4;
    more.maxRayDepth = 9;
    counts += more;
    EXPECT_EQ(counts.totalRays(), 18u);
    EXPECT_EQ(counts.maxRayDepth, 9u);
}

TEST(TraceCounts, StatsFilesReportWhatTheBackendMeasures) {
    RenderStats stats;
    stats.primaryRays = 12;
    stats.depthLimitHits = 2;
    stats.maxMediumDepth = 3;
    stats.loopSteps = 40;
    stats.backend = "vulkan";
    nlohmann::json gpu = toJson(stats);
    EXPECT_EQ(gpu["rays"]["primary"], 12);
    EXPECT_EQ(gpu["rays"]["total"], 12);
    EXPECT_EQ(gpu["limits"]["depth_limit"], 2);
    EXPECT_EQ(gpu["max_medium_depth"], 3);
    EXPECT_EQ(gpu["loop_steps"], 40);
    EXPECT_TRUE(gpu.contains("dispatches"));
    EXPECT_FALSE(gpu.contains("unfinished_pixels"));  // the host's own, not a statistic

    // The CPU reference has no loop, dispatches or SIMD groups: it writes no value for them
    // rather than a 0 that reads as measured.
    stats.backend = "cpu";
    nlohmann::json cpu = toJson(stats);
    EXPECT_EQ(cpu["max_medium_depth"], 3);
    EXPECT_TRUE(cpu.contains("touching_interfaces"));
    EXPECT_TRUE(cpu.contains("max_ray_depth"));
    for (const char* gpuOnly : {"loop_steps", "group_loop_steps", "max_pixel_loop_steps", "restarted_steps", "dispatches",
                                "restarted_pixels", "lanes_per_group"})
        EXPECT_FALSE(cpu.contains(gpuOnly)) << gpuOnly;
}

}  // namespace
}  // namespace vitrum
