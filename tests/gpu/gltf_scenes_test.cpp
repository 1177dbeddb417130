// Scenes read from glTF 2.0 render as the same scenes read from OBJ + MTL (docs/scene-format.md,
// "glTF 2.0"): tests/support/gltf_writer.h converts a project scene's OBJ files into glTF, a copy
// of the JSON scene names those instead, and both are loaded and rendered on both backends. Clear
// glass carries over exactly (IOR, a closed volume), so those scenes must render bit for bit the
// same; the opaque models and Beer-Lambert's exp/log round trip do not, and are held to the
// image-diff thresholds of gpu_test_support.h.
#include "gpu_test_support.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "../support/gltf_writer.h"
#include "../support/temporary_folder_test.h"

namespace vitrum::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class GltfScenes : public TemporaryFolderTest {};

// Loaded without instancing, so that the two formats' triangles compare one by one (a scene that
// names one OBJ twice would store it once; its glTF copy has a file each).
Scene sized(const fs::path& path) {
    Scene scene = loadScene(path, {.instancing = false});
    scene.camera.width = 160;
    scene.camera.height = 120;
    return scene;
}

json readJson(const fs::path& path) { return json::parse(std::ifstream(path)); }

// A path the scene file gives, made absolute: the copy lives in another folder.
std::string absoluteFrom(const fs::path& folder, const std::string& path) {
    return fs::path(path).is_absolute() ? path : (folder / path).lexically_normal().string();
}

// Every primitive has a material and every material transmits: a glass object.
bool allGlass(const json& gltf) {
    for (const json& mesh : gltf["meshes"])
        for (const json& primitive : mesh["primitives"])
            if (!primitive.contains("material") ||
                !gltf["materials"][primitive["material"].get<std::size_t>()]["extensions"].contains(
                    "KHR_materials_transmission"))
                return false;
    return true;
}

enum class Convert { GlassObjects, EveryObject };

struct GltfCopy {
    fs::path scene;             // the JSON scene, in the test's folder
    std::size_t converted = 0;  // objects entries that now name a glTF file
};

// Writes, into `folder`, glTF files converted from the scene's OBJ files (with their "mtl"
// overrides) and a copy of the scene whose entries for the objects chosen name them instead, with
// the same transforms. Every other path of the copy is absolute.
GltfCopy gltfCopyOf(const fs::path& sceneFile, const fs::path& folder, Convert which) {
    const fs::path from = sceneFile.parent_path();
    json scene = readJson(sceneFile);
    if (scene.contains("background")) {
        json& background = scene["background"];
        for (const char* key : {"spherical", "cube_cross"})
            if (background.contains(key)) background[key] = absoluteFrom(from, background[key]);
        if (background.contains("cube"))
            for (json& face : background["cube"]) face = absoluteFrom(from, face);
    }
    GltfCopy copy;
    for (std::size_t i = 0; i < scene["objects"].size(); ++i) {
        json& object = scene["objects"][i];
        const std::string obj = absoluteFrom(from, object["obj"]);
        std::optional<fs::path> mtl;
        if (object.contains("mtl")) mtl = absoluteFrom(from, object["mtl"]);
        const std::string gltf = "object" + std::to_string(i) + ".gltf";
        writeGltfFromObj(obj, mtl, folder / gltf);
        if (which == Convert::GlassObjects && !allGlass(readJson(folder / gltf))) {
            object["obj"] = obj;
            if (mtl) object["mtl"] = mtl->string();
            continue;
        }
        object.erase("obj");
        object.erase("mtl");
        object["gltf"] = gltf;  // relative to the copy's folder
        ++copy.converted;
    }
    copy.scene = folder / sceneFile.filename();
    std::ofstream(copy.scene) << scene.dump(2) << '\n';
    return copy;
}

