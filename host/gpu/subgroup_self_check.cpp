#include "gpu/subgroup_self_check.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "gpu/trace_pipeline.h"
#include "gpu/vulkan_device.h"
#include "shared/subgroup_check_types.h"
#include "subgroup_check.spv.h"

namespace vitrum {
namespace {

// Two workgroups of trace.comp's 8x8 (16 subgroups of lavapipe's 8 lanes) take 64 units: each
// subgroup takes several, in whatever order the device's threads run them.
constexpr std::uint32_t kWorkgroups = 2;
constexpr std::uint32_t kInvocationsPerWorkgroup = kTraceGroupSize * kTraceGroupSize;
constexpr std::uint32_t kUnits = 64;

struct LaneResult {
    std::uint32_t rounds, trips, received, sumPlusOne;
};

// What every lane of `unit` must have written, worked out as the kernel's loop does.
std::vector<LaneResult> expectedUnit(std::uint32_t unit, std::uint32_t lanes) {
    std::vector<std::uint32_t> trips(lanes), mine(lanes, 0);
    std::vector<bool> busy(lanes);
    std::uint32_t rounds = 0, received = 0, sum = 0;
    for (std::uint32_t lane = 0; lane < lanes; ++lane) {
        trips[lane] = gpu::subgroupCheckTrips(unit, lane);
        busy[lane] = trips[lane] > 0;
        sum += trips[lane];
    }
    while (std::find(busy.begin(), busy.end(), true) != busy.end()) {
        ++rounds;
        std::uint32_t key = 0;
        for (std::uint32_t lane = 0; lane < lanes; ++lane) {
            if (!busy[lane]) continue;
            ++mine[lane];
            key = std::max(key, ((trips[lane] - mine[lane]) << 8) | (255 - lane));
        }
        const std::uint32_t giver = key == 0 ? 0 : 255 - (key & 0xFF);
        received += gpu::subgroupCheckValue(unit, giver, rounds);
        for (std::uint32_t lane = 0; lane < lanes; ++lane) busy[lane] = busy[lane] && mine[lane] < trips[lane];
    }
    std::vector<LaneResult> result(lanes);
    for (std::uint32_t lane = 0; lane < lanes; ++lane) result[lane] = {rounds, trips[lane], received, sum + 1};
    return result;
}

}  // namespace

SubgroupSelfCheck checkSubgroupMachinery(VulkanDevice& device, bool subgroupBarrier, bool injectFault) {
    const std::uint32_t lanes = device.subgroups().size;
    if (statisticsSumsFor(device, StatisticsSums::shuffles) != StatisticsSums::shuffles)
        return {false, "the device cannot run the kernel in full subgroups"};
    const std::array<VkDescriptorType, 2> bindings = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                                      VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    const std::uint32_t barrier = subgroupBarrier ? 1u : 0u;
    const VkSpecializationMapEntry entry{.constantID = 0, .offset = 0, .size = sizeof(std::uint32_t)};
    const VkSpecializationInfo specialization{
        .mapEntryCount = 1, .pMapEntries = &entry, .dataSize = sizeof(barrier), .pData = &barrier};
    ComputePipeline pipeline(device, std::span<const std::uint32_t>(subgroup_check_spv, std::size(subgroup_check_spv)),
                             bindings, &specialization, VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT_EXT);
    GpuBuffer control(device, sizeof(gpu::SubgroupCheckControl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                      "subgroup self-check control");
    *control.as<gpu::SubgroupCheckControl>() = {0, kUnits, injectFault ? 1u : 0u, 0};
    const std::size_t resultCount = std::size_t(kUnits) * lanes;
    GpuBuffer results(device, resultCount * sizeof(gpu::SubgroupCheckResult), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                      "subgroup self-check results");
    std::fill_n(results.as<gpu::SubgroupCheckResult>(), resultCount, gpu::SubgroupCheckResult{});
    const std::array<const GpuBuffer*, 2> bound = {&control, &results};
    pipeline.bind(bound);
    device.submitAndWait([&](VkCommandBuffer commands) { pipeline.record(commands, kWorkgroups); });

    // Each subgroup took units until it drew one past the last: one draw each beyond the units.
    const std::uint32_t subgroups = kWorkgroups * kInvocationsPerWorkgroup / lanes;
    const std::uint32_t cursor = control.as<gpu::SubgroupCheckControl>()->cursor;
    if (cursor != kUnits + subgroups)
        return {false, "units taken by elected lanes: the counter reached " + std::to_string(cursor) + ", not " +
                           std::to_string(kUnits + subgroups)};
    const gpu::SubgroupCheckResult* got = results.as<gpu::SubgroupCheckResult>();
    for (std::uint32_t unit = 0; unit < kUnits; ++unit) {
        const std::vector<LaneResult> want = expectedUnit(unit, lanes);
        for (std::uint32_t lane = 0; lane < lanes; ++lane) {
            const gpu::SubgroupCheckResult& packed = got[unit * lanes + lane];
            const LaneResult g{packed.counts >> 24, (packed.counts >> 16) & 0xFF, packed.received, packed.counts & 0xFFFF};
            const LaneResult& w = want[lane];
            const std::string where = "unit " + std::to_string(unit) + ", lane " + std::to_string(lane);
            if (g.sumPlusOne == 0) return {false, "an invocation never finished (" + where + ")"};
            if (g.rounds != w.rounds || g.trips != w.trips)
                return {false, "lanes that loop together until the last is done (" + where + ": " +
                                   std::to_string(g.rounds) + " rounds, " + std::to_string(g.trips) + " busy; expected " +
                                   std::to_string(w.rounds) + ", " + std::to_string(w.trips) + ")"};
            if (g.received != w.received) return {false, "a shuffle from a lane the subgroup picked (" + where + ")"};
            if (g.sumPlusOne != w.sumPlusOne) return {false, "a butterfly sum of shuffles (" + where + ")"};
        }
    }
    return {true, ""};
}

}  // namespace vitrum
