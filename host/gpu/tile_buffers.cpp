#include "gpu/tile_buffers.h"

#include "gpu/trace_pipeline.h"

namespace vitrum {

std::uint64_t tileBufferBytesPerPixel(const TileBuffer& buffer, std::uint32_t pendingRayCapacity) {
    return buffer.perPendingRay ? pendingRayCapacity * (buffer.bytesPerPixel / gpu::kRayStackSize) : buffer.bytesPerPixel;
}

std::uint64_t tileBufferBytes(const TileBuffer& buffer, glm::uvec2 tile, std::uint32_t pendingRayCapacity) {
    if (!buffer.perPendingRay) return std::uint64_t(tile.x) * tile.y * buffer.bytesPerPixel;
    const auto wholeGroups = [](std::uint32_t side) { return (side + kTraceGroupSize - 1) / kTraceGroupSize; };
    const std::uint64_t invocations =
        std::uint64_t(wholeGroups(tile.x)) * wholeGroups(tile.y) * kTraceGroupSize * kTraceGroupSize;
    return invocations * tileBufferBytesPerPixel(buffer, pendingRayCapacity);
}

}  // namespace vitrum
