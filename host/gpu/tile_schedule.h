// The image's tiles, numbered row by row, and which of them a process renders: every one in turn
// (LocalTiles, one process), or those a coordinator hands it (distributed/tile_coordinator.h).
// A pixel's value does not depend on its tile or on who renders it, so any schedule gives the
// same image.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <optional>

#include <glm/glm.hpp>

#include "image/image.h"

namespace vitrum {

struct TileGrid {
    std::uint32_t width = 0, height = 0;  // the image's
    glm::uvec2 tile{0};                   // a tile's pixels; tiles at the right and bottom are cut off

    std::uint32_t columns() const { return (width + tile.x - 1) / tile.x; }
    std::uint32_t rows() const { return (height + tile.y - 1) / tile.y; }
    std::uint32_t count() const { return columns() * rows(); }
    // x, y, width, height of tile `index` (its full size, which may reach past the image).
    glm::uvec4 rect(std::uint32_t index) const {
        return glm::uvec4(index % columns() * tile.x, index / columns() * tile.y, tile.x, tile.y);
    }
    // Its part inside the image.
    glm::uvec2 pixelsInside(std::uint32_t index) const {
        const glm::uvec4 r = rect(index);
        return glm::uvec2(std::min(r.z, width - r.x), std::min(r.w, height - r.y));
    }
};

class TileSchedule {
public:
    virtual ~TileSchedule() = default;
    // The next tile for this process, or none once it has no more to render.
    virtual std::optional<std::uint32_t> next() = 0;
    // A tile's pixels inside the image (an image of TileGrid::pixelsInside), once rendered.
    virtual void finished(std::uint32_t index, const Image& pixels) = 0;
};

// Every tile, in order, into one image; `progress` gets the share of tiles done.
class LocalTiles final : public TileSchedule {
public:
    LocalTiles(const TileGrid& grid, std::function<void(double)> progress)
        : grid_(grid), image_(grid.width, grid.height), progress_(std::move(progress)) {}

    std::optional<std::uint32_t> next() override {
        if (next_ == grid_.count()) return std::nullopt;
        return next_++;
    }
    void finished(std::uint32_t index, const Image& pixels) override {
        copyTile(grid_, index, pixels, image_);
        if (progress_) progress_(double(++done_) / double(grid_.count()));
    }
    Image& image() { return image_; }

    // Puts a tile's pixels into their place in `image`.
    static void copyTile(const TileGrid& grid, std::uint32_t index, const Image& pixels, Image& image) {
        const glm::uvec4 r = grid.rect(index);
        for (std::uint32_t y = 0; y < pixels.height; ++y)
            std::copy_n(&pixels.at(0, y), pixels.width, &image.at(r.x, r.y + y));
    }

private:
    TileGrid grid_;
    Image image_;
    std::function<void(double)> progress_;
    std::uint32_t next_ = 0, done_ = 0;
};

}  // namespace vitrum
