// Where the samples of a pixel go (../shared/docs/render-model.md, "Geometry and camera"): the
// pixel centre for one sample, otherwise stratified jitter on a grid. Written so that
// shaders/camera.glsl (sampleOffsetInPixel) gives the same positions bit for bit: the same integer
// hash (gpu::pcgHash), the same float operations in the same order.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "shared/gpu_types.h"

namespace vitrum {

// Columns of the stratified grid for n samples: the largest divisor of n that is at most
// sqrt(n), so the grid is as square as n allows (16 -> 4 x 4, 8 -> 2 x 4, 7 -> 1 x 7). Both
// backends use it (the GPU gets it in RenderParams::pass.y). c * c is taken in 64 bits: in 32 it
// wraps at c = 65536, so from n = 65535^2 on the loop would run on until c wraps to 0.
constexpr std::uint32_t stratifiedColumns(std::uint32_t n) {
    std::uint32_t columns = 1;
    for (std::uint32_t c = 1; std::uint64_t(c) * c <= n; ++c)
        if (n % c == 0) columns = c;
    return columns;
}

// Offset of sample k of n inside pixel `pixelIndex` (= y * width + x), in [0, 1]^2 from the
// pixel's top-left corner. Sample k lies in cell (k % columns, k / columns) of a columns x rows
// grid, jittered by two hashes of the pixel and the sample. All integer arithmetic wraps (uint32).
// Float rounding of (cell + jitter) / columns can give exactly the cell's far edge (e.g. 1.0);
// kept so that the GPU's identical expression agrees.
inline glm::vec2 stratifiedSample(std::uint32_t pixelIndex, std::uint32_t k, std::uint32_t n) {
    if (n <= 1) return glm::vec2(0.5f);
    const std::uint32_t columns = stratifiedColumns(n);
    const std::uint32_t rows = n / columns;
    const std::uint32_t seed = pixelIndex * 2654435761u;  // Knuth's multiplicative hash spreads pixels
    const float jx = gpu::hashToUnit(gpu::pcgHash(seed ^ gpu::pcgHash(2u * k)));
    const float jy = gpu::hashToUnit(gpu::pcgHash(seed ^ gpu::pcgHash(2u * k + 1u)));
    return glm::vec2((float(k % columns) + jx) / float(columns), (float(k / columns) + jy) / float(rows));
}

}  // namespace vitrum
