// Bad input never hurts, end to end through the `vitrum` binary: for each kind of bad input (OBJ,
// MTL, JSON scene, image, path, a scene too large for the device) the command exits with 1, its
// message names the file (and the line where there is one), and no output file is left behind.
// Unknown keys and unreadable textures are the exceptions that only warn.
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "cli_support.h"

namespace {

namespace fs = std::filesystem;

using vitrum::testing::CommandRun;
using vitrum::testing::vitrum;

std::string randomBytes(std::size_t count, unsigned seed) {
    std::mt19937 random(seed);
    std::string bytes(count, '\0');
    for (char& b : bytes) b = char(random() & 0xff);
    return bytes;
}

const std::string kGeosphere = std::string(VITRUM_SHARED_DIR) + "/scenes/course/geosphere/geosphere.obj";
const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

class CliBadInput : public vitrum::testing::CliTest {
protected:
    void SetUp() override {
        CliTest::SetUp();
        write("tri.obj", kTriangle);
    }

    // A scene file whose line 2 is `secondLine` (line 1 names tri.obj).
    std::string scene(const std::string& secondLine, const std::string& name = "scene.json") const {
        return write(name, "{\"objects\": [{\"obj\": \"tri.obj\"}],\n" + secondLine + "\n}\n");
    }

