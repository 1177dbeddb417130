// Instancing (issue 50; docs/gpu-design.md, "Instancing"): the two-level BVH, its CPU traversal
// against the flattened scene's, the instances' boxes, the scene's analysis and the JSON loader's
// instances.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <tuple>
#include <stdexcept>
#include <string>
#include <vector>

#include "analysis/scene_features.h"
#include "bvh/bvh.h"
#include "bvh/bvh_traversal.h"
#include "common/error.h"
#include "scene/instances.h"
#include "scene/scene_loader.h"

#include "../support/instanced_scene.h"

namespace vitrum {
namespace {

using testing::instancedScene;

std::uint32_t objectBits(const gpu::TriangleVertices& t) { return std::bit_cast<std::uint32_t>(t.v1.w); }

// Random rays from around the scene towards points in it, many of them through the instances.
std::vector<Ray<float>> randomRays(std::uint32_t count) {
    std::mt19937 random(50);
    std::uniform_real_distribution<float> around(-4.0f, 4.0f), inside(-1.8f, 1.8f), height(0.0f, 1.6f);
    std::vector<Ray<float>> rays;
    for (std::uint32_t i = 0; i < count; ++i) {
        const glm::vec3 from(around(random), around(random), 1.0f + height(random) * 2.0f);
        const glm::vec3 to(inside(random), inside(random), height(random));
        rays.push_back({from, to - from, 0.0f, 1e30f});
    }
    return rays;
}

TEST(Instancing, TheTwoLevelTraversalFindsWhatTheFlattenedSceneHolds) {
    const Scene scene = instancedScene();
    const Scene flat = flattened(scene);
    ASSERT_EQ(flat.triangles.size(), 12u + 2 * 12u + 2 * 4u);
    const Bvh bvh = buildSceneBvh(scene);
    const Bvh flatBvh = buildSceneBvh(flat);
    ASSERT_EQ(bvh.instances.size(), 5u);  // four placed, and the floor's tree
    EXPECT_TRUE(flatBvh.instances.empty());
    const std::vector<gpu::TriangleVertices> vertices = packTriangleVertices(bvh, scene.triangles);
    const std::vector<gpu::TriangleVertices> flatVertices = packTriangleVertices(flatBvh, flat.triangles);
    const TraversalInput twoLevels{bvh.nodes, vertices, bvh.instances};
    const TraversalInput oneLevel{flatBvh.nodes, flatVertices};
    std::uint32_t hits = 0, instanceHits = 0;
    for (const Ray<float>& ray : randomRays(4000)) {
        const auto a = traceClosest(twoLevels, ray);
        const auto b = traceClosest(oneLevel, ray);
        ASSERT_EQ(a.has_value(), b.has_value());
        EXPECT_EQ(traceAny(twoLevels, ray), b.has_value());
        if (!a) continue;
        ++hits;
        // The same surface at the same distance: t to float rounding of the moved ray.
        EXPECT_NEAR(a->t, b->t, 1e-5f * b->t);
        const std::uint32_t object =
            objectBits(vertices[a->triangle]) + (a->instance == gpu::kNoInstance ? 0u : bvh.instances[a->instance].info.z);
        EXPECT_EQ(object, objectBits(flatVertices[b->triangle]));
        if (a->instance != gpu::kNoInstance) ++instanceHits;
        // Every surface along the ray, as many as the flattened scene's.
        std::vector<TriangleHit<float>> all, flatAll;
        traceAll(twoLevels, ray, all);
        traceAll(oneLevel, ray, flatAll);
        EXPECT_EQ(all.size(), flatAll.size());
    }
    EXPECT_GT(hits, 3000u);
    EXPECT_GT(instanceHits, 500u);
}

TEST(Instancing, AnInstancesBoxHoldsEveryVertexOfItsCopy) {
    const Scene scene = instancedScene();
    const Scene flat = flattened(scene);
    const std::vector<FloatBox> meshes = meshBoxes(scene);
    std::uint32_t next = worldTriangleCount(scene);
    for (const Instance& instance : scene.instances) {
        const FloatBox box = instanceBox(instance, meshes[instance.mesh]);
        for (std::uint32_t i = 0; i < scene.meshes[instance.mesh].count; ++i, ++next)
            for (const glm::vec3& p : flat.triangles[next].position)
                EXPECT_TRUE(glm::all(glm::lessThanEqual(box.min, p)) && glm::all(glm::lessThanEqual(p, box.max)));
    }
}

TEST(Instancing, ASingularTransformIsRefused) {
    EXPECT_THROW(makeInstance(0, 0, glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 1.0f))), std::invalid_argument);
    const Instance instance = makeInstance(0, 0, glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 2.0f, 3.0f)));
    EXPECT_EQ(glm::vec3(instance.worldToObject * glm::vec4(1.0f, 2.0f, 3.0f, 1.0f)), glm::vec3(0.0f));
}

