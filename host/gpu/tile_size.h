// How large a tile the Vulkan backend renders at a time. A tile's pixels each have a slot in the
// per-tile buffers (gpu/tile_buffers.h), so its size decides their memory, and the number of
// dispatches (with a submit and a wait each) the image takes.
#pragma once

#include <cstdint>

#include "gpu/vulkan_device.h"

namespace vitrum {

inline constexpr std::uint32_t kMinTileSize = 8;
inline constexpr std::uint32_t kMaxTileSize = 4096;  // pixels a side; --tile's bound too
// On a device that runs on the CPU (lavapipe): larger tiles render no faster there
// (docs/gpu-design.md), and the memory is the host's own.
inline constexpr std::uint32_t kCpuTileSize = 256;
// Of a GPU's largest device-local heap, the share the tile's buffers may take by default: the rest
// is left to the scene, to the driver and to other programs.
inline constexpr std::uint64_t kTileShareOfDeviceMemory = 8;  // one eighth

// The default tile's side in pixels: kCpuTileSize on a CPU device; on a GPU the largest multiple
// of 8, at most kMaxTileSize, whose every per-tile buffer fits one storage buffer binding
// (maxStorageBufferRange) and whose buffers together take at most 1/kTileShareOfDeviceMemory of
// the largest device-local heap (a GPU runs many more invocations at once than a CPU, and each
// tile costs a submit and a wait: on an NVIDIA H200 a 1080p image rendered 2.5x faster in one
// tile than in 256-pixel tiles, docs/other-devices.md). At least kMinTileSize.
std::uint32_t defaultTileSize(const DeviceDescription& device);

// `requested` pixels a side (at least kMinTileSize), or the device's default where it is 0.
std::uint32_t tileSizeFor(const DeviceDescription& device, std::uint32_t requested);

}  // namespace vitrum
