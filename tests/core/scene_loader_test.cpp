// Scene loading: the course's real OBJ/MTL files, the JSON scene format and its errors.
#include "scene/scene_loader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <glm/glm.hpp>
#include <initializer_list>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <stb/stb_image_write.h>

#include "analysis/scene_features.h"
#include "common/error.h"
#include "image/srgb.h"
#include "scene/json_lines.h"
#include "scene/mtl_material.h"
#include "scene/mtl_parser.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

fs::path course(const std::string& relative) { return fs::path(VITRUM_SHARED_DIR) / "scenes/course" / relative; }

// A fresh directory per test, so that file names (and with them warning texts) are new.
fs::path tempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    fs::path dir =
        fs::temp_directory_path() / "vitrum_scene_test" / (std::string(info->test_suite_name()) + "." + info->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

fs::path write(const fs::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
    return file;
}

// Runs `load` and expects an InputError whose message contains every one of `parts`.
void expectInputError(const std::function<void()>& load, std::initializer_list<std::string> parts) {
    try {
        load();
        ADD_FAILURE() << "no InputError thrown";
    } catch (const InputError& e) {
        for (const std::string& part : parts)
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
}

const Material& materialNamed(const Scene& scene, const std::string& name) {
    for (const Material& m : scene.materials)
        if (m.name == name) return m;
    throw std::runtime_error("no material " + name);
}

void expectVec3Near(glm::vec3 a, glm::vec3 b, float tolerance = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

const std::string kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

// ---------------------------------------------------------------------------------------- OBJ

// The field of view's range as messages state it names the two numbers validFovY tests.
TEST(SceneCamera, TheFieldOfViewsRangeTextNamesItsBounds) {
    char bounds[64];
    std::snprintf(bounds, sizeof bounds, "between %g and %g degrees", kMinFovY, kMaxFovY);
    EXPECT_EQ(std::string(kFovYRange).rfind(bounds, 0), 0u) << kFovYRange;
    EXPECT_FALSE(validFovY(kMinFovY));
    EXPECT_TRUE(validFovY(std::nextafter(kMinFovY, 1.0)));
    EXPECT_FALSE(validFovY(kMaxFovY));
}

TEST(SceneObj, CourseTriangleAndObjectCounts) {
    struct Case {
        const char* file;
        std::size_t triangles, objects;
    };
    for (const Case& c :
         {Case{"geosphere/geosphere.obj", 1280, 1}, Case{"cornell_box2/cornell_box2.obj", 2906, 7},
          Case{"geospheres_5x5/geospheres_5x5.obj", 32000, 25}, Case{"box_sphere/box_sphere.obj", 734, 3}}) {
        Scene scene = loadScene(course(c.file));
        EXPECT_EQ(scene.triangles.size(), c.triangles) << c.file;
        EXPECT_EQ(scene.objectNames.size(), c.objects) << c.file;
        for (const Triangle& t : scene.triangles) {
            ASSERT_LT(t.material, scene.materials.size());
            ASSERT_LT(t.object, scene.objectNames.size());
            for (int i = 0; i < 3; ++i) {
                ASSERT_NEAR(glm::length(t.normal[i]), 1.0f, 1e-4f);
                ASSERT_TRUE(std::isfinite(t.position[i].x + t.position[i].y + t.position[i].z));
            }
        }
    }
    Scene geosphere = loadScene(course("geosphere/geosphere.obj"));
    EXPECT_EQ(geosphere.objectNames[0], "geosphere.obj/GeoSphere001");
    EXPECT_EQ(geosphere.source, course("geosphere/geosphere.obj"));
}

TEST(SceneObj, NormalsUvsAndPolygons) {
    fs::path dir = tempDir();
    fs::path obj = write(dir / "quad.obj",
                         "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\n"
                         "vn 0 0 2\nvn 0 0 0\nvt 0.25 0.75\n"
                         "o quad\nf 1/1/1 2//2 3 4\n"  // a quad: normals on two corners only, one of them zero
                         "o tri\nf 1 3 2\n");
    Scene scene = loadScene(obj);
    ASSERT_EQ(scene.triangles.size(), 3u);
    ASSERT_EQ(scene.objectNames.size(), 2u);
    EXPECT_EQ(scene.objectNames[0], "quad.obj/quad");
    const Triangle& a = scene.triangles[0];
    expectVec3Near(a.normal[0], {0, 0, 1});  // normalised
    expectVec3Near(a.normal[1], {0, 0, 1});  // zero vn -> geometric
    expectVec3Near(a.normal[2], {0, 0, 1});  // none -> geometric
    EXPECT_EQ(a.uv[0], glm::vec2(0.25f, 0.75f));
    EXPECT_EQ(a.uv[1], glm::vec2(0.0f));
    expectVec3Near(scene.triangles[1].position[2], {0, 2, 0});
    EXPECT_EQ(scene.triangles[2].object, 1u);
    expectVec3Near(scene.triangles[2].normal[0], {0, 0, -1});  // wound the other way
    EXPECT_EQ(scene.materials[a.material].name, "default");
    EXPECT_EQ(scene.materials[a.material].model, MaterialModel::Lambert);
}

// A UTF-8 byte order mark made tinyobjloader read the first line as an unknown statement: the
// vertex was lost and the face used the next three, without an error. It is dropped now (in MTL
// files too, where it lost the first material), and UTF-16 text is refused.
TEST(SceneObj, AByteOrderMarkLosesNoVertexAndUtf16IsRefused) {
    const fs::path dir = tempDir();
    write(dir / "m.mtl", "\xEF\xBB\xBFnewmtl red\nshader 2\nKd 1 0 0\n");
    const Scene scene = loadScene(write(dir / "bom.obj", "\xEF\xBB\xBFv 0 0 5\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                         "mtllib m.mtl\nusemtl red\nf 1 2 3\n"));
    ASSERT_EQ(scene.triangles.size(), 1u);
    EXPECT_EQ(scene.triangles[0].position[0], glm::vec3(0, 0, 5));
    EXPECT_EQ(scene.triangles[0].position[1], glm::vec3(0, 0, 0));
    EXPECT_EQ(scene.materials.at(scene.triangles[0].material).name, "red");
    try {
        loadScene(write(dir / "wide.obj", std::string("\xFF\xFEv\0 \0" "1\0", 7)));
        ADD_FAILURE() << "UTF-16 text was read";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("wide.obj: cannot read the OBJ file: it is UTF-16 or UTF-32 text"),
                  std::string::npos)
            << e.what();
    }
}

// Lines that tinyobjloader read differently from what they say, without an error: a lone "\r"
// ends a line for it (and now for the MTL reader, which read such a file as one line), a NUL
// byte ended a face early (a quad became a triangle), "1.5" was vertex 1, and a normal or texture
// coordinate that is no number was 0.
TEST(SceneObj, TextTheObjReaderReadDifferentlyIsReadAsWrittenOrRefused) {
    fs::path dir = tempDir();
    write(dir / "mac.mtl", "newmtl a\rshader 2\rKd 0.25 0.5 1\r");
    fs::path mac = write(dir / "mac.obj", "mtllib mac.mtl\rusemtl a\rv 0 0 0\rv 1 0 0\rv 1 1 0\r\nv 0 1 0\rf 1 2 3 4\r");
    const Scene scene = loadScene(mac);
    EXPECT_EQ(scene.triangles.size(), 2u);
    ASSERT_EQ(scene.materials.size(), 1u);
    expectVec3Near(scene.materials[0].diffuse, glm::vec3(srgbToLinear(0.25f), srgbToLinear(0.5f), 1.0f), 1e-7f);

    const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
    fs::path obj = write(dir / "nul.obj", quad + "f 1 2 3" + std::string(1, '\0') + " 4\n");
    expectInputError([&] { loadScene(obj); }, {"nul.obj:5:", "a NUL byte"});
    write(dir / "nul.mtl", "newmtl a\nKd 1 1 1" + std::string(1, '\0') + "\n");
    obj = write(dir / "nul_mtl.obj", "mtllib nul.mtl\nusemtl a\n" + quad + "f 1 2 3\n");
    expectInputError([&] { loadScene(obj); }, {"nul.mtl:2:", "a NUL byte"});
    for (const char* face : {"f 1.5 2 3", "f 1 2 3x", "f 1/1.0 2 3", "f 1 2\v4 3", "f 1 2 3 # the face"}) {
        obj = write(dir / "corner.obj", quad + "vt 0 0\n" + face + "\n");
        expectInputError([&] { loadScene(obj); }, {"corner.obj:6:", "face corner", "in integers"});
    }
    for (const char* line : {"vn 0 0 x", "vn 0 0", "vt u", "vt", "vn 0 0 1e99"}) {
        obj = write(dir / "number.obj", quad + line + "\nf 1 2 3\n");
        expectInputError([&] { loadScene(obj); }, {"number.obj:5:", std::string(line).substr(0, 2) + " expects"});
    }
    // What OBJ allows stays read: vt with one to three numbers, a comment after them, + signs.
    obj = write(dir / "fine.obj", quad + "vt 0.5\nvt 0.5 0.5 0 # w\nvn +0 0 1\nf 1/1/1 2/2/1 +3/+1/+1\n");
    EXPECT_EQ(loadScene(obj).triangles.size(), 1u);
}

// A big model reports its parsing (a call a megabyte of text) and its triangles (a call every
// 65,536 faces) as two phases, each from 0 and never backwards.
TEST(SceneObj, ParsingAndTrianglesReportTheirProgressInPhases) {
    fs::path dir = tempDir();
    std::string obj;
    constexpr int kSide = 300;  // 90,000 vertices, 178,802 triangles, about 3.4 MB
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x) obj += "v " + std::to_string(x) + " " + std::to_string(y) + " 0\n";
    for (int y = 0; y + 1 < kSide; ++y)
        for (int x = 0; x + 1 < kSide; ++x) {
            const int a = y * kSide + x + 1, b = a + 1, c = a + kSide, d = c + 1;
            obj += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(d) + "\nf " +
                   std::to_string(a) + " " + std::to_string(d) + " " + std::to_string(c) + "\n";
        }
    write(dir / "grid.obj", obj);
    std::vector<std::pair<std::string, double>> calls;
    SceneLoadOptions options;
    options.progress = [&](const std::string& phase, double fraction) { calls.emplace_back(phase, fraction); };
    const Scene scene = loadScene(dir / "grid.obj", options);
    ASSERT_EQ(scene.triangles.size(), 2u * (kSide - 1) * (kSide - 1));
    std::map<std::string, std::vector<double>> byPhase;
    std::vector<std::string> order;
    for (const auto& [phase, fraction] : calls) {
        if (order.empty() || order.back() != phase) order.push_back(phase);
        byPhase[phase].push_back(fraction);
    }
    EXPECT_EQ(order, (std::vector<std::string>{"parsing grid.obj", "triangles of grid.obj"}));
    EXPECT_EQ(byPhase["parsing grid.obj"].size(), (obj.size() + (1u << 20) - 1) >> 20);  // a call a chunk
    // Every 65,536 faces of the calling thread's share of them (all of them on one core).
    EXPECT_GE(byPhase["triangles of grid.obj"].size(), 2u);
    for (const auto& [phase, fractions] : byPhase) {
        EXPECT_EQ(fractions.front(), 0.0) << phase;
        EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end())) << phase;
        EXPECT_LT(fractions.back(), 1.0) << phase;
    }
}

TEST(SceneObj, ZeroAreaTriangleIsKeptWithAUnitNormal) {
    fs::path obj = write(tempDir() / "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    Scene scene = loadScene(obj);
    ASSERT_EQ(scene.triangles.size(), 1u);
    EXPECT_NEAR(glm::length(scene.triangles[0].normal[0]), 1.0f, 1e-6f);
}

// A coordinate below float's smallest is 0, as tinyobjloader reads it: not an error (it was
// refused as "not a finite number").
TEST(SceneObj, CoordinatesTooSmallForAFloatAreZero) {
    fs::path dir = tempDir();
    // Beyond long double's range too (it was "not a finite number"), by the digits' places.
    for (const char* tiny : {"1e-50", "-1e-50", "1e-400", "1e-999999999", "-0.0001e-99999", "12345e-99999",
                             "1e-99999999999999999999"}) {
        fs::path obj = write(dir / "tiny.obj", std::string("v ") + tiny + " 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n");
        const Scene scene = loadScene(obj);
        ASSERT_EQ(scene.triangles.size(), 1u) << tiny;
        EXPECT_EQ(scene.triangles[0].position[0], glm::vec3(0.0f)) << tiny;
    }
    // The same in an MTL (it was "Kd expects three numbers").
    write(dir / "tiny.mtl", "newmtl a\nshader 2\nKd 1e-50 0.5 0.5\n");
    fs::path obj = write(dir / "tiny_mtl.obj", "mtllib tiny.mtl\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n");
    const Scene scene = loadScene(obj);
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].diffuse.x, 0.0f);
    EXPECT_GT(scene.materials[0].diffuse.y, 0.0f);
}

