// The material whose medium each object encloses (render_model/medium_materials.h): one rule, which
// the CPU reference and the GPU's packed scene both follow.
#include <gtest/gtest.h>

#include <vector>

#include "bvh/bvh.h"
#include "render_model/medium_materials.h"
#include "gpu_input/packed_scene.h"

#include "../support/scenes_in_code.h"

namespace vitrum {
namespace {

using namespace vitrum::testing;

// Materials 0 and 1 opaque, 2 and 3 glass of different IOR. Object 0 mixes them, its opaque
// triangle first; object 1 has no glass; object 2 has no triangles; object 3 is named only by a
// triangle. Triangles lie further along -x the later they come, so a BVH's order differs from
// the scene's.
Scene mixedObjects() {
    Scene scene;
    scene.materials = {makeMaterial(MaterialModel::Lambert, glm::vec3(0), glm::vec3(0.5f)),
                       makeMaterial(MaterialModel::Phong, glm::vec3(0), glm::vec3(0.5f)),
                       makeMaterial(MaterialModel::Glass, glm::vec3(0), glm::vec3(0), glm::vec3(0), 1.0f, 1.5f),
                       makeMaterial(MaterialModel::Glass, glm::vec3(0), glm::vec3(0), glm::vec3(0), 1.0f, 2.4f)};
    scene.objectNames = {"mixed", "opaque", "empty"};
    const std::vector<std::pair<std::uint32_t, std::uint32_t>> triangles = {  // (material, object)
        {1, 0}, {1, 1}, {2, 0}, {0, 1}, {3, 0}, {0, 0}, {0, 3}, {2, 3}};
    float x = 0.0f;
    for (auto [material, object] : triangles) {
        scene.triangles.push_back(makeTriangle(glm::vec3(x, 0, 0), glm::vec3(x + 1, 0, 0), glm::vec3(x, 0, 1),
                                               material, object));
        x -= 10.0f;
    }
    return scene;
}

TEST(MediumMaterials, AnObjectsMediumIsItsFirstGlassTrianglesMaterial) {
    const std::vector<std::uint32_t> media = objectMediumMaterials(mixedObjects());
    ASSERT_EQ(media.size(), 4u);  // three names, and object 3 named by its triangles
    EXPECT_EQ(media[0], 2u) << "the first glass triangle's, not the first triangle's nor the last glass's";
    EXPECT_EQ(media[3], 2u);
}

TEST(MediumMaterials, AnObjectWithoutGlassGetsItsFirstTrianglesMaterial) {
    EXPECT_EQ(objectMediumMaterials(mixedObjects())[1], 1u);
}

TEST(MediumMaterials, AnObjectWithoutTrianglesGetsMaterialZero) {
    EXPECT_EQ(objectMediumMaterials(mixedObjects())[2], 0u);
    Scene scene;
    scene.objectNames = {"a", "b"};
    EXPECT_EQ(objectMediumMaterials(scene), (std::vector<std::uint32_t>{0, 0}));
}

// "First" is the scene's order, not the BVH's, which the GPU's packed triangles follow.
TEST(MediumMaterials, ThePackedSceneFollowsTheRule) {
    const Scene scene = mixedObjects();
    const Bvh bvh = buildSceneBvh(scene);
    std::vector<std::uint32_t> sceneOrder(scene.triangles.size());
    for (std::uint32_t i = 0; i < sceneOrder.size(); ++i) sceneOrder[i] = i;
    ASSERT_NE(bvh.triangleOrder, sceneOrder) << "the BVH keeps the scene's order: the test shows nothing";
    EXPECT_EQ(packScene(scene, bvh).tables.objectMaterials, objectMediumMaterials(scene));
    EXPECT_EQ(packScene(scene, bvh).tables.objectMaterials, (std::vector<std::uint32_t>{2, 1, 0, 2}));
}

}  // namespace
}  // namespace vitrum