// The analysis finds for a small instanced scene what it finds for the flattened one (it compares
// the placed triangles), and by the copies' boxes, beyond kFlatAnalysisTriangles placed triangles,
// as much or more (never less: that would cost images).
TEST(Instancing, TheAnalysisOfAnInstancedSceneCoversItsFlattenedOnes) {
    Scene scene = instancedScene();
    const SceneFeatures instanced = analyseScene(scene);
    const SceneFeatures byBoxes = analyseScene(scene, 0);
    const SceneFeatures flat = analyseScene(flattened(scene));
    EXPECT_EQ(instanced.glassObjects, 4u);
    EXPECT_EQ(instanced.glassObjects, flat.glassObjects);
    EXPECT_EQ(instanced.openGlassObjects, 0u);
    EXPECT_EQ(instanced.materialModels, flat.materialModels);
    EXPECT_GE(instanced.mediumStackDepth, flat.mediumStackDepth);
    for (const SceneFeatures* f : {&instanced, &byBoxes}) {
        EXPECT_TRUE(f->opaqueContactPossible || !flat.opaqueContactPossible);
        EXPECT_TRUE(f->coincidentOpaquePossible || !flat.coincidentOpaquePossible);
        EXPECT_TRUE(f->touchingMediaPossible || !flat.touchingMediaPossible);
    }
    EXPECT_EQ(instanced.opaqueContactPossible, flat.opaqueContactPossible);
    EXPECT_EQ(instanced.coincidentOpaquePossible, flat.coincidentOpaquePossible);
    EXPECT_EQ(instanced.touchingMediaPossible, flat.touchingMediaPossible);
    // This scene's only opaque object is its floor, so no two opaque surfaces can coincide: the
    // triangles find none, the boxes take any opaque triangle as making them possible.
    EXPECT_TRUE(byBoxes.coincidentOpaquePossible);
    EXPECT_FALSE(flat.coincidentOpaquePossible);
    // The touching distance goes by the instances' boxes, a little wider than their triangles'.
    EXPECT_NEAR(instanced.touchingDistance, flat.touchingDistance, 1e-3 * flat.touchingDistance);
    // A camera inside the stretched box's copy is in its medium (object 2: floor, box moved, this).
    scene.camera.from = {0.4f, 1.2f, 0.6f};
    EXPECT_EQ(analyseScene(scene).cameraMedia, std::vector<std::uint32_t>{2u});
    EXPECT_EQ(analyseScene(flattened(scene)).cameraMedia, std::vector<std::uint32_t>{2u});
    // An open mesh (a box without its top) makes every copy's object open.
    Scene open = instancedScene();
    open.triangles.erase(open.triangles.begin() + open.meshes[0].first);
    open.meshes[0].count -= 1;
    open.meshes[1].first -= 1;
    EXPECT_EQ(openGlassObjects(open), (std::set<std::uint32_t>{1u, 2u}));
}