TEST(SceneObj, NonFiniteCoordinatesAreErrorsWithLine) {
    fs::path dir = tempDir();
    for (const char* bad : {"nan", "inf", "-inf", "1e39", "1e999999999", "0.0001e99999"}) {
        fs::path obj = write(dir / "bad.obj", std::string("# comment\nv 0 0 0\nv 1 ") + bad + " 0\nv 0 1 0\nf 1 2 3\n");
        expectInputError([&] { loadScene(obj); }, {"bad.obj:3:", "not a finite number"});
    }
    fs::path obj = write(dir / "words.obj", "v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n");
    expectInputError([&] { loadScene(obj); }, {"words.obj:2:", "v expects three numbers"});
}

// A big OBJ is scanned in parts, one a core (issue 52): an error far into it is named by its own
// line, the first of two errors is the one reported, and statements after the split still count.
TEST(SceneObj, ABigFileScannedInPartsNamesTheLineOfItsFirstError) {
    fs::path dir = tempDir();
    std::string text = "mtllib big.mtl\n";
    const int vertexLines = 2'000'000;  // about 40 MB: two parts or more wherever there are two cores
    for (int i = 0; i < vertexLines; ++i) text += "v " + std::to_string(i % 1000) + ".25 1.5 " + std::to_string(i / 1000) + "\n";
    const std::string faces = "f 1 2 1001\nusemtl glass\nf 2 1002 1001\n";
    write(dir / "big.mtl", "newmtl glass\nillum 7\nNi 1.5\n");
    const Scene scene = loadScene(write(dir / "big.obj", text + faces));
    ASSERT_EQ(scene.triangles.size(), 2u);
    EXPECT_NE(scene.materials[scene.triangles[1].material].model, scene.materials[scene.triangles[0].material].model);
    EXPECT_EQ(scene.materials[scene.triangles[1].material].model, MaterialModel::Glass);

    std::string bad = text;
    const std::size_t at = bad.find("\nv ", bad.size() - 200) + 1;
    const int badLine = int(std::count(bad.begin(), bad.begin() + std::ptrdiff_t(at), '\n')) + 1;
    ASSERT_GT(badLine, vertexLines / 2);  // in the file's last part
    bad.insert(at, "v 1 nan 0\n");
    expectInputError([&] { loadScene(write(dir / "late.obj", bad + faces)); },
                     {"late.obj:" + std::to_string(badLine) + ":", "not a finite number"});
    bad.insert(bad.find('\n') + 1, "v 1 2 x\n");  // line 2: the first error
    expectInputError([&] { loadScene(write(dir / "two.obj", bad + faces)); }, {"two.obj:2:", "v expects three numbers"});
}

// The faces become triangles on every core, each in its place: the same triangles as in the file's
// order, and of two faces with indices out of range the first in the file is the one named.
TEST(SceneObj, FacesMadeOnEveryCoreKeepTheirOrderAndTheFirstError) {
    fs::path dir = tempDir();
    std::string text;
    constexpr int kSide = 301;  // 180,000 triangles: a share for each of several threads
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x) text += "v " + std::to_string(x) + " " + std::to_string(y) + " 0\n";
    std::string faces;
    for (int y = 0; y + 1 < kSide; ++y)
        for (int x = 0; x + 1 < kSide; ++x) {
            const int a = y * kSide + x + 1, b = a + 1, c = a + kSide, d = c + 1;
            faces += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(d) + " " +
                     std::to_string(c) + "\n";  // a quad: two triangles of its fan
        }
    const Scene scene = loadScene(write(dir / "quads.obj", text + faces));
    ASSERT_EQ(scene.triangles.size(), 2u * (kSide - 1) * (kSide - 1));
    for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
        const std::size_t quad = i / 2;
        const glm::vec3 corner(float(quad % (kSide - 1)), float(quad / (kSide - 1)), 0.0f);
        ASSERT_EQ(scene.triangles[i].position[0], corner) << "triangle " << i;
    }
    // A bad index in the last face and another in the middle one: the middle one is named.
    std::string bad = faces;
    bad.replace(bad.rfind("f "), 2, "f 999999 ");
    const std::size_t middle = bad.find("\nf ", bad.size() / 2) + 1;
    bad.replace(middle, 2, "f 888888 ");
    expectInputError([&] { loadScene(write(dir / "bad.obj", text + bad)); }, {"uses index 888888"});
}

