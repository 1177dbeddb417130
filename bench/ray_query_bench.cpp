// vitrum's own traversal against the driver's (docs/performance.md): Mesa 25's lavapipe offers
// VK_KHR_ray_query, a traversal of an acceleration structure that the driver builds and walks
// itself, so a renderer on it could leave its BVH to the driver (issue 51). Each glass scene of
// the Whitted workload (whitted_workload.h) gives the rays of its trees as the CPU reference
// traces them; the rays are traced in one dispatch by the driver's ray queries
// (ray_query_tracer.h) and by vitrum's traversal alone (trace_only_kernel.h) on the same device,
// in the same order: every pixel's primary ray, then every pixel's second ray, and so on (the
// compacted passes of bench/ray_schedules.h), and the primary rays alone. The driver builds its
// structure twice: from the triangles in the scene's order, as a renderer on ray queries alone
// would hand them over, and in vitrum's BVH order (its leaves left to right), since how the
// driver's tree comes out may depend on the order it is given. All are checked against vitrum's
// CPU traversal first; then they take turns, with the build of each one's tree.
//
//   vitrum_bench_ray_query [RUNS]     the report's section, on the first device that offers ray queries
//   vitrum_bench_ray_query --check    the checks alone (the first round), for a run under validation
//   vitrum_bench_ray_query --devices  whether each device offers them
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_support.h"
#include "bvh/bvh.h"
#include "bvh/bvh_traversal.h"
#include "gpu/vulkan_device.h"
#include "gpu_input/traversal_nodes.h"
#include "ray_query_tracer.h"
#include "ray_schedules.h"
#include "trace_only_kernel.h"
#include "whitted_workload.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

// The driver's structures over the scene's triangles in one order, and the rays traced through them.
struct DriverTraversal {
    // The scene triangle of each of the structure's primitives.
    std::vector<std::uint32_t> sceneTriangle;
    bench::RayQueryScene structures;
    bench::RayQueryTrace all, primary;

    DriverTraversal(const bench::RayQueryDevice& device, const Scene& scene, std::vector<std::uint32_t> order,
                    std::span<const TracedRay> rays, std::span<const std::size_t> allOrder,
                    std::span<const std::size_t> primaryOrder)
        : sceneTriangle(std::move(order)),
          structures(device, corners(scene, sceneTriangle)),
          all(device, structures, rays, allOrder),
          primary(device, structures, rays, primaryOrder) {}

    static std::vector<glm::vec3> corners(const Scene& scene, std::span<const std::uint32_t> order) {
        std::vector<glm::vec3> c;
        c.reserve(3 * order.size());
        for (std::uint32_t i : order) c.insert(c.end(), scene.triangles[i].position, scene.triangles[i].position + 3);
        return c;
    }
};

// How closely two traversals agree on a list of rays (closest-hit and shadow rays alike).
struct Agreement {
    std::size_t checked = 0;
    std::size_t agree = 0;         // the same hit or miss, and the same t to 1e-4 for closest hits
    std::size_t closestHits = 0;   // closest-hit rays that both found a hit for
    std::size_t sameTriangle = 0;  // ... at the same triangle
    double share() const { return checked == 0 ? 1.0 : double(agree) / double(checked); }
    double sameTriangleShare() const { return closestHits == 0 ? 1.0 : double(sameTriangle) / double(closestHits); }
};

// The same t to 1e-4 relative, as Embree is held to vitrum's traversal (whitted_bench.cpp): the
// two triangle tests are not the same computation, and their t may differ in the last bits.
bool sameT(float a, float b) { return std::fabs(a - b) <= 1e-4f * std::max(std::fabs(a), std::fabs(b)); }

// The ray queries' results against vitrum's CPU traversal on every 97th ray of `order`.
Agreement checkAgainstCpu(const bench::RayQueryTrace& trace, const std::vector<std::uint32_t>& sceneTriangle,
                          std::span<const std::size_t> order, const bench::WhittedScene& w,
                          const std::vector<TracedRay>& rays) {
    Agreement a;
    for (std::size_t k = 0; k < order.size(); k += 97) {
        const TracedRay& r = rays[order[k]];
        const Ray<float> ray{r.origin, r.direction, r.tMin, r.tMax};
        const bench::RayQueryTrace::Hit& theirs = trace.hit(k);
        ++a.checked;
        if (r.anyHit) {
            a.agree += traceAny<float>(w.bvh.nodes, w.triangles, ray) == (theirs.t >= 0.0f);
            continue;
        }
        const auto ours = traceClosest<float>(w.bvh.nodes, w.triangles, ray);
        if (!ours) {
            a.agree += theirs.t < 0.0f;
            continue;
        }
        a.agree += theirs.t >= 0.0f && sameT(theirs.t, ours->t);
        if (theirs.t >= 0.0f) {
            ++a.closestHits;
            a.sameTriangle += sceneTriangle[theirs.primitive] == w.bvh.triangleOrder[ours->triangle];
        }
    }
    return a;
}