namespace fs = std::filesystem;

fs::path writeScene(const std::string& name, const std::string& objects) {
    const fs::path dir = fs::temp_directory_path() / "vitrum_instancing_test";
    fs::create_directories(dir);
    const fs::path file = dir / name;
    std::ofstream(file) << R"({"camera": {"from": [0, -6, 2], "at": [0, 0, 0]}, "objects": [)" << objects << "]}";
    return file;
}

std::string entry(const std::string& obj, const std::string& extra = "") {
    return R"({"obj": ")" + std::string(VITRUM_SOURCE_DIR) + "/scenes/meshes/" + obj + "\"" + extra + "}";
}

// A copy's box in the top level (buildSceneBvh) is the union of upper boxes of its mesh's tree
// moved to the world: it holds every vertex of the copy, and a sphere turned 45 degrees about z gets
// a box close to its own, where its moved mesh box is sqrt(2) as wide.
TEST(Instancing, ATurnedCopysBoxFitsTheCopy) {
    const fs::path file = writeScene(
        "turned.json", entry("sphere.obj", R"(, "transform": {"rotate_deg": [0, 0, 45]})") + ", " +
                           entry("sphere.obj", R"(, "transform": {"translate": [5, 0, 0]})"));
    const Scene scene = loadScene(file);
    ASSERT_EQ(scene.instances.size(), 2u);
    const Bvh bvh = buildSceneBvh(scene);
    const Scene flat = flattened(scene);
    FloatBox copy{glm::vec3(1e30f), glm::vec3(-1e30f)};  // the turned copy's vertices
    for (const Triangle& t : flat.triangles)
        if (t.object == scene.instances[0].firstObject)
            for (const glm::vec3& p : t.position) {
                copy.min = glm::min(copy.min, p);
                copy.max = glm::max(copy.max, p);
            }
    const gpu::BvhNode* leaf = nullptr;  // the top level's leaf of instance 0 (a count of 0)
    for (const gpu::BvhNode& node : bvh.nodes)
        if (std::bit_cast<std::uint32_t>(node.boundsMax.w) == 0u && std::bit_cast<std::uint32_t>(node.boundsMin.w) == 0u)
            leaf = &node;
    ASSERT_NE(leaf, nullptr);
    EXPECT_TRUE(glm::all(glm::lessThanEqual(glm::vec3(leaf->boundsMin), copy.min)));
    EXPECT_TRUE(glm::all(glm::lessThanEqual(copy.max, glm::vec3(leaf->boundsMax))));
    const glm::vec3 fitted = glm::vec3(leaf->boundsMax) - glm::vec3(leaf->boundsMin);
    const FloatBox moved = instanceBox(scene.instances[0], meshBox(scene, scene.meshes[0]));
    const glm::vec3 exact = copy.max - copy.min;
    for (int a = 0; a < 2; ++a) {
        EXPECT_GT((moved.max - moved.min)[a], 1.4f * exact[a]);  // sqrt(2)
        EXPECT_LT(fitted[a], 0.9f * (moved.max - moved.min)[a]) << fitted[a] / exact[a];
    }
}

