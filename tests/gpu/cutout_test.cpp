// Cut-out surfaces (glTF's alphaMode MASK; docs/render-model-decisions.md, "Cut-out surfaces"):
// where a material's cutout texture is below 1 at a hit's uv, the surface is not there, for
// every ray (camera, shadow, reflected, refracted) on both backends and both kernels. The
// expectations are the background itself, and the same scene built without the cut part.
#include "gpu_test_support.h"

#include <vector>

#include "../support/scenes_in_code.h"

namespace vitrum::testing {
namespace {

// baseScene's wall of the normal model (colour (n + 1) / 2 = (0.5, 0, 0.5) facing the camera),
// u running along +x across it, cut where u < 1/2: the texture (0, 2) read nearest, or read
// bilinear and wrapping (then 4u - 1 between the texel centres, and from 1 at u = 0 down to 0 at
// u = 1/4: below 1 on (0, 1/2)). Columns 0 to 3 look at u in (0.23, 0.43) and see the background,
// exactly; columns 5 to 8 the wall. A ray a pixel and nothing else.
TEST(Cutout, AWallIsNotThereWhereItsTextureIsBelowOne) {
    for (TextureFilter filter : {TextureFilter::Nearest, TextureFilter::Bilinear}) {
        SCOPED_TRACE(filter == TextureFilter::Nearest ? "nearest" : "bilinear");
        Scene scene = wallOf(makeMaterial(MaterialModel::Normal, {}, {}));
        scene.settings.filter = filter;
        scene.textures.push_back(greyRow({0.0f, 2.0f}));
        scene.materials[0].cutout = 0;
        const RenderPair p = renderBoth(scene);
        for (const Image* image : {&p.gpu, &p.cpu})
            for (std::uint32_t y = 0; y < 9; ++y) {
                for (std::uint32_t x = 0; x < 4; ++x)
                    EXPECT_EQ(image->at(x, y), scene.background.colour) << x << ", " << y;
                for (std::uint32_t x = 5; x < 9; ++x)
                    EXPECT_EQ(image->at(x, y), glm::vec3(0.5f, 0.0f, 0.5f)) << x << ", " << y;
            }
        for (const RenderStats* stats : {&p.gpuStats, &p.cpuStats}) {
            EXPECT_EQ(stats->primaryRays, 81u);
            EXPECT_EQ(stats->shadowRays + stats->reflectionRays + stats->refractionRays, 0u);
        }
        EXPECT_TRUE(p.gpuStats.kernel && p.gpuStats.kernel->cutouts);
        expectTheGeneralKernelAgrees(scene, p);
    }
}

// A lit room of every kind of ray: a Lambert floor, a glass box on it, a light, and before them a
// wall of `material` whose left half (u < 1/2, x < 0) is cut away, read nearest. It must render as
// the same room with only the wall's right half built (x from 0 to 3, its uvs from 1/2): what the
// camera sees through the cut half, the shadow the half that is left casts, what the glass and the
// wall reflect and refract. Pixels agree to float rounding (the two walls' triangles differ),
// but for rays that pass within rounding of the cut.
Scene roomWithWall(const Material& material, bool cut) {
    Scene scene;
    scene.camera = {.from = {0.8f, -7.0f, 2.5f},
                    .at = {0.0f, 0.0f, 0.3f},
                    .up = {0, 0, 1},
                    .fovY = 45.0f,
                    .width = 48,
                    .height = 36};
    scene.background.colour = glm::vec3(0.3f, 0.5f, 0.8f);
    scene.lights.push_back({.position = {-2.0f, -6.0f, 5.0f}, .colour = glm::vec3(0.9f)});
    scene.settings.fresnel = FresnelModel::Exact;
    scene.settings.filter = TextureFilter::Nearest;
    scene.materials = {makeMaterial(MaterialModel::Lambert, glm::vec3(0.1f), glm::vec3(0.7f, 0.6f, 0.5f)),
                       makeMaterial(MaterialModel::Glass, {}, {}, {}, 1.0f, 1.5f), material};
    scene.objectNames = {"floor", "glass", "wall"};
    scene.triangles.push_back(makeTriangle({-9, -9, -1}, {9, -9, -1}, {9, 9, -1}, 0, 0));
    scene.triangles.push_back(makeTriangle({-9, -9, -1}, {9, 9, -1}, {-9, 9, -1}, 0, 0));
    addBox(scene, {-0.6f, 1.5f, -1.0f}, {0.9f, 2.5f, 0.2f}, 1, 1);
    // The wall, in the plane y = 0 from z = -0.5 to 2, facing the camera; u along +x.
    const float left = cut ? -3.0f : 0.0f, uLeft = cut ? 0.0f : 0.5f;
    Triangle a = makeTriangle({left, 0, -0.5f}, {3, 0, -0.5f}, {3, 0, 2}, 2, 2);
    Triangle b = makeTriangle({left, 0, -0.5f}, {3, 0, 2}, {left, 0, 2}, 2, 2);
    a.uv[0] = {uLeft, 0}, a.uv[1] = {1, 0}, a.uv[2] = {1, 1};
    b.uv[0] = {uLeft, 0}, b.uv[1] = {1, 1}, b.uv[2] = {uLeft, 1};
    scene.triangles.push_back(a);
    scene.triangles.push_back(b);
    if (cut) {
        scene.textures.push_back(greyRow({0.5f, 1.0f}));
        scene.materials[2].cutout = 0;
    }
    return scene;
}

TEST(Cutout, ACutWallRendersAsTheHalfThatIsLeftStanding) {
    const Material walls[] = {
        makeMaterial(MaterialModel::Phong, glm::vec3(0.05f), glm::vec3(0.2f, 0.5f, 0.3f), glm::vec3(0.4f), 30.0f, 1.5f),
        makeMaterial(MaterialModel::Lambert, glm::vec3(0.05f), glm::vec3(0.2f, 0.5f, 0.3f)),
        makeMaterial(MaterialModel::Mirror, {}, {}, glm::vec3(0.8f)),
        makeMaterial(MaterialModel::ThinGlass, {}, glm::vec3(0.9f, 0.6f, 0.3f), {}, 1.0f, 1.5f),
    };
    for (const Material& wall : walls) {
        SCOPED_TRACE("model " + std::to_string(int(wall.model)));
        const Scene scene = roomWithWall(wall, true);
        const RenderPair cut = renderBoth(scene);
        const RenderPair half = renderBoth(roomWithWall(wall, false));
        expectImagesMatch(cut);
        for (auto [a, b] : {std::pair{&cut.gpu, &half.gpu}, std::pair{&cut.cpu, &half.cpu}}) {
            const ImageDiff d = diffImages(*a, *b);
            EXPECT_LE(d.shareOver005, 2.0 / 1728.0) << (a == &cut.gpu ? "GPU" : "CPU");
            EXPECT_LE(d.meanAbsError, 1e-4) << (a == &cut.gpu ? "GPU" : "CPU");
        }
        // The cut half matters: without the cut the image is another.
        Scene whole = scene;
        whole.materials[2].cutout = -1;
        EXPECT_GT(diffImages(renderBoth(whole).gpu, cut.gpu).shareOver005, 0.05);
        EXPECT_TRUE(cut.gpuStats.kernel && cut.gpuStats.kernel->cutouts);
        expectTheGeneralKernelAgrees(scene, cut);
    }
}

}  // namespace
}  // namespace vitrum::testing