// The ray queries' results against vitrum's trace-only kernel's on every ray of the list.
Agreement checkAgainstKernel(const bench::RayQueryTrace& trace, const bench::TraceOnlyKernel& kernel,
                             std::span<const std::size_t> order, const std::vector<TracedRay>& rays) {
    Agreement a;
    for (std::size_t k = 0; k < order.size(); ++k) {
        const float theirs = trace.hit(k).t, ours = kernel.hit(k).x;
        ++a.checked;
        if (rays[order[k]].anyHit || ours < 0.0f || theirs < 0.0f)
            a.agree += (ours >= 0.0f) == (theirs >= 0.0f);
        else
            a.agree += sameT(theirs, ours);
    }
    return a;
}

// The share a traversal may disagree on: rays that graze an edge or end within rounding of a
// surface, where two triangle tests may decide apart (and a ray query's interval is closed,
// [tMin, tMax], where vitrum's is open).
constexpr double kMinAgreement = 0.999;

void requireAgreement(const Agreement& a, const char* file, const std::string& what) {
    if (a.share() < kMinAgreement)
        throw std::runtime_error(std::string(file) + ": the driver's ray queries disagree with " + what + " on " +
                                 std::to_string(a.checked - a.agree) + " of " + std::to_string(a.checked) + " rays");
}