TEST(Instancing, AJsonSceneStoresAFileItNamesTwiceOnce) {
    const fs::path file = writeScene(
        "twice.json", entry("cube.obj", R"(, "transform": {"translate": [-1, 0, 0]})") + ", " + entry("prism.obj") + ", " +
                          entry("cube.obj", R"(, "transform": {"rotate_deg": [0, 0, 45], "scale": [1, 2, 1]})"));
    const Scene scene = loadScene(file);
    ASSERT_EQ(scene.meshes.size(), 1u);
    ASSERT_EQ(scene.instances.size(), 2u);
    EXPECT_EQ(scene.meshes[0].count, 12u);
    EXPECT_EQ(worldTriangleCount(scene) + 12u, scene.triangles.size());  // the prism in the world, the cube once
    EXPECT_EQ(scene.objectNames.size(), 3u);
    EXPECT_EQ(scene.instances[0].firstObject, 1u);  // after the prism's
    EXPECT_EQ(scene.instances[1].firstObject, 2u);
    EXPECT_EQ(glm::vec3(scene.instances[0].objectToWorld[3]), glm::vec3(-1.0f, 0.0f, 0.0f));
    // Without instancing, the same triangles in the world.
    const Scene flat = loadScene(file, {.instancing = false});
    EXPECT_TRUE(flat.instances.empty());
    EXPECT_EQ(flat.triangles.size(), worldTriangleCount(scene) + 24u);
    // A different "mtl" is another mesh: the two stay in the world.
    const Scene other = loadScene(writeScene(
        "other.json", entry("cube.obj") + ", " +
                          entry("cube.obj", R"(, "mtl": ")" + std::string(VITRUM_SOURCE_DIR) +
                                                R"(/scenes/materials/clear_glass.mtl", "transform": {"translate": [2, 0, 0]})")));
    EXPECT_TRUE(other.instances.empty());
}

TEST(Instancing, AnInstanceMovedBeyondFloatIsRefusedNamingItsEntry) {
    const fs::path file = writeScene(
        "far.json", entry("cube.obj") + ", " + entry("cube.obj", R"(, "transform": {"scale": [1e38, 1e38, 1e38], "translate": [3e38, 0, 0]})"));
    try {
        loadScene(file);
        ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("beyond"), std::string::npos) << e.what();
    }
}

// A glTF file whose nodes share a mesh, in a JSON scene before an OBJ file in the world and one
// named twice: the glTF's mesh is made first, yet the world's triangles end up before every mesh's
// (putMeshesLast), and the copies are the triangles the flat load makes.
TEST(Instancing, MeshesFromAGltfAndFromRepeatedEntriesComeAfterTheWorld) {
    const std::string gltf = std::string(VITRUM_SOURCE_DIR) + "/tests/fuzz/corpus/gltf/instanced.gltf";
    const fs::path file =
        writeScene("mixed.json", R"({"gltf": ")" + gltf + R"("}, )" + entry("prism.obj") + ", " +
                                     entry("cube.obj", R"(, "transform": {"translate": [3, 0, 0]})") + ", " +
                                     entry("cube.obj", R"(, "transform": {"translate": [5, 0, 0]})"));
    const Scene scene = loadScene(file);
    ASSERT_EQ(scene.meshes.size(), 2u);  // the glTF's triangle, the cube
    EXPECT_EQ(scene.instances.size(), 5u);
    std::uint32_t next = worldTriangleCount(scene);
    for (const Mesh& mesh : scene.meshes) {
        EXPECT_EQ(mesh.first, next);
        next += mesh.count;
    }
    EXPECT_EQ(next, scene.triangles.size());
    const Scene flat = loadScene(file, {.instancing = false});
    const Scene placed = flattened(scene);
    ASSERT_EQ(placed.triangles.size(), flat.triangles.size());
    // The same triangles (corners to float rounding of the transforms), each of its own object.
    auto key = [](const Triangle& t) {
        return std::tuple(std::lround(t.position[0].x * 1e4f), std::lround(t.position[0].y * 1e4f),
                          std::lround(t.position[0].z * 1e4f), std::lround(t.position[1].x * 1e4f),
                          std::lround(t.position[2].z * 1e4f));
    };
    std::multiset<std::tuple<long, long, long, long, long>> a, b;
    for (const Triangle& t : placed.triangles) a.insert(key(t));
    for (const Triangle& t : flat.triangles) b.insert(key(t));
    EXPECT_EQ(a, b);
    EXPECT_EQ(scene.objectNames.size(), flat.objectNames.size());
}

}  // namespace
}  // namespace vitrum
