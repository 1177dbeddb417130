// Environment maps: the images of a spherical or cube background, loaded into Scene::textures
// (linear RGB; PNG/JPEG decoded from sRGB, HDR as is). Conventions: docs/scene-format.md.
#pragma once

#include <array>
#include <filesystem>

#include "scene/scene.h"
#include "scene/texel_limit.h"

namespace vitrum {

// An equirectangular map (render model: u = 1 - phi / 2 pi, v = theta / pi, v = 0 at the top).
void loadSphericalBackground(Scene& scene, const std::filesystem::path& file, const TexelLimit& limit = {});

// Six square faces of one size, in the order +x, -x, +y, -y, +z, -z.
void loadCubeBackground(Scene& scene, const std::array<std::filesystem::path, 6>& faces,
                        const TexelLimit& limit = {});

// One image holding the six faces as a horizontal cross, 4 faces wide and 3 high:
//         +z
//     -x  +y  +x  -y
//         -z
void loadCubeCrossBackground(Scene& scene, const std::filesystem::path& file, const TexelLimit& limit = {});

}  // namespace vitrum
