// Whether a scene's GPU buffers fit the device: refused, naming the limit, before the long work
// where the counts already tell (the load, the BVH build), and checked exactly once the BVH and
// the shading layout are known, before any buffer is made (gpu/vulkan_renderer.cpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "gpu/vulkan_device.h"
#include "gpu_input/scene_geometry_bytes.h"
#include "scene/scene.h"

namespace vitrum {

// Throws InputError when a buffer is beyond the device's limit for its kind or all of them beyond
// its largest device-local heap. Without `scene`, the buffers the triangles alone size: the load
// checks them as soon as an OBJ's statements tell how many triangles it has (SceneLoadOptions).
// `tileSize` as VulkanRenderOptions::tileSize.
void checkSceneFitsDevice(const VulkanDevice& device, std::size_t triangles, const SceneGeometryBytes& geometry,
                          const Scene* scene, std::uint32_t tileSize);

}  // namespace vitrum
