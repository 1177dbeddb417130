// The parts of a distributed render that need neither MPI nor a device (docs/distributed.md):
// the tile grid every rank numbers alike, the scene fingerprint ranks compare, and what each rank
// takes of its host.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "distributed/launch.h"
#include "gpu/tile_schedule.h"
#include "scene/scene_fingerprint.h"
#include "scene/scene_loader.h"

namespace vitrum {
namespace {

TEST(TileGrid, TilesCoverTheImageOnceRowByRow) {
    const TileGrid grid{100, 70, glm::uvec2(32, 32)};
    ASSERT_EQ(grid.columns(), 4u);  // 32 + 32 + 32 + 4
    ASSERT_EQ(grid.rows(), 3u);     // 32 + 32 + 6
    ASSERT_EQ(grid.count(), 12u);
    std::vector<int> covered(100 * 70, 0);
    for (std::uint32_t i = 0; i < grid.count(); ++i) {
        const glm::uvec4 r = grid.rect(i);
        const glm::uvec2 inside = grid.pixelsInside(i);
        for (std::uint32_t y = 0; y < inside.y; ++y)
            for (std::uint32_t x = 0; x < inside.x; ++x) ++covered[(r.y + y) * 100 + r.x + x];
    }
    for (int c : covered) ASSERT_EQ(c, 1);
    EXPECT_EQ(grid.rect(5), glm::uvec4(32, 32, 32, 32));             // row 1, column 1
    EXPECT_EQ(grid.pixelsInside(11), glm::uvec2(4, 6));               // the bottom-right corner
    EXPECT_EQ(grid.pixelsInside(3), glm::uvec2(4, 32));               // the top row's last
}

TEST(TileGrid, LocalTilesPutEveryTileInItsPlace) {
    const TileGrid grid{5, 3, glm::uvec2(2, 2)};
    LocalTiles tiles(grid, nullptr);
    while (const auto i = tiles.next()) {
        const glm::uvec2 inside = grid.pixelsInside(*i);
        Image pixels(inside.x, inside.y);
        const glm::uvec4 r = grid.rect(*i);
        for (std::uint32_t y = 0; y < inside.y; ++y)
            for (std::uint32_t x = 0; x < inside.x; ++x) pixels.at(x, y) = glm::vec3(float(r.x + x), float(r.y + y), 0);
        tiles.finished(*i, pixels);
    }
    for (std::uint32_t y = 0; y < 3; ++y)
        for (std::uint32_t x = 0; x < 5; ++x) EXPECT_EQ(tiles.image().at(x, y), glm::vec3(float(x), float(y), 0));
}

TEST(SceneFingerprint, TwoLoadsAgreeAndAnyChangeThatMattersShows) {
    const std::string path = std::string(VITRUM_SOURCE_DIR) + "/scenes/water_glass.json";
    const Scene a = loadScene(path), b = loadScene(path);
    ASSERT_EQ(sceneFingerprint(a), sceneFingerprint(b));
    const std::uint64_t print = sceneFingerprint(a);
    auto changed = [&](auto change) {
        Scene c = a;
        change(c);
        return sceneFingerprint(c) != print;
    };
    EXPECT_TRUE(changed([](Scene& s) { s.triangles[7].position[1].x = std::nextafter(s.triangles[7].position[1].x, 1e9f); }));
    EXPECT_TRUE(changed([](Scene& s) { s.triangles.pop_back(); }));
    EXPECT_TRUE(changed([](Scene& s) { s.materials.back().ior += 0.01f; }));
    EXPECT_TRUE(changed([](Scene& s) { s.settings.samplesPerPixel += 1; }));
    EXPECT_TRUE(changed([](Scene& s) { s.camera.width += 1; }));
    EXPECT_TRUE(changed([](Scene& s) { s.lights.front().colour.g *= 0.5f; }));
    // The file it came from does not decide the image.
    EXPECT_FALSE(changed([](Scene& s) { s.source = "elsewhere/water_glass.json"; }));
}

TEST(RankResources, LavapipeThreadsAreSharedByTheRanksOfAHost) {
    EXPECT_EQ(lavapipeThreadsPerRank(16, 16, 4), 4u);
    EXPECT_EQ(lavapipeThreadsPerRank(2, 2, 2), 1u);
    EXPECT_EQ(lavapipeThreadsPerRank(2, 2, 3), 1u);  // oversubscribed: still one each
    EXPECT_EQ(lavapipeThreadsPerRank(2, 2, 1), 2u);
    EXPECT_EQ(lavapipeThreadsPerRank(4, 16, 4), 4u);  // bound by mpirun to 4 cores: those
}

TEST(RankResources, GpusAreTakenInTurnByLocalRankAndLavapipeOtherwise) {
    auto device = [](std::uint32_t index, const char* type, bool cpu) {
        DeviceDescription d;
        d.index = index;
        d.type = type;
        d.cpu = cpu;
        return d;
    };
    const std::vector<DeviceDescription> cpuOnly{device(0, "CPU", true)};
    EXPECT_EQ(deviceForLocalRank(cpuOnly, 0), "");
    EXPECT_EQ(deviceForLocalRank(cpuOnly, 3), "");
    const std::vector<DeviceDescription> twoGpus{device(0, "discrete GPU", false), device(1, "CPU", true),
                                                 device(2, "discrete GPU", false)};
    EXPECT_EQ(deviceForLocalRank(twoGpus, 0), "0");
    EXPECT_EQ(deviceForLocalRank(twoGpus, 1), "2");
    EXPECT_EQ(deviceForLocalRank(twoGpus, 2), "0");
}

}  // namespace
}  // namespace vitrum