// Skin weights ("vw", tinyobjloader's extension) are ignored with one warning: tinyobjloader
// converts their joint numbers to int unchecked, undefined beyond the int range (found by fuzzing).
TEST(SceneObj, SkinWeightLinesAreIgnoredWithAWarning) {
    fs::path dir = tempDir();
    write(dir / "w.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvw 0 99999999999 0.5 1 0.5\n  vw 1 0 1\nf 1 2 3\n");
    const int before = warningCount();
    Scene scene = loadScene(dir / "w.obj");
    EXPECT_EQ(warningCount(), before + 1);
    ASSERT_EQ(scene.triangles.size(), 1u);
    EXPECT_EQ(scene.triangles[0].position[1], glm::vec3(1, 0, 0));
}

TEST(SceneObj, MissingEmptyAndGarbageFiles) {
    fs::path dir = tempDir();
    expectInputError([&] { loadScene(dir / "missing.obj"); }, {"missing.obj", "cannot open"});
    fs::path empty = write(dir / "empty.obj", "");
    expectInputError([&] { loadScene(empty); }, {"empty.obj", "contains no triangles"});
    fs::path verticesOnly = write(dir / "points.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n");
    expectInputError([&] { loadScene(verticesOnly); }, {"points.obj", "contains no triangles"});
    std::mt19937 random(12345);
    for (int round = 0; round < 20; ++round) {
        std::string bytes(4096, '\0');
        for (char& b : bytes) b = char(random() & 0xff);
        if (round % 2) {  // make sure the parser meets face and vertex statements among the garbage
            for (std::size_t i = 0; i + 8 < bytes.size(); i += 97)
                bytes.replace(i, 3, round % 4 == 1 ? "\nf " : "\nv ");
        }
        fs::path garbage = write(dir / "garbage.obj", bytes);
        expectInputError([&] { loadScene(garbage); }, {"garbage.obj"});
    }
}

TEST(SceneObj, OutOfRangeIndicesAreErrors) {
    fs::path dir = tempDir();
    const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (const char* face :
         {"f 1 2 9", "f 1 2 -9", "f 0 1 2", "f 1 2 3 70000", "f 1 2 3 4 5 -100", "f 1//4 2 3", "f 1/9 2 3"}) {
        fs::path obj = write(dir / "index.obj", vertices + face + "\n");
        expectInputError([&] { loadScene(obj); }, {"index.obj"});
    }
}

// ---------------------------------------------------------------------------------------- MTL

TEST(SceneMtl, CornellBoxMaterialMapping) {
    Scene scene = loadScene(course("cornell_box2/cornell_box2.obj"));
    EXPECT_EQ(materialNamed(scene, "white_lambert").model, MaterialModel::Lambert);  // shader 5
    const Material& glass = materialNamed(scene, "clear_glass");                     // "clear_glass\t"
    EXPECT_EQ(glass.model, MaterialModel::Glass);
    EXPECT_FLOAT_EQ(glass.ior, 1.5f);
    EXPECT_EQ(glass.attenuation, glm::vec3(0.0f));                               // no Tf: clear
    EXPECT_EQ(materialNamed(scene, "mirror").model, MaterialModel::Phong);       // shader 3
    EXPECT_EQ(materialNamed(scene, "white_phong").model, MaterialModel::Phong);  // shader 7, illum 2
    EXPECT_FLOAT_EQ(materialNamed(scene, "white_phong").ior, 1.46f);
    const Material& red = materialNamed(scene, "red_lambert");
    expectVec3Near(red.diffuse, {srgbToLinear(0.95f), srgbToLinear(0.05f), srgbToLinear(0.05f)}, 1e-7f);
    expectVec3Near(red.ambient, glm::vec3(srgbToLinear(0.1f)), 1e-7f);
    EXPECT_EQ(red.attenuation, glm::vec3(1.0f));  // Tf 1 1 1 is kept as written (matters only for glass)
    EXPECT_FLOAT_EQ(red.shininess, 32.0f);
    // Each object has one material: the glass sphere's triangles are glass.
    for (const Triangle& t : scene.triangles) {
        if (scene.materials[t.material].name == "clear_glass") {
            EXPECT_NE(scene.objectNames[t.object].find("/Sphere"), std::string::npos);
        }
    }
}

TEST(SceneMtl, GeosphereShader7FallsBackToIllumWithAWarning) {
    fs::path dir = tempDir();
    fs::copy(course("geosphere/geosphere.obj"), dir / "geosphere.obj");
    fs::copy(course("geosphere/geosphere.mtl"), dir / "geosphere.mtl");
    int before = warningCount();
    Scene scene = loadScene(dir / "geosphere.obj");
    EXPECT_EQ(warningCount(), before + 1);
    const Material& m = materialNamed(scene, "wire_214229166");
    EXPECT_EQ(m.model, MaterialModel::Phong);
    EXPECT_NEAR(m.diffuse.x, srgbToLinear(0.83921576f), 1e-7f);
    expectVec3Near(m.attenuation, {1.0f, 0.1f, 1.0f}, 0.0f);  // Tf is not decoded
}

TEST(SceneMtl, ModelTable) {
    EXPECT_EQ(materialModelFor(1, std::nullopt), MaterialModel::Normal);
    EXPECT_EQ(materialModelFor(2, 4), MaterialModel::Lambert);
    EXPECT_EQ(materialModelFor(3, 4), MaterialModel::Phong);
    EXPECT_EQ(materialModelFor(4, 2), MaterialModel::Glass);
    EXPECT_EQ(materialModelFor(5, 7), MaterialModel::Lambert);
    EXPECT_EQ(materialModelFor(6, 2), MaterialModel::Mirror);
    bool substituted = false;
    for (std::optional<int> shader :
         {std::optional<int>(7), std::optional<int>(8), std::optional<int>(0), std::optional<int>()}) {
        EXPECT_EQ(materialModelFor(shader, 4, &substituted), MaterialModel::Glass);
        EXPECT_TRUE(substituted);
        EXPECT_EQ(materialModelFor(shader, 6), MaterialModel::Glass);
        EXPECT_EQ(materialModelFor(shader, 7), MaterialModel::Glass);
        EXPECT_EQ(materialModelFor(shader, 3), MaterialModel::Mirror);
        EXPECT_EQ(materialModelFor(shader, 5), MaterialModel::Mirror);
        EXPECT_EQ(materialModelFor(shader, 2), MaterialModel::Phong);
        EXPECT_EQ(materialModelFor(shader, std::nullopt), MaterialModel::Phong);
    }
    materialModelFor(4, std::nullopt, &substituted);
    EXPECT_FALSE(substituted);
}

TEST(SceneMtl, SrgbDecodingDefaultsAndLinearTf) {
    fs::path dir = tempDir();
    write(dir / "m.mtl",
          "newmtl half\nKd 0.5 0.5 0.5\nKs 0.5\nTf 0.5 1 2\nshader 4\n"
          "newmtl bare\nshader 2\n");
    write(dir / "m.obj",
          "mtllib m.mtl\n" + kTriangleObj.substr(0, 24) + "usemtl half\nf 1 2 3\nusemtl bare\nf 1 3 2\n");
    Scene scene = loadScene(dir / "m.obj");
    const Material& half = materialNamed(scene, "half");
    expectVec3Near(half.diffuse, glm::vec3(0.21404114f), 1e-7f);
    expectVec3Near(half.specular, glm::vec3(0.21404114f), 1e-7f);  // one value: a grey
    expectVec3Near(half.attenuation, {0.5f, 1.0f, 2.0f}, 0.0f);
    const Material& bare = materialNamed(scene, "bare");
    const Material defaults;
    EXPECT_EQ(bare.diffuse, defaults.diffuse);
    EXPECT_EQ(bare.ambient, glm::vec3(0.0f));
    EXPECT_EQ(bare.specular, glm::vec3(0.0f));
    EXPECT_EQ(bare.shininess, 1.0f);
    EXPECT_EQ(bare.ior, 1.5f);
    EXPECT_EQ(bare.attenuation, glm::vec3(0.0f));
    EXPECT_EQ(scene.materials[scene.triangles[0].material].name, "half");
    EXPECT_EQ(scene.materials[scene.triangles[1].material].name, "bare");
}

