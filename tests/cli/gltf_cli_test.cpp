// glTF 2.0 files that another program wrote, through the command line: Debian's assimp
// (assimp-utils) exports course meshes, and `vitrum render` and `vitrum info` take the files as
// scenes of their own (docs/scene-format.md, "glTF 2.0"), framed automatically.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "cli_support.h"
#include "image/image.h"
#include "image/image_diff.h"

namespace {

namespace fs = std::filesystem;

using vitrum::testing::CommandRun;
using vitrum::testing::run;
using vitrum::testing::vitrum;
using GltfCli = vitrum::testing::CliTest;

// The number in `vitrum info`'s "triangles: N in M objects", or -1 without one.
long long trianglesIn(const std::string& info) {
    std::smatch match;
    if (!std::regex_search(info, match, std::regex("triangles: ([0-9]+)"))) return -1;
    return std::stoll(match[1]);
}

// assimp writes what its OBJ importer read: the course's z-up data as glTF's y-up (the meshes lie
// on their side, which automatic framing does not mind), Kd as baseColorFactor, its own extensions
// (KHR_materials_pbrSpecularGlossiness, FB_ngon_encoding) as used, not required, and
// three-component TEXCOORD_0 where the OBJ's vt lines have three numbers.
TEST_F(GltfCli, AssimpExportedCourseMeshesLoadFrameAndRender) {
    // A failure, not a skip, without assimp: CI installs it, and a skip would hide that it did not.
    const CommandRun version = run("assimp version");
    ASSERT_EQ(version.exitCode, 0) << "assimp (Debian's assimp-utils) is needed: " << version.output;
    for (const std::string mesh : {"geosphere", "cornell_box2"}) {
        SCOPED_TRACE(mesh);
        const std::string obj = std::string(VITRUM_SHARED_DIR) + "/scenes/course/" + mesh + "/" + mesh + ".obj";
        const std::string gltf = path(mesh + ".gltf");
        const std::string png = path(mesh + ".png");
        // gltf2 by name: assimp's "gltf" format is glTF 1.0.
        const CommandRun exported = run("assimp export " + obj + " " + gltf + " -fgltf2");
        ASSERT_EQ(exported.exitCode, 0) << exported.output;
        ASSERT_TRUE(fs::exists(gltf)) << exported.output;

        const CommandRun render = vitrum("render " + gltf + " --width 64 --height 48 -o " + png);
        ASSERT_EQ(render.exitCode, 0) << render.output;
        const vitrum::Image image = vitrum::readImage(png);
        ASSERT_EQ(image.width, 64u);
        ASSERT_EQ(image.height, 48u);
        // The automatic camera sees the mesh, lit by the automatic light: not one colour.
        EXPECT_TRUE(std::any_of(image.pixels.begin(), image.pixels.end(),
                                [&](const glm::vec3& p) { return p != image.pixels.front(); }));

        const CommandRun gltfInfo = vitrum("info " + gltf);
        ASSERT_EQ(gltfInfo.exitCode, 0) << gltfInfo.output;
        const CommandRun objInfo = vitrum("info " + obj);
        ASSERT_EQ(objInfo.exitCode, 0) << objInfo.output;
        EXPECT_GT(trianglesIn(objInfo.output), 0) << objInfo.output;
        EXPECT_EQ(trianglesIn(gltfInfo.output), trianglesIn(objInfo.output)) << gltfInfo.output;
    }
}

// `--camera NAME` picks a glTF file's camera; a name the file lacks is refused with the names it
// has, and the option is refused for scenes that are no glTF file.
TEST_F(GltfCli, CameraAndVariantOptionsPickWhatTheFileHas) {
    // One triangle (three glTF vertices: the origin, +x and +y) seen by two cameras.
    const std::string gltf = write("two_cameras.gltf", R"({
  "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1, 2]}],
  "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "cameras": [{"name": "front", "type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}},
              {"name": "wide", "type": "perspective", "perspective": {"yfov": 1.2, "aspectRatio": 2.0, "znear": 0.1}}],
  "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0.3, 0.3, 3]}, {"camera": 1, "translation": [0.3, 0.3, 2]}]
})");
    const CommandRun front = vitrum("render " + gltf + " --camera front -o " + path("front.png"));
    ASSERT_EQ(front.exitCode, 0) << front.output;
    EXPECT_NE(front.output.find("image: 640x480"), std::string::npos) << front.output;
    // The second camera's aspect ratio 2 gives its image 640 x 320.
    const CommandRun wide = vitrum("render " + gltf + " --camera wide --width 64 -o " + path("wide.png"));
    ASSERT_EQ(wide.exitCode, 0) << wide.output;
    EXPECT_NE(wide.output.find("image: 64x320"), std::string::npos) << wide.output;

    const CommandRun missing = vitrum("render " + gltf + " --camera top -o " + path("top.png"));
    EXPECT_EQ(missing.exitCode, 1);
    EXPECT_NE(missing.output.find("has no camera named \"top\"; its cameras: \"front\", \"wide\""), std::string::npos)
        << missing.output;
    EXPECT_FALSE(fs::exists(path("top.png")));

    const std::string obj = write("triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const CommandRun notGltf = vitrum("render " + obj + " --camera front -o " + path("obj.png"));
    EXPECT_EQ(notGltf.exitCode, 1);
    EXPECT_NE(notGltf.output.find("--camera picks a camera of a glTF file"), std::string::npos) << notGltf.output;
    // --variant (KHR_materials_variants) likewise: a file without variants has none to pick.
    const CommandRun objVariant = vitrum("render " + obj + " --variant off -o " + path("obj.png"));
    EXPECT_EQ(objVariant.exitCode, 1);
    EXPECT_NE(objVariant.output.find("--variant picks a material variant of a glTF file"), std::string::npos)
        << objVariant.output;
    const CommandRun noVariants = vitrum("render " + gltf + " --variant off -o " + path("off.png"));
    EXPECT_EQ(noVariants.exitCode, 1);
    EXPECT_NE(noVariants.output.find("has no material variant named \"off\" (it has none)"), std::string::npos)
        << noVariants.output;
    EXPECT_FALSE(fs::exists(path("off.png")));
    // `vitrum info` takes both as `vitrum render` does.
    const CommandRun info = vitrum("info " + gltf + " --camera wide");
    ASSERT_EQ(info.exitCode, 0) << info.output;
    EXPECT_NE(info.output.find(", 640x320\n"), std::string::npos) << info.output;
    const CommandRun infoVariant = vitrum("info " + gltf + " --variant off");
    EXPECT_EQ(infoVariant.exitCode, 1);
    EXPECT_NE(infoVariant.output.find("has no material variant named \"off\""), std::string::npos)
        << infoVariant.output;
}

