// WebP images (RIFF "WEBP", lossy or lossless; still images, not animations), decoded with
// Debian's libwebp: glTF's EXT_texture_webp (what gltf-transform's optimize writes by default),
// and textures and backgrounds of any scene. 8-bit sRGB like PNG and JPEG; alpha is dropped.
#pragma once

#include <filesystem>
#include <vector>

#include "image/image.h"

namespace vitrum {

// Whether the bytes begin as a WebP file does ("RIFF", a length, "WEBP").
bool isWebp(const std::vector<unsigned char>& bytes);

// The image in the bytes of the file at `path`, its declared size checked before it is decoded
// (declared_size.h). Throws InputError naming the file for a corrupt, truncated or animated file,
// and ImageTooLarge for one beyond `limit`.
Image readWebp(const std::filesystem::path& path, const std::vector<unsigned char>& bytes,
               const PixelLimit& limit = {});

}  // namespace vitrum