// Counts the triangles where `differ` holds and names the first.
template <class Differ>
void expectNoTriangleWhere(const Scene& fromObj, const Scene& fromGltf, const char* what, Differ differ) {
    std::size_t count = 0, first = 0;
    for (std::size_t i = 0; i < fromObj.triangles.size() && i < fromGltf.triangles.size(); ++i)
        if (differ(fromObj.triangles[i], fromGltf.triangles[i]) && count++ == 0) first = i;
    EXPECT_EQ(count, 0u) << what << " differ, first at triangle " << first << " ("
                         << fromObj.objectNames[fromObj.triangles[first].object] << ")";
}

// The same triangles of the same objects in the same order: vertices and normals equal (exact)
// or equal to rounding (where the transform's rotation may sum its terms in another order).
void expectSameGeometry(const Scene& fromObj, const Scene& fromGltf, bool exact) {
    ASSERT_EQ(fromGltf.triangles.size(), fromObj.triangles.size());
    EXPECT_EQ(fromGltf.objectNames.size(), fromObj.objectNames.size());
    auto same = [exact](glm::vec3 a, glm::vec3 b) {
        if (exact) return a == b;
        return glm::all(glm::lessThanEqual(glm::abs(a - b), 1e-5f * (1.0f + glm::abs(a))));
    };
    expectNoTriangleWhere(fromObj, fromGltf, "objects", [](const Triangle& a, const Triangle& b) {
        return a.object != b.object;
    });
    expectNoTriangleWhere(fromObj, fromGltf, "vertices", [&](const Triangle& a, const Triangle& b) {
        return !same(a.position[0], b.position[0]) || !same(a.position[1], b.position[1]) ||
               !same(a.position[2], b.position[2]);
    });
    expectNoTriangleWhere(fromObj, fromGltf, "normals", [&](const Triangle& a, const Triangle& b) {
        return !same(a.normal[0], b.normal[0]) || !same(a.normal[1], b.normal[1]) || !same(a.normal[2], b.normal[2]);
    });
}

// Triangle by triangle, the glass is the same medium: the same IOR, and the same attenuation to
// the rounding of exp and log (KHR_materials_volume stores exp(-mu)). With `everyModel`, every
// triangle's model is the same too; else only whether it is glass.
void expectSameMedia(const Scene& fromObj, const Scene& fromGltf, bool everyModel) {
    ASSERT_EQ(fromGltf.triangles.size(), fromObj.triangles.size());
    auto materials = [&](const Triangle& a, const Triangle& b) {
        return std::pair<const Material&, const Material&>(fromObj.materials[a.material],
                                                            fromGltf.materials[b.material]);
    };
    auto glass = [](const Material& m) { return m.model == MaterialModel::Glass; };
    expectNoTriangleWhere(fromObj, fromGltf, "material models", [&](const Triangle& a, const Triangle& b) {
        const auto [ma, mb] = materials(a, b);
        return everyModel ? ma.model != mb.model : glass(ma) != glass(mb);
    });
    expectNoTriangleWhere(fromObj, fromGltf, "media", [&](const Triangle& a, const Triangle& b) {
        const auto [ma, mb] = materials(a, b);
        if (!glass(ma) || !glass(mb)) return false;
        const glm::vec3 tolerance = 1e-6f * glm::max(glm::abs(ma.attenuation), glm::abs(mb.attenuation));
        return ma.ior != mb.ior || ma.priority != mb.priority ||
               !glm::all(glm::lessThanEqual(glm::abs(ma.attenuation - mb.attenuation), tolerance));
    });
}

// Every glass of the scene is clear: Tf zero, which the glTF file gives without a round trip.
bool clearGlassOnly(const Scene& scene) {
    return std::none_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) {
        return m.model == MaterialModel::Glass && m.attenuation != glm::vec3(0.0f);
    });
}

