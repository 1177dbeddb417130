#include "scene/environment_map.h"

#include <cstdint>
#include <limits>

#include "common/error.h"
#include "image/image.h"

namespace vitrum {
namespace {

Texture toTexture(const std::filesystem::path& path, Image image) {
    return Texture{path, int(image.width), int(image.height), std::move(image.pixels)};
}

}  // namespace

void loadSphericalBackground(Scene& scene, const std::filesystem::path& file, const TexelLimit& limit) {
    Image image = readImage(file, limit.leftAfter(scene));
    scene.background.kind = BackgroundKind::Spherical;
    scene.background.map = int(scene.textures.size());
    scene.textures.push_back(toTexture(file, std::move(image)));
}

void loadCubeBackground(Scene& scene, const std::array<std::filesystem::path, 6>& faces,
                        const TexelLimit& limit) {
    std::vector<Texture> loaded;
    std::uint64_t loadedBytes = 0;
    for (const auto& file : faces) {
        Image image = readImage(file, limit.leftAfter(scene, loadedBytes));
        if (image.width != image.height)
            throw inputError(file, 0, "a cube map face must be square, this one is " + std::to_string(image.width) +
                                          "x" + std::to_string(image.height));
        if (!loaded.empty() && int(image.width) != loaded.front().width)
            throw inputError(file, 0, "all six cube map faces must have the same size: this one is " +
                                          std::to_string(image.width) + " wide, " +
                                          loaded.front().path.filename().string() + " is " +
                                          std::to_string(loaded.front().width));
        loadedBytes += image.pixels.size() * PixelLimit::kBytesPerPixel;
        loaded.push_back(toTexture(file, std::move(image)));
    }
    scene.background.kind = BackgroundKind::Cube;
    scene.background.map = int(scene.textures.size());
    for (Texture& t : loaded) scene.textures.push_back(std::move(t));
}

void loadCubeCrossBackground(Scene& scene, const std::filesystem::path& file, const TexelLimit& limit) {
    // Six of the cross's twelve cells are kept.
    PixelLimit left = limit.leftAfter(scene);
    left.pixels = left.pixels > std::numeric_limits<std::uint64_t>::max() / 2 ? left.pixels : 2 * left.pixels;
    Image cross = readImage(file, left);
    const std::uint32_t size = cross.width / 4;
    if (size == 0 || cross.width != 4 * size || cross.height != 3 * size)
        throw inputError(file, 0, "a cube cross must be 4 faces wide and 3 high (for example 1024x768), got " +
                                      std::to_string(cross.width) + "x" + std::to_string(cross.height));
    // (column, row) of +x, -x, +y, -y, +z, -z in the cross.
    constexpr int kCells[6][2] = {{2, 1}, {0, 1}, {1, 1}, {3, 1}, {1, 0}, {1, 2}};
    scene.background.kind = BackgroundKind::Cube;
    scene.background.map = int(scene.textures.size());
    for (const auto& cell : kCells) {
        Texture face{file, int(size), int(size), {}};
        face.texels.reserve(std::size_t(size) * size);
        for (std::uint32_t y = 0; y < size; ++y)
            for (std::uint32_t x = 0; x < size; ++x) face.texels.push_back(cross.at(cell[0] * size + x, cell[1] * size + y));
        scene.textures.push_back(std::move(face));
    }
}

}  // namespace vitrum