// Negative coefficients would make negative radiance: each is clamped to 0 with a warning; an
// IOR must be positive, so Ni 0 (which some exporters write for opaque materials) and below warn
// and keep the default 1.5. Values that are fine stay as they are, without a warning.
TEST(SceneMtl, NegativeCoefficientsClampAndNonPositiveNiFallsBackWithWarnings) {
    fs::path dir = tempDir();
    write(dir / "m.mtl",
          "newmtl bad\nshader 4\nKa -0.1 0.5 0.5\nKd 0.5 -1 0.5\nKs -2\nNs -5\nTf 1 -0.5 2\nNi 0\n"
          "newmtl worse\nshader 4\nNi -1.2\n"
          "newmtl good\nshader 4\nKd 0.5 0.5 0.5\nNs 20\nTf 0.25 0 1\nNi 1.33\n");
    write(dir / "m.obj", "mtllib m.mtl\n" + kTriangleObj.substr(0, 24) +
                             "usemtl bad\nf 1 2 3\nusemtl worse\nf 1 3 2\nusemtl good\nf 2 1 3\n");
    const int before = warningCount();
    Scene scene = loadScene(dir / "m.obj");
    EXPECT_EQ(warningCount(), before + 7);  // Ka, Kd, Ks, Ns, Tf and Ni of "bad", Ni of "worse"
    const float half = srgbToLinear(0.5f);
    const Material& bad = materialNamed(scene, "bad");
    expectVec3Near(bad.ambient, {0.0f, half, half}, 1e-7f);
    expectVec3Near(bad.diffuse, {half, 0.0f, half}, 1e-7f);
    EXPECT_EQ(bad.specular, glm::vec3(0.0f));
    EXPECT_EQ(bad.shininess, 0.0f);
    EXPECT_EQ(bad.attenuation, glm::vec3(1.0f, 0.0f, 2.0f));
    EXPECT_EQ(bad.ior, 1.5f);
    EXPECT_EQ(materialNamed(scene, "worse").ior, 1.5f);
    const Material& good = materialNamed(scene, "good");
    expectVec3Near(good.diffuse, glm::vec3(half), 1e-7f);
    EXPECT_EQ(good.shininess, 20.0f);
    EXPECT_EQ(good.attenuation, glm::vec3(0.25f, 0.0f, 1.0f));
    EXPECT_EQ(good.ior, 1.33f);
}

// `priority N` (render-model-decisions.md, "Overlapping media by priority"): 0 where it is absent.
TEST(SceneMtl, PriorityIsAnInteger) {
    fs::path dir = tempDir();
    write(dir / "p.mtl", "newmtl glass\nshader 4\nNi 1.5\npriority 3\nnewmtl water\nshader 4\nNi 1.33\n"
                         "newmtl under\nshader 4\npriority -2\n");
    write(dir / "p.obj", "mtllib p.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl glass\nf 1 2 3\nusemtl water\nf 1 3 2\n"
                         "usemtl under\nf 1 2 3\n");
    const Scene scene = loadScene(dir / "p.obj");
    EXPECT_EQ(materialNamed(scene, "glass").priority, 3);
    EXPECT_EQ(materialNamed(scene, "water").priority, 0);
    EXPECT_EQ(materialNamed(scene, "under").priority, -2);
}

// `thin_walled 1` makes a glass thin glass (render-model-decisions.md, "Thin-walled glass"): its
// Kd, sRGB as every Kd, tints what it transmits, white without a Kd line; Tf, priority and Vd,
// which only a medium has, are dropped with one warning. On another model it is ignored with a
// warning; anything but 0 or 1 is an error naming the line.
TEST(SceneMtl, ThinWalledMakesAGlassThinGlass) {
    fs::path dir = tempDir();
    write(dir / "t.mtl",
          "newmtl pane\nshader 4\nNi 1.52\nthin_walled 1\n"
          "newmtl green\nshader 4\nKd 0.5 1 0.5\nthin_walled 1\n"
          "newmtl medium\nshader 4\nTf 1 0 0\npriority 2\nVd 30\nthin_walled 1\n"
          "newmtl solid\nshader 4\nthin_walled 0\n"
          "newmtl plastic\nshader 3\nthin_walled 1\n");
    write(dir / "t.obj",
          "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl pane\nf 1 2 3\nusemtl green\nf 1 2 3\n"
          "usemtl medium\nf 1 2 3\nusemtl solid\nf 1 2 3\nusemtl plastic\nf 1 2 3\n");
    const int before = warningCount();
    const Scene scene = loadScene(dir / "t.obj");
    EXPECT_EQ(warningCount(), before + 2);  // medium's Tf, priority and Vd; plastic's thin_walled
    const Material& pane = materialNamed(scene, "pane");
    EXPECT_EQ(pane.model, MaterialModel::ThinGlass);
    EXPECT_EQ(pane.ior, 1.52f);
    EXPECT_EQ(pane.diffuse, glm::vec3(1.0f));
    EXPECT_EQ(materialNamed(scene, "green").diffuse, glm::vec3(srgbToLinear(0.5f), 1.0f, srgbToLinear(0.5f)));
    const Material& medium = materialNamed(scene, "medium");
    EXPECT_EQ(medium.model, MaterialModel::ThinGlass);
    EXPECT_EQ(medium.attenuation, glm::vec3(0.0f));
    EXPECT_EQ(medium.priority, 0);
    EXPECT_EQ(medium.abbe, 0.0f);
    EXPECT_EQ(materialNamed(scene, "solid").model, MaterialModel::Glass);
    EXPECT_EQ(materialNamed(scene, "plastic").model, MaterialModel::Phong);
    write(dir / "bad.mtl", "newmtl pane\nshader 4\nthin_walled 2\n");
    try {
        parseMtlFile(dir / "bad.mtl");
        ADD_FAILURE() << "thin_walled 2 was read";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("bad.mtl:3: thin_walled expects 0 or 1"), std::string::npos) << e.what();
    }
}

// `tint r g b` (render-model-decisions.md, "Glass tint"): a glass's surface tint, sRGB as Kd,
// white without it; outside [0, 1] it is kept within, with a warning. On another model it is
// ignored with a warning, and a thin glass, tinted by Kd, drops it with its medium's keys.
TEST(SceneMtl, TintTintsAGlassSurface) {
    fs::path dir = tempDir();
    write(dir / "t.mtl",
          "newmtl sapphire\nshader 4\nNi 1.77\ntint 0.5 0.75 1\n"
          "newmtl clear\nshader 4\n"
          "newmtl grey\nshader 4\ntint 0.5\n"
          "newmtl beyond\nshader 4\ntint 1.5 -1 0.5\n"
          "newmtl pane\nshader 4\ntint 0.5 0.5 0.5\nthin_walled 1\n"
          "newmtl plastic\nshader 3\ntint 0.5 0.5 0.5\n");
    write(dir / "t.obj", "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl sapphire\nf 1 2 3\nusemtl clear\nf 1 2 3\n"
                         "usemtl grey\nf 1 2 3\nusemtl beyond\nf 1 2 3\nusemtl pane\nf 1 2 3\nusemtl plastic\nf 1 2 3\n");
    const int before = warningCount();
    const Scene scene = loadScene(dir / "t.obj");
    EXPECT_EQ(warningCount(), before + 3);  // beyond's range, pane's tint, plastic's tint
    const float half = srgbToLinear(0.5f);
    EXPECT_EQ(materialNamed(scene, "sapphire").tint, glm::vec3(half, srgbToLinear(0.75f), 1.0f));
    EXPECT_EQ(materialNamed(scene, "clear").tint, glm::vec3(1.0f));
    EXPECT_EQ(materialNamed(scene, "grey").tint, glm::vec3(half));
    EXPECT_EQ(materialNamed(scene, "beyond").tint, glm::vec3(1.0f, 0.0f, half));
    EXPECT_EQ(materialNamed(scene, "pane").model, MaterialModel::ThinGlass);
    EXPECT_EQ(materialNamed(scene, "pane").tint, glm::vec3(1.0f));
    EXPECT_EQ(materialNamed(scene, "plastic").tint, glm::vec3(1.0f));
    EXPECT_TRUE(analyseScene(scene).glassTints);
}

