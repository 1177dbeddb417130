// Decisions of docs/render-model-decisions.md that the render model leaves open, each pinned on
// both backends by a value worked out by hand: ambient light, texture orientation, the Fresnel
// term and the highlight of the opaque dielectric, a ray that leaves the scene inside an
// absorbing medium, which material an object's medium is, and glass whose shading normal faces
// the wrong way.
#include "gpu_test_support.h"

#include <cmath>
#include <utility>

#include "../support/scenes_in_code.h"

namespace vitrum::testing {
namespace {

void expectEveryPixel(const Image& image, const glm::dvec3& expected, double tolerance, const char* backend) {
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(image.pixels[i][c], expected[c], tolerance) << backend << " pixel " << i << " channel " << c;
}

// Ambient is m_a times each light's colour, summed over the lights, whether or not the light
// reaches the surface; a scene without lights has no ambient either. Both lights are behind the
// wall, so only ambient is left, the same in every pixel.
TEST(ShadingDecisions, AmbientSumsOverTheLightsAndNeedsOne) {
    Scene scene = wallOf(makeMaterial(MaterialModel::Lambert, {0.05f, 0.1f, 0.02f}, {0.8f, 0.5f, 0.3f}));
    scene.lights.push_back({{1, 2, 0}, {0.9f, 1.0f, 0.7f}, false});
    scene.lights.push_back({{-1, 3, 1}, {0.3f, 0.2f, 0.1f}, false});
    RenderPair lit = renderBoth(scene);
    const glm::dvec3 ambient = glm::dvec3(0.9 + 0.3, 1.0 + 0.2, 0.7 + 0.1) * glm::dvec3(0.05, 0.1, 0.02);
    expectEveryPixel(lit.gpu, ambient, 1e-6, "gpu");
    expectEveryPixel(lit.cpu, ambient, 1e-6, "cpu");
    scene.lights.clear();
    RenderPair dark = renderBoth(scene);
    expectEveryPixel(dark.gpu, glm::dvec3(0.0), 0.0, "gpu");
    expectEveryPixel(dark.cpu, glm::dvec3(0.0), 0.0, "cpu");
}

// A mesh texture is sampled at (u, 1 - v): the image's row 0 is where v = 1, at the top of a
// square whose v runs up. With nearest filtering each quarter of the square shows one texel:
// red, green / blue, white, as the image is laid out.
TEST(ShadingDecisions, TexturesAreUprightRowZeroAtTheTop) {
    Material m = makeMaterial(MaterialModel::Lambert, {0, 0, 0}, {1, 1, 1});
    m.diffuseTexture = 0;
    Scene scene = wallOf(m);
    scene.textures.push_back(Texture{"quarters", 2, 2, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}}});
    scene.settings.filter = TextureFilter::Nearest;
    scene.lights.push_back({{0, -5, 0}, {1, 1, 1}, false});
    RenderPair r = renderBoth(scene);
    for (const Image* image : {&r.gpu, &r.cpu}) {
        // Top left, top right, bottom left, bottom right of the 9 x 9 image: the light seen at an
        // angle dims each a little, so the colour is checked as which channels are lit.
        const glm::vec3 topLeft = image->at(1, 1), topRight = image->at(7, 1), bottomLeft = image->at(1, 7),
                        bottomRight = image->at(7, 7);
        EXPECT_GT(topLeft.r, 0.5f);
        EXPECT_EQ(topLeft.g + topLeft.b, 0.0f);
        EXPECT_GT(topRight.g, 0.5f);
        EXPECT_EQ(topRight.r + topRight.b, 0.0f);
        EXPECT_GT(bottomLeft.b, 0.5f);
        EXPECT_EQ(bottomLeft.r + bottomLeft.g, 0.0f);
        EXPECT_GT(bottomRight.r, 0.5f);
        EXPECT_EQ(bottomRight.r, bottomRight.g);
        EXPECT_EQ(bottomRight.g, bottomRight.b);
    }
}

// The opaque dielectric (MTL shader 3) weights its reflection by Schlick's term whatever
// render.fresnel says: render.fresnel chooses the glass's model only. Off the centre the rays
// meet the plastic at up to about 25 degrees, where the exact term differs from Schlick's by a
// few parts in 10^4 of the reflected wall, so any use of the setting would change the image.
TEST(ShadingDecisions, PlasticReflectsBySchlickWhateverTheFresnelSetting) {
    Scene scene = plasticBeforeWall();
    scene.lights.push_back({{1, -4, 2}, {1, 1, 1}, false});
    scene.camera.fovY = 50.0f;
    scene.settings.fresnel = FresnelModel::Schlick;
    RenderPair schlick = renderBoth(scene);
    scene.settings.fresnel = FresnelModel::Exact;
    RenderPair exact = renderBoth(scene);
    EXPECT_EQ(exact.gpu.pixels, schlick.gpu.pixels);
    EXPECT_EQ(exact.cpu.pixels, schlick.cpu.pixels);
    expectImagesMatch(schlick);
}