// The project's glTF scene (scenes/meshes/glass_set.gltf, written by
// scenes/generate/make_gltf_scene.py; scenes/glass_set.json renders it under a sky, and EveryScene
// holds that render to the CPU reference) is a scene of its own: its camera, its light, and each
// glass's KHR_materials_volume as Beer-Lambert mu = -ln(attenuationColor) / attenuationDistance.
TEST_F(GltfCli, TheProjectsGlassSetIsASceneOfItsOwn) {
    const std::string gltf = std::string(VITRUM_SOURCE_DIR) + "/scenes/meshes/glass_set.gltf";
    const CommandRun info = vitrum("info " + gltf);
    ASSERT_EQ(info.exitCode, 0) << info.output;
    EXPECT_NE(info.output.find("in 6 objects"), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("lights: 1"), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("camera: from (0, -5.2, 2.6)"), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("glass (refraction, medium stack): yes, 5 objects"), std::string::npos) << info.output;
    // The file's colours and distances (make_gltf_scene.py), in `info`'s three significant digits.
    auto mu = [](double colour, double distance) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3g", -std::log(colour) / distance);
        return std::string(text);
    };
    const std::string green = "Ni 1.52  Tf " + mu(0.3, 0.12) + " " + mu(0.75, 0.12) + " " + mu(0.4, 0.12);
    const std::string amber = "Ni 1.72  Tf " + mu(0.9, 0.12) + " " + mu(0.55, 0.12) + " " + mu(0.2, 0.12);
    const std::string water = "Ni 1.33  Tf " + mu(0.55, 0.5) + " " + mu(0.8, 0.5) + " " + mu(0.95, 0.5);
    for (const std::string& line : {green, amber, water, std::string("Ni 2.42  Tf 0 0 0"), std::string("Ni 1.5  Tf 0 0 0")})
        EXPECT_NE(info.output.find(line), std::string::npos) << line << "\n" << info.output;

    const std::string png = path("glass_set.png");
    const CommandRun render = vitrum("render " + gltf + " --width 64 --height 48 -o " + png);
    ASSERT_EQ(render.exitCode, 0) << render.output;
    const vitrum::Image image = vitrum::readImage(png);
    EXPECT_TRUE(std::any_of(image.pixels.begin(), image.pixels.end(),
                            [&](const glm::vec3& p) { return p != image.pixels.front(); }));
}

// gltfpack's output of the glass set, quantized (tests/fuzz/corpus/gltf/glass_set_quantized.glb)
// and also meshopt-compressed (glass_set_meshopt.glb), through the command line: the same
// triangles (GltfAccessors.GltfpacksCompressedFileLoadsAsItsUncompressedOne), so the same picture,
// but where a ray passes within an ulp of an edge (the compressed file starts some triangles at
// another corner).
TEST_F(GltfCli, GltfpacksCompressedGlassSetRendersAsItsUncompressedOne) {
    const std::string corpus = std::string(VITRUM_SOURCE_DIR) + "/tests/fuzz/corpus/gltf/";
    for (const char* name : {"glass_set_quantized", "glass_set_meshopt"}) {
        const CommandRun render =
            vitrum("render " + corpus + name + ".glb --width 96 --height 72 -o " + path(std::string(name) + ".pfm"));
        ASSERT_EQ(render.exitCode, 0) << render.output;
        EXPECT_NE(render.output.find("refraction"), std::string::npos) << render.output;
    }
    const vitrum::ImageDiff d = vitrum::diffImages(vitrum::readImage(path("glass_set_quantized.pfm")),
                                                   vitrum::readImage(path("glass_set_meshopt.pfm")));
    EXPECT_LE(d.shareOver1of255, 0.002) << "psnr " << d.psnr;
}

