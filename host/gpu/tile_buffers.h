// The buffers sized by the tile the Vulkan backend renders at a time: one table, from which the
// renderer makes them (gpu/vulkan_renderer.cpp), the default tile is sized (gpu/tile_size.h) and
// a scene is checked against the device before it is loaded (app/render_command.cpp).
#pragma once

#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "gpu/gpu_buffer.h"
#include "gpu/gpu_layout.h"
#include "shared/trace_bindings.h"

namespace vitrum {

struct TileBuffer {
    const char* what;  // names the buffer in errors
    std::uint32_t binding;
    MemoryUse memory;
    std::uint64_t bytesPerPixel;  // the most a pixel can need: the general kernel's
    bool perPendingRay = false;   // sized by the kernel's pending rays a pixel (kRayStackSize here)
};

inline constexpr std::array<TileBuffer, 4> kTileBuffers{{
    // The kernel writes each pixel, with its slot's status in .w (shaders/suspend.glsl); the host
    // reads the colours.
    {"pixels of one tile", gpu::kBindingPixels, MemoryUse::Readback, sizeof(glm::vec4)},
    {"trace state of one tile", gpu::kBindingStates, MemoryUse::DeviceOnly, gpu::kTraceStateBytes},
    {"pending rays of one tile", gpu::kBindingPendingRays, MemoryUse::DeviceOnly,
     gpu::kRayStackSize * sizeof(gpu::PendingRay), true},
    {"traversal stacks of one tile", gpu::kBindingTraversalStacks, MemoryUse::DeviceOnly,
     gpu::kTraversalStackSize * sizeof(std::uint32_t)},
}};

// The bytes of `buffer` a pixel, for a kernel that keeps `pendingRayCapacity` pending rays a pixel.
std::uint64_t tileBufferBytesPerPixel(const TileBuffer& buffer, std::uint32_t pendingRayCapacity);

// The bytes of `buffer` for a tile of `tile` pixels and a kernel that keeps `pendingRayCapacity`
// pending rays a pixel. The resumable kernel keeps pending rays by slot, the first dispatch by
// invocation (shaders/pending_rays.glsl): as many as the tile's whole 8x8 workgroups have.
std::uint64_t tileBufferBytes(const TileBuffer& buffer, glm::uvec2 tile, std::uint32_t pendingRayCapacity);

}  // namespace vitrum