// The Phong highlight is max(0, l_r.v)^Ns, added even where n.l <= 0, with 0^0 = 1. A square
// whose vertex normals lean away from the light, n = normalize(-1, -0.3, 0), lit from (2, -3, 0)
// in front of it (so the shadow ray reaches the light): at the centre n.l = -0.29 (no diffuse)
// and l_r.v = -1.0 (c = 0). With Ns = 0 the highlight is 1: the pixel is l_c (m_a + m_s) =
// 0.05 + 0.5. Gating it on n.l, or taking 0^0 as 0, would leave the ambient 0.05 alone.
// max_depth 1: the reflection is not traced.
TEST(ShadingDecisions, PhongHighlightIsNotGatedOnNDotLAndZeroToTheZeroIsOne) {
    Scene scene =
        wallOf(makeMaterial(MaterialModel::Phong, {0.05f, 0.05f, 0.05f}, {0.8f, 0.8f, 0.8f}, {0.5f, 0.5f, 0.5f}, 0.0f));
    for (Triangle& t : scene.triangles)
        for (glm::vec3& n : t.normal) n = glm::normalize(glm::vec3(-1.0f, -0.3f, 0.0f));
    scene.lights.push_back({{2, -3, 0}, {1, 1, 1}, false});
    scene.background.colour = glm::vec3(0.0f);
    scene.settings.maxDepth = 1;
    const glm::dvec3 n = glm::normalize(glm::dvec3(-1.0, -0.3, 0.0));
    const glm::dvec3 l = glm::normalize(glm::dvec3(2.0, -3.0, 0.0));
    ASSERT_LT(glm::dot(n, l), -0.2);
    ASSERT_LT(glm::dot(2.0 * glm::dot(n, l) * n - l, glm::dvec3(0.0, -1.0, 0.0)), -0.9);
    RenderPair r = renderBoth(scene);
    for (const Image* image : {&r.gpu, &r.cpu})
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(image->at(4, 4)[c], 0.55, 1e-6);
}

// A shadow ray is traced only for a direct term of at least the smallest normal float in some
// channel: below it a device may flush the term to 0 (lavapipe flushes some), so only that threshold makes
// every device and the CPU trace the same rays. Kd 0.5 under a light of 2e-38 gives at most 1e-38
// (below FLT_MIN, 1.18e-38): no ray; under 4e-38 at least 0.5 n.l 4e-38 > 1.8e-38 (n.l > 0.92 in
// every pixel): 81 rays, on both backends.
TEST(ShadingDecisions, AShadowRayIsTracedOnlyForADirectTermOfAtLeastTheSmallestNormalFloat) {
    for (const auto& [light, rays] : {std::pair{2e-38f, 0u}, std::pair{4e-38f, 81u}}) {
        Scene scene = wallOf(makeMaterial(MaterialModel::Lambert, {0.0f, 0.0f, 0.0f}, {0.5f, 0.5f, 0.5f}));
        scene.lights.push_back({{0, -5, 0}, glm::vec3(light), false});
        const RenderPair r = renderBoth(scene);
        EXPECT_EQ(r.gpuStats.shadowRays, rays) << light;
        EXPECT_EQ(r.cpuStats.shadowRays, rays) << light;
    }
}

// A ray that leaves the scene inside an absorbing medium (only an open mesh allows it) brings
// back nothing in the channels the medium absorbs, and is counted. A glass sheet (Ni 1.5, Tf 1 0
// 0) seen head-on against a white background, max_depth 2: its refraction (1 - R0 = 0.96)
// escapes inside the sheet's medium and keeps green and blue; its reflection (R0 = 0.04) returns
// to the white background in air. Every pixel: (0.04, 1, 1).
TEST(ShadingDecisions, EscapingInsideAnAbsorbingMediumKeepsOnlyTheClearChannels) {
    Material glass = makeMaterial(MaterialModel::Glass, {}, {});
    glass.attenuation = {1.0f, 0.0f, 0.0f};
    Scene scene = wallOf(glass);  // an open sheet
    scene.background.colour = glm::vec3(1.0f);
    scene.settings.maxDepth = 2;
    scene.settings.fresnel = FresnelModel::Exact;
    scene.camera.fovY = 1.0f;  // every ray within a degree of normal incidence: R within 1e-6 of R0
    RenderPair r = renderBoth(scene);
    expectEveryPixel(r.gpu, {0.04, 1.0, 1.0}, 1e-5, "gpu");
    expectEveryPixel(r.cpu, {0.04, 1.0, 1.0}, 1e-5, "cpu");
    EXPECT_EQ(r.gpuStats.absorbedEscapes, 81u);
    EXPECT_EQ(r.cpuStats.absorbedEscapes, 81u);
}

