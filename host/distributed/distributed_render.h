// One image rendered by every rank of an MPI job: image-parallel, as OSPRay's MPI offload mode
// does it. Rank 0 hands out the tiles one at a time as ranks ask for them (so a fast GPU rank
// and a slow lavapipe rank each take what they can), renders tiles itself between serving them,
// and puts every tile into the image. Each rank loaded the same scene and built its own BVH and
// device; a pixel's value does not depend on who renders it, so the image is the one a single
// process renders, bit for bit (docs/distributed.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "distributed/mpi_job.h"
#include "gpu/vulkan_device.h"
#include "gpu/vulkan_renderer.h"
#include "image/image.h"
#include "scene/scene.h"
#include "stats/render_stats.h"

namespace vitrum {

struct RankReport {
    int rank = 0;
    std::string host, device;
    std::uint64_t tiles = 0;
    double renderSeconds = 0;
};

struct DistributedReport {
    std::vector<RankReport> ranks;
    std::uint64_t tiles = 0;
    // Every byte the ranks sent each other for this image: the tiles' requests, pixels and
    // replies, and the ranks' reports (all to or from rank 0), but the start's few collectives.
    std::uint64_t bytesSent = 0;
    double assembleSeconds = 0;  // rank 0 putting tiles into the image
};

// On rank 0: the image, with `stats` summed over the ranks (the phases are rank 0's) and
// `report` filled. On the other ranks: an empty image. `options.progress` is called on rank 0
// only, "rendering" by the tiles done in the whole image.
Image renderDistributed(MpiJob& job, VulkanDevice& device, const Scene& scene, const Bvh& bvh,
                        const VulkanRenderOptions& options, RenderStats& stats, DistributedReport& report);

}  // namespace vitrum
