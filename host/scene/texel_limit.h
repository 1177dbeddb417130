// The most bytes a scene's textures and environment maps may take together as linear RGB float
// texels of 16 bytes (a render's device holds them in one texel buffer), so that the loaders
// refuse an image too large for what is left by its header, before decoding it
// (image/pixel_limit.h).
#pragma once

#include <cstdint>
#include <limits>
#include <string>

#include "common/byte_size.h"
#include "image/pixel_limit.h"
#include "scene/scene.h"

namespace vitrum {

struct TexelLimit {
    std::uint64_t bytes = std::numeric_limits<std::uint64_t>::max();
    std::string source;  // whose limit: "llvmpipe allows 128 MiB per storage buffer (maxStorageBufferRange)"

    // What is left for the next image once the scene's images so far, and `alsoHeld` bytes of
    // images not yet in it, are held.
    PixelLimit leftAfter(const Scene& scene, std::uint64_t alsoHeld = 0) const {
        if (bytes == std::numeric_limits<std::uint64_t>::max()) return {};
        std::uint64_t used = alsoHeld;
        for (const Texture& texture : scene.textures) used += texture.texels.size() * PixelLimit::kBytesPerPixel;
        std::string reason = source + " for all of its textures";
        if (used > 0) reason += ", and the scene's images before this one take " + describeBytes(used);
        return {used < bytes ? (bytes - used) / PixelLimit::kBytesPerPixel : 0, reason};
    }
};

}  // namespace vitrum