// Bad glTF input (issue 50): refused with a message that names the file and what in it is wrong,
// a non-zero exit and no image written.
TEST_F(GltfCli, BadFilesAreRefusedNamingTheFileAndWriteNoImage) {
    // One triangle (glTF 2.0's minimal file), its 36 bytes of positions inline or in tri.bin.
    const std::string triangle = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
    const std::string inlineBuffer = R"({"byteLength": 36, "uri": "data:application/octet-stream;base64,)" + triangle + R"("})";
    const std::string view = R"({"buffer": 0, "byteLength": 36})";
    const std::string positions = R"({"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"})";
    const std::string mesh = R"([{"mesh": 0}])";
    auto gltf = [&](const std::string& nodes, const std::string& buffers, const std::string& views,
                    const std::string& accessors, const std::string& primitive = "", const std::string& more = "") {
        return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": )" + nodes +
               R"(, "meshes": [{"primitives": [{"attributes": {"POSITION": 0})" + primitive + R"(}]}], "buffers": [)" +
               buffers + R"(], "bufferViews": [)" + views + R"(], )" + more + R"("accessors": [)" + accessors + "]}";
    };
    struct Bad {
        std::string name, contents, message;
    };
    std::vector<Bad> bad = {
        {"missing_bin.gltf", gltf(mesh, R"({"byteLength": 36, "uri": "tri.bin"})", view, positions),
         "buffers[0]: File not found : tri.bin"},
        {"component_type.gltf",
         gltf(mesh, inlineBuffer, view, R"({"bufferView": 0, "componentType": 5121, "count": 3, "type": "VEC3"})"),
         "accessors[0] (meshes[0].primitives[0].attributes.POSITION) has component type 5121; glTF 2.0 allows it FLOAT (5126)"},
        {"beyond_buffer.gltf",
         gltf(mesh, inlineBuffer, view, R"({"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"})"),
         "accessors[0] (meshes[0].primitives[0].attributes.POSITION) reaches beyond its buffer"},
        {"cycle.gltf", gltf(R"([{"mesh": 0, "children": [1]}, {"children": [0]}])", inlineBuffer, view, positions),
         "nodes[0] is its own ancestor"},
        {"index_range.gltf",  // indices 0, 1, 7 as unsigned shorts
         gltf(mesh, inlineBuffer + R"(, {"byteLength": 6, "uri": "data:application/octet-stream;base64,AAABAAcA"})",
              view + R"(, {"buffer": 1, "byteLength": 6})",
              positions + R"(, {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"})", R"(, "indices": 1)"),
         "meshes[0].primitives[0] uses vertex 7, but it has 3"},
        {"missing_image.gltf",  // a base colour texture whose image file is not there
         gltf(mesh, inlineBuffer, view, positions, R"(, "material": 0)",
              R"("images": [{"uri": "label.png"}], "textures": [{"source": 0}], )"
              R"("materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}], )"),
         "materials[0] (\"material0\"): its baseColorTexture's image cannot be read"},
        {"overflowing_matrix.gltf",
         gltf(R"([{"mesh": 0, "matrix": [1e400, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}])", inlineBuffer, view, positions),
         "1e400"},
    };
    // A .glb cut short: its header promises more bytes than the file has (glTF 2.0, 4.4).
    const std::string json = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "buffers": [{"byteLength": 36}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}], "accessors": [)" + positions + "]}";
    std::string padded = json;
    while (padded.size() % 4) padded += ' ';
    auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    std::string glb = u32(0x46546C67) + u32(2) + u32(std::uint32_t(12 + 8 + padded.size() + 8 + 36)) +
                      u32(std::uint32_t(padded.size())) + u32(0x4E4F534A) + padded + u32(36) + u32(0x004E4942) +
                      std::string(36, '\0');
    bad.push_back({"truncated.glb", glb.substr(0, glb.size() - 20),
                   "is cut short: its header gives " + std::to_string(glb.size()) + " bytes, the file has " +
                       std::to_string(glb.size() - 20)});
    for (const Bad& b : bad) {
        SCOPED_TRACE(b.name);
        const std::string file = write(b.name, b.contents);
        const std::string png = path(b.name + ".png");
        const CommandRun r = vitrum("render " + file + " --width 8 --height 8 -o " + png);
        EXPECT_EQ(r.exitCode, 1) << r.output;
        EXPECT_NE(r.output.find("error: " + file + ": "), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(b.message), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(png));
    }
    // The same files made right render: each refusal is the one fault.
    write("tri.bin", std::string("\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\0\0", 36));
    for (const std::string& good : {bad[0].name, std::string("whole.glb")}) {
        if (good == "whole.glb") write(good, glb);
        const CommandRun r = vitrum("render " + path(good) + " --width 8 --height 8 -o " + path(good + ".png"));
        EXPECT_EQ(r.exitCode, 0) << good << ": " << r.output;
    }
}

}  // namespace