double secondsOf(const std::function<void()>& work) {
    const auto start = std::chrono::steady_clock::now();
    work();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int run(int argc, char** argv) {
    if (argc > 1 && std::string(argv[1]) == "--devices") {
        std::cout << bench::RayQueryDevice::describeDevices();
        return 0;
    }
    const bool checkOnly = argc > 1 && std::string(argv[1]) == "--check";
    const int runs = checkOnly ? 0 : argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
    // The ray-query device first (the first that offers them), then vitrum's on the same one.
    const bench::RayQueryDevice rayQueryDevice;
    VulkanDevice device(std::to_string(rayQueryDevice.index()));
    std::string rows;
    double worstSample = 1.0, worstAll = 1.0, leastSameTriangle = 1.0;
    double lowRatio = 1e30, highRatio = 0.0, lowSorted = 1e30, highSorted = 0.0;
    for (const char* file : bench::kWhittedScenes) {
        const bench::WhittedScene workload = bench::loadWhittedScene(fs::path(VITRUM_SOURCE_DIR) / file);
        const std::vector<TracedRay> rays = bench::whittedRays(workload);
        std::cerr << file << ": " << std::flush;

        // Pass k holds every pixel's k-th ray; at 1 spp the first is every pixel's primary ray.
        const auto passes = bench::rayPasses(rays, bench::kWhittedWidth, bench::kWhittedHeight, false);
        if (passes.empty() || passes[0].size() != std::size_t(bench::kWhittedWidth) * bench::kWhittedHeight)
            throw std::runtime_error(std::string(file) + ": not one primary ray a pixel");
        const std::vector<std::size_t>& primaryOrder = passes[0];
        std::vector<std::size_t> allOrder;
        for (const auto& pass : passes) allOrder.insert(allOrder.end(), pass.begin(), pass.end());

        const TraversalNodes tree = makeTraversalNodes(workload.bvh.nodes);
        const bench::TraceOnlyKernel vitrumAll(device, tree, workload.triangles, rays, allOrder);
        const bench::TraceOnlyKernel vitrumPrimary(device, tree, workload.triangles, rays, primaryOrder);
        std::vector<std::uint32_t> sceneOrder(workload.scene.triangles.size());
        std::iota(sceneOrder.begin(), sceneOrder.end(), 0u);
        const DriverTraversal driver(rayQueryDevice, workload.scene, sceneOrder, rays, allOrder, primaryOrder);
        const DriverTraversal driverSorted(rayQueryDevice, workload.scene, workload.bvh.triangleOrder, rays, allOrder,
                                           primaryOrder);

        // Each round times every configuration once, starting at another each round, so that none
        // always follows the same one. The first round (compiles, first touches) is not counted:
        // it is the one whose results are checked.
        std::vector<double> asBuild, bvhBuild, allQuery, allSorted, allVitrum, primaryQuery, primarySorted,
            primaryVitrum;
        const std::vector<std::function<double()>> configurations = {
            [&] { return driver.structures.build(rayQueryDevice); },
            [&] {
                return secondsOf([&] {
                    const Bvh bvh = buildSceneBvh(workload.scene);
                    const std::vector<gpu::TriangleVertices> triangles =
                        packTriangleVertices(bvh, workload.scene.triangles);
                    const TraversalNodes nodes = makeTraversalNodes(bvh.nodes);
                });
            },
            [&] { return driver.all.trace(rayQueryDevice); },
            [&] { return driverSorted.all.trace(rayQueryDevice); },
            [&] { return vitrumAll.trace(device); },
            [&] { return driver.primary.trace(rayQueryDevice); },
            [&] { return driverSorted.primary.trace(rayQueryDevice); },
            [&] { return vitrumPrimary.trace(device); },
        };
        std::vector<double>* const times[] = {&asBuild,   &bvhBuild,     &allQuery,      &allSorted,
                                              &allVitrum, &primaryQuery, &primarySorted, &primaryVitrum};
        for (int r = 0; r <= runs; ++r) {
            for (std::size_t i = 0; i < configurations.size(); ++i) {
                const std::size_t c = (i + std::size_t(r)) % configurations.size();
                const double seconds = configurations[c]();
                if (r > 0) times[c]->push_back(seconds);
            }
            if (r > 0) continue;
            bench::checkTraceOnly(vitrumAll, allOrder, workload.bvh, workload.triangles, rays, file);
            bench::checkTraceOnly(vitrumPrimary, primaryOrder, workload.bvh, workload.triangles, rays, file);
            for (const DriverTraversal* d : {&driver, &driverSorted}) {
                for (const auto& [trace, order] :
                     {std::pair{&d->all, std::span<const std::size_t>(allOrder)},
                      std::pair{&d->primary, std::span<const std::size_t>(primaryOrder)}}) {
                    const Agreement sample = checkAgainstCpu(*trace, d->sceneTriangle, order, workload, rays);
                    requireAgreement(sample, file, "vitrum's CPU traversal");
                    worstSample = std::min(worstSample, sample.share());
                    leastSameTriangle = std::min(leastSameTriangle, sample.sameTriangleShare());
                    std::cerr << bench::fixed(100.0 * sample.share(), 2) << "% ("
                              << bench::fixed(100.0 * sample.sameTriangleShare(), 2) << "% same triangle), ";
                }
                const Agreement all = checkAgainstKernel(d->all, vitrumAll, allOrder, rays);
                requireAgreement(all, file, "vitrum's trace-only kernel");
                worstAll = std::min(worstAll, all.share());
                std::cerr << bench::fixed(100.0 * all.share(), 3) << "% of all rays; ";
            }
        }
        if (checkOnly) {
            std::cerr << "checked\n";
            continue;
        }

        auto rate = [](std::size_t count, const std::vector<double>& seconds) {
            return double(count) / bench::median(seconds) * 1e-6;
        };
        const double vitrumRate = rate(allOrder.size(), allVitrum), queryRate = rate(allOrder.size(), allQuery);
        const double sortedRate = rate(allOrder.size(), allSorted);
        const double vitrumPrimaryRate = rate(primaryOrder.size(), primaryVitrum);
        const double queryPrimaryRate = rate(primaryOrder.size(), primaryQuery);
        const double sortedPrimaryRate = rate(primaryOrder.size(), primarySorted);
        lowRatio = std::min({lowRatio, vitrumRate / queryRate, vitrumPrimaryRate / queryPrimaryRate});
        highRatio = std::max({highRatio, vitrumRate / queryRate, vitrumPrimaryRate / queryPrimaryRate});
        lowSorted = std::min({lowSorted, vitrumRate / sortedRate, vitrumPrimaryRate / sortedPrimaryRate});
        highSorted = std::max({highSorted, vitrumRate / sortedRate, vitrumPrimaryRate / sortedPrimaryRate});
        std::size_t shadow = 0;
        for (const TracedRay& r : rays) shadow += r.anyHit;
        auto against = [](double ours, double theirs) {
            return " | " + bench::fixed(theirs, 2) + " | **" + bench::fixed(ours / theirs, 2) + "x**";
        };
        rows += "| " + fs::path(file).stem().string() + " | " + std::to_string(workload.scene.triangles.size()) +
                " | " + std::to_string(allOrder.size()) + " | " +
                bench::fixed(100.0 * double(shadow) / double(std::max<std::size_t>(1, rays.size())), 0) + "% | " +
                bench::fixed(vitrumRate, 2) + against(vitrumRate, queryRate) + against(vitrumRate, sortedRate) + " | " +
                bench::fixed(vitrumPrimaryRate, 2) + against(vitrumPrimaryRate, queryPrimaryRate) +
                against(vitrumPrimaryRate, sortedPrimaryRate) + " | " + bench::fixed(bench::median(asBuild), 4) +
                " | " + bench::fixed(bench::median(bvhBuild), 4) + " |\n";
        std::cerr << "vitrum " << bench::fixed(vitrumRate, 2) << ", ray queries " << bench::fixed(queryRate, 2) << " ("
                  << bench::fixed(sortedRate, 2) << " in vitrum's order) Mrays/s; primary rays "
                  << bench::fixed(vitrumPrimaryRate, 2) << ", " << bench::fixed(queryPrimaryRate, 2) << " ("
                  << bench::fixed(sortedPrimaryRate, 2) << "); builds " << bench::fixed(bench::median(asBuild), 4)
                  << " s (driver: " << driver.structures.bottomLevelBytes() / workload.scene.triangles.size()
                  << " bytes a triangle), " << bench::fixed(bench::median(bvhBuild), 4) << " s (vitrum)\n";
    }
    const std::uint32_t messages = VulkanInstance::validationMessages();  // both devices'
    if (messages > 0)
        throw std::runtime_error("the Vulkan validation layer sent " + std::to_string(messages) + " messages");
    if (checkOnly) return 0;

    std::cout
        << "## vitrum's traversal against the driver's ray queries\n\n"
        << "Generated by `bench/ray-query " << runs << "` (bench/ray_query_bench.cpp; `make bench-performance`) on "
        << bench::today() << ". Machine: " << bench::machine() << "; device: " << rayQueryDevice.name() << ", driver "
        << rayQueryDevice.driverInfo() << ".\n\n"
        << "Mesa 25's lavapipe offers `VK_KHR_ray_query`: a kernel may ask the driver to trace a ray through an "
           "acceleration structure that the driver builds (`vkCmdBuildAccelerationStructuresKHR`, on the device: it "
           "offers no host builds) and walks itself, so a renderer on it could leave its BVH and traversal to the "
           "driver. The Whitted workload's rays (every glass scene at "
        << bench::kWhittedWidth << "x" << bench::kWhittedHeight << ", 1 spp, max_depth " << bench::kWhittedMaxDepth
        << ": every ray the CPU reference traces, as above) are traced in one dispatch each way, one ray an "
           "invocation, in the same order (every pixel's primary ray, then every pixel's second ray, and so on: the "
           "compacted passes above), and the primary rays alone, on the same device: by vitrum's own traversal in "
           "the trace-only kernel (bench/trace_only/trace_rays.comp: the *compacted* column above, which is Mesa "
           "22.3's) and by ray queries (bench/ray_query/trace_rays_query.comp: `rayQueryInitializeEXT` with "
           "`gl_RayFlagsOpaqueEXT`, and `gl_RayFlagsTerminateOnFirstHitEXT` for shadow rays). Both read their rays "
           "from a storage texel buffer and write each hit to a storage buffer; neither does anything else. The "
           "driver's structures: one bottom level (one opaque geometry, three corners a triangle, no index buffer, "
           "`PREFER_FAST_TRACE`) and a top level of one identity instance. The bottom level is built twice: from "
           "the triangles in the scene's order, as a renderer on ray queries alone would hand them over, and in "
           "vitrum's BVH order (its leaves from left to right: *vitrum's order*). *AS build* is the first one's "
           "two levels built on the device, from recording to the end of the build; *vitrum BVH build* is vitrum's "
           "(binned SAH on every thread, the triangles put in its order, the nodes the kernel reads), on the host. "
           "All eight take turns, "
        << runs << " rounds after one that is not counted (compiles; its results are the ones checked); medians. "
        << "The ray queries find what vitrum's CPU traversal finds (hit or miss, the same t to 1e-4) on at least "
        << bench::fixed(100.0 * worstSample, 2) << "% of every 97th ray of each scene (the same triangle on at least "
        << bench::fixed(100.0 * leastSameTriangle, 2)
        << "% of the closest hits: where two surfaces coincide, as water_glass's water and glass do, either "
           "triangle is the closest), and what the trace-only kernel finds on at least "
        << bench::fixed(100.0 * worstAll, 2) << "% of all the rays; below " << bench::fixed(100.0 * kMinAgreement, 1)
        << "% the benchmark stops.\n\n"
        << "| scene | triangles | rays | shadow rays | vitrum Mrays/s | ray query Mrays/s | vitrum against ray query | "
           "ray query, vitrum's order | vitrum against it | primary rays: vitrum Mrays/s | ray query | vitrum against "
           "ray query | ray query, vitrum's order | vitrum against it | AS build s | vitrum BVH build s |\n"
        << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n"
        << rows << "\nvitrum's traversal traces " << bench::fixed(lowRatio, 2) << "x to " << bench::fixed(highRatio, 2)
        << "x the rays per second of the driver's ray queries, and " << bench::fixed(lowSorted, 2) << "x to "
        << bench::fixed(highSorted, 2) << "x where the driver is given the triangles in vitrum's order.\n";
    return 0;
}

}  // namespace
}  // namespace vitrum

int main(int argc, char** argv) {
    return vitrum::bench::guardedMain("vitrum_bench_ray_query", [&] { return vitrum::run(argc, argv); });
}