// `map_d file` (render-model-decisions.md, "Cut-out surfaces"): the surface is cut where the
// mask is below 1/2, its alpha where the image has an alpha channel, else its grey level as the
// file stores it (not sRGB-decoded); Material::cutout holds twice it. Options come before the
// file, as map_Kd's; a glass volume's map_d and an unreadable file are ignored with a warning.
TEST(SceneMtl, MapDCutsTheSurfaceWhereTheMaskIsBelowOneHalf) {
    fs::path dir = tempDir();
    const std::uint8_t grey[4] = {0, 100, 128, 255}, rgba[8] = {9, 9, 9, 200, 9, 9, 9, 60};
    ASSERT_NE(stbi_write_png((dir / "grey.png").string().c_str(), 4, 1, 1, grey, 4), 0);
    ASSERT_NE(stbi_write_png((dir / "rgba.png").string().c_str(), 2, 1, 4, rgba, 8), 0);
    write(dir / "t.mtl",
          "newmtl leaf\nshader 3\nmap_d grey.png\n"
          "newmtl fence\nshader 2\nmap_d -imfchan m rgba.png\n"
          "newmtl pane\nshader 4\nthin_walled 1\nmap_d grey.png\n"
          "newmtl volume\nshader 4\nmap_d grey.png\n"
          "newmtl lost\nshader 3\nmap_d missing.png\n");
    write(dir / "t.obj",
          "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl leaf\nf 1 2 3\nusemtl fence\nf 1 2 3\n"
          "usemtl pane\nf 1 2 3\nusemtl volume\nf 1 2 3\nusemtl lost\nf 1 2 3\n");
    const int before = warningCount();
    const Scene scene = loadScene(dir / "t.obj");
    EXPECT_EQ(warningCount(), before + 2);  // the volume's map_d, the missing file
    auto values = [&](const std::string& name) {
        std::vector<float> v;
        const int cutout = materialNamed(scene, name).cutout;
        if (cutout >= 0)
            for (const glm::vec3& texel : scene.textures[std::size_t(cutout)].texels) v.push_back(texel.x);
        return v;
    };
    const std::vector<float> leaf = values("leaf");
    ASSERT_EQ(leaf.size(), 4u);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(leaf[std::size_t(i)], 2.0 * grey[i] / 255.0, 1e-6) << i;
    EXPECT_LT(leaf[1], 1.0f);  // 100 / 255 < 1/2: cut
    EXPECT_GE(leaf[2], 1.0f);  // 128 / 255 > 1/2: kept
    EXPECT_EQ(values("fence"), (std::vector<float>{2.0f * (200 / 255.0f), 2.0f * (60 / 255.0f)}));
    EXPECT_EQ(materialNamed(scene, "pane").model, MaterialModel::ThinGlass);
    EXPECT_EQ(values("pane"), leaf) << "one mask for the file";
    EXPECT_EQ(materialNamed(scene, "volume").cutout, -1);
    EXPECT_EQ(materialNamed(scene, "lost").cutout, -1);
    EXPECT_TRUE(analyseScene(scene).cutouts);
}

// vitrum's MTL keys for partial coverage (render-model-decisions.md, "Partial coverage"):
// `coverage a`, a share of the surface there everywhere (one texel), and `map_coverage`, a grey
// map read as map_d's is but not doubled (its alpha where it has one, else its grey level as
// stored). Only Lambert, Phong and mirror surfaces are partly there; a value outside [0, 1] is
// kept within it; the map wins beside the scalar; each with a warning.
TEST(SceneMtl, CoverageAndMapCoverageMakeASurfacePartlyThere) {
    fs::path dir = tempDir();
    const std::uint8_t grey[4] = {0, 100, 128, 255}, rgba[8] = {9, 9, 9, 200, 9, 9, 9, 60};
    ASSERT_NE(stbi_write_png((dir / "grey.png").string().c_str(), 4, 1, 1, grey, 4), 0);
    ASSERT_NE(stbi_write_png((dir / "rgba.png").string().c_str(), 2, 1, 4, rgba, 8), 0);
    write(dir / "t.mtl",
          "newmtl gauze\nshader 2\ncoverage 0.25\n"
          "newmtl lace\nshader 3\nmap_coverage grey.png\n"
          "newmtl smoke\nshader 6\nmap_coverage -imfchan m rgba.png\ncoverage 0.5\n"
          "newmtl whole\nshader 3\ncoverage 1\n"
          "newmtl beyond\nshader 2\ncoverage 1.5\n"
          "newmtl glass\nshader 4\ncoverage 0.5\n");
    write(dir / "t.obj",
          "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl gauze\nf 1 2 3\nusemtl lace\nf 1 2 3\n"
          "usemtl smoke\nf 1 2 3\nusemtl whole\nf 1 2 3\nusemtl beyond\nf 1 2 3\nusemtl glass\nf 1 2 3\n");
    const int before = warningCount();
    const Scene scene = loadScene(dir / "t.obj");
    EXPECT_EQ(warningCount(), before + 3);  // smoke's scalar beside its map, beyond's 1.5, the glass
    auto values = [&](const std::string& name) {
        std::vector<float> v;
        const int coverage = materialNamed(scene, name).coverage;
        if (coverage >= 0)
            for (const glm::vec3& texel : scene.textures[std::size_t(coverage)].texels) v.push_back(texel.x);
        return v;
    };
    EXPECT_EQ(values("gauze"), std::vector<float>{0.25f});
    const std::vector<float> lace = values("lace");
    ASSERT_EQ(lace.size(), 4u);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(lace[std::size_t(i)], grey[i] / 255.0, 1e-6) << i;
    EXPECT_EQ(values("smoke"), (std::vector<float>{200 / 255.0f, 60 / 255.0f})) << "the map, not the 0.5";
    EXPECT_EQ(materialNamed(scene, "whole").coverage, -1);
    EXPECT_EQ(values("beyond"), std::vector<float>{}) << "1.5 kept within [0, 1] is all there";
    EXPECT_EQ(materialNamed(scene, "glass").coverage, -1);
    EXPECT_EQ(materialNamed(scene, "lace").cutout, -1) << "no holes of its own: map_d cuts";
    EXPECT_TRUE(analyseScene(scene).partialCoverage);
}

TEST(SceneMtl, KsTypoReadsAsOneWithOneWarningPerFile) {
    for (const char* file : {"box_sphere/box_sphere.mtl", "allied_avenger_6887/6887_allied_avenger.mtl"}) {
        std::vector<MtlEntry> entries = parseMtlFile(course(file));
        ASSERT_FALSE(entries.empty());
        for (const MtlEntry& e : entries) EXPECT_EQ(e.ks, glm::vec3(1.0f)) << file << " " << e.name;
    }
    fs::path mtl = write(tempDir() / "typo.mtl", "newmtl a\nKs 1.0. 1.0 1.0\nKd 0.5. 0.5 0.5\n");
    int before = warningCount();
    std::vector<MtlEntry> entries = parseMtlFile(mtl);
    EXPECT_EQ(warningCount(), before + 1);
    EXPECT_EQ(entries[0].kd, glm::vec3(0.5f));
}

TEST(SceneMtl, MalformedNumbersAreErrorsWithLine) {
    fs::path dir = tempDir();
    for (const char* line :
         {"Kd 0.5 x 0.2", "Kd 0.5 0.5", "Kd", "Ks 1..0 1 1", "Ns nan", "Ni 1.5 2", "illum 2.5", "Tf 1 1 1 1",
          "priority 1.5", "priority"}) {
        fs::path mtl = write(dir / "bad.mtl", std::string("newmtl a\nNs 1\n") + line + "\n");
        std::string key = std::string(line).substr(0, std::string(line).find(' '));
        expectInputError([&] { parseMtlFile(mtl); }, {"bad.mtl:3:", key, "expects"});
    }
    expectInputError([&] { parseMtlFile(dir / "none.mtl"); }, {"none.mtl"});
}

TEST(SceneMtl, MissingTextureFallsBackToKdWithAWarning) {
    fs::path dir = tempDir();
    fs::copy(course("box_sphere/box_sphere.obj"), dir / "box_sphere.obj");
    fs::copy(course("box_sphere/box_sphere.mtl"), dir / "box_sphere.mtl");
    int before = warningCount();
    Scene scene = loadScene(dir / "box_sphere.obj");
    EXPECT_GT(warningCount(), before);
    const Material& chessboard = materialNamed(scene, "chessboard");
    EXPECT_EQ(chessboard.diffuseTexture, -1);
    EXPECT_EQ(chessboard.model, MaterialModel::Lambert);
    expectVec3Near(chessboard.diffuse, glm::vec3(srgbToLinear(0.95f)), 1e-7f);
    const Material& glass = materialNamed(scene, "glass");  // named glass, but shader 3
    EXPECT_EQ(glass.model, MaterialModel::Phong);
    EXPECT_EQ(glass.specular, glm::vec3(1.0f));  // "Ks 1.0. 1.0 1.0"
    EXPECT_TRUE(scene.textures.empty());
}

