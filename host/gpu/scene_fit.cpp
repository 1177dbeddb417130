#include "gpu/scene_fit.h"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "common/byte_size.h"
#include "common/error.h"
#include "gpu/gpu_buffer.h"
#include "gpu/tile_buffers.h"
#include "gpu/tile_size.h"
#include "image/pixel_limit.h"
#include "shared/gpu_types.h"

namespace vitrum {
namespace {

// The largest device-local heap, or VITRUM_MAX_HEAP_BYTES=N where that is less (never more): how a
// scene behaves on a device with less memory (docs/environment.md).
VkDeviceSize deviceLocalLimit(const VulkanDevice& device) {
    VkDeviceSize limit = device.description().deviceLocalBytes;
    if (const char* text = std::getenv("VITRUM_MAX_HEAP_BYTES"); text && *text) {
        char* end = nullptr;
        const unsigned long long value = std::strtoull(text, &end, 10);
        if (*end == '\0' && (limit == 0 || value < limit)) limit = VkDeviceSize(value);
    }
    return limit;
}

}  // namespace

void checkSceneFitsDevice(const VulkanDevice& device, std::size_t triangles, const SceneGeometryBytes& geometry,
                          const Scene* scene, std::uint32_t tileSize) {
    const VkDeviceSize triangleCount = triangles;
    if (triangleCount > gpu::kMaxTriangles)
        throw InputError("the scene has " + std::to_string(triangleCount) + " triangles; the Vulkan backend traces at most " +
                         std::to_string(gpu::kMaxTriangles));
    // As gpu/vulkan_renderer.cpp binds them: the scene's geometry and materials as texel buffers.
    constexpr BufferKind kTexel = BufferKind::Texel, kStorage = BufferKind::Storage;
    struct Buffer {
        const char* what;
        VkDeviceSize bytes;
        BufferKind kind;
        bool perTile = false;  // sized by --tile, not by the scene or the image
    };
    std::vector<Buffer> buffers{
        {"BVH nodes", geometry.nodes, kTexel},
        {"triangle vertices", geometry.vertices, kTexel},
        {"triangle normals and uvs", geometry.shading, kTexel},
    };
    if (scene) {
        VkDeviceSize texels = 0;
        for (const Texture& texture : scene->textures) texels += texture.texels.size();
        buffers.push_back({"materials", scene->materials.size() * sizeof(gpu::GpuMaterial), kTexel});
        buffers.push_back({"lights", scene->lights.size() * sizeof(gpu::GpuLight), kTexel});
        // Within the limit: loadScene refused more.
        buffers.push_back({"texture texels", texels * PixelLimit::kBytesPerPixel, kTexel});
        // The general kernel's: the scene's analysis, which may need fewer pending rays, comes later.
        const std::uint32_t tile = tileSizeFor(device.description(), tileSize);
        const glm::uvec2 tilePixels(std::min(tile, scene->camera.width), std::min(tile, scene->camera.height));
        for (const TileBuffer& buffer : kTileBuffers)
            buffers.push_back({buffer.what, tileBufferBytes(buffer, tilePixels, gpu::kRayStackSize), kStorage, true});
    }
    VkDeviceSize total = 0, perTile = 0;
    for (const auto& buffer : buffers) {
        if (buffer.perTile) perTile += buffer.bytes;
        if (buffer.bytes > bufferLimit(device, buffer.kind).bytes) {
            const InputError error = bufferTooLarge(device, buffer.what, buffer.bytes, buffer.kind);
            if (buffer.perTile) throw InputError(std::string(error.what()) + "; a smaller --tile needs less");
            throw error;
        }
        total += buffer.bytes;
    }
    // All of them live in device-local memory (gpu/gpu_buffer.h's MemoryUse) but the tile's pixels.
    const VkDeviceSize deviceLocal = deviceLocalLimit(device);
    if (deviceLocal > 0 && total > deviceLocal) {
        // Where the scene's own buffers fit, the tile's decide (a 20M-triangle smooth mesh on
        // Mesa 22.3's 2 GiB heap fits with --tile 128).
        const std::string tileHint = total - perTile < deviceLocal
                                         ? "; one tile's buffers take " + describeBytes(perTile) + ": a smaller --tile needs less"
                                         : "";
        throw InputError("the scene does not fit the device: its buffers need " + describeBytes(total) +
                         " in all, but the largest device-local memory heap of " + device.name() + " has " +
                         describeBytes(deviceLocal) + tileHint);
    }
}

}  // namespace vitrum
