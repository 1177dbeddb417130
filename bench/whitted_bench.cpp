// The whole Whitted workload on lavapipe against Embree 3 on the CPU (docs/performance.md).
//
// Each glass scene is rendered at max_depth 10 by vitrum's kernel on lavapipe; its rays per
// second count every ray of the tree (primary, shadow, reflected, refracted). The CPU reference
// renders the same image and logs every ray it traces: the same ray tree, since it makes the same
// decisions (the tests hold the two images together). Embree then traces exactly those rays
// (closest hit, or any hit for shadow rays) on all cores, and its time is that of the traversal
// alone, with no shading: the comparison is vitrum's whole renderer against Embree's traversal.
// Embree's hits are checked against vitrum's CPU traversal on a sample of the rays first. A kernel
// that only traverses (trace_only_kernel.h) traces the same rays too, in a wavefront's passes:
// what the traversal alone costs lavapipe, without the rest of the renderer.
//
//   vitrum_bench_whitted [RUNS]
#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench_support.h"
#include "embree_triangles.h"
#include "ray_schedules.h"
#include "trace_only_kernel.h"
#include "whitted_workload.h"
#include "bvh/bvh.h"
#include "bvh/bvh_traversal.h"
#include "cpu/reference_renderer.h"
#include "gpu/trace_kernel_cache.h"
#include "gpu/vulkan_device.h"
#include "gpu/vulkan_renderer.h"
#include "gpu_input/traversal_nodes.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kWidth = bench::kWhittedWidth, kHeight = bench::kWhittedHeight;
constexpr std::uint32_t kMaxDepth = bench::kWhittedMaxDepth;

// Embree's scene: one triangle geometry, vertices in vitrum's BVH leaf order, Embree's defaults.
class EmbreeScene {
public:
    explicit EmbreeScene(std::span<const gpu::TriangleVertices> triangles)
        : triangles_(triangles.size(),
                     [&](std::size_t i, int c) { return c == 0 ? triangles[i].v0 : c == 1 ? triangles[i].v1 : triangles[i].v2; },
                     {}) {}

    // The closest hit's t (or -1), or for a shadow ray 1 when blocked, else -1.
    float trace(const TracedRay& r) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        if (r.anyHit) {
            RTCRay ray = bench::embreeRay(r.origin, r.direction, r.tMin, r.tMax);
            rtcOccluded1(triangles_.scene(), &context, &ray);
            return ray.tfar < 0.0f ? 1.0f : -1.0f;  // Embree sets tfar to -inf on a hit
        }
        RTCRayHit hit;
        hit.ray = bench::embreeRay(r.origin, r.direction, r.tMin, r.tMax);
        hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(triangles_.scene(), &context, &hit);
        return hit.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1.0f : hit.ray.tfar;
    }

private:
    bench::EmbreeTriangles triangles_;
};

