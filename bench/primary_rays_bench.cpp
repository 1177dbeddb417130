// Primary rays on lavapipe: vitrum's kernel against the plain baseline (bench/baseline/
// plain_primary.comp: one ray per invocation, Aila-Laine nodes, a stack) on a generated terrain
// of about 72k triangles at 640x480. The baseline's hits are checked against the CPU traversal
// before it is timed. Prints a Markdown section for docs/performance.md; `make bench-performance`.
//
//   vitrum_bench_primary_rays [RUNS]
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <vector>

#include "bench_support.h"
#include "bench_terrain.h"
#include "bvh/bvh.h"
#include "bvh/bvh_traversal.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "gpu/trace_kernel_cache.h"
#include "gpu/vulkan_device.h"
#include "gpu/vulkan_renderer.h"
#include "plain_primary.spv.h"
#include "plain_primary_texel.spv.h"
#include "gpu_input/traversal_nodes.h"

namespace vitrum {
namespace {

constexpr int kTerrainCells = 190;  // 2 * 190^2 = 72,200 triangles
constexpr std::uint32_t kWidth = 640, kHeight = 480;

struct PlainNode {
    glm::vec4 lo0, hi0, lo1, hi1;
    glm::ivec4 links;
};
struct PlainCamera {
    glm::vec4 origin, lowerLeft, right, down;
    glm::ivec4 rootLeaf;
};

// vitrum's GPU nodes (gpu_input/traversal_nodes.h, already Aila-Laine: both children's boxes in the
// parent) in the baseline's textbook encoding: links in a texel of their own, a leaf as
// ~firstTriangle with its count.
std::vector<PlainNode> toPlainNodes(const TraversalNodes& tree) {
    auto link = [](std::uint32_t entry, int& count) {
        if (!(entry & gpu::kLeafEntryFlag)) return int(entry);
        count = int(entry & 15u);
        return ~int((entry & ~gpu::kLeafEntryFlag) >> 4);
    };
    std::vector<PlainNode> plain(std::max<std::size_t>(tree.nodes.size(), 1));
    for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
        const gpu::TraversalNode& n = tree.nodes[i];
        PlainNode& p = plain[i];
        p.lo0 = glm::vec4(glm::vec3(n.min0), 0.0f);
        p.hi0 = glm::vec4(glm::vec3(n.max0), 0.0f);
        p.lo1 = glm::vec4(glm::vec3(n.min1), 0.0f);
        p.hi1 = glm::vec4(glm::vec3(n.max1), 0.0f);
        p.links = glm::ivec4(0);
        p.links.x = link(glm::floatBitsToUint(n.min0.w), p.links.z);
        p.links.y = link(glm::floatBitsToUint(n.min1.w), p.links.w);
    }
    return plain;
}

PlainCamera plainCamera(const Camera& camera, const TraversalNodes& tree) {
    const glm::vec3 forward = glm::normalize(camera.at - camera.from);
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
    const glm::vec3 up = glm::cross(right, forward);
    const float halfHeight = std::tan(glm::radians(camera.fovY) * 0.5f);
    const float halfWidth = halfHeight * float(camera.width) / float(camera.height);
    PlainCamera c;
    c.origin = glm::vec4(camera.from, float(camera.width));
    c.lowerLeft = glm::vec4(forward - halfWidth * right + halfHeight * up, float(camera.height));
    c.right = glm::vec4(right * (2.0f * halfWidth / float(camera.width)), 0.0f);
    c.down = glm::vec4(-up * (2.0f * halfHeight / float(camera.height)), 0.0f);
    const bool rootIsLeaf = (tree.rootEntry & gpu::kLeafEntryFlag) != 0;
    c.rootLeaf = rootIsLeaf ? glm::ivec4(1, int(tree.rootEntry & 15u), 0, 0) : glm::ivec4(0);
    return c;
}

// One of the two baseline kernels with its buffers: nodes and triangles in storage buffers
// (plain_primary.comp) or in uniform texel buffers (plain_primary_texel.comp).
class PlainKernel {
public:
    template <std::size_t N>
    PlainKernel(VulkanDevice& device, const std::uint32_t (&spirv)[N], VkDescriptorType sceneBinding,
                const std::vector<PlainNode>& nodes, const std::vector<gpu::TriangleVertices>& triangles,
                const PlainCamera& camera)
        : pipeline_(device, std::span<const std::uint32_t>(spirv, N),
                    std::array<VkDescriptorType, 4>{sceneBinding, sceneBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                                    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}),
          nodes_(sceneBuffer(device, sceneBinding, std::span<const PlainNode>(nodes), "baseline nodes")),
          triangles_(sceneBuffer(device, sceneBinding, std::span<const gpu::TriangleVertices>(triangles), "baseline triangles")),
          camera_(makeStorageBuffer(device, std::span<const PlainCamera>(&camera, 1), "baseline camera")),
          hits_(device, VkDeviceSize(kWidth) * kHeight * sizeof(glm::vec2), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "baseline hits", MemoryUse::Readback) {
        const std::array<const GpuBuffer*, 4> bound = {&nodes_, &triangles_, &camera_, &hits_};
        pipeline_.bind(bound);
    }

