#include "gpu/tile_size.h"

#include <algorithm>

#include "gpu/tile_buffers.h"

namespace vitrum {

std::uint32_t defaultTileSize(const DeviceDescription& device) {
    if (device.cpu) return kCpuTileSize;
    std::uint64_t allBytesPerPixel = 0, largestBytesPerPixel = 0;
    for (const TileBuffer& buffer : kTileBuffers) {
        allBytesPerPixel += buffer.bytesPerPixel;
        largestBytesPerPixel = std::max(largestBytesPerPixel, buffer.bytesPerPixel);
    }
    const std::uint64_t pixels = std::min(device.maxStorageBufferRange / largestBytesPerPixel,
                                          device.deviceLocalBytes / kTileShareOfDeviceMemory / allBytesPerPixel);
    std::uint32_t side = kMaxTileSize;
    while (side > kMinTileSize && std::uint64_t(side) * side > pixels) side -= 8;
    return side;
}

std::uint32_t tileSizeFor(const DeviceDescription& device, std::uint32_t requested) {
    return requested == 0 ? defaultTileSize(device) : std::max(kMinTileSize, requested);
}

}  // namespace vitrum