// Seconds to trace every ray with Embree on `threads` threads, chunks handed out atomically.
double embreeSeconds(const EmbreeScene& embree, const std::vector<TracedRay>& rays, unsigned threads) {
    constexpr std::size_t kChunk = 4096;
    std::atomic<std::size_t> next{0};
    std::atomic<std::size_t> hits{0};  // consumed, so that no tracing is optimised away
    const auto start = std::chrono::steady_clock::now();
    auto worker = [&] {
        std::size_t local = 0;
        for (std::size_t begin = next.fetch_add(kChunk); begin < rays.size(); begin = next.fetch_add(kChunk))
            for (std::size_t i = begin; i < std::min(rays.size(), begin + kChunk); ++i) local += embree.trace(rays[i]) >= 0.0f;
        hits += local;
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (hits.load() > rays.size()) throw std::logic_error("impossible hit count");
    return seconds;
}

// Share of a sample of the rays on which Embree and vitrum's CPU traversal agree: hit or miss,
// and for closest hits the same t to 1e-4 relative (ties and grazing rays may differ).
double agreement(const EmbreeScene& embree, const Bvh& bvh, std::span<const gpu::TriangleVertices> triangles,
                 const std::vector<TracedRay>& rays) {
    std::size_t checked = 0, agree = 0;
    for (std::size_t i = 0; i < rays.size(); i += 97) {
        const TracedRay& r = rays[i];
        const Ray<float> ray{r.origin, r.direction, r.tMin, r.tMax};
        const float theirs = embree.trace(r);
        ++checked;
        if (r.anyHit) {
            agree += traceAny<float>(bvh.nodes, triangles, ray) == (theirs >= 0.0f);
        } else {
            const auto ours = traceClosest<float>(bvh.nodes, triangles, ray);
            agree += ours ? theirs >= 0.0f && std::fabs(theirs - ours->t) <= 1e-4f * ours->t : theirs < 0.0f;
        }
    }
    return checked == 0 ? 1.0 : double(agree) / double(checked);
}

// The rays of all passes, pass after pass (bench/ray_schedules.h).
std::vector<std::size_t> passOrder(std::span<const TracedRay> rays, bool sorted, std::size_t& passCount) {
    std::vector<std::size_t> order;
    const auto passes = bench::rayPasses(rays, kWidth, kHeight, sorted);
    for (const auto& pass : passes) order.insert(order.end(), pass.begin(), pass.end());
    passCount = passes.size();
    return order;
}

// The SIMD groups' iterations over the rays they traced: each invocation of a trace-only kernel
// writes its group's count, so the first of each group's `lanes` holds it.
double groupStepsPerRay(const bench::TraceOnlyKernel& kernel, const std::vector<std::size_t>& order,
                        std::uint32_t lanes) {
    double steps = 0;
    std::size_t traced = 0;
    for (std::size_t k = 0; k < order.size(); ++k) {
        if (k % lanes == 0) steps += kernel.hit(k).w;
        traced += order[k] != bench::kIdleLane;
    }
    return steps / double(std::max<std::size_t>(1, traced));
}

// What each ray costs vitrum's CPU traversal: nodes visited, triangles tested, and one.
std::vector<double> traversalSteps(const Bvh& bvh, std::span<const gpu::TriangleVertices> triangles,
                                   const std::vector<TracedRay>& rays) {
    std::vector<double> steps;
    steps.reserve(rays.size());
    for (const TracedRay& r : rays) {
        TraversalCounters counters;
        const Ray<float> ray{r.origin, r.direction, r.tMin, r.tMax};
        if (r.anyHit) traceAny<float>(bvh.nodes, triangles, ray, &counters);
        else traceClosest<float>(bvh.nodes, triangles, ray, &counters);
        steps.push_back(double(counters.nodeVisits + counters.triangleTests + 1));
    }
    return steps;
}

int run(int argc, char** argv) {
    const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    VulkanDevice device("");
    TraceKernelCache kernels;  // each scene's kernel created once, not once a render
    std::string rows, fillRows, traceOnlyRows;
    double worstRatio = 1e30, bestRatio = 0, worstAgreement = 1.0;
    for (const char* file : bench::kWhittedScenes) {
        const bench::WhittedScene workload = bench::loadWhittedScene(fs::path(VITRUM_SOURCE_DIR) / file);
        const Scene& scene = workload.scene;
        const Bvh& bvh = workload.bvh;
        const std::vector<gpu::TriangleVertices>& triangles = workload.triangles;
        std::cerr << file << ": " << std::flush;

        // The same rays, from the CPU reference's log, traced by Embree.
        const std::vector<TracedRay> rays = bench::whittedRays(workload);
        const EmbreeScene embree(triangles);
        const double agreed = agreement(embree, bvh, triangles, rays);
        worstAgreement = std::min(worstAgreement, agreed);
        if (agreed < 0.99)
            throw std::runtime_error(std::string(file) + ": Embree disagrees with vitrum's traversal on " +
                                     bench::fixed(100.0 * (1.0 - agreed), 2) + "% of the sampled rays");

        // Traversal alone, on the same rays: as the kernel's lanes take them (idle lanes included),
        // and in two wavefront orders (compacted and sorted passes).
        const TraversalNodes tree = makeTraversalNodes(bvh.nodes);
        std::size_t passCount = 0;
        const std::vector<std::size_t> scheduleOrder =
            bench::kernelSchedule(rays, kWidth, kHeight, std::max(1u, device.subgroups().size));
        const std::vector<std::size_t> compactedOrder = passOrder(rays, false, passCount);
        const std::vector<std::size_t> sortedOrder = passOrder(rays, true, passCount);
        const bench::TraceOnlyKernel scheduled(device, tree, triangles, rays, scheduleOrder);
        const bench::TraceOnlyKernel compacted(device, tree, triangles, rays, compactedOrder);
        const bench::TraceOnlyKernel sorted(device, tree, triangles, rays, sortedOrder);
        // One ray a subgroup needs a lane for each of a wide node's 8 children.
        const std::uint32_t lanes = std::max(1u, device.subgroups().size);
        const bench::WideBvh wideTree = bench::makeWideBvh(bvh.nodes);
        std::optional<bench::TraceOnlyKernel> wide;
        if (lanes >= bench::kWideChildren) wide.emplace(device, wideTree, triangles, rays, scheduleOrder);

        // vitrum on lavapipe and Embree take turns, so that the machine's drifts fall on both
        // alike. The first round (vitrum's compile, Embree's first touch of its data) is not counted.
        std::vector<double> gpuTimes, embreeTimes, scheduledTimes, compactedTimes, sortedTimes, wideTimes;
        std::uint64_t gpuRays = 0, touchingProbes = 0;
        RenderStats gpuStats;
        for (int r = 0; r <= runs; ++r) {
            RenderStats stats;
            renderVulkan(device, scene, bvh, VulkanRenderOptions{.kernels = &kernels}, stats);
            const double embreeTime = embreeSeconds(embree, rays, threads);
            const double scheduledTime = scheduled.trace(device);
            const double compactedTime = compacted.trace(device);
            const double sortedTime = sorted.trace(device);
            const double wideTime = wide ? wide->trace(device) : 0.0;
            if (r == 0) {
                bench::checkTraceOnly(scheduled, scheduleOrder, bvh, triangles, rays, file);
                bench::checkTraceOnly(compacted, compactedOrder, bvh, triangles, rays, file);
                bench::checkTraceOnly(sorted, sortedOrder, bvh, triangles, rays, file);
                if (wide) bench::checkTraceOnly(*wide, scheduleOrder, bvh, triangles, rays, file);
                continue;
            }
            scheduledTimes.push_back(scheduledTime);
            compactedTimes.push_back(compactedTime);
            sortedTimes.push_back(sortedTime);
            wideTimes.push_back(wideTime);
            gpuTimes.push_back(stats.seconds("render"));
            embreeTimes.push_back(embreeTime);
            gpuRays = stats.totalRays();
            touchingProbes = stats.touchingProbes;
            gpuStats = stats;
        }
        const double gpu = bench::median(gpuTimes);
        const double cpu = bench::median(embreeTimes);

        const double ours = double(gpuRays) / gpu * 1e-6;
        const double theirs = double(rays.size()) / cpu * 1e-6;
        const double ratio = ours / theirs;
        worstRatio = std::min(worstRatio, ratio);
        bestRatio = std::max(bestRatio, ratio);
        std::size_t shadow = 0;
        for (const TracedRay& r : rays) shadow += r.anyHit;
        rows += "| " + fs::path(file).stem().string() + " | " + std::to_string(scene.triangles.size()) + " | " +
                std::to_string(gpuRays) + " | " + std::to_string(touchingProbes) + " | " + std::to_string(rays.size()) + " | " +
                bench::fixed(100.0 * double(shadow) / double(std::max<std::size_t>(1, rays.size())), 0) + "% | " +
                bench::fixed(gpu, 3) + " | " + bench::fixed(ours, 2) + " | " + bench::fixed(cpu, 4) + " | " +
                bench::fixed(theirs, 2) + " | **" + bench::fixed(ratio, 3) + "x** |\n";
        std::cerr << bench::fixed(ours, 2) << " against " << bench::fixed(theirs, 2) << " Mrays/s";
        const double scheduledRate = double(rays.size()) / bench::median(scheduledTimes) * 1e-6;
        const double compactedRate = double(rays.size()) / bench::median(compactedTimes) * 1e-6;
        const double sortedRate = double(rays.size()) / bench::median(sortedTimes) * 1e-6;
        const double wideRate = wide ? double(rays.size()) / bench::median(wideTimes) * 1e-6 : 0.0;
        std::cerr << "; traversal alone " << bench::fixed(scheduledRate, 2) << " (the kernel's schedule), "
                  << bench::fixed(compactedRate, 2) << " (compacted), " << bench::fixed(sortedRate, 2) << " (sorted), "
                  << bench::fixed(wideRate, 2) << " (one ray a subgroup)\n";
        auto traceOnlyColumns = [&](const std::vector<double>& times, double rate) {
            return " | " + bench::fixed(bench::median(times), 3) + " | " + bench::fixed(rate, 2) + " | " +
                   bench::fixed(rate / theirs, 3) + "x";
        };
        traceOnlyRows += "| " + fs::path(file).stem().string() + " | " + bench::fixed(ratio, 3) + "x" +
                         traceOnlyColumns(scheduledTimes, scheduledRate) + " | " + std::to_string(passCount) +
                         traceOnlyColumns(compactedTimes, compactedRate) + traceOnlyColumns(sortedTimes, sortedRate) +
                         (wide ? traceOnlyColumns(wideTimes, wideRate) : std::string(" | - | - | -")) + " | " +
                         bench::fixed(wideTree.meanChildren, 1) + " | " +
                         bench::fixed(groupStepsPerRay(scheduled, scheduleOrder, lanes), 1) + " | " +
                         (wide ? bench::fixed(groupStepsPerRay(*wide, scheduleOrder, lanes), 1) : std::string("-")) + " |\n";

        // How full vitrum's SIMD groups were, and how full other schedules of the same rays could be.
        const double measured = double(gpuStats.loopSteps + gpuStats.restartedSteps) /
                                double(std::max<std::uint64_t>(1, gpuStats.groupLoopSteps * gpuStats.lanesPerGroup));
        const bench::ScheduleFill model = bench::scheduleFill(rays, traversalSteps(bvh, triangles, rays), kWidth,
                                                              kHeight, std::max(1u, gpuStats.lanesPerGroup));
        fillRows += "| " + fs::path(file).stem().string() + " | " + bench::fixed(measured, 2) + " | " +
                    bench::fixed(model.kernel, 2) + " | " + bench::fixed(model.compacted, 2) + " | " +
                    bench::fixed(model.sorted, 2) + " | " + bench::fixed(model.sorted / model.kernel, 2) + "x | " +
                    bench::fixed(1.0 / model.kernel, 2) + "x |\n";
    }

    std::cout << "\n## The Whitted workload: vitrum on lavapipe against Embree 3\n\n"
              << "Generated by `make bench-performance` (bench/whitted_bench.cpp) on " << bench::today()
              << ". Machine: " << bench::machine() << "; device: " << device.name() << "; Embree " << RTC_VERSION_STRING
              << " on " << threads << " threads.\n\n"
              << "Every glass scene at " << kWidth << "x" << kHeight << ", 1 spp, max_depth " << kMaxDepth
              << ". vitrum's rays are every ray of its trees (primary, shadow, reflected, refracted), and its time is "
                 "the whole render "
                 "on lavapipe, shading included; where two glass objects can touch, its closest-hit traversals also "
                 "collect the glass surfaces within the touching distance of each hit (the column counts the glass hits "
                 "so examined; the CPU reference runs a second traversal for each, which Embree does not trace). "
                 "Embree traces the rays that the CPU reference "
                 "logged while rendering the same image (closest hit with `rtcIntersect1`, shadow rays with "
                 "`rtcOccluded1`, default scene flags), traversal only, no shading. The two take turns, "
              << runs << " times each after a first round that is not counted (vitrum's compile, Embree's first touch of "
                 "its data); the times are medians. Embree agrees with vitrum's CPU traversal (hit or miss, and the "
                 "same t to 1e-4) on at least "
              << bench::fixed(100.0 * worstAgreement, 2) << "% of a sample of every 97th ray of each scene (the rest graze edges "
                 "or end on a surface, where the two triangle tests may differ: Embree's default one is not the watertight "
                 "test vitrum uses, and it accepts t = tnear). The two ray counts differ a little where float rounding "
                 "sends a ray down another branch of the tree.\n\n"
              << "| scene | triangles | vitrum rays | glass hits examined for touching | Embree rays | shadow rays | vitrum s | vitrum Mrays/s | "
                 "Embree s | Embree Mrays/s | vitrum against Embree |\n"
              << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n"
              << rows << "\nvitrum reaches " << bench::fixed(worstRatio, 3) << "x to " << bench::fixed(bestRatio, 3)
              << "x of Embree's rays per second; issue 51's target is at least 0.5x on every scene.\n"
              << "\n### How full the SIMD groups are\n\n"
                 "The same renders. *Measured*: the steps vitrum's lanes ran (`loop_steps` + `restarted_steps`) over the "
                 "steps their SIMD groups ran (`group_loop_steps`, as the budget counts them, which misses at most "
                 "about 20 of lavapipe's iterations a dispatch) times the lanes a group (`lanes_per_group`): lanes that wait for the others of their group "
                 "make it less than 1. The other columns are a model (bench/ray_schedules.h) of the CPU reference's rays "
                 "in groups of as many lanes, in which a group's traversal costs as many steps as its longest ray's "
                 "(vitrum's CPU traversal: nodes visited + triangles tested + 1). *The kernel's schedule*: a lane a pixel, "
                 "the pixels as trace.comp orders them, the k-th rays of a group's lanes together. *Compacted*: one ray a "
                 "pixel a pass, pass k tracing the k-th ray of every pixel that has one, packed into groups in the same "
                 "pixel order. *Sorted*: the same passes sorted by the kind of ray, its direction's octant and its origin's "
                 "Morton code. The model leaves out the waits inside a traversal (the inner loops run as long as their "
                 "longest lane) and the shading rounds, so it says what a schedule could gain, not what the kernel "
                 "measures; the last column is what every lane busy would gain over the kernel's schedule.\n\n"
                 "| scene | measured | model: the kernel's schedule | compacted | sorted | sorted against the kernel's | "
                 "every lane busy against the kernel's |\n"
                 "|---|---:|---:|---:|---:|---:|---:|\n"
              << fillRows
              << "\n### Traversal alone: what the rest of the kernel costs, and a wavefront's trace passes\n\n"
                 "The same rays traced by a kernel that only traverses (bench/trace_only/trace_rays.comp: vitrum's "
                 "own traversal, shaders/bvh.glsl, one ray an invocation, the hit written out; no shading, no pixel "
                 "state, no pending rays, and no collection of touching surfaces, which water_glass's renders do), "
                 "in one dispatch, in three orders: *the kernel's schedule* (a lane a pixel, the k-th rays of a group's "
                 "lanes together, a lane without a k-th ray idle, as trace.comp's lanes trace them: the whole "
                 "kernel's time less this is what everything but the traversal costs it, or more where its ray "
                 "sharing fills idle lanes), and all the passes of the model above, one after another, *compacted* and "
                 "*sorted*. "
                 "Timed in turns with the renders above; medians. Every traversal ends, and on at least 99.5% of "
                 "every 97th ray it finds what vitrum's CPU traversal finds (hit or miss, the same t to 4 ulps, "
                 "which a device's division may add), or the benchmark stops. A wavefront renderer would add to this its shading passes, the rays' and hits' "
                 "trips through memory and a dispatch a pass.\n\n"
                 "The last columns trace the kernel's schedule another way (bench/trace_only/trace_rays_wide.comp): "
                 "*one ray a subgroup*, its lanes testing the children of one node of the tree collapsed into 8-wide "
                 "nodes (bench/wide_bvh.h; *children a wide node* gives their mean) or the triangles of one leaf, "
                 "as a CPU tracer's SIMD lanes do for one ray, and the subgroup's rays one after another: no lane waits "
                 "on a ray that went another way, however incoherent the rays. The iterations a ray are those of the "
                 "SIMD groups over the rays they trace: the lanes' traversal shares each of its iterations among the "
                 "group's rays, one ray a subgroup has a whole iteration for each visit (cross-lane operations are "
                 "loops over the lanes on lavapipe: docs/gpu-design.md).\n\n"
                 "| scene | the whole kernel against Embree | the kernel's schedule s | Mrays/s | against Embree | "
                 "passes | compacted s | Mrays/s | against Embree | sorted s | Mrays/s | against Embree | "
                 "one ray a subgroup s | Mrays/s | against Embree | children a wide node | group iterations a ray: "
                 "the kernel's schedule | one ray a subgroup |\n"
                 "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n"
              << traceOnlyRows;
    return 0;
}

}  // namespace
}  // namespace vitrum

int main(int argc, char** argv) {
    return vitrum::bench::guardedMain("vitrum_bench_whitted", [&] { return vitrum::run(argc, argv); });
}