TEST(SceneMtl, TexturesAreLoadedOncePerFile) {
    fs::path dir = tempDir();
    fs::create_directories(dir / "tex");
    fs::copy(course("allied_avenger_6887/4150p04.jpg"), dir / "tex/4150p04.jpg");
    write(dir / "t.mtl", "newmtl a\nmap_Kd tex/4150p04.jpg\nnewmtl b\nmap_Kd -s 1 1 1 tex\\4150p04.jpg\n");
    write(dir / "t.obj",
          "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl a\nf 1/1 2/1 3/1\nusemtl b\nf 1 3 2\n");
    Scene scene = loadScene(dir / "t.obj");
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_GT(scene.textures[0].width, 0);
    EXPECT_EQ(scene.textures[0].texels.size(), std::size_t(scene.textures[0].width) * scene.textures[0].height);
    EXPECT_EQ(materialNamed(scene, "a").diffuseTexture, 0);
    EXPECT_EQ(materialNamed(scene, "b").diffuseTexture, 0);
}

// A PFM of width x height black pixels: 12 bytes a pixel, as the scene holds it.
std::string blackPfm(int width, int height) {
    return "PF\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1\n" +
           std::string(std::size_t(width) * height * 3 * sizeof(float), '\0');
}

// A PNG whose header declares width x height RGB pixels and whose image data is `dataBytes` bytes
// that do not inflate: decoding it fails, reading its header does not.
std::string pngWithUndecodableData(std::uint32_t width, std::uint32_t height, std::size_t dataBytes) {
    auto crc32 = [](const std::string& bytes) {  // PNG's CRC (ISO 3309), bit by bit
        std::uint32_t crc = 0xFFFFFFFFu;
        for (unsigned char byte : bytes) {
            crc ^= byte;
            for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
        }
        return crc ^ 0xFFFFFFFFu;
    };
    auto bigEndian = [](std::uint32_t v) {
        return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
    };
    auto chunk = [&](const std::string& type, const std::string& data) {
        return bigEndian(std::uint32_t(data.size())) + type + data + bigEndian(crc32(type + data));
    };
    const std::string header = bigEndian(width) + bigEndian(height) + std::string{8, 2, 0, 0, 0};
    return "\x89PNG\r\n\x1a\n" + chunk("IHDR", header) + chunk("IDAT", std::string(dataBytes, '\xff')) +
           chunk("IEND", "");
}

// A render passes its device's texel-buffer limit for the scene's textures (app/render_command.cpp):
// an image beyond what the images before it leave is refused by its header, before it is decoded,
// naming the MTL line or the background and the limit. An image that cannot be read still only warns.
TEST(SceneMtl, TexturesBeyondTheTexelLimitAreRefusedByTheirHeaders) {
    fs::path dir = tempDir();
    write(dir / "small.pfm", blackPfm(4, 4));  // 256 bytes as the device holds it (16 a pixel)
    write(dir / "large.pfm", blackPfm(8, 8));  // 1024 bytes
    write(dir / "t.mtl", "newmtl a\nmap_Kd small.pfm\nnewmtl b\nmap_Kd large.pfm\n");
    write(dir / "t.obj",
          "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl a\nf 1/1 2/1 3/1\nusemtl b\nf 1/1 3/1 2/1\n");
    const TexelLimit limit{1279, "the test's device allows 1279 bytes"};
    EXPECT_EQ(loadScene(dir / "t.obj", {TexelLimit{1280, "1280"}}).textures.size(), 2u);  // 256 + 1024 fit 1280
    expectInputError(
        [&] { loadScene(dir / "t.obj", {limit}); },
        {"t.mtl:4: map_Kd", "large.pfm: image of 8x8 pixels does not fit the device",
         "it needs 1024 bytes as linear RGB float texels of 16 bytes, but the test's device allows 1279 bytes",
         "the scene's images before this one take 256 bytes"});

    // 4000 x 4000 pixels declared over 4 KB of data that does not inflate.
    write(dir / "f.mtl", "newmtl a\nshader 2\nmap_Kd forged.png\n");
    write(dir / "f.obj", "mtllib f.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl a\nf 1/1 2/1 3/1\n");
    write(dir / "forged.png", pngWithUndecodableData(4000, 4000, 4096));
    const int before = warningCount();
    EXPECT_EQ(loadScene(dir / "f.obj").textures.size(), 0u);  // decoding it fails: a warning
    EXPECT_EQ(warningCount(), before + 1);
    expectInputError(
        [&] {
            loadScene(dir / "f.obj", {TexelLimit{1 << 20, "1 MiB"}});
        },
        {"f.mtl:3: map_Kd", "forged.png: image of 4000x4000 pixels does not fit the device",
         "245 MiB"});  // 4000 * 4000 * 16 bytes, rounded up

    // Environment maps count as textures: the sixth face of a cube finds five before it.
    write(dir / "s.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write(dir / "cube.json", R"({"objects": [{"obj": "s.obj"}], "background": {"cube": )"
                             R"(["small.pfm", "small.pfm", "small.pfm", "small.pfm", "small.pfm", "small.pfm"]}})");
    EXPECT_EQ(loadScene(dir / "cube.json", {TexelLimit{1536, "1536"}}).textures.size(), 6u);
    expectInputError(
        [&] {
            loadScene(dir / "cube.json", {TexelLimit{1535, "1535 bytes"}});
        },
        {"cube.json", "small.pfm: image of 4x4 pixels does not fit the device",
         "images before this one take 1280 bytes"});
    write(dir / "sphere.json", R"({"objects": [{"obj": "s.obj"}], "background": {"spherical": "forged.png"}})");
    expectInputError([&] { loadScene(dir / "sphere.json", {TexelLimit{1 << 20, "1 MiB"}}); },
                     {"sphere.json", "forged.png: image of 4000x4000 pixels does not fit the device"});
}

TEST(SceneMtl, UnknownMaterialAndMissingLibraryWarn) {
    fs::path dir = tempDir();
    write(dir / "u.mtl", "newmtl known\nKd 1 0 0\nshader 2\n");
    write(dir / "u.obj", "mtllib u.mtl\n" + kTriangleObj.substr(0, 24) + "usemtl unknown\nf 1 2 3\n");
    int before = warningCount();
    Scene scene = loadScene(dir / "u.obj");
    EXPECT_EQ(warningCount(), before + 1);
    EXPECT_EQ(scene.materials[scene.triangles[0].material].name, "default");

    write(dir / "m.obj", "mtllib nowhere.mtl\n" + kTriangleObj.substr(0, 24) + "usemtl x\nf 1 2 3\n");
    before = warningCount();
    scene = loadScene(dir / "m.obj");
    EXPECT_GE(warningCount(), before + 1);
    EXPECT_EQ(scene.materials[scene.triangles[0].material].name, "default");
}

// A file name longer than the file system allows (NAME_MAX, 255 bytes on Linux) cannot be
// opened: a texture or a library so named is reported like a missing one, never thrown as a
// file-system error (found by fuzzing, tests/fuzz/regressions/obj_mtl).
TEST(SceneMtl, NamesLongerThanTheFileSystemAllowsWarnLikeMissingFiles) {
    fs::path dir = tempDir();
    const std::string longName(300, 'x');
    write(dir / "t.mtl", "newmtl textured\nshader 2\nKd 0.5 0.5 0.5\nmap_Kd " + longName + ".png\n");
    write(dir / "t.obj", "mtllib t.mtl\n" + kTriangleObj.substr(0, 24) + "usemtl textured\nf 1 2 3\n");
    int before = warningCount();
    Scene scene = loadScene(dir / "t.obj");
    EXPECT_EQ(warningCount(), before + 1);
    EXPECT_EQ(materialNamed(scene, "textured").diffuseTexture, -1);

    write(dir / "l.obj", "mtllib " + longName + ".mtl\n" + kTriangleObj.substr(0, 24) + "usemtl x\nf 1 2 3\n");
    before = warningCount();
    scene = loadScene(dir / "l.obj");
    EXPECT_GE(warningCount(), before + 1);
    EXPECT_EQ(scene.materials[scene.triangles[0].material].name, "default");
}

// --------------------------------------------------------------------------------------- JSON

TEST(SceneJson, EveryFieldRoundTrips) {
    fs::path dir = tempDir();
    write(dir / "tri.obj", kTriangleObj);
    write(dir / "scene.json", R"({
  "camera": {"from": [1, -4, 2], "at": [0.5, 0, 0.25], "up": [0, 1, 0], "fov_y": 30.5, "width": 320, "height": 200},
  "lights": [{"position": [1, 2, 3], "colour": [0.5, 0.25, 2], "falloff": "inverse_square"},
             {"position": [-1, -2, -3]}],
  "background": {"colour": [0.1, 0.2, 0.3]},
  "air_ior": 1.33,
  "objects": [{"obj": "tri.obj"}, {"obj": ")" +
                                  (dir / "tri.obj").string() + R"("}],
  "render": {"spp": 16, "max_depth": 0, "fresnel": "schlick-exp2", "min_weight": 0.01}
})");
    Scene s = loadScene(dir / "scene.json");
    EXPECT_EQ(s.source, dir / "scene.json");
    EXPECT_EQ(s.camera.from, glm::vec3(1, -4, 2));
    EXPECT_EQ(s.camera.at, glm::vec3(0.5f, 0, 0.25f));
    EXPECT_EQ(s.camera.up, glm::vec3(0, 1, 0));
    EXPECT_FLOAT_EQ(s.camera.fovY, 30.5f);
    EXPECT_EQ(s.camera.width, 320u);
    EXPECT_EQ(s.camera.height, 200u);
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].position, glm::vec3(1, 2, 3));
    EXPECT_EQ(s.lights[0].colour, glm::vec3(0.5f, 0.25f, 2));
    EXPECT_TRUE(s.lights[0].inverseSquare);
    EXPECT_EQ(s.lights[1].colour, glm::vec3(1.0f));
    EXPECT_FALSE(s.lights[1].inverseSquare);
    EXPECT_EQ(s.background.colour, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_FLOAT_EQ(s.airIor, 1.33f);
    // The two entries name one file (relatively and absolutely): it is stored once and placed
    // twice, each copy an object (docs/scene-format.md, "Instancing").
    EXPECT_EQ(s.triangles.size(), 1u);
    ASSERT_EQ(s.instances.size(), 2u);
    ASSERT_EQ(s.objectNames.size(), 2u);
    EXPECT_EQ(s.instances[1].firstObject, 1u);
    EXPECT_EQ(s.settings.samplesPerPixel, 16u);
    EXPECT_EQ(s.settings.maxDepth, 0u);
    EXPECT_EQ(s.settings.fresnel, FresnelModel::SchlickExp2);
    EXPECT_FLOAT_EQ(s.settings.minWeight, 0.01f);
}