    // Renders `arguments` to out.png and expects a refusal: exit code 1, an error message with each
    // of `parts`, and no out.png (nor a temporary file next to it).
    void expectRefused(const std::string& arguments, std::initializer_list<std::string> parts,
                       const std::string& environment = "") const {
        CommandRun r = vitrum("render " + arguments + " -o " + path("out.png"), environment);
        EXPECT_EQ(r.exitCode, 1) << arguments << "\n" << r.output;
        EXPECT_NE(r.output.find("vitrum: error: "), std::string::npos) << arguments << "\n" << r.output;
        for (const std::string& part : parts)
            EXPECT_NE(r.output.find(part), std::string::npos) << arguments << ": no \"" << part << "\" in\n" << r.output;
        expectNoOutput();
    }
    void expectNoOutput() const {
        for (const auto& entry : fs::directory_iterator(dir_))
            EXPECT_NE(entry.path().filename().string().rfind("out", 0), 0u) << entry.path() << " was left behind";
    }
};

// ------------------------------------------------------------------------------------ OBJ, MTL

TEST_F(CliBadInput, MalformedObjNamesFileAndLine) {
    expectRefused(write("bad.obj", "# a comment\nv 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n"),
                  {"bad.obj:3:", "v expects three numbers"});
}

TEST_F(CliBadInput, TruncatedObjNamesFileAndLine) {
    expectRefused(write("cut.obj", "v 0 0 0\nv 1 0 0\nv 0 1"), {"cut.obj:3:", "v expects three numbers"});
    expectRefused(write("cut_face.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2"), {"cut_face.obj"});
}

TEST_F(CliBadInput, EmptyFilesAreErrors) {
    expectRefused(write("empty.obj", ""), {"empty.obj", "contains no triangles"});
    expectRefused(write("empty.json", ""), {"empty.json:1:", "invalid JSON"});
    expectRefused(write("blank.json", "\n\n  \n"), {"blank.json", "invalid JSON"});
}

TEST_F(CliBadInput, BinaryGarbageIsAnError) {
    for (unsigned seed : {1u, 2u, 3u}) {
        expectRefused(write("garbage.obj", randomBytes(4096, seed)), {"garbage.obj"});
        expectRefused(write("garbage.json", randomBytes(4096, seed)), {"garbage.json", "invalid JSON"});
    }
    // Garbage after a Kd key: the number is malformed at line 2 (NUL bytes, refused with their
    // line wherever they are, become 'x').
    write("m.obj", "mtllib garbage.mtl\nusemtl a\n" + kTriangle);
    std::string garbage = randomBytes(4096, 4);
    std::replace(garbage.begin(), garbage.end(), '\0', 'x');
    write("garbage.mtl", "newmtl a\nKd " + garbage);
    expectRefused(path("m.obj"), {"garbage.mtl:2:", "Kd"});
}

TEST_F(CliBadInput, HugeFaceIndicesAreErrors) {
    const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    // Beyond the int range: tinyobjloader would wrap "4294967299" around to vertex 3.
    for (const char* face : {"f 1 2 4294967296", "f 1 2 4294967299", "f 1 2 99999999999999999999999",
                             "f 1 2 -2147483648", "f 1/99999999999 2 3", "f 1//-4294967297 2 3"}) {
        expectRefused(write("huge.obj", vertices + face + "\n"), {"huge.obj:4:", "face index", "out of range"});
    }
    // In the int range, beyond the file's vertices.
    expectRefused(write("huge.obj", vertices + "f 1 2 2147483647\n"), {"huge.obj", "index 2147483647"});
    expectRefused(write("huge.obj", vertices + "f 1 2 -2147483647\n"), {"huge.obj", "before the first"});
}

// tinyobjloader reads a number's exponent into an int that overflowed at 2147483648 (undefined
// behaviour, found by fuzzing: tests/fuzz/regressions/obj_mtl/): a normal or texture coordinate
// with an exponent of ten digits is refused with its line; nine digits, or leading zeros, are read.
TEST_F(CliBadInput, NumbersWithHugeExponentsAreErrors) {
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (const char* line :
         {"vn 0 0 1e-2147483648", "vn 0 0 1E+2147483648", "vt 0.5 5e12345678901", "vp 1e2147483649"}) {
        SCOPED_TRACE(line);
        expectRefused(write("exp.obj", triangle + line + "\nf 1 2 3\n"), {"exp.obj:4:", "exponent", "out of range"});
    }
    for (const char* line : {"vn 0 0 1e-999999999", "vt 0.5 0.5e-0000000000001"}) {
        SCOPED_TRACE(line);
        write("exp.obj", triangle + line + "\nf 1 2 3\n");
        CommandRun r =
            vitrum("render " + path("exp.obj") + " --width 4 --height 4 --backend cpu -o " + path("out.png"));
        EXPECT_EQ(r.exitCode, 0) << r.output;
    }
}

TEST_F(CliBadInput, MalformedMtlNamesFileAndLine) {
    write("m.obj", "mtllib bad.mtl\nusemtl a\n" + kTriangle);
    write("bad.mtl", "newmtl a\nshader 4\nKd 0.5 x 0.2\n");
    expectRefused(path("m.obj"), {"bad.mtl:3:", "Kd expects three numbers"});
    write("bad.mtl", "newmtl a\nNi one\n");
    expectRefused(path("m.obj"), {"bad.mtl:2:", "Ni"});
}

TEST_F(CliBadInput, NonFiniteCoordinatesAreErrors) {
    for (const char* bad : {"inf", "-inf", "nan", "1e39"}) {
        std::string obj = write("inf.obj", std::string("v 0 0 0\nv 1 ") + bad + " 0\nv 0 1 0\nf 1 2 3\n");
        expectRefused(obj, {"inf.obj:2:", "not a finite number"});
    }
    // Finite in the file, not after the transform.
    expectRefused(scene(R"("camera": {"from": [0, -5, 0], "at": [0, 0, 0]},
 "lights": [], "objects": [{"obj": "tri.obj", "transform": {"scale": 1e38, "translate": [3e38, 0, 0]}}])"),
                  {"tri.obj", "not finite after the transform"});
    // JSON has no NaN or infinity; a number too large for a double is refused by the JSON parser
    // (nlohmann's out-of-range error has no position: the message names the file only).
    expectRefused(scene(R"("camera": {"from": [1e999, 0, 0], "at": [0, 0, 0]})"), {"scene.json", "1e999"});
    expectRefused(scene(R"("lights": [{"position": [0, -1e400, 0]}])"), {"scene.json", "1e400"});
    // Finite as a double, not as a float.
    expectRefused(scene(R"("camera": {"from": [1e39, 0, 0], "at": [0, 0, 0]})"), {"scene.json:2:", "from"});
    expectRefused(kGeosphere + " --camera-from nan,0,0", {"--camera-from"});
    expectRefused(kGeosphere + " --light 0,inf,0", {"--light"});
}

// ------------------------------------------------------------------------------------ JSON

TEST_F(CliBadInput, WrongTypesNameFileAndLine) {
    expectRefused(scene(R"("camera": {"from": [0, -5, 0], "at": [0, 0, 0], "fov_y": "wide"})"),
                  {"scene.json:2:", "fov_y", "\"wide\""});
    expectRefused(scene(R"("render": {"spp": "many"})"), {"scene.json:2:", "spp"});
    expectRefused(scene(R"("render": {"max_depth": 2.5})"), {"scene.json:2:", "max_depth"});
    expectRefused(scene(R"("lights": {"position": [0, 0, 0]})"), {"scene.json:2:", "lights"});
    expectRefused(scene(R"("background": {"colour": "red"})"), {"scene.json:2:", "colour"});
    expectRefused(scene(R"("air_ior": true)"), {"scene.json:2:", "air_ior"});
    expectRefused(write("s.json", "{\n\"objects\": \"tri.obj\"\n}\n"), {"s.json:2:", "objects"});
    expectRefused(write("s.json", "[\"tri.obj\"]\n"), {"s.json", "object"});
}

TEST_F(CliBadInput, MissingFieldsAreErrors) {
    expectRefused(write("s.json", "{\n\"camera\": {\"from\": [0, -5, 0], \"at\": [0, 0, 0]}\n}\n"),
                  {"s.json", "\"objects\""});
    expectRefused(scene(R"("camera": {"at": [0, 0, 0]})"), {"scene.json:2:", "\"from\""});
    expectRefused(scene(R"("lights": [{"colour": [1, 1, 1]}])"), {"scene.json:2:", "position"});
    expectRefused(write("s.json", "{\n\"objects\": [{\"mtl\": \"tri.mtl\"}]\n}\n"), {"s.json:2:", "obj"});
}

TEST_F(CliBadInput, AbsurdValuesInTheSceneFileNameTheKey) {
    const std::string camera = R"("camera": {"from": [0, -5, 0], "at": [0, 0, 0], )";
    struct Case {
        std::string line, key;
    };
    for (const Case& c : {Case{camera + R"("fov_y": 0})", "fov_y"}, Case{camera + R"("fov_y": 180})", "fov_y"},
                          Case{camera + R"("fov_y": 0.4})", "fov_y"},
                          Case{camera + R"("width": 0})", "width"}, Case{camera + R"("width": 1000000})", "width"},
                          Case{camera + R"("height": -3})", "height"}, Case{R"("render": {"max_depth": -1})", "max_depth"},
                          Case{R"("render": {"spp": 0})", "spp"}, Case{R"("render": {"spp": 1e9})", "spp"},
                          Case{R"("air_ior": 0)", "air_ior"}, Case{R"("render": {"min_weight": -1})", "min_weight"}}) {
        expectRefused(scene(c.line), {"scene.json:2:", c.key});
    }
    expectRefused(scene(camera + R"("fov_y": 179.5})"), {"scene.json:2:", "between 0.5 and 179.5 degrees"});
}

TEST_F(CliBadInput, AbsurdValuesOnTheCommandLineNameTheOption) {
    for (std::string option : {"--width 0", "--height 0", "--width 1000000", "--spp 0", "--max-depth -1",
                               "--fov 0", "--fov 0.4", "--fov 179.6", "--spp 1e3", "--threads 0", "--tile 1"}) {
        expectRefused(kGeosphere + " --backend cpu " + option, {option.substr(0, option.find(' '))});
    }
    expectRefused(kGeosphere + " --backend cpu --fov 0.5", {"--fov", "between 0.5 and 179.5 degrees"});
}

TEST_F(CliBadInput, UnknownKeysOnlyWarn) {
    std::string json = scene(R"("rendr": {"spp": 4}, "objects_extra": 1)");
    CommandRun r = vitrum("render " + json + " --backend cpu --width 8 --height 8 -o " + path("out.png"));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("vitrum: warning: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("scene.json:2:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("rendr"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(path("out.png")));
}

// A scene nested 60,000 levels deep once overflowed the stack (nlohmann's dump, in an error
// message) after 5.6 s and 7.3 GB, and 100,000 levels under an unknown key took 11 GB: nesting is
// refused before parsing, at the line of the first bracket too deep, in time and memory linear in
// the file.
TEST_F(CliBadInput, DeepNestingIsRefusedAtOnce) {
    const std::string deep = std::string(60000, '[') + std::string(60000, ']');
    expectRefused(write("deep.json", "{\"objects\":\n" + deep + "}"), {"deep.json:2:", "nesting deeper than 64 levels"},
                  "timeout 20");
    expectRefused(scene("\"unknown\": " + std::string(100000, '[') + std::string(100000, ']')),
                  {"scene.json:2:", "nesting deeper than 64 levels"}, "timeout 20");
}

// Camera and light numbers whose arithmetic overflows float: refused, saying what overflowed,
// never a black image (from and at 6e38 apart rendered one) nor the wrong reason (from 1e20 away
// was refused as if up were parallel to the view).
TEST_F(CliBadInput, CameraAndLightNumbersThatOverflowAreRefusedSayingWhat) {
    expectRefused(write("far.json", "{\"objects\": [{\"obj\": \"tri.obj\"}],\n"
                                    "\"camera\": {\"from\": [1e20, 1, 1], \"at\": [0, 0, 0]}}"),
                  {"far.json:2:", "\"from\" and \"at\" are apart by 1e+20", "overflows"});
    expectRefused(path("tri.obj") + " --camera-from 3e38,0,0 --camera-at -3e38,0,1",
                  {"--camera-from", "apart by 6e+38", "overflows"});
    expectRefused(path("tri.obj") + " --camera-from 0,-5,0 --camera-at 0,0,0 --camera-up 0,0,1e20",
                  {"--camera-up", "\"up\" is as long as 1e+20"});
    // A light 3e38 away lit nothing, without a word.
    expectRefused(scene(R"("lights": [{"position": [3, 0, 5]},
{"position": [3e38, 0, 5]}])"),
                  {"scene.json:3:", "the light is as far from the scene's triangles as 3e+38"});
    expectRefused(path("tri.obj") + " --light 3e38,0,5", {"light 1 (--light", "3e+38"});
}

// A render far larger than usual says so before it starts, with its size and a lower bound on its
// time (a 16384 x 16384 render at 4096 samples, about 15 hours, once started without a word). The
// render itself is not waited for: `timeout` ends it.
TEST_F(CliBadInput, AFarLargerRenderThanUsualSaysItsSizeUpFront) {
    CommandRun r = vitrum("render " + path("tri.obj") + " --backend cpu --width 1024 --height 1024 --spp 4096 -o " +
                              path("out.png"),
                          "timeout 3");
    EXPECT_NE(r.output.find("warning: a large render: 4.29e+09 primary rays (1024 x 1024 pixels x 4096 samples)"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("at least 4 minutes"), std::string::npos) << r.output;
    CommandRun usual = vitrum("render " + path("tri.obj") + " --backend cpu --width 64 --height 64 --spp 16 -o " +
                              path("usual.png"));
    EXPECT_EQ(usual.exitCode, 0) << usual.output;
    EXPECT_EQ(usual.output.find("a large render"), std::string::npos) << usual.output;
}

// Running out of memory is the input's size, not a bug: an OBJ of 600,000 triangles under a
// 120 MB address-space limit is refused naming the file, with exit 1, not "internal error:
// std::bad_alloc" with exit 3. (Loading it peaks at 190 MB; 316 MB before the text was read
// without copies, and 200 MB of address space no longer stopped it.)
TEST_F(CliBadInput, RunningOutOfMemoryNamesTheInput) {
    if (std::getenv("ASAN_OPTIONS")) GTEST_SKIP() << "AddressSanitizer reserves more address space than the limit";
    std::string obj;
    constexpr int kVertices = 600000;
    for (int i = 0; i < kVertices; ++i) obj += "v " + std::to_string(i) + " 0 " + std::to_string(i % 7) + "\n";
    for (int i = 1; i + 2 <= kVertices; ++i)
        obj += "f " + std::to_string(i) + " " + std::to_string(i + 1) + " " + std::to_string(i + 2) + "\n";
    write("huge.obj", obj);
    // The CPU backend's render: the Vulkan one opens its device before the scene, and lavapipe
    // cannot start in 120 MB.
    for (const std::string& command :
         {"info " + path("huge.obj"), "render " + path("huge.obj") + " --backend cpu -o " + path("out.png")}) {
        CommandRun r = vitrum(command, "ulimit -v 120000;");
        EXPECT_EQ(r.exitCode, 1) << command << "\n" << r.output;
        EXPECT_NE(r.output.find("vitrum: error: "), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("not enough memory"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("huge.obj"), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
    }
    expectNoOutput();
}

// ------------------------------------------------------------------------------------ images

TEST_F(CliBadInput, CorruptOrUnknownImagesAreErrorsNamingTheFile) {
    write("sky.hdr", randomBytes(2000, 5));
    expectRefused(scene(R"("background": {"spherical": "sky.hdr"})"), {"sky.hdr", "cannot read image"});
    write("sky.png", std::string("\x89PNG\r\n\x1a\n", 8) + randomBytes(500, 6));
    expectRefused(scene(R"("background": {"spherical": "sky.png"})"), {"sky.png"});
    write("sky.exr", randomBytes(500, 7));
    expectRefused(scene(R"("background": {"spherical": "sky.exr"})"), {"sky.exr", "cannot read OpenEXR image"});
    write("sky.xyz", randomBytes(500, 8));
    expectRefused(scene(R"("background": {"cube_cross": "sky.xyz"})"), {"sky.xyz"});
    write("sky.pfm", "PF\n4 3\n-1.0\n" + std::string(20, '\0'));  // truncated raster
    expectRefused(scene(R"("background": {"spherical": "sky.pfm"})"), {"sky.pfm", "corrupt PFM"});

    // `vitrum diff` with a corrupt or unknown image writes no heat map.
    std::string good = write("good.pfm", "PF\n1 1\n-1.0\n" + std::string(12, '\0'));
    for (std::string bad : {"sky.hdr", "sky.png", "sky.exr", "sky.xyz", "sky.pfm"}) {
        CommandRun r = vitrum("diff " + path(bad) + " " + good + " --heatmap " + path("out_heat.png"));
        EXPECT_EQ(r.exitCode, 1) << bad << "\n" << r.output;
        EXPECT_NE(r.output.find(path(bad)), std::string::npos) << r.output;
        expectNoOutput();
    }
}

TEST_F(CliBadInput, UnreadableTextureOnlyWarns) {
    write("m.obj", "mtllib m.mtl\nusemtl a\nvt 0 0\n" + kTriangle);
    write("m.mtl", "newmtl a\nshader 2\nKd 0.5\nmap_Kd corrupt.png\n");
    write("corrupt.png", randomBytes(300, 9));
    CommandRun r = vitrum("render " + path("m.obj") + " --backend cpu --width 8 --height 8 -o " + path("out.png"));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("m.mtl:4:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("corrupt.png"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(path("out.png")));
}

// ------------------------------------------------------------------------------------ paths

TEST_F(CliBadInput, PathsThatDoNotExistAreNamed) {
    expectRefused(path("missing.obj"), {"missing.obj"});
    expectRefused(path("missing.json"), {"missing.json"});
    expectRefused(path("no_dir/scene.json"), {"no_dir/scene.json"});
    expectRefused(write("s.json", "{\n\"objects\": [\n{\"obj\": \"nope.obj\"}]}"), {"s.json:3:", "nope.obj"});
    expectRefused(write("s.json", "{\"objects\": [\n{\"obj\": \"tri.obj\",\n \"mtl\": \"nope.mtl\"}]}"),
                  {"s.json:3:", "nope.mtl"});
    expectRefused(scene(R"("background": {"spherical": "nope.hdr"})"), {"nope.hdr"});
    fs::create_directories(dir_ / "folder.json");
    expectRefused(path("folder.json"), {"folder.json"});
    expectRefused(write("scene.txt", "{}"), {"scene.txt", "unknown scene format"});

    CommandRun r = vitrum("diff " + path("nope.png") + " " + path("nope2.pfm"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("nope.png"), std::string::npos) << r.output;
    r = vitrum("info " + path("nope.obj"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("nope.obj"), std::string::npos) << r.output;
}

// Files that exist but are no regular files: a FIFO would block the reader for ever, and a device
// would be read without end (/dev/zero: 8 GB before the size check, once). Each is refused at once,
// by name, as not a regular file; a texture so named only warns, as an unreadable one does. Every
// command runs under `timeout 20`, so that a reader that blocks fails the test instead of hanging.
TEST_F(CliBadInput, FilesThatAreNotRegularAreRefusedAtOnceByName) {
    const std::string timeout = "timeout 20";
    ASSERT_EQ(::mkfifo((dir_ / "fifo.json").c_str(), 0600), 0);
    ASSERT_EQ(::mkfifo((dir_ / "fifo.obj").c_str(), 0600), 0);
    ASSERT_EQ(::mkfifo((dir_ / "fifo.mtl").c_str(), 0600), 0);
    ASSERT_EQ(::mkfifo((dir_ / "fifo.png").c_str(), 0600), 0);
    const std::string fifo = "not a regular file (a FIFO)";
    expectRefused(path("fifo.json"), {"fifo.json", fifo}, timeout);
    expectRefused(path("fifo.obj"), {"fifo.obj", fifo}, timeout);
    CommandRun info = vitrum("info " + path("fifo.json"), timeout);
    EXPECT_EQ(info.exitCode, 1) << info.output;
    EXPECT_NE(info.output.find(fifo), std::string::npos) << info.output;
    expectRefused(write("lib.obj", "mtllib fifo.mtl\n" + kTriangle), {"fifo.mtl", fifo}, timeout);
    fs::create_directories(dir_ / "folder.mtl");
    expectRefused(write("lib.obj", "mtllib folder.mtl\n" + kTriangle), {"folder.mtl", "(a directory)"}, timeout);
    expectRefused(write("s.json", "{\"objects\": [\n{\"obj\": \"/dev/zero\"}]}"),
                  {"s.json:2:", "not a regular file \"/dev/zero\""}, timeout);
    expectRefused(write("s.json", "{\"objects\": [\n{\"obj\": \"fifo.obj\"}]}"), {"s.json:2:", "fifo.obj"}, timeout);
    expectRefused(scene(R"("background": {"spherical": "/dev/zero"})"),
                  {"/dev/zero", "not a regular file (a character device)"}, timeout);
    expectRefused(scene(R"("background": {"spherical": "fifo.png"})"), {"fifo.png", fifo}, timeout);
    for (const std::string texture : {"/dev/zero", "fifo.png"}) {
        write("t.mtl", "newmtl a\nshader 2\nKd 0.5\nmap_Kd " + texture + "\n");
        write("t.obj", "mtllib t.mtl\nusemtl a\n" + kTriangle);
        CommandRun r = vitrum("render " + path("t.obj") + " --backend cpu --width 8 --height 8 -o " + path("t.png"),
                              timeout);
        EXPECT_EQ(r.exitCode, 0) << r.output;
        EXPECT_NE(r.output.find("t.mtl:4: texture cannot be read"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("not a regular file"), std::string::npos) << r.output;
    }
}

// A name longer than the file system allows (255 bytes a name on Linux): inputs are reported as
// not found, outputs are refused before the render (which could take minutes) and leave nothing.
TEST_F(CliBadInput, NamesTooLongForTheFileSystemAreRefusedBeforeRendering) {
    const std::string longName(300, 'y');
    expectRefused(path(longName + ".obj"), {longName + ".obj"});
    for (const std::string& output : {"-o " + path(longName + ".png"), "-o " + path("out.png") + " --stats " +
                                                                           path(longName + ".json")}) {
        CommandRun r = vitrum("render " + path("tri.obj") + " --width 8 --height 8 " + output);
        EXPECT_EQ(r.exitCode, 1) << r.output;
        EXPECT_NE(r.output.find(longName + "."), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("cannot write the file"), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("rays:"), std::string::npos) << "rendered before refusing: " << r.output;
        expectNoOutput();
    }
    // A texture so named only warns, as an unreadable one does.
    write("long.mtl", "newmtl a\nshader 2\nKd 0.5\nmap_Kd " + longName + ".png\n");
    write("long.obj", "mtllib long.mtl\nusemtl a\n" + kTriangle);
    CommandRun r = vitrum("render " + path("long.obj") + " --backend cpu --width 8 --height 8 -o " + path("out.png"));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("long.mtl:4:"), std::string::npos) << r.output;
}

// An output named like an existing folder: the temporary could be written, but renaming it onto
// the folder would fail after the render, so it is refused before.
TEST_F(CliBadInput, AnOutputNamedLikeAFolderIsRefusedBeforeRendering) {
    fs::create_directories(dir_ / "folder.png");
    fs::create_directories(dir_ / "folder.json");
    for (const std::string& output :
         {"-o " + path("folder.png"), "-o " + path("out.png") + " --stats " + path("folder.json")}) {
        CommandRun r = vitrum("render " + path("tri.obj") + " --width 8 --height 8 " + output);
        EXPECT_EQ(r.exitCode, 1) << r.output;
        EXPECT_NE(r.output.find("a folder has that name"), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("rays:"), std::string::npos) << "rendered before refusing: " << r.output;
    }
    EXPECT_FALSE(fs::exists(dir_ / "out.png"));
}

// An output that is a file the render reads (the scene itself, by --stats, or a texture or
// background, by -o, through another path to it) is refused before the render, and the file is
// left as it was; so is a heat map of `vitrum diff` over an image it compares.
TEST_F(CliBadInput, AnOutputThatIsOneOfTheScenesFilesIsRefusedAndTheFileKept) {
    const std::string sceneText = "{\"objects\": [{\"obj\": \"tri.obj\"}]}\n";
    const std::string sceneFile = write("scene.json", sceneText);
    CommandRun r = vitrum("render " + sceneFile + " --width 8 --height 8 -o " + path("out.png") + " --stats " +
                          path("./scene.json"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("it is the scene file"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(path("out.png")));
    std::ifstream scene(sceneFile);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(scene), {}), sceneText);

    // A texture of the scene, and the scene's background, written to by -o.
    write("m.obj", "mtllib m.mtl\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
    write("m.mtl", "newmtl a\nshader 2\nKd 1 1 1\nmap_Kd texture.pfm\n");
    const std::string texel = "PF\n1 1\n-1.0\n" + std::string(12, '\0');
    write("texture.pfm", texel);
    write("sky.pfm", texel);
    write("sky.json", "{\"objects\": [{\"obj\": \"tri.obj\"}], \"background\": {\"spherical\": \"sky.pfm\"}}");
    for (const auto& [scenePath, image] : {std::pair{path("m.obj"), "texture.pfm"}, std::pair{path("sky.json"), "sky.pfm"}}) {
        CommandRun o = vitrum("render " + scenePath + " --width 8 --height 8 -o " + (dir_ / "." / image).string());
        EXPECT_EQ(o.exitCode, 1) << o.output;
        EXPECT_NE(o.output.find("it is one of the scene's images"), std::string::npos) << o.output;
        EXPECT_EQ(o.output.find("rays:"), std::string::npos) << "rendered before refusing: " << o.output;
        std::ifstream kept(path(image), std::ios::binary);
        EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), texel) << image;
    }
    // diff's heat map over one of the images it compares.
    CommandRun d = vitrum("diff " + path("sky.pfm") + " " + path("texture.pfm") + " --heatmap " + path("sky.pfm"));
    EXPECT_EQ(d.exitCode, 1) << d.output;
    EXPECT_NE(d.output.find("it is an image compared"), std::string::npos) << d.output;
    std::ifstream kept(path("sky.pfm"), std::ios::binary);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), texel);
}

// ------------------------------------------------------------------------------------ device limits

// VITRUM_MAX_BUFFER_BYTES (for tests only, host/gpu/gpu_buffer.cpp) lowers the storage buffer
// limit: the scene is refused from its counts, before the BVH build, naming the buffer and the
// limit, where the least any BVH and shading layout take does not fit (gpu_input/scene_geometry_bytes.h);
// else once the BVH and the shading layout are known, before any buffer is made.
TEST_F(CliBadInput, SceneTooLargeForTheDeviceIsRefusedEarly) {
    // The geosphere's 1280 triangles need at least 160 leaves, so 159 interior nodes of 64 bytes:
    // the first buffer checked.
    expectRefused(kGeosphere + " --width 16 --height 16 --stats " + path("out.json"),
                  {"does not fit the device", "BVH nodes needs 10176 bytes", "allows 4096 bytes",
                   "VITRUM_MAX_BUFFER_BYTES"},
                  "VITRUM_MAX_BUFFER_BYTES=4096");
    // 2000 textured triangles whose 6000 corners each have a normal of their own: their vertices
    // (48 bytes a triangle) fit 100000 bytes, and so would the least shading (16 a triangle), but
    // their shading texels are 2000 + 6000 normals + 2 x 2000 uv texels, 192000 bytes.
    std::string corners = "mtllib tiny.mtl\nusemtl a\nvt 0 0\n";
    for (int i = 0; i < 2000; ++i) {
        corners += "v " + std::to_string(i) + " 0 0\nv " + std::to_string(i) + " 1 0\nv " + std::to_string(i) + ".5 0 1\n";
        for (int k = 0; k < 3; ++k) corners += "vn 0 " + std::to_string(1e-4 * (3 * i + k)) + " 1\n";
        const std::string a = std::to_string(3 * i + 1), b = std::to_string(3 * i + 2), c = std::to_string(3 * i + 3);
        corners += "f " + a + "/1/" + a + " " + b + "/1/" + b + " " + c + "/1/" + c + "\n";
    }
    write("corners.obj", corners);
    write("tiny.pfm", "PF\n2 2\n-1\n" + std::string(2 * 2 * 3 * sizeof(float), '\0'));
    write("tiny.mtl", "newmtl a\nshader 2\nKd 1 1 1\nmap_Kd tiny.pfm\n");
    expectRefused(path("corners.obj") + " --width 4 --height 4",
                  {"does not fit the device", "triangle normals and uvs needs 192000 bytes", "allows 100000 bytes"},
                  "VITRUM_MAX_BUFFER_BYTES=100000");
    EXPECT_EQ(vitrum("render " + path("corners.obj") + " --width 4 --height 4 -o " + path("corners.png"),
                     "VITRUM_MAX_BUFFER_BYTES=200000").exitCode, 0);
    // All the buffers against the device's memory (VITRUM_MAX_HEAP_BYTES lowers its largest heap):
    // where the scene's own fit and a tile's tip the sum, the message says a smaller --tile needs
    // less, and with one the scene renders; where even the least the geometry takes does not fit,
    // it is refused as its counts are read, with no word of tiles.
    expectRefused(kGeosphere + " --width 300 --height 300",
                  {"does not fit the device: its buffers need", "in all, but the largest device-local memory heap of",
                   "has 48 MiB; one tile's buffers take", "a smaller --tile needs less"},
                  "VITRUM_MAX_HEAP_BYTES=50000000");
    EXPECT_EQ(vitrum("render " + kGeosphere + " --width 300 --height 300 --tile 64 -o " + path("tiled.png"),
                     "VITRUM_MAX_HEAP_BYTES=50000000").exitCode, 0);
    // The geosphere's least: 159 nodes of 64 bytes, 1280 triangles of 48 and 16.
    const CommandRun tiny = vitrum("render " + kGeosphere + " -o " + path("tiny.png"), "VITRUM_MAX_HEAP_BYTES=60000");
    EXPECT_EQ(tiny.exitCode, 1);
    EXPECT_NE(tiny.output.find("its buffers need " + std::to_string(159 * 64 + 1280 * (48 + 16)) +
                               " bytes in all, but the largest device-local memory heap"), std::string::npos) << tiny.output;
    EXPECT_EQ(tiny.output.find("--tile"), std::string::npos) << tiny.output;
    // The geometry fits 1 MB; the buffers of a 256 x 256 tile do not, the first of them its 16-byte
    // pixels. The image's size does not matter (tests/cli/cli_test.cpp), the tile's does.
    expectRefused(kGeosphere + " --width 2000 --height 1000",
                  {"pixels of one tile needs 1 MiB", "allows 1000000 bytes", "a smaller --tile needs less"},
                  "VITRUM_MAX_BUFFER_BYTES=1000000");
    // An OBJ too large is refused as soon as its statements give its triangles' count, before it
    // makes them (the long part of a big model's load): before the face whose index is out of
    // range is met. 101 triangles need 4848 bytes of vertices.
    std::string strip = "v 0 0 0\nv 0 1 0\n";
    for (int i = 1; i <= 51; ++i) strip += "v " + std::to_string(i) + " 0 0\nv " + std::to_string(i) + " 1 0\n";
    for (int i = 0; i < 50; ++i) {
        const int a = 2 * i + 1;
        strip += "f " + std::to_string(a) + " " + std::to_string(a + 2) + " " + std::to_string(a + 3) + "\n";
        strip += "f " + std::to_string(a) + " " + std::to_string(a + 3) + " " + std::to_string(a + 1) + "\n";
    }
    write("strip.obj", strip + "f 1 2 999\n");
    expectRefused(path("strip.obj") + " --width 16 --height 16", {"does not fit the device", "triangle vertices needs 4848 bytes"},
                  "VITRUM_MAX_BUFFER_BYTES=4096");
    expectRefused(path("strip.obj") + " --width 16 --height 16", {"uses index 999"});  // where the triangles fit
    // The CPU backend has no such limit.
    CommandRun r = vitrum("render " + kGeosphere + " --backend cpu --width 8 --height 8 -o " + path("cpu.png"),
                          "VITRUM_MAX_BUFFER_BYTES=4096");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    // A texture too large for the textures' buffer is refused by its header as the scene loads,
    // named with its MTL line and its size (32 x 32 texels of 16 bytes); tests/core has the cases.
    write("wall.pfm", "PF\n32 32\n-1\n" + std::string(32 * 32 * 3 * sizeof(float), '\0'));
    write("wall.mtl", "newmtl a\nshader 2\nKd 1 1 1\nmap_Kd wall.pfm\n");
    write("wall.obj", "mtllib wall.mtl\nusemtl a\nvt 0 0\nvt 1 0\nvt 0 1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/2 3/3\n");
    expectRefused(
        path("wall.obj") + " --width 16 --height 16",
        {path("wall.mtl") + ":4: map_Kd " + path("wall.pfm"), "image of 32x32 pixels does not fit the device",
         "needs 16384 bytes", "allows 4096 bytes per texel buffer of 16-byte texels (VITRUM_MAX_BUFFER_BYTES)"},
        "VITRUM_MAX_BUFFER_BYTES=4096");
}

}  // namespace
