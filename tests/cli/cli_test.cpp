// The `vitrum` command as a user runs it: exit codes, messages that name the file, no output
// left behind on failure, and the two backends agreeing through the command line.
#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "cli_support.h"
#include <nlohmann/json.hpp>

#include "image/image.h"
#include "image/image_diff.h"

namespace {

namespace fs = std::filesystem;

using vitrum::testing::CommandRun;
using vitrum::testing::vitrum;
using Cli = vitrum::testing::CliTest;

const std::string kGeosphere = std::string(VITRUM_SHARED_DIR) + "/scenes/course/geosphere/geosphere.obj";

TEST_F(Cli, GeosphereRendersTheSameOnBothBackends) {
    std::string common = kGeosphere + " --camera-from 3,-3,1 --camera-at 0,0,0 --light 4,-6,5 --width 96 --height 72";
    CommandRun gpu = vitrum("render " + common + " --backend vulkan -o " + path("gpu.pfm") + " --stats " + path("gpu.json"));
    ASSERT_EQ(gpu.exitCode, 0) << gpu.output;
    CommandRun cpu = vitrum("render " + common + " --backend cpu -o " + path("cpu.pfm"));
    ASSERT_EQ(cpu.exitCode, 0) << cpu.output;
    vitrum::ImageDiff d = vitrum::diffImages(vitrum::readImage(path("gpu.pfm")), vitrum::readImage(path("cpu.pfm")));
    EXPECT_LE(d.shareOver005, 0.005);  // thresholds justified in tests/gpu/gpu_test_support.h
    EXPECT_LE(d.meanAbsError, 2e-3);

    nlohmann::json stats = nlohmann::json::parse(std::ifstream(path("gpu.json")));
    EXPECT_EQ(stats["backend"], "vulkan");
    EXPECT_EQ(stats["rays"]["primary"], 96 * 72);
    EXPECT_GT(stats["rays"]["shadow"].get<int>(), 0);
    // Every phase of the work, the scene's analysis included (a million-triangle model spent
    // seconds there, counted in no phase).
    for (const char* phase : {"device", "load", "analysis", "bvh", "upload", "pipeline", "render", "write"})
        EXPECT_TRUE(stats["seconds"].contains(phase)) << phase;
    EXPECT_NE(gpu.output.find("Mrays/s"), std::string::npos);
    // The device's buffers: at least the triangles' vertices (48 bytes each) for the scene, and the
    // trace state of every pixel of the one tile the image fits in.
    const auto triangles = stats["triangles"].get<std::uint64_t>();
    EXPECT_GE(stats["device_bytes"]["scene"].get<std::uint64_t>(), triangles * 48);
    EXPECT_GE(stats["device_bytes"]["tile"].get<std::uint64_t>(),
              96 * 72 * stats["kernel"]["state_bytes_per_pixel"].get<std::uint64_t>());

    CommandRun diff = vitrum("diff " + path("gpu.pfm") + " " + path("cpu.pfm") + " --heatmap " + path("heat.png"));
    EXPECT_EQ(diff.exitCode, 0) << diff.output;
    EXPECT_NE(diff.output.find("psnr"), std::string::npos);
    EXPECT_TRUE(fs::exists(path("heat.png")));
}

// The GPU's buffers hold one tile at a time, the pixels included: an image whose 16-byte pixels
// would not fit one storage buffer of the device renders tile by tile, each tile's pixels put in
// their place. Here the limit is lowered (VITRUM_MAX_BUFFER_BYTES) below the 480,000 bytes that
// 200 x 150 pixels need, and tiles of 16 pixels fit it; the image is the same, bit for bit, as one
// rendered in one tile without the limit.
TEST_F(Cli, ImageLargerThanTheDeviceBufferLimitRendersTileByTile) {
    const std::string common = "render " + kGeosphere + " --width 200 --height 150 --backend vulkan";
    CommandRun tiled = vitrum(common + " --tile 16 -o " + path("tiled.pfm"), "VITRUM_MAX_BUFFER_BYTES=300000");
    ASSERT_EQ(tiled.exitCode, 0) << tiled.output;
    CommandRun whole = vitrum(common + " -o " + path("whole.pfm"));
    ASSERT_EQ(whole.exitCode, 0) << whole.output;
    const vitrum::Image a = vitrum::readImage(path("tiled.pfm"));
    const vitrum::Image b = vitrum::readImage(path("whole.pfm"));
    ASSERT_EQ(a.width, 200u);
    ASSERT_EQ(a.height, 150u);
    // Not a uniform image, so a tile out of place would show: the geosphere in the middle, the
    // background in the corner.
    ASSERT_NE(b.at(100, 75), b.at(0, 0));
    EXPECT_EQ(a.pixels, b.pixels);
}

// OpenEXR output holds the render's linear floats, as PFM does: the two files read back the same,
// and `vitrum diff` reads both.
TEST_F(Cli, ExrOutputHoldsTheSameValuesAsPfm) {
    std::string common = "render " + kGeosphere + " --camera-from 3,-3,1 --camera-at 0,0,0 --width 24 --height 18 --backend cpu";
    ASSERT_EQ(vitrum(common + " -o " + path("out.exr")).exitCode, 0);
    ASSERT_EQ(vitrum(common + " -o " + path("out.pfm")).exitCode, 0);
    const vitrum::Image exr = vitrum::readImage(path("out.exr"));
    const vitrum::Image pfm = vitrum::readImage(path("out.pfm"));
    ASSERT_EQ(exr.width, 24u);
    ASSERT_EQ(exr.height, 18u);
    EXPECT_EQ(exr.pixels, pfm.pixels);
    float largest = 0.0f;
    for (const glm::vec3& p : exr.pixels) largest = std::max({largest, p.r, p.g, p.b});
    EXPECT_GT(largest, 0.1f);  // the geosphere is lit, not a black image
    CommandRun diff = vitrum("diff " + path("out.exr") + " " + path("out.pfm"));
    EXPECT_EQ(diff.exitCode, 0) << diff.output;
    EXPECT_NE(diff.output.find("rmse: 0\n"), std::string::npos) << diff.output;
}

TEST_F(Cli, MissingSceneIsAnErrorNamingTheFile) {
    CommandRun r = vitrum("render " + path("nope.json") + " -o " + path("out.png"));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("nope.json"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(path("out.png")));
}

TEST_F(Cli, MalformedJsonNamesFileAndLine) {
    std::string scene = write("bad.json", "{\n  \"camera\": {\n    \"fov_y\": ,\n  }\n}\n");
    CommandRun r = vitrum("render " + scene + " -o " + path("out.png"));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("bad.json:3"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(path("out.png")));
}

TEST_F(Cli, AbsurdImageSizesAreRefused) {
    for (std::string size : {"--width 0", "--height 0", "--width 1000000", "--spp 0", "--max-depth -1", "--fov 180"}) {
        CommandRun r = vitrum("render " + kGeosphere + " " + size + " -o " + path("out.png"));
        EXPECT_EQ(r.exitCode, 1) << size << ": " << r.output;
        EXPECT_FALSE(fs::exists(path("out.png"))) << size;
    }
}

TEST_F(Cli, UnwritableOutputLeavesNothingBehind) {
    CommandRun r = vitrum("render " + kGeosphere + " --width 8 --height 8 -o " + path("missing-dir/out.png"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("out.png"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(Cli, UnknownOptionsAndOutputFormatsAreRefused) {
    EXPECT_EQ(vitrum("render " + kGeosphere + " --frobnicate -o " + path("a.png")).exitCode, 1);
    EXPECT_EQ(vitrum("render " + kGeosphere + " -o " + path("a.jpg")).exitCode, 1);
    EXPECT_EQ(vitrum("frobnicate").exitCode, 1);
    EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(Cli, NanCoordinatesAreAnError) {
    std::string obj = write("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
    CommandRun r = vitrum("render " + obj + " -o " + path("out.png"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("nan.obj"), std::string::npos) << r.output;
}

TEST_F(Cli, EmptyMeshIsAnError) {
    std::string obj = write("empty.obj", "# nothing here\n");
    CommandRun r = vitrum("render " + obj + " -o " + path("out.png"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("empty.obj"), std::string::npos) << r.output;
}

TEST_F(Cli, HelpIsThereForEveryCommand) {
    for (std::string command : {"--help", "render --help", "info --help", "diff --help", "devices --help"}) {
        CommandRun r = vitrum(command);
        EXPECT_EQ(r.exitCode, 0) << command;
        EXPECT_NE(r.output.find("usage"), std::string::npos) << command;
    }
}

// What `render --help` says an option accepts is what the command accepts: each range's upper end
// read from the help text passes the option's check (the command goes on, and fails only on the
// scene file that is not there), and the next value up is refused, naming the option.
TEST_F(Cli, RenderHelpStatesTheRangesTheOptionsAccept) {
    const std::string help = vitrum("render --help").output;
    const std::string missingScene = path("missing.json");
    auto expectAccepted = [&](const std::string& option) {
        CommandRun r = vitrum("render " + missingScene + " " + option + " -o " + path("out.png"));
        EXPECT_EQ(r.exitCode, 1) << option << "\n" << r.output;
        EXPECT_NE(r.output.find("missing.json"), std::string::npos) << option << " was refused:\n" << r.output;
    };
    auto expectRefused = [&](const std::string& option) {
        CommandRun r = vitrum("render " + missingScene + " " + option + " -o " + path("out.png"));
        EXPECT_EQ(r.exitCode, 1) << option << "\n" << r.output;
        EXPECT_NE(r.output.find(option.substr(0, option.find(' '))), std::string::npos) << option << "\n" << r.output;
        EXPECT_EQ(r.output.find("missing.json"), std::string::npos) << option << " was accepted:\n" << r.output;
    };
    // "--spp N   samples per pixel (1..4096)": the number after "..", on the option's line.
    auto upperEnd = [&](const std::string& line) -> long {
        const std::size_t at = help.find("\n  " + line);
        const std::size_t dots = help.find("..", at);
        if (at == std::string::npos || dots == std::string::npos || dots > help.find('\n', at + 1)) return -1;
        return std::stol(help.substr(dots + 2));
    };
    for (std::string option : {"--width", "--spp", "--max-depth"}) {
        const long most = upperEnd(option);
        ASSERT_GT(most, 0) << "no range for " << option << " in\n" << help;
        expectAccepted(option + " " + std::to_string(most));
        expectRefused(option + " " + std::to_string(most + 1));
    }
    expectAccepted("--height " + std::to_string(upperEnd("--width")));  // the line "--width N, --height N"
    expectRefused("--height " + std::to_string(upperEnd("--width") + 1));
    // "--fov DEG   vertical field of view, between 0.5 and 179.5 degrees (exclusive)"
    float lowest = 0, highest = 0;
    const std::size_t fov = help.find("between ", help.find("\n  --fov"));
    ASSERT_EQ(std::sscanf(help.c_str() + fov, "between %f and %f degrees (exclusive)", &lowest, &highest), 2) << help;
    expectRefused("--fov " + std::to_string(lowest));
    expectAccepted("--fov " + std::to_string(lowest + 0.01f));
    expectAccepted("--fov " + std::to_string(highest - 0.01f));
    expectRefused("--fov " + std::to_string(highest));
}

// Each device with its subgroups and limits. lavapipe on a 256-bit CPU runs 8 lanes a SIMD group
// and has full subgroups (the platform facts of DEVELOPERS.md), so trace.comp sums its statistics
// by shuffles there.
TEST_F(Cli, DevicesListsSubgroupsAndLimits) {
    CommandRun r = vitrum("devices");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.rfind("0: ", 0), 0u) << r.output;
    EXPECT_NE(r.output.find("subgroups of "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("statistics summed by "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("storage buffers up to "), std::string::npos) << r.output;
    if (r.output.find("llvmpipe (LLVM 15.0.6, 256 bits)") != std::string::npos) {
        EXPECT_NE(r.output.find("subgroups of 8 lanes, arithmetic and ballots: yes, full subgroups: yes; "
                                "statistics summed by shuffles"),
                  std::string::npos)
            << r.output;
        EXPECT_NE(r.output.find("storage buffers up to 128 MiB"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("driver: llvmpipe, Mesa "), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("kernel: fast: full subgroups"), std::string::npos) << r.output;
    }
}

// A device whose subgroups fail the self-check (VITRUM_SELF_CHECK_FAULT=1 makes one lane of it
// act lost) is listed with the safe kernel and the reason, and a render warns once and still
// traces every pixel.
TEST_F(Cli, ADeviceThatFailsTheSelfCheckGetsTheSafeKernelAndSaysWhy) {
    CommandRun listed = vitrum("devices", "VITRUM_SELF_CHECK_FAULT=1");
    ASSERT_EQ(listed.exitCode, 0) << listed.output;
    if (listed.output.find("llvmpipe") == std::string::npos) GTEST_SKIP() << "lavapipe is the device with the fast kernel here";
    EXPECT_NE(listed.output.find("kernel: safe: statistics summed by subgroupAdd (the self-check of full subgroups failed: "),
              std::string::npos)
        << listed.output;
    CommandRun render = vitrum("render " + std::string(VITRUM_SOURCE_DIR) +
                                   "/scenes/demo.json --width 64 --height 48 -o " + path("demo.pfm") + " --stats " +
                                   path("demo.json"),
                               "VITRUM_SELF_CHECK_FAULT=1");
    ASSERT_EQ(render.exitCode, 0) << render.output;
    const std::string warning = "failed the self-check of full subgroups";
    const std::size_t first = render.output.find(warning);
    EXPECT_NE(first, std::string::npos) << render.output;
    EXPECT_EQ(render.output.find(warning, first + 1), std::string::npos) << "warned more than once: " << render.output;
    nlohmann::json stats = nlohmann::json::parse(std::ifstream(path("demo.json")));
    EXPECT_EQ(stats["rays"]["primary"], 64 * 48);
}

TEST_F(Cli, InfoReportsTrianglesAndBvh) {
    CommandRun r = vitrum("info " + kGeosphere);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("triangles: 1280"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("SAH cost"), std::string::npos) << r.output;
    // The device bytes: 64 an interior node (the nodes less the leaves), 48 a triangle's vertices,
    // and a shading texel of 16 for each triangle and each of the geosphere's 642 smooth normals.
    std::smatch bvh;
    ASSERT_TRUE(std::regex_search(r.output, bvh, std::regex("bvh: ([0-9]+) nodes, ([0-9]+) leaves"))) << r.output;
    const long long bytes = (std::stoll(bvh[1]) - std::stoll(bvh[2])) * 64 + 1280 * 48 + (1280 + 642) * 16;
    EXPECT_NE(r.output.find(", " + std::to_string(bytes) + " bytes in all"), std::string::npos) << r.output;
}

// Glass of two priorities: `vitrum info` gives each material's and says the kernel has the rule.
TEST_F(Cli, InfoReportsMediumPriorities) {
    write("p.mtl", "newmtl glass\nshader 4\nNi 1.5\npriority 2\nnewmtl water\nshader 4\nNi 1.33\n");
    write("p.obj", "mtllib p.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\no glass\nusemtl glass\nf 1 3 2\nf 1 2 4\n"
                   "f 1 4 3\nf 2 3 4\no water\nusemtl water\nf 1 3 2\n");
    CommandRun r = vitrum("info " + path("p.obj"));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("priority 2\n"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("overlapping media by priority: yes"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("overlapping media by priority: compiled in"), std::string::npos) << r.output;
}

// A glass sheet (one open triangle) beside a closed glass tetrahedron: rendering and `info` name
// the sheet, not the tetrahedron, as glass a ray may enter and never leave, and point to
// thin-walled glass; made thin-walled, the sheet is no medium and nothing is said.
TEST_F(Cli, OpenGlassIsNamedWithTheThinWalledHint) {
    const std::string geometry = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\no tetrahedron\nusemtl solid\nf 1 3 2\nf 1 2 4\n"
                                 "f 1 4 3\nf 2 3 4\no sheet\nusemtl pane\nf 2 3 4\n";
    write("open.mtl", "newmtl solid\nshader 4\nnewmtl pane\nshader 4\n");
    write("open.obj", "mtllib open.mtl\n" + geometry);
    for (const std::string& command : {"render " + path("open.obj") + " --width 8 --height 6 -o " + path("open.png"),
                                      "info " + path("open.obj")}) {
        CommandRun r = vitrum(command);
        EXPECT_EQ(r.exitCode, 0) << r.output;
        EXPECT_NE(r.output.find("warning: glass object \"open.obj/sheet\" is not a closed, consistently wound mesh"),
                  std::string::npos)
            << r.output;
        EXPECT_NE(r.output.find("`thin_walled 1`"), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("open.obj/tetrahedron"), std::string::npos) << r.output;
    }
    write("thin.mtl", "newmtl solid\nshader 4\nnewmtl pane\nshader 4\nthin_walled 1\n");
    write("thin.obj", "mtllib thin.mtl\n" + geometry);
    CommandRun thin = vitrum("render " + path("thin.obj") + " --width 8 --height 6 -o " + path("thin.png"));
    EXPECT_EQ(thin.exitCode, 0) << thin.output;
    EXPECT_EQ(thin.output.find("warning"), std::string::npos) << thin.output;
}

// bubble.json with its camera moved into the air bubble, which lies in the glass block.
TEST_F(Cli, InfoSaysWhichMediaTheCameraIsIn) {
    std::ifstream in(std::string(VITRUM_SOURCE_DIR) + "/scenes/bubble.json");
    nlohmann::json scene = nlohmann::json::parse(in);
    for (auto& object : scene["objects"])
        object["obj"] = std::string(VITRUM_SOURCE_DIR) + "/scenes/" + object["obj"].get<std::string>();
    for (auto& object : scene["objects"])
        if (object.contains("mtl"))
            object["mtl"] = std::string(VITRUM_SOURCE_DIR) + "/scenes/" + object["mtl"].get<std::string>();
    CommandRun outside = vitrum("info " + write("outside.json", scene.dump()));
    EXPECT_NE(outside.output.find("camera medium: air\n"), std::string::npos) << outside.output;
    scene["camera"]["from"] = {0.0, -0.1, 1.0};
    CommandRun inside = vitrum("info " + write("inside.json", scene.dump()));
    EXPECT_EQ(inside.exitCode, 0) << inside.output;
    EXPECT_NE(inside.output.find("camera medium: inside block.obj/block, then sphere.obj/sphere\n"), std::string::npos)
        << inside.output;
}

// one_box.json with its camera on the middle of the glass box's top face (z = 0.5), where the
// face's two triangles meet: rays going up start in air, rays going down in the box (object 1).
TEST_F(Cli, StatsSayWhereTheCameraLies) {
    const std::string box = std::string(VITRUM_SOURCE_DIR) + "/scenes/one_box.json --width 8 --height 6";
    CommandRun r = vitrum("render " + box + " --camera-from 0,0,0.5 --camera-at 0.3,0,-0.5 -o " + path("on.png") +
                          " --stats " + path("on.json"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json on = nlohmann::json::parse(std::ifstream(path("on.json")))["features"];
    EXPECT_EQ(on["camera_surface_triangles"], 2);
    EXPECT_EQ(on["camera_media"], nlohmann::json::array());
    EXPECT_EQ(on["camera_media_behind_surface"], nlohmann::json::array({1}));
    r = vitrum("render " + box + " --camera-from 0,0,0.4 --camera-at 0.3,0,-0.5 -o " + path("in.png") + " --stats " +
               path("in.json"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json in = nlohmann::json::parse(std::ifstream(path("in.json")))["features"];
    EXPECT_EQ(in["camera_surface_triangles"], 0);
    EXPECT_EQ(in["camera_media"], nlohmann::json::array({1}));
    EXPECT_EQ(in["camera_media_behind_surface"], nlohmann::json::array({1}));
}

}  // namespace

namespace {

// --background FILE puts an equirectangular map behind any scene, a bare glTF's or OBJ's included
// (glTF glass assets bring no environment): the image of the scene whose JSON names the same map
// as its "spherical" background, bit for bit; the last --background wins; the map is an input, so
// an output naming it is refused before anything is rendered, and leaves it as it was.
TEST_F(Cli, BackgroundMapFromTheCommandLineIsTheScenesSphericalBackground) {
    const std::string source = VITRUM_SOURCE_DIR;
    const std::string sky = source + "/scenes/environment/sky.hdr";
    const std::string scene = source + "/scenes/glass_set.json --width 64 --height 48";
    auto bytes = [](const std::string& file) {
        std::ifstream in(file, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(in)), {});
    };
    ASSERT_EQ(vitrum("render " + scene + " -o " + path("json.pfm")).exitCode, 0);
    const CommandRun mapped = vitrum("render " + scene + " --background 0,0,0 --background " + sky + " -o " + path("map.pfm"));
    ASSERT_EQ(mapped.exitCode, 0) << mapped.output;
    const CommandRun black = vitrum("render " + scene + " --background " + sky + " --background 0,0,0 -o " + path("black.pfm"));
    ASSERT_EQ(black.exitCode, 0) << black.output;
    EXPECT_GT(bytes(path("json.pfm")).size(), 64u * 48u * 12u);
    EXPECT_TRUE(bytes(path("json.pfm")) == bytes(path("map.pfm"))) << "the map given on the command line differs";
    EXPECT_GT(vitrum::diffImages(vitrum::readImage(path("json.pfm")), vitrum::readImage(path("black.pfm"))).shareOver005, 0.3);

    // A bare glTF under the map: its automatic grey background is replaced.
    const std::string gltf = source + "/scenes/meshes/glass_set.gltf --width 64 --height 48";
    ASSERT_EQ(vitrum("render " + gltf + " -o " + path("bare.pfm")).exitCode, 0);
    ASSERT_EQ(vitrum("render " + gltf + " --background " + sky + " -o " + path("bare_sky.pfm")).exitCode, 0);
    EXPECT_GT(vitrum::diffImages(vitrum::readImage(path("bare.pfm")), vitrum::readImage(path("bare_sky.pfm"))).shareOver005,
              0.3);

    fs::copy_file(sky, path("sky.hdr"));
    const std::string before = bytes(path("sky.hdr"));
    const CommandRun overwrite = vitrum("render " + gltf + " --background " + path("sky.hdr") + " -o " + path("sky.hdr"));
    EXPECT_EQ(overwrite.exitCode, 1);
    EXPECT_NE(overwrite.output.find("it is the background map"), std::string::npos) << overwrite.output;
    EXPECT_TRUE(bytes(path("sky.hdr")) == before);
    const CommandRun twoNumbers = vitrum("render " + gltf + " --background 0.1,0.2 -o " + path("out.png"));
    EXPECT_EQ(twoNumbers.exitCode, 1);
    EXPECT_NE(twoNumbers.output.find("--background takes a colour R,G,B or an image file"), std::string::npos)
        << twoNumbers.output;
    const CommandRun missing = vitrum("render " + gltf + " --background " + path("nothere.exr") + " -o " + path("out.png"));
    EXPECT_EQ(missing.exitCode, 1);
    EXPECT_NE(missing.output.find("nothere.exr"), std::string::npos) << missing.output;
    EXPECT_FALSE(fs::exists(path("out.png")));
}

TEST_F(Cli, NoSpecializeRendersTheSameImageWithTheGeneralKernel) {
    const std::string scene = std::string(VITRUM_SOURCE_DIR) + "/scenes/touching_cubes.json --width 48 --height 36";
    CommandRun specialized =
        vitrum("render " + scene + " -o " + path("specialized.pfm") + " --stats " + path("specialized.json"));
    ASSERT_EQ(specialized.exitCode, 0) << specialized.output;
    CommandRun general = vitrum("render " + scene + " --no-specialize -o " + path("general.pfm") + " --stats " +
                                path("general.json"));
    ASSERT_EQ(general.exitCode, 0) << general.output;
    std::ifstream a(path("specialized.pfm"), std::ios::binary), b(path("general.pfm"), std::ios::binary);
    const std::string bytesA((std::istreambuf_iterator<char>(a)), {}), bytesB((std::istreambuf_iterator<char>(b)), {});
    EXPECT_GT(bytesA.size(), 48u * 36u * 12u);
    EXPECT_TRUE(bytesA == bytesB) << "the two kernels' images differ";
    nlohmann::json s = nlohmann::json::parse(std::ifstream(path("specialized.json")));
    nlohmann::json g = nlohmann::json::parse(std::ifstream(path("general.json")));
    EXPECT_EQ(s["kernel"]["specialized"], true);
    EXPECT_EQ(g["kernel"]["specialized"], false);
    EXPECT_EQ(s["kernel"]["medium_stack_depth"], 2);  // two cubes sharing a face
    EXPECT_EQ(g["kernel"]["medium_stack_depth"], 4);
    EXPECT_EQ(s["features"]["touching_media_possible"], true);
    EXPECT_LT(s["kernel"]["state_bytes_per_pixel"].get<int>(), g["kernel"]["state_bytes_per_pixel"].get<int>());
    EXPECT_TRUE(s["seconds"].contains("compile"));
}

}  // namespace