// The glTF scene's images against the OBJ scene's, backend by backend, held to the image-diff
// thresholds (gpu_test_support.h's expectImagesAgree says why these numbers).
void expectCloseRenders(const RenderPair& fromObj, const RenderPair& fromGltf) {
    for (const bool gpu : {true, false}) {
        SCOPED_TRACE(gpu ? "GPU" : "CPU");
        const ImageDiff d = diffImages(gpu ? fromGltf.gpu : fromGltf.cpu, gpu ? fromObj.gpu : fromObj.cpu);
        EXPECT_LE(d.shareOver005, 0.005) << "rmse " << d.rmse << " psnr " << d.psnr;
        EXPECT_LE(d.meanAbsError, 2e-3) << "rmse " << d.rmse << " psnr " << d.psnr;
    }
}

// The glass objects of scenes whose other objects are a Lambert floor (kept as OBJ, since glTF
// has no Lambert): diamond's high IOR under an environment map, two clear cubes that touch,
// bubble's air bubble in a tinted block, and thin_glass's panes and hollow sphere (transmission
// without a volume, tinted by the base colour) beside a solid sphere.
TEST_F(GltfScenes, GlassScenesRenderBitIdenticalFromGltf) {
    for (const char* path :
         {"scenes/diamond.json", "scenes/touching_cubes.json", "scenes/bubble.json", "scenes/thin_glass.json"}) {
        SCOPED_TRACE(path);
        const fs::path folder = dir_ / fs::path(path).stem();
        fs::create_directories(folder);
        const GltfCopy copy = gltfCopyOf(sourcePath(path), folder, Convert::GlassObjects);
        ASSERT_GT(copy.converted, 0u);
        const Scene fromObj = sized(sourcePath(path));
        const Scene fromGltf = sized(copy.scene);
        expectSameGeometry(fromObj, fromGltf, true);
        expectSameMedia(fromObj, fromGltf, true);
        const RenderPair objImages = renderBoth(fromObj);
        const RenderPair gltfImages = renderBoth(fromGltf);
        expectImagesMatch(gltfImages);  // the glTF scene on its own: the GPU against the CPU
        EXPECT_GT(gltfImages.gpuStats.refractionRays, 0u);
        if (clearGlassOnly(fromObj)) {
            EXPECT_EQ(differingPixels(objImages.gpu, gltfImages.gpu), 0u);
            EXPECT_EQ(differingPixels(objImages.cpu, gltfImages.cpu), 0u);
        } else {
            // A tinted glass's mu comes back as -ln(exp(-mu)), which may round to a neighbouring
            // float: the absorption, and so the image, may differ in the last bits.
            expectCloseRenders(objImages, gltfImages);
        }
    }
}

// Every object converted, the floor and the plastics too. glTF has no ambient term: the OBJ
// scene's Ka is set to 0 for the comparison (and the glTF's must be 0). Lambert (specularFactor
// 0) maps exactly; a Phong's Ns becomes a roughness and back and its Ks a colour over F0 and
// back, so scenes with Phong materials are held to the thresholds. plastics_green_glass's tinted
// glass stays the same medium.
TEST_F(GltfScenes, OpaqueScenesRenderCloseFromGltf) {
    for (const char* path : {"scenes/lambert_spheres.json", "scenes/plastics_green_glass.json"}) {
        SCOPED_TRACE(path);
        const fs::path folder = dir_ / fs::path(path).stem();
        fs::create_directories(folder);
        const GltfCopy copy = gltfCopyOf(sourcePath(path), folder, Convert::EveryObject);
        Scene fromObj = sized(sourcePath(path));
        for (Material& m : fromObj.materials) m.ambient = glm::vec3(0.0f);
        const Scene fromGltf = sized(copy.scene);
        for (const Material& m : fromGltf.materials) EXPECT_EQ(m.ambient, glm::vec3(0.0f)) << m.name;
        ASSERT_EQ(copy.converted, fromObj.objectNames.size());  // one shape an OBJ file here
        expectSameGeometry(fromObj, fromGltf, false);
        expectSameMedia(fromObj, fromGltf, false);
        const RenderPair objImages = renderBoth(fromObj);
        const RenderPair gltfImages = renderBoth(fromGltf);
        expectNoTriangleWhere(fromObj, fromGltf, "Lambert", [&](const Triangle& a, const Triangle& b) {
            const Material& ma = fromObj.materials[a.material];
            const Material& mb = fromGltf.materials[b.material];
            return (ma.model == MaterialModel::Lambert) !=
                       (mb.model == MaterialModel::Lambert) ||
                   (ma.model == MaterialModel::Lambert && ma.diffuse != mb.diffuse);
        });
        expectImagesMatch(gltfImages);
        expectCloseRenders(objImages, gltfImages);
    }
}