TEST(SceneJson, DefaultsAndAutomaticCamera) {
    fs::path dir = tempDir();
    write(dir / "tri.obj", kTriangleObj);
    Scene s = loadScene(write(dir / "a.json", R"({"objects": [{"obj": "tri.obj"}]})"));
    const RenderSettings defaults;
    EXPECT_EQ(s.settings.samplesPerPixel, defaults.samplesPerPixel);
    EXPECT_EQ(s.settings.maxDepth, 10u);
    EXPECT_EQ(s.settings.fresnel, FresnelModel::Schlick);
    EXPECT_EQ(s.background.colour, glm::vec3(0.0f));
    EXPECT_EQ(s.airIor, 1.0f);
    EXPECT_EQ(s.lights.size(), 1u);  // the automatic camera's light
    expectVec3Near(s.camera.at, {0.5f, 0.5f, 0.0f});

    s = loadScene(write(dir / "b.json", R"({"objects": [{"obj": "tri.obj"}], "lights": []})"));
    EXPECT_TRUE(s.lights.empty());
    expectVec3Near(s.camera.at, {0.5f, 0.5f, 0.0f});

    s = loadScene(
        write(dir / "c.json",
              R"({"objects": [{"obj": "tri.obj"}], "camera": {"from": [0, 0, 5], "at": [0, 0, 0], "up": [0, 1, 0]}})"));
    EXPECT_TRUE(s.lights.empty());
    EXPECT_FLOAT_EQ(s.camera.fovY, 45.0f);
    EXPECT_EQ(s.camera.width, 640u);
}

TEST(SceneJson, GlassOverrideForGeospheres) {
    fs::path dir = tempDir();
    fs::path json =
        write(dir / "glass.json", R"({"objects": [{"obj": ")" + course("geospheres_5x5/geospheres_5x5.obj").string() +
                                      R"(", "mtl": ")" + course("geospheres_5x5/geospheres_5x5_glass.mtl").string() +
                                      R"("}]})");
    Scene s = loadScene(json);
    EXPECT_EQ(s.triangles.size(), 32000u);
    EXPECT_EQ(s.materials.size(), 25u);
    for (const Material& m : s.materials) {
        EXPECT_EQ(m.model, MaterialModel::Glass) << m.name;
        EXPECT_FLOAT_EQ(m.ior, 1.46f);
    }
}

TEST(SceneJson, OverrideWorksWithoutAnMtllibLine) {
    fs::path dir = tempDir();
    write(dir / "g.mtl", "newmtl g\nshader 4\nNi 1.7\n");
    write(dir / "tri.obj", "# no mtllib\n" + kTriangleObj.substr(0, 24) + "usemtl g\nf 1 2 3\n");
    Scene s = loadScene(write(dir / "s.json", R"({"objects": [{"obj": "tri.obj", "mtl": "g.mtl"}]})"));
    EXPECT_EQ(s.materials[s.triangles[0].material].model, MaterialModel::Glass);
    EXPECT_FLOAT_EQ(s.materials[s.triangles[0].material].ior, 1.7f);
}

TEST(SceneJson, TransformsApplyScaleRotateTranslateInOrder) {
    fs::path dir = tempDir();
    write(dir / "tri.obj", "v 1 0 0\nv 0 1 0\nv 0 0 0\nvn 0 0 1\nf 1//1 2//1 3//1\n");
    auto load = [&](const std::string& transform) {
        return loadScene(write(dir / "t.json", R"({"objects": [{"obj": "tri.obj", "transform": )" + transform + "}]}"));
    };
    Scene moved = load(R"({"translate": [1, 2, 3]})");
    expectVec3Near(moved.triangles[0].position[0], {2, 2, 3});
    expectVec3Near(moved.triangles[0].position[2], {1, 2, 3});
    // (1,0,0) scaled by 2 -> (2,0,0), rotated 90 deg about z -> (0,2,0), translated -> (1,3,1).
    Scene s = load(R"({"scale": 2, "rotate_deg": [0, 0, 90], "translate": [1, 1, 1]})");
    expectVec3Near(s.triangles[0].position[0], {1, 3, 1});
    // x first, then z: (0,1,0) -> (0,0,1) -> (0,0,1); z first would give (-1,0,0).
    s = load(R"({"rotate_deg": [90, 0, 90]})");
    expectVec3Near(s.triangles[0].position[1], {0, 0, 1});
    // Normals use the inverse transpose: a triangle in the plane x + y = const keeps its normal
    // perpendicular after a non-uniform scale.
    write(dir / "tri.obj", "v 1 0 0\nv 0 1 0\nv 1 0 1\nvn 1 1 0\nf 1//1 2//1 3//1\n");
    s = load(R"({"scale": [1, 3, 1]})");
    const Triangle& t = s.triangles[0];
    EXPECT_NEAR(glm::dot(t.normal[0], t.position[1] - t.position[0]), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(t.normal[0]), 1.0f, 1e-6f);
}

TEST(SceneJson, MirroringKeepsTheWindingOutward) {
    fs::path dir = tempDir();
    auto outward = [](const Triangle& t) {  // the geosphere is centred on the origin
        glm::vec3 g = glm::cross(t.position[1] - t.position[0], t.position[2] - t.position[0]);
        return glm::dot(g, t.position[0] + t.position[1] + t.position[2]) > 0.0f;
    };
    Scene plain = loadScene(course("geosphere/geosphere.obj"));
    ASSERT_TRUE(outward(plain.triangles[0]));
    fs::path json = write(dir / "m.json", R"({"objects": [{"obj": ")" + course("geosphere/geosphere.obj").string() +
                                              R"(", "transform": {"scale": [-1, 1, 1]}}]})");
    Scene mirrored = loadScene(json);
    for (std::size_t i = 0; i < mirrored.triangles.size(); ++i)
        ASSERT_EQ(outward(mirrored.triangles[i]), outward(plain.triangles[i])) << i;
}

