// Traversal alone on the device: a list of rays traced with vitrum's own traversal, one ray an
// invocation, nothing else (bench/trace_only/trace_rays.comp), or one ray a subgroup over the
// tree's 8-wide collapse (trace_rays_wide.comp). bench/whitted_bench.cpp times them on the
// Whitted workload's rays, in the kernel's order and in the order a wavefront renderer would
// trace them, to measure what the rest of the kernel and such a renderer's trace passes cost
// against the whole kernel and Embree; bench/ray_query_bench.cpp times the first against a
// driver's own traversal (ray queries) on the same rays.
#pragma once

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/bvh_traversal.h"
#include "cpu/reference_renderer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "gpu/vulkan_device.h"
#include "ray_schedules.h"
#include "gpu_input/traversal_nodes.h"
#include "trace_rays.spv.h"
#include "trace_rays_wide.spv.h"
#include "wide_bvh.h"

namespace vitrum::bench {

class TraceOnlyKernel {
public:
    // `order`: the rays to trace, in the order the kernel's invocations take them; an invocation
    // given bench::kIdleLane traces nothing, as a lane of trace.comp without a ray waits.
    // trace_rays.comp on vitrum's binary tree:
    TraceOnlyKernel(VulkanDevice& device, const TraversalNodes& tree,
                    std::span<const gpu::TriangleVertices> triangles, std::span<const TracedRay> rays,
                    std::span<const std::size_t> order)
        : TraceOnlyKernel(device, trace_rays_spv, nodeTexels(tree), tree.rootEntry, triangles, rays, order) {}
    // trace_rays_wide.comp on the same tree collapsed into 8-wide nodes (wide_bvh.h):
    TraceOnlyKernel(VulkanDevice& device, const WideBvh& tree, std::span<const gpu::TriangleVertices> triangles,
                    std::span<const TracedRay> rays, std::span<const std::size_t> order)
        : TraceOnlyKernel(device, trace_rays_wide_spv, tree.texels, tree.rootEntry, triangles, rays, order) {}

    // Seconds to trace every ray once (the first call includes lavapipe's compile).
    double trace(VulkanDevice& device) const {
        constexpr std::uint32_t kGroupSize = 64, kMaxGroupsX = 32768;
        const std::uint32_t groups = (count_ + kGroupSize - 1) / kGroupSize;
        const std::uint32_t groupsX = std::min(groups, kMaxGroupsX);
        const std::uint32_t groupsY = (groups + groupsX - 1) / groupsX;
        const auto start = std::chrono::steady_clock::now();
        device.submitAndWait([&](VkCommandBuffer commands) { pipeline_.record(commands, groupsX, groupsY); });
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }

    // Ray k of `order`: .x = the closest (or some) hit's t, or -1; .z = 1 when its traversal is
    // over; .w = the steps its SIMD group ran.
    const glm::vec4& hit(std::size_t k) const { return hits_.as<glm::vec4>()[k]; }

private:
    template <std::size_t N>
    TraceOnlyKernel(VulkanDevice& device, const std::uint32_t (&spirv)[N], std::span<const glm::vec4> nodes,
                    std::uint32_t rootEntry, std::span<const gpu::TriangleVertices> triangles,
                    std::span<const TracedRay> rays, std::span<const std::size_t> order)
        : pipeline_(device, std::span<const std::uint32_t>(spirv),
                    std::array<VkDescriptorType, 5>{VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER,
                                                    VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER,
                                                    VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER,
                                                    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                    nullptr, VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT_EXT),
          count_(std::uint32_t(order.size())) {
        if (!device.subgroups().fullSubgroups) throw std::runtime_error("the trace-only kernel needs full subgroups");
        std::vector<glm::vec4> texels;
        texels.reserve(2 * order.size());
        for (std::size_t i : order) {
            if (i == kIdleLane) {  // tMin -1: no ray (a traced ray's tMin is never negative)
                texels.emplace_back(0.0f, 0.0f, 0.0f, -1.0f);
                texels.emplace_back(0.0f, 0.0f, 1.0f, 1.0f);
                continue;
            }
            const TracedRay& r = rays[i];
            texels.emplace_back(r.origin, r.tMin);
            texels.emplace_back(r.direction, r.anyHit ? -r.tMax : r.tMax);
        }
        nodes_ = makeTexelBuffer(device, nodes, "trace-only nodes");
        triangles_ = makeTexelBuffer(device, triangles, "trace-only triangles");
        rays_ = makeTexelBuffer(device, std::span<const glm::vec4>(texels), "trace-only rays");
        const glm::uvec4 control(rootEntry, count_, 0u, 0u);
        control_ = makeStorageBuffer(device, std::span<const glm::uvec4>(&control, 1), "trace-only control");
        hits_ = GpuBuffer(device, std::max<VkDeviceSize>(16, VkDeviceSize(count_) * sizeof(glm::vec4)),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "trace-only hits", MemoryUse::Readback);
        const std::array<const GpuBuffer*, 5> bound = {&nodes_, &triangles_, &rays_, &control_, &hits_};
        pipeline_.bind(bound);
    }

    // The binary tree's nodes as texels (one node, unused, for a tree that is one leaf).
    static std::vector<glm::vec4> nodeTexels(const TraversalNodes& tree) {
        const std::vector<gpu::TraversalNode> nodes =
            tree.nodes.empty() ? std::vector<gpu::TraversalNode>(1) : tree.nodes;
        std::vector<glm::vec4> texels;
        for (const gpu::TraversalNode& n : nodes) texels.insert(texels.end(), {n.min0, n.max0, n.min1, n.max1});
        return texels;
    }

    ComputePipeline pipeline_;
    GpuBuffer nodes_, triangles_, rays_, control_, hits_;
    std::uint32_t count_;
};

// Checks the trace-only kernel's results against vitrum's CPU traversal on every 97th ray:
// every traversal over, and the same hit or miss, at the same t for closest hits (to the ulps a
// device's division may add).
inline void checkTraceOnly(const TraceOnlyKernel& kernel, const std::vector<std::size_t>& order, const Bvh& bvh,
                           std::span<const gpu::TriangleVertices> triangles, const std::vector<TracedRay>& rays,
                           const char* file) {
    std::size_t checked = 0, agree = 0, anyHitDisagreements = 0;
    for (std::size_t k = 0; k < order.size(); ++k) {
        const glm::vec4& h = kernel.hit(k);
        if (h.z != 1.0f) throw std::runtime_error(std::string(file) + ": a trace-only traversal did not finish");
        if (k % 97 != 0 || order[k] == kIdleLane) continue;
        const TracedRay& r = rays[order[k]];
        const Ray<float> ray{r.origin, r.direction, r.tMin, r.tMax};
        ++checked;
        if (r.anyHit) {
            const bool same = traceAny<float>(bvh.nodes, triangles, ray) == (h.x >= 0.0f);
            agree += same;
            anyHitDisagreements += !same;
        } else {
            const auto ours = traceClosest<float>(bvh.nodes, triangles, ray);
            // The same t to 4 ulps: t divides by the triangle's determinant, which Vulkan lets a
            // device round to 2.5 ulps (lavapipe rounds it as the CPU does: the same t exactly).
            agree += ours ? std::abs(h.x - ours->t) <= 4.0f * (std::nextafter(ours->t, INFINITY) - ours->t) : h.x < 0.0f;
        }
    }
    // Where a device divides less exactly, a hit within ulps of a ray's tMin or tMax may fall on
    // the other side of it: up to 0.5% of the rays (lavapipe: none).
    if (agree + checked / 200 < checked)
        throw std::runtime_error(std::string(file) + ": the trace-only kernel disagrees with the CPU traversal on " +
                                 std::to_string(checked - agree) + " of " + std::to_string(checked) + " rays (" +
                                 std::to_string(anyHitDisagreements) + " of them any-hit)");
}

}  // namespace vitrum::bench