// An object's medium is the material of its first glass triangle. A box (y from -1 to 1) whose
// first triangle, on its bottom face, is an absorbing glass (Tf 1 0 0) and all others clear glass
// of the same Ni 1.5, seen head-on through its clear faces against a white background at
// max_depth 3: 0.04 reflected at the front, and 0.96 x 0.96 through both faces, attenuated over
// the 2 units inside by the absorbing glass's Tf: red 0.04 + 0.9216 e^-2, green and blue 0.9616.
TEST(ShadingDecisions, AnObjectsMediumIsItsFirstGlassTriangles) {
    Scene scene = baseScene();
    Material clear = makeMaterial(MaterialModel::Glass, {}, {});
    Material absorbing = clear;
    absorbing.attenuation = {1.0f, 0.0f, 0.0f};
    scene.materials = {clear, absorbing};
    scene.objectNames = {"box"};
    addBox(scene, glm::vec3(-1.0f), glm::vec3(1.0f), 0, 0);
    scene.triangles[0].material = 1;
    ASSERT_EQ(scene.triangles[0].position[0].z, -1.0f);  // on the bottom face, out of the centre ray's way
    scene.background.colour = glm::vec3(1.0f);
    scene.settings.maxDepth = 3;
    scene.settings.fresnel = FresnelModel::Exact;
    RenderPair r = renderBoth(scene);
    const glm::dvec3 expected(0.04 + 0.9216 * std::exp(-2.0), 0.04 + 0.9216, 0.04 + 0.9216);
    for (const Image* image : {&r.gpu, &r.cpu})
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(image->at(4, 4)[c], expected[c], 1e-5) << c;
}

// Glass whose shading normal, taken on the incoming side, still faces along the ray (vertex
// normals bent past 90 degrees) is shaded with its geometric normal instead: a glass sheet whose
// vertex normals all point to (0.3, 1, 0), away from the camera and along every camera ray (the
// rays are within 20 degrees of +y), renders as the same sheet with its own normals, in front
// of a lit wall it refracts.
TEST(ShadingDecisions, GlassWithItsShadingNormalOnTheWrongSideUsesTheGeometricOne) {
    Scene plain = wallOf(makeMaterial(MaterialModel::Glass, {}, {}));
    plain.materials.push_back(makeMaterial(MaterialModel::Lambert, {0.1f, 0.1f, 0.1f}, {0.5f, 0.6f, 0.7f}));
    plain.objectNames.push_back("backdrop");
    addSquareY(plain, {0, 3, 0}, 30.0f, true, 1, 1);
    plain.lights.push_back({{0.5f, 2, 0.5f}, {1, 1, 1}, false});  // between the sheet and the wall
    plain.settings.fresnel = FresnelModel::Exact;
    Scene bent = plain;
    for (Triangle& t : bent.triangles)
        if (t.object == 0)
            for (glm::vec3& n : t.normal) n = glm::normalize(glm::vec3(0.3f, 1.0f, 0.0f));
    RenderPair a = renderBoth(plain);
    RenderPair b = renderBoth(bent);
    for (auto [x, y] : {std::pair{&a.gpu, &b.gpu}, std::pair{&a.cpu, &b.cpu}}) {
        const ImageDiff d = diffImages(*x, *y);
        EXPECT_LE(d.maxAbsError, 1e-5) << "psnr " << d.psnr;
    }
    expectImagesMatch(b);
}

// An index-matched continuation is the same ray going on, not a new branch: min_weight does not
// cut it. Two touching glass boxes of Ni 1.5 and mu 3 (y from -1 to 0 and from 0 to 1), and in
// the second a Lambert box (Ka 1) whose face at y = 0.4 the centre ray meets, lit only by ambient
// (the glass shadows it). At min_weight 0.1 the ray crosses the shared face with weight 0.96 e^-3
// = 0.048, below it, and reaches the Lambert face with 0.96 e^-4.2: that is the pixel on a black
// background (the front face's reflection, 0.04, is cut).
TEST(ShadingDecisions, MinWeightDoesNotCutAnIndexMatchedContinuation) {
    Scene scene = baseScene();
    Material glass = makeMaterial(MaterialModel::Glass, {}, {});
    glass.attenuation = glm::vec3(3.0f);
    scene.materials = {glass, makeMaterial(MaterialModel::Lambert, {1, 1, 1}, {0.5f, 0.5f, 0.5f})};
    scene.objectNames = {"front", "back", "inside"};
    addBox(scene, {-1, -1, -1}, {1, 0, 1}, 0, 0);
    addBox(scene, {-1, 0, -1}, {1, 1, 1}, 0, 1);
    addBox(scene, {-0.3f, 0.4f, -0.3f}, {0.3f, 0.6f, 0.3f}, 1, 2);
    scene.lights.push_back({{0, -5, 0}, {1, 1, 1}, false});
    scene.background.colour = glm::vec3(0.0f);
    scene.settings.fresnel = FresnelModel::Exact;
    scene.settings.minWeight = 0.1f;
    RenderPair r = renderBoth(scene);
    for (const Image* image : {&r.gpu, &r.cpu})
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(image->at(4, 4)[c], 0.96 * std::exp(-4.2), 1e-6) << c;
    EXPECT_GT(r.gpuStats.touchingInterfaces, 0u);
}

}  // namespace
}  // namespace vitrum::testing