class SceneJsonErrors : public ::testing::Test {
protected:
    void SetUp() override {
        dir = tempDir();
        write(dir / "tri.obj", kTriangleObj);
    }
    // The scene's objects line is line 1, the tested value is on line 2.
    void expectError(const std::string& secondLine, std::initializer_list<std::string> parts) {
        fs::path json = write(dir / "scene.json", "{\"objects\": [{\"obj\": \"tri.obj\"}],\n" + secondLine + "\n}\n");
        expectInputError([&] { loadScene(json); }, parts);
    }
    fs::path dir;
};

TEST_F(SceneJsonErrors, CameraValues) {
    const std::string camera = R"("camera": {"from": [0, -5, 0], "at": [0, 0, 0], )";
    expectError(camera + R"("fov_y": "wide"})", {"scene.json:2:", "\"fov_y\" must be", "got \"wide\""});
    expectError(camera + R"("fov_y": 0})", {"scene.json:2:", "fov_y"});
    expectError(camera + R"("fov_y": 180})", {"scene.json:2:", "fov_y"});
    expectError(camera + R"("fov_y": 0.5})", {"scene.json:2:", "fov_y"});
    expectError(camera + R"("width": 0})", {"scene.json:2:", "\"width\" must be an integer from 1 to 16384"});
    expectError(camera + R"("width": 1000000})", {"scene.json:2:", "width"});
    expectError(camera + R"("height": 2.5})", {"scene.json:2:", "height"});
    expectError(camera + R"("up": [0, 1, 0]})", {"scene.json:2:", "parallel"});
    expectError(camera + R"("up": [0, 0]})", {"scene.json:2:", "\"up\" must be an array of 3"});
    expectError(R"("camera": {"from": [0, 0, 0], "at": [0, 0, 0]})", {"scene.json:2:", "differ"});
    expectError(R"("camera": {"from": [0, 0, 5], "at": [0, 0, 0]})", {"scene.json:2:", "default"});
    expectError(R"("camera": {"at": [0, 0, 0]})", {"scene.json:2:", "\"from\""});
    expectError(R"("camera": [1, 2])", {"scene.json:2:", "\"camera\" must be an object"});
}

TEST_F(SceneJsonErrors, RenderAndLightValues) {
    expectError(R"("render": {"max_depth": -1})", {"scene.json:2:", "max_depth", "from 0 to 64"});
    expectError(R"("render": {"spp": 0})", {"scene.json:2:", "spp"});
    expectError(R"("render": {"spp": 5000})", {"scene.json:2:", "spp"});
    expectError(R"("render": {"min_weight": 2})", {"scene.json:2:", "min_weight"});
    expectError(R"("render": {"fresnel": "fast"})", {"scene.json:2:", "\"schlick\""});
    expectError(R"("lights": [{"position": [0, 0, "x"]}])", {"scene.json:2:", "position"});
    expectError(R"("lights": [{"colour": [1, 1, 1]}])", {"scene.json:2:", "position"});
    expectError(R"("lights": [{"position": [0, 0, 0], "colour": [-1, 1, 1]}])", {"scene.json:2:", "non-negative"});
    expectError(R"("lights": [{"position": [0, 0, 0], "falloff": "linear"}])", {"scene.json:2:", "inverse_square"});
    expectError(R"("lights": {})", {"scene.json:2:", "lights"});
    expectError(R"("background": {"colour": "red"})", {"scene.json:2:", "colour"});
    expectError(R"("air_ior": 0.5)", {"scene.json:2:", "air_ior"});
}

TEST_F(SceneJsonErrors, ObjectsAndFiles) {
    expectInputError([&] { loadScene(dir / "missing.json"); }, {"missing.json", "cannot open"});
    expectInputError([&] { loadScene(write(dir / "s.txt", "{}")); }, {"s.txt", "unknown scene format"});
    fs::create_directories(dir / "course_scene");
    expectInputError([&] { loadScene(dir / "course_scene"); }, {"course_scene", "is a folder", "no .json, .obj, .gltf or .glb"});
    write(dir / "course_scene" / "b.OBJ", "v 0 0 0\n");
    write(dir / "course_scene" / "a.json", "{}");
    write(dir / "course_scene" / "a.mtl", "newmtl m\n");
    write(dir / "course_scene" / "c.glb", "");
    expectInputError([&] { loadScene(dir / "course_scene"); }, {"course_scene", "the scenes in it: a.json b.OBJ c.glb"});
    expectInputError([&] { loadScene(write(dir / "bad.json", "{\n  \"objects\": [\n  }\n")); },
                     {"bad.json:3:", "invalid JSON"});
    expectInputError([&] { loadScene(write(dir / "bad.json", "[1, 2]")); }, {"bad.json", "object"});
    expectInputError([&] { loadScene(write(dir / "bad.json", "{\"lights\": []}")); }, {"bad.json", "objects"});
    expectInputError([&] { loadScene(write(dir / "bad.json", "{\"objects\": []}")); }, {"bad.json:1:", "non-empty"});
    expectInputError([&] { loadScene(write(dir / "bad.json", "{\"objects\": [{\"obj\": 3}]}")); },
                     {"bad.json:1:", "\"obj\" must be a string"});
    expectInputError([&] { loadScene(write(dir / "bad.json", "{\n\"objects\": [{\"obj\": \"nope.obj\"}]}")); },
                     {"bad.json:2:", "nope.obj"});
    expectInputError(
        [&] { loadScene(write(dir / "bad.json", "{\n\"objects\": [{\"obj\": \"tri.obj\", \"mtl\": \"no.mtl\"}]}")); },
        {"bad.json:2:", "no.mtl"});
    expectInputError([&] { loadScene(write(dir / "bad.json", "{\"objects\": [\"tri.obj\"]}")); },
                     {"bad.json:1:", "\"objects[0]\" must be an object"});
    expectError(R"("objects": [{"obj": "tri.obj", "transform": {"scale": 0}}])", {"scene.json:2:", "scale"});
    expectError(R"("objects": [{"obj": "tri.obj", "transform": {"rotate_deg": 90}}])", {"scene.json:2:", "rotate_deg"});
}

TEST_F(SceneJsonErrors, UnknownKeysOnlyWarn) {
    fs::path json =
        write(dir / "scene.json", "{\"objects\": [{\"obj\": \"tri.obj\", \"colour\": 1}],\n \"foo\": {\"bar\": 1}}");
    int before = warningCount();
    EXPECT_NO_THROW(loadScene(json));
    EXPECT_EQ(warningCount(), before + 2);
}

TEST(SceneJson, ValueLinesFollowTheText) {
    auto lines = jsonValueLines("{\n \"a\": [1,\n  {\"b\\\"\": 2}],\n \"c\": {\"d\": \"x,]}\"}\n}");
    EXPECT_EQ(lines[""], 1);
    EXPECT_EQ(lines["/a"], 2);
    EXPECT_EQ(lines["/a/0"], 2);
    EXPECT_EQ(lines["/a/1"], 3);
    EXPECT_EQ(lines["/a/1/b\\\""], 3);
    EXPECT_EQ(lines["/c/d"], 4);
}

// ------------------------------------------------------------------------ automatic framing

TEST(SceneLoader, BareObjIsFramedAutomatically) {
    Scene s = loadScene(course("geosphere/geosphere.obj"));
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const Triangle& t : s.triangles)
        for (const glm::vec3& p : t.position) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const float radius = glm::length(hi - lo) / 2;
    expectVec3Near(s.camera.at, (lo + hi) / 2.0f);
    const glm::vec3 view = s.camera.from - s.camera.at;
    expectVec3Near(glm::normalize(view), glm::normalize(glm::vec3(1, -2, 1)));
    EXPECT_NEAR(glm::length(view), 1.1f * radius / std::sin(glm::radians(22.5f)), 1e-4f);
    EXPECT_EQ(s.camera.up, glm::vec3(0, 0, 1));
    EXPECT_EQ(s.camera.fovY, 45.0f);
    EXPECT_EQ(s.camera.width, 640u);
    EXPECT_EQ(s.camera.height, 480u);
    ASSERT_EQ(s.lights.size(), 1u);
    expectVec3Near(s.lights[0].position, s.camera.from + glm::vec3(0, 0, radius));
    EXPECT_EQ(s.lights[0].colour, glm::vec3(1.0f));
    EXPECT_FALSE(s.lights[0].inverseSquare);
}

TEST(SceneLoader, FramingAnEmptySceneStaysFinite) {
    Scene s;
    frameAutomatically(s);
    EXPECT_TRUE(std::isfinite(s.camera.from.x + s.camera.from.y + s.camera.from.z));
    EXPECT_GT(glm::length(s.camera.from - s.camera.at), 0.0f);
}

}  // namespace
}  // namespace vitrum
