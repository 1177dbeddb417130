// The two lavapipes of `make test` against each other (docs/testing.md, "Two drivers"): every
// scene of scenes/ rendered by `vitrum` on Debian 12's Mesa 22.3 and on bookworm-backports' Mesa
// 25.0 must trace the same rays and hit the same limits, and give the same image but for the
// last bits of the math library. Both drivers compile with LLVM 15, and the kernel's arithmetic
// is IEEE (gpu/spirv_float_semantics.h), so every counter is the same.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../cli/cli_support.h"
#include "image/image.h"
#include "image/image_diff.h"

namespace {

namespace fs = std::filesystem;
using vitrum::testing::CommandRun;
using vitrum::testing::vitrum;
using TwoDrivers = vitrum::testing::CliTest;

// Every counter of a render's statistics: all but the times, the device's name and the kernel's
// description (which names no driver).
nlohmann::json counters(nlohmann::json stats) {
    for (const char* key : {"seconds", "device", "kernel"}) stats.erase(key);
    return stats;
}

TEST_F(TwoDrivers, BothLavapipesArePresentAndNamed) {
    for (const char* icd : {VITRUM_SYSTEM_LAVAPIPE_ICD, VITRUM_BACKPORTS_LAVAPIPE_ICD}) {
        ASSERT_TRUE(fs::exists(icd)) << icd << " is missing: `make test` fetches it (.ci/fetch-backports-lavapipe)";
        CommandRun devices = vitrum("devices", std::string("VK_ICD_FILENAMES=") + icd);
        ASSERT_EQ(devices.exitCode, 0) << devices.output;
        EXPECT_NE(devices.output.find("driver: llvmpipe, Mesa"), std::string::npos) << devices.output;
        EXPECT_NE(devices.output.find("kernel: fast:"), std::string::npos) << devices.output;
        const std::size_t driver = devices.output.find("driver:");
        std::printf("%s: %s\n", icd, devices.output.substr(driver, devices.output.find('\n', driver) - driver).c_str());
    }
    CommandRun older = vitrum("devices", std::string("VK_ICD_FILENAMES=") + VITRUM_SYSTEM_LAVAPIPE_ICD);
    CommandRun newer = vitrum("devices", std::string("VK_ICD_FILENAMES=") + VITRUM_BACKPORTS_LAVAPIPE_ICD);
    EXPECT_NE(older.output.find("Mesa 22."), std::string::npos) << older.output;
    EXPECT_NE(newer.output.find("Mesa 25."), std::string::npos) << newer.output;
}

TEST_F(TwoDrivers, EveryProjectSceneTracesTheSameOnBoth) {
    int scenes = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(std::string(VITRUM_SOURCE_DIR) + "/scenes")) {
        if (entry.path().extension() != ".json") continue;
        const std::string name = entry.path().stem().string();
        SCOPED_TRACE(name);
        const std::string render = "render " + entry.path().string() + " --width 160 --height 120 --backend vulkan";
        CommandRun older = vitrum(render + " -o " + path(name + "-22.pfm") + " --stats " + path(name + "-22.json"),
                                  std::string("VK_ICD_FILENAMES=") + VITRUM_SYSTEM_LAVAPIPE_ICD);
        ASSERT_EQ(older.exitCode, 0) << older.output;
        CommandRun newer = vitrum(render + " -o " + path(name + "-25.pfm") + " --stats " + path(name + "-25.json"),
                                  std::string("VK_ICD_FILENAMES=") + VITRUM_BACKPORTS_LAVAPIPE_ICD);
        ASSERT_EQ(newer.exitCode, 0) << newer.output;
        const nlohmann::json a = nlohmann::json::parse(std::ifstream(path(name + "-22.json")));
        const nlohmann::json b = nlohmann::json::parse(std::ifstream(path(name + "-25.json")));
        EXPECT_EQ(a["rays"]["primary"], 160 * 120 * a["settings"]["spp"].get<int>());  // every pixel traced
        EXPECT_EQ(counters(a), counters(b));
        // Environment lookups (atan, acos) come from each Mesa's own math lowering: measured, the
        // two images differ by at most 1.0e-5 (diamond, glass_sphere_spherical) and are otherwise
        // identical.
        const vitrum::ImageDiff d =
            vitrum::diffImages(vitrum::readImage(path(name + "-22.pfm")), vitrum::readImage(path(name + "-25.pfm")));
        EXPECT_LE(d.maxAbsError, 1e-4);
        ++scenes;
    }
    EXPECT_GE(scenes, 13);
}

}  // namespace
