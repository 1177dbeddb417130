// How full SIMD groups would be if they traced a render's rays in lock step, in three schedules: a
// model, for docs/performance.md's question of whether another schedule could fill the lanes that
// trace.comp leaves idle (docs/gpu-design.md). Its one rule: a group's traversal costs as many steps
// as its longest ray's. The model leaves out what the kernel adds (the traversal's inner loops wait
// for their longest lane, and shading is a round for every lane), so it says what a schedule could
// gain, not what the kernel measures.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "cpu/reference_renderer.h"

namespace vitrum::bench {

struct ScheduleFill {
    // Lanes as trace.comp has them: a lane a pixel, 8x8 workgroups walked in Morton order, each
    // lane tracing its pixel's rays in their order, the k-th rays of a group's lanes together.
    double kernel = 0;
    // One ray a pixel a pass: pass k traces the k-th ray of every pixel that has one, packed into
    // groups in the kernel's pixel order, so that no lane waits for a pixel that has more rays.
    double compacted = 0;
    // The same passes, each sorted by the kind of ray (shadow or not), its direction's octant and
    // its origin's Morton code, so that a group's rays start near one another and go the same way.
    double sorted = 0;
};

namespace detail {

// x's low 10 bits spread to every third bit.
inline std::uint64_t spreadBits(std::uint32_t x) {
    std::uint64_t r = 0;
    for (int b = 0; b < 10; ++b) r |= std::uint64_t((x >> b) & 1u) << (3 * b);
    return r;
}

// The pixels in the order of trace.comp's invocations: workgroups of 8x8 row by row, each walked
// in Morton order (tilePixel in trace.comp).
inline std::vector<std::uint32_t> kernelPixelOrder(std::uint32_t width, std::uint32_t height) {
    std::vector<std::uint32_t> order;
    for (std::uint32_t groupY = 0; groupY < height; groupY += 8)
        for (std::uint32_t groupX = 0; groupX < width; groupX += 8)
            for (std::uint32_t i = 0; i < 64; ++i) {
                const std::uint32_t x = groupX + ((i & 1u) | ((i >> 1u) & 2u) | ((i >> 2u) & 4u));
                const std::uint32_t y = groupY + (((i >> 1u) & 1u) | ((i >> 2u) & 2u) | ((i >> 3u) & 4u));
                if (x < width && y < height) order.push_back(y * width + x);
            }
    return order;
}

}  // namespace detail

// The rays of `rays` (as the reference logged them: each pixel's rays together, in order) one ray a
// pixel a pass: pass k holds the k-th ray of every pixel that has one, in the kernel's pixel
// order, or with `sorted` ordered by the kind of ray (shadow or not), its direction's octant and
// its origin's Morton code, so that neighbouring rays start near one another and go the same way.
inline std::vector<std::vector<std::size_t>> rayPasses(std::span<const TracedRay> rays, std::uint32_t width,
                                                       std::uint32_t height, bool sorted) {
    std::vector<std::vector<std::size_t>> perPixel(std::size_t(width) * height);
    for (std::size_t i = 0; i < rays.size(); ++i) perPixel[rays[i].pixel].push_back(i);
    const std::vector<std::uint32_t> order = detail::kernelPixelOrder(width, height);
    glm::vec3 low(3.0e38f), high(-3.0e38f);
    for (const TracedRay& r : rays) {
        low = glm::min(low, r.origin);
        high = glm::max(high, r.origin);
    }
    const glm::vec3 extent = glm::max(high - low, glm::vec3(1e-30f));
    std::vector<std::uint64_t> sortKeys;
    if (sorted) {
        sortKeys.reserve(rays.size());
        for (const TracedRay& r : rays) {
            const glm::uvec3 cell(glm::clamp((r.origin - low) / extent, 0.0f, 1.0f) * 1023.0f);
            const std::uint64_t octant = (r.direction.x < 0) | (r.direction.y < 0) << 1 | (r.direction.z < 0) << 2;
            const std::uint64_t morton =
                detail::spreadBits(cell.x) | detail::spreadBits(cell.y) << 1 | detail::spreadBits(cell.z) << 2;
            sortKeys.push_back(std::uint64_t(r.anyHit) << 40 | octant << 32 | morton);
        }
    }
    std::vector<std::vector<std::size_t>> passes;
    for (std::size_t k = 0;; ++k) {
        std::vector<std::size_t> pass;
        for (std::uint32_t pixel : order)
            if (k < perPixel[pixel].size()) pass.push_back(perPixel[pixel][k]);
        if (pass.empty()) break;
        if (sorted)
            std::stable_sort(pass.begin(), pass.end(),
                             [&](std::size_t a, std::size_t b) { return sortKeys[a] < sortKeys[b]; });
        passes.push_back(std::move(pass));
    }
    return passes;
}

// An index in kernelSchedule's order that holds no ray: a lane with nothing to trace.
constexpr std::size_t kIdleLane = ~std::size_t(0);

// The rays as trace.comp's lanes trace them: a lane a pixel, `lanes` pixels a group in the
// kernel's pixel order, round k of a group the k-th ray of each of its lanes, kIdleLane for a
// lane whose pixel has no k-th ray. Every group's rounds are `lanes` entries each.
inline std::vector<std::size_t> kernelSchedule(std::span<const TracedRay> rays, std::uint32_t width,
                                               std::uint32_t height, std::uint32_t lanes) {
    std::vector<std::vector<std::size_t>> perPixel(std::size_t(width) * height);
    for (std::size_t i = 0; i < rays.size(); ++i) perPixel[rays[i].pixel].push_back(i);
    const std::vector<std::uint32_t> order = detail::kernelPixelOrder(width, height);
    std::vector<std::size_t> schedule;
    for (std::size_t first = 0; first < order.size(); first += lanes) {
        std::size_t rounds = 0;
        for (std::size_t l = first; l < std::min(order.size(), first + lanes); ++l)
            rounds = std::max(rounds, perPixel[order[l]].size());
        for (std::size_t k = 0; k < rounds; ++k)
            for (std::size_t l = first; l < first + lanes; ++l)
                schedule.push_back(l < order.size() && k < perPixel[order[l]].size() ? perPixel[order[l]][k]
                                                                                      : kIdleLane);
    }
    return schedule;
}

// `rays` as the reference logged them (each pixel's rays together, in order), `steps[i]` what
// tracing ray i costs (for example node visits + triangle tests + 1). Each fill is the lanes' steps
// over the steps their groups run: 1 when no lane ever waits.
inline ScheduleFill scheduleFill(std::span<const TracedRay> rays, std::span<const double> steps, std::uint32_t width,
                                 std::uint32_t height, std::uint32_t lanes) {
    double total = 0;
    for (double s : steps) total += s;
    // Rays packed into groups of `lanes`: each group costs its longest ray (idle lanes cost nothing).
    auto packedCost = [&](const std::vector<std::size_t>& order) {
        double cost = 0;
        for (std::size_t first = 0; first < order.size(); first += lanes) {
            double longest = 0;
            for (std::size_t i = first; i < std::min(order.size(), first + lanes); ++i)
                if (order[i] != kIdleLane) longest = std::max(longest, steps[order[i]]);
            cost += longest;
        }
        return cost;
    };
    // A lane a pixel: round k of a group costs the longest k-th ray of its lanes.
    const double kernelCost = packedCost(kernelSchedule(rays, width, height, lanes));
    double compactedCost = 0, sortedCost = 0;
    for (const std::vector<std::size_t>& pass : rayPasses(rays, width, height, false)) compactedCost += packedCost(pass);
    for (const std::vector<std::size_t>& pass : rayPasses(rays, width, height, true)) sortedCost += packedCost(pass);
    const double laneSteps = total / double(lanes);
    return {laneSteps / kernelCost, laneSteps / compactedCost, laneSteps / sortedCost};
}

}  // namespace vitrum::bench
