// The CPU reference renderer: docs/render-model.md written as plainly as possible. Recursive,
// multithreaded over rows, in float (to hold the GPU to it) or double (ground truth). Built with
// -ffp-contract=off so that float results are not changed by FMA contraction.
#pragma once

#include <functional>
#include <span>

#include "bvh/bvh.h"
#include "image/image.h"
#include "render/render_stats.h"
#include "scene/scene.h"

namespace vitrum {

struct ReferenceOptions {
    bool doublePrecision = false;
    unsigned threads = 0;  // 0: all hardware threads
    std::function<void(double)> progress;  // fraction done, called from worker threads
};

// Renders scene.camera with scene.settings. `bvh` was built over scene.triangles.
Image renderReference(const Scene& scene, const Bvh& bvh, const ReferenceOptions& options, RenderStats& stats);

}  // namespace vitrum