    // Seconds for one frame (the first one includes lavapipe's compile).
    double dispatch(VulkanDevice& device) const {
        const auto start = std::chrono::steady_clock::now();
        device.submitAndWait([&](VkCommandBuffer commands) { pipeline_.record(commands, kWidth / 8, kHeight / 8); });
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    const glm::vec2* hits() const { return hits_.as<glm::vec2>(); }

private:
    template <class T>
    static GpuBuffer sceneBuffer(VulkanDevice& device, VkDescriptorType type, std::span<const T> data, const char* what) {
        return type == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER ? makeTexelBuffer(device, data, what)
                                                               : makeStorageBuffer(device, data, what);
    }

    ComputePipeline pipeline_;
    GpuBuffer nodes_, triangles_, camera_, hits_;
};

int run(int argc, char** argv) {
    const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
    Scene scene;
    scene.triangles = bench::terrain(kTerrainCells);
    for (Triangle& t : scene.triangles) t.material = 0;
    scene.materials.resize(1);  // one default (Phong, diffuse only) material
    scene.camera.from = {0.0f, -3.2f, 2.4f};
    scene.camera.at = {0.0f, 0.0f, 0.0f};
    scene.camera.fovY = 50.0f;
    scene.camera.width = kWidth;
    scene.camera.height = kHeight;
    scene.background.colour = glm::vec3(0.2f);
    scene.settings.maxDepth = 1;  // primary rays only; no lights, so no shadow rays
    const Bvh bvh = buildSceneBvh(scene);
    const std::vector<gpu::TriangleVertices> vertices = packTriangleVertices(bvh, scene.triangles);
    const TraversalNodes tree = makeTraversalNodes(bvh.nodes);
    const std::vector<PlainNode> plainNodes = toPlainNodes(tree);
    const PlainCamera camera = plainCamera(scene.camera, tree);

    VulkanDevice device("");
    PlainKernel storage(device, plain_primary_spv, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, plainNodes, vertices, camera);
    PlainKernel texel(device, plain_primary_texel_spv, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, plainNodes, vertices, camera);
    const double baselineCompile = storage.dispatch(device);
    const double texelCompile = texel.dispatch(device);

    // Correctness first: the same hits as the CPU traversal of vitrum's own nodes.
    std::size_t agree = 0, agreeTexel = 0, hitCount = 0;
    for (std::uint32_t y = 0; y < kHeight; ++y)
        for (std::uint32_t x = 0; x < kWidth; ++x) {
            const glm::vec3 direction = glm::normalize(glm::vec3(camera.lowerLeft) + (float(x) + 0.5f) * glm::vec3(camera.right) +
                                                       (float(y) + 0.5f) * glm::vec3(camera.down));
            const auto cpu = traceClosest<float>(bvh.nodes, vertices, Ray<float>{glm::vec3(camera.origin), direction});
            hitCount += cpu.has_value();
            auto agrees = [&](const PlainKernel& kernel) {
                const glm::vec2 gpu = kernel.hits()[y * kWidth + x];
                return cpu ? std::fabs(gpu.x - cpu->t) <= 1e-4f * cpu->t : gpu.x < 0.0f;
            };
            agree += agrees(storage);
            agreeTexel += agrees(texel);
        }
    const double agreement = double(std::min(agree, agreeTexel)) / double(kWidth * kHeight);
    if (agreement < 0.999) throw std::runtime_error("a baseline disagrees with the CPU traversal on " +
                                                    bench::fixed(100.0 * (1.0 - agreement), 2) + "% of the pixels");
    // The kernels take turns, so that the machine's drifts (other tenants of a shared host) fall
    // on all alike.
    std::vector<double> baselineTimes, texelTimes, vitrumTimes;
    TraceKernelCache kernels;  // created and compiled in the first run, which is not counted
    double vitrumCompile = 0;
    std::uint64_t rays = 0;
    for (int r = 0; r <= runs; ++r) {
        RenderStats stats;
        renderVulkan(device, scene, bvh, VulkanRenderOptions{.kernels = &kernels}, stats);
        if (r == 0) {
            vitrumCompile = stats.seconds("pipeline") + stats.seconds("compile");
            continue;
        }
        vitrumTimes.push_back(stats.seconds("render"));
        rays = stats.totalRays();
        baselineTimes.push_back(storage.dispatch(device));
        texelTimes.push_back(texel.dispatch(device));
    }
    const double baseline = bench::median(baselineTimes);
    const double baselineTexel = bench::median(texelTimes);
    const double ours = bench::median(vitrumTimes);
    const double pixels = double(kWidth) * kHeight;

    std::cout << "\n## Primary rays: vitrum against a plain GPU traversal\n\n"
              << "Generated by `make bench-performance` (bench/primary_rays_bench.cpp) on " << bench::today()
              << ". Machine: " << bench::machine() << "; device: " << device.name() << ".\n\n"
              << "A generated terrain of " << scene.triangles.size() << " triangles (BVH: " << bvh.stats.nodeCount
              << " nodes), seen at an angle, " << kWidth << "x" << kHeight << ", one ray a pixel (" << hitCount
              << " of them hit). The baseline (`bench/baseline/plain_primary.comp`) is the textbook kernel: one ray per "
                 "invocation, Aila-Laine nodes (both children's boxes in the parent, " << plainNodes.size()
              << " nodes of 80 bytes), a 64-entry stack, the same watertight triangle test; it only finds the hit. "
                 "It agrees with the CPU traversal on "
              << bench::fixed(100.0 * agreement, 2) << "% of the pixels. vitrum renders the same view with `max_depth` 1 and no "
                 "lights: its full kernel (tiles, the first dispatch of each, shading of the hit), " << rays << " rays. The "
                 "baseline's second build reads its nodes and triangles from uniform texel buffers (`texelFetch`); vitrum "
                 "reads its scene from storage texel buffers (`imageLoad`, docs/gpu-design.md). Times are "
                 "medians of " << runs << " runs, the two kernels taking turns; the first run (compile) is not counted.\n\n"
              << "| kernel | s a frame | Mrays/s | compile s | vitrum against the baseline |\n"
              << "|---|---:|---:|---:|---:|\n"
              << "| plain baseline | " << bench::fixed(baseline, 3) << " | " << bench::fixed(pixels / baseline * 1e-6, 2) << " | "
              << bench::fixed(baselineCompile, 2) << " | |\n"
              << "| plain baseline, texel buffers | " << bench::fixed(baselineTexel, 3) << " | "
              << bench::fixed(pixels / baselineTexel * 1e-6, 2) << " | " << bench::fixed(texelCompile, 2) << " | |\n"
              << "| vitrum | " << bench::fixed(ours, 3) << " | " << bench::fixed(pixels / ours * 1e-6, 2) << " | " << bench::fixed(vitrumCompile, 2)
              << " | **" << bench::fixed(baseline / ours, 2) << "x** |\n";
    std::cerr << "baseline " << bench::fixed(pixels / baseline * 1e-6, 2) << " Mrays/s, on texel buffers "
              << bench::fixed(pixels / baselineTexel * 1e-6, 2) << " Mrays/s, vitrum " << bench::fixed(pixels / ours * 1e-6, 2)
              << " Mrays/s\n";
    return 0;
}

}  // namespace
}  // namespace vitrum

int main(int argc, char** argv) {
    return vitrum::bench::guardedMain("vitrum_bench_primary_rays", [&] { return vitrum::run(argc, argv); });
}