// A texture on a polygon (fanned from its first corner), found through a URI that leaves the
// glTF file's folder and has spaces in it (percent-encoded, glTF 2.0 "URIs"); its v runs down the
// image in glTF and up in OBJ. With a rotated and scaled instance, an opaque dielectric, and a
// shape without a material, which both loaders give the default grey Lambert.
TEST_F(GltfScenes, TexturedPolygonRendersCloseFromGltf) {
    fs::create_directories(dir_ / "tex folder");
    fs::create_directories(dir_ / "gltf");
    fs::copy_file(sharedPath("scenes/course/images/test.png"), dir_ / "tex folder/test image.png");
    std::ofstream(dir_ / "textured.mtl") << "newmtl textured\nshader 2\nKd 0.2 0.2 0.2\nmap_Kd tex folder/test image.png\n"
                                            "newmtl plain\nshader 3\nKd 0.7 0.3 0.2\nKs 0.5 0.5 0.5\nNs 30\nNi 1.4\n";
    std::ofstream(dir_ / "textured.obj")
        << "mtllib textured.mtl\n"
           "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
           "v -1 1 0\nv 1 1 0\nv 1 1 1\nv -1 1 1\n"
           "v -0.6 -0.6 0.01\nv -0.1 -0.6 0.01\nv -0.35 -0.1 0.01\nv -0.35 -0.35 0.5\n"
           "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
           "o stand\nf 9 11 10\nf 9 10 12\nf 10 11 12\nf 11 9 12\n"
           "o floor\nusemtl textured\nf 1/1 2/2 3/3 4/4\n"
           "o wall\nusemtl plain\nf 5 6 7 8\n";
    writeGltfFromObj(dir_ / "textured.obj", std::nullopt, dir_ / "gltf/textured.gltf");
    const json transform = {{"scale", 1.5}, {"rotate_deg", {0, 0, 30}}};
    json scene = {{"camera", {{"from", {0.4, -3.2, 3.0}}, {"at", {0, 0, 0.3}}, {"fov_y", 45}}},
                  {"lights", {{{"position", {1.0, -2.0, 4.0}}}}},
                  {"background", {{"colour", {0.2, 0.25, 0.3}}}},
                  {"objects", {{{"obj", "textured.obj"}, {"transform", transform}}}}};
    std::ofstream(dir_ / "obj.json") << scene.dump(2);
    scene["objects"] = {{{"gltf", "gltf/textured.gltf"}, {"transform", transform}}};
    std::ofstream(dir_ / "gltf.json") << scene.dump(2);

    const Scene fromObj = sized(dir_ / "obj.json");
    const Scene fromGltf = sized(dir_ / "gltf.json");
    ASSERT_EQ(fromObj.triangles.size(), 8u);  // the stand's four faces, two for each square
    expectSameGeometry(fromObj, fromGltf, false);
    ASSERT_EQ(fromObj.textures.size(), 1u);
    ASSERT_EQ(fromGltf.textures.size(), 1u);
    EXPECT_EQ(fromGltf.textures[0].width, fromObj.textures[0].width);
    EXPECT_TRUE(fromGltf.textures[0].texels == fromObj.textures[0].texels);
    const RenderPair objImages = renderBoth(fromObj);
    const RenderPair gltfImages = renderBoth(fromGltf);
    expectImagesMatch(gltfImages);
    expectCloseRenders(objImages, gltfImages);
}

}  // namespace
}  // namespace vitrum::testing
