// Environment maps on lavapipe against the CPU reference: the (u, v) each backend reads for known
// directions, glass spheres inside every kind of background, the course's images, and big maps.
#include "gpu_test_support.h"

#include <cstdlib>
#include <string>

#include "common/error.h"
#include "scene/environment_map.h"

namespace vitrum::testing {
namespace {

// A texture whose texel (i, j) holds its own centre (u, v) and `tag`: bilinear filtering of this
// linear ramp returns the (u, v) it was asked for (away from the edges), so a pixel shows which
// (u, v) the backend looked up.
Texture uvRamp(int w, int h, float tag) {
    Texture t{"uv ramp", w, h, {}};
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) t.texels.emplace_back((i + 0.5f) / w, (j + 0.5f) / h, tag);
    return t;
}

// A one-pixel image looking along d: the pixel is the background in direction d.
Scene lookingAlong(glm::vec3 d) {
    Scene scene;
    scene.camera.from = glm::vec3(0.0f);
    scene.camera.at = d;
    scene.camera.up = std::abs(d.z) > 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
    scene.camera.fovY = 1.0f;
    scene.camera.width = scene.camera.height = 1;
    scene.materials.push_back(Material{});
    return scene;
}

void expectBothSee(Scene scene, glm::vec3 expected, float tolerance, const std::string& what) {
    Bvh bvh = buildSceneBvh(scene);
    RenderStats gpuStats, cpuStats;
    Image gpu = renderVulkan(testDevice(), scene, bvh, {}, gpuStats);
    Image cpu = renderReference(scene, bvh, {}, cpuStats);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(gpu.pixels[0][c], expected[c], tolerance) << what << " (GPU), channel " << c;
        EXPECT_NEAR(cpu.pixels[0][c], expected[c], tolerance) << what << " (CPU), channel " << c;
    }
}

TEST(Environment, SphericalMapUvOfKnownDirectionsOnBothBackends) {
    // Render model: u = 1 - (atan2(y, x) + pi) / 2 pi, v = acos(z) / pi.
    struct Case {
        glm::vec3 d;
        glm::vec2 uv;
        const char* name;
    } cases[] = {
        {{1, 0, 0}, {0.5f, 0.5f}, "+x"},
        {{0, 1, 0}, {0.25f, 0.5f}, "+y"},
        {{0, -1, 0}, {0.75f, 0.5f}, "-y"},
        {glm::normalize(glm::vec3(1, 0, 1)), {0.5f, 0.25f}, "45 degrees up"},
        {glm::normalize(glm::vec3(1, 0, -1)), {0.5f, 0.75f}, "45 degrees down"},
        // The seam: u = 0 = 1 wraps, so the lookup blends the last and first columns equally.
        {{-1, 0, 0}, {0.5f, 0.5f}, "-x, on the seam"},
    };
    for (const Case& c : cases) {
        Scene scene = lookingAlong(c.d);
        scene.textures.push_back(uvRamp(64, 32, 0.0f));
        scene.background = {.kind = BackgroundKind::Spherical, .map = 0};
        expectBothSee(scene, glm::vec3(c.uv, 0.0f), 2e-3f, c.name);
    }
    // At the poles v clamps to the centre of the first / last row.
    for (auto [d, v] : {std::pair{glm::vec3(0, 0, 1), 0.5f / 32}, std::pair{glm::vec3(0, 0, -1), 1 - 0.5f / 32}}) {
        Scene scene = lookingAlong(d);
        scene.textures.push_back(uvRamp(64, 32, 0.0f));
        scene.background = {.kind = BackgroundKind::Spherical, .map = 0};
        Bvh bvh = buildSceneBvh(scene);
        RenderStats stats;
        EXPECT_NEAR(renderVulkan(testDevice(), scene, bvh, {}, stats).pixels[0].y, v, 2e-3f);
    }
}

TEST(Environment, CubeMapFaceAndUvOfKnownDirectionsOnBothBackends) {
    struct Case {
        glm::vec3 d;
        int face;
        glm::vec2 uv;
    } cases[] = {
        {{1, 0, 0}, 0, {0.5f, 0.5f}},
        {{-1, 0, 0}, 1, {0.5f, 0.5f}},
        {{0, 1, 0}, 2, {0.5f, 0.5f}},
        {{0, -1, 0}, 3, {0.5f, 0.5f}},
        {{0, 0, 1}, 4, {0.5f, 0.5f}},
        {{0, 0, -1}, 5, {0.5f, 0.5f}},
        // Orientation (render model table): +x: u from -y, v from -z.
        {glm::normalize(glm::vec3(1, -0.5f, -0.25f)), 0, {0.75f, 0.625f}},
        // -y: u from -x, v from -z.
        {glm::normalize(glm::vec3(0.5f, -1, 0.5f)), 3, {0.25f, 0.25f}},
        // +z: u from +x, v from +y.
        {glm::normalize(glm::vec3(0.5f, 0.5f, 1)), 4, {0.75f, 0.75f}},
        // -z: u from +x, v from -y.
        {glm::normalize(glm::vec3(-0.5f, 0.5f, -1)), 5, {0.25f, 0.25f}},
    };
    for (const Case& c : cases) {
        Scene scene = lookingAlong(c.d);
        for (int face = 0; face < 6; ++face) scene.textures.push_back(uvRamp(16, 16, face / 8.0f));
        scene.background = {.kind = BackgroundKind::Cube, .map = 0};
        expectBothSee(scene, glm::vec3(c.uv, c.face / 8.0f), 2e-3f, "face " + std::to_string(c.face));
    }
}

Scene glassSphereIn(const std::string& scene, TextureFilter filter) {
    Scene s = loadScene(sourcePath(scene));
    s.camera.width = 96;
    s.camera.height = 72;
    s.settings.filter = filter;
    return s;
}

class GlassInBackground : public ::testing::TestWithParam<std::tuple<const char*, TextureFilter>> {};

TEST_P(GlassInBackground, GpuMatchesReference) {
    RenderPair r = renderBoth(glassSphereIn(std::get<0>(GetParam()), std::get<1>(GetParam())));
    expectImagesMatch(r);
    EXPECT_EQ(r.gpuStats.loopLimitSuspected, 0u);
}

INSTANTIATE_TEST_SUITE_P(
    Backgrounds, GlassInBackground,
    ::testing::Combine(::testing::Values("scenes/glass_sphere_spherical.json", "scenes/glass_sphere_cube.json",
                                         "scenes/glass_sphere_cube_cross.json"),
                       ::testing::Values(TextureFilter::Bilinear, TextureFilter::Nearest)),
    [](const auto& info) {
        std::string name = std::filesystem::path(std::get<0>(info.param)).stem().string();
        return name + (std::get<1>(info.param) == TextureFilter::Nearest ? "_nearest" : "_bilinear");
    });

TEST(Environment, CubeCrossAndSixFacesAreTheSameBackground) {
    Scene faces = glassSphereIn("scenes/glass_sphere_cube.json", TextureFilter::Bilinear);
    Scene cross = glassSphereIn("scenes/glass_sphere_cube_cross.json", TextureFilter::Bilinear);
    RenderStats a, b;
    Image fromFaces = renderVulkan(testDevice(), faces, buildSceneBvh(faces), {}, a);
    Image fromCross = renderVulkan(testDevice(), cross, buildSceneBvh(cross), {}, b);
    EXPECT_EQ(diffImages(fromFaces, fromCross).maxAbsError, 0.0);
}

TEST(Environment, CourseImagesServeAsBackgrounds) {
    for (const char* image :
         {"scenes/course/images/test.hdr", "scenes/course/images/test.png", "scenes/course/images/test.exr"}) {
        Scene scene = glassSphereIn("scenes/glass_sphere_spherical.json", TextureFilter::Bilinear);
        scene.textures.clear();
        loadSphericalBackground(scene, sharedPath(image));
        RenderPair r = renderBoth(scene);
        expectImagesMatch(r);
    }
}

TEST(Environment, A4096x2048HdrMapFitsAndAnOversizedOneIsRefusedNamingTheLimit) {
    auto render = [](int w, int h) {
        Scene scene = lookingAlong({1, 0, 0});
        scene.textures.push_back(Texture{"big", w, h, std::vector<glm::vec3>(std::size_t(w) * h, glm::vec3(0.5f))});
        scene.background = {.kind = BackgroundKind::Spherical, .map = 0};
        RenderStats stats;
        return renderVulkan(testDevice(), scene, buildSceneBvh(scene), {}, stats);
    };
    EXPECT_NEAR(render(4096, 2048).pixels[0].x, 0.5f, 1e-6f);  // 128 MiB of 16-byte texels
    // The texture texels are one texel buffer (lavapipe allows 2 GiB, more than a test should
    // allocate): a limit of 128 MiB (VITRUM_MAX_BUFFER_BYTES, docs/environment.md) holds that map
    // exactly, and one row more is refused, naming the buffer and the limit.
    const std::uint64_t limit = std::uint64_t(4096) * 2048 * 16;
    const std::uint64_t device = testDevice().properties().limits.maxTexelBufferElements * std::uint64_t(16);
    if (device < limit) GTEST_SKIP() << "this device's texel buffers hold less than 128 MiB";
    setenv("VITRUM_MAX_BUFFER_BYTES", std::to_string(limit).c_str(), 1);
    EXPECT_NEAR(render(4096, 2048).pixels[0].x, 0.5f, 1e-6f);
    try {
        render(4096, 2049);
        ADD_FAILURE() << "a 4096 x 2049 map cannot fit in a texel buffer of " << limit << " bytes";
    } catch (const InputError& e) {
        std::string message = e.what();
        EXPECT_NE(message.find("texture texels"), std::string::npos) << message;
        EXPECT_NE(message.find("per texel buffer of 16-byte texels (VITRUM_MAX_BUFFER_BYTES)"), std::string::npos)
            << message;
    }
    unsetenv("VITRUM_MAX_BUFFER_BYTES");
}

// A 2 x 2 quad on z = 0 facing +z, object "quad" of material 0, whose corners (-1, -1), (1, -1),
// (1, 1), (-1, 1) have the uvs `uv`.
void addTexturedQuad(Scene& scene, const std::array<glm::vec2, 4>& uv) {
    const glm::vec3 p[4] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    for (auto [a, b, c] : {std::array{0, 1, 2}, std::array{0, 2, 3}}) {
        Triangle t;
        t.position[0] = p[a], t.position[1] = p[b], t.position[2] = p[c];
        t.uv[0] = uv[a], t.uv[1] = uv[b], t.uv[2] = uv[c];
        t.normal[0] = t.normal[1] = t.normal[2] = glm::vec3(0, 0, 1);
        scene.triangles.push_back(t);
    }
    scene.objectNames = {"quad"};
}

// map_Kd on a quad: sampled at (u, 1 - v) with wrapping, bilinear or nearest, the same on both
// backends; the course's texture image as input.
TEST(MeshTexture, TexturedQuadMatchesReferenceWithBothFilters) {
    for (TextureFilter filter : {TextureFilter::Bilinear, TextureFilter::Nearest}) {
        Scene scene;
        scene.camera = {.from = {0, -3, 1.5f}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fovY = 50, .width = 96, .height = 72};
        scene.lights = {{.position = {1, -2, 3}, .colour = glm::vec3(1.0f)}};
        Image image = readImage(sharedPath("scenes/course/allied_avenger_6887/4150p04.jpg"));
        scene.textures.push_back(Texture{"4150p04.jpg", int(image.width), int(image.height), image.pixels});
        Material m;
        m.model = MaterialModel::Lambert;
        m.ambient = glm::vec3(0.05f);
        m.diffuseTexture = 0;
        scene.materials.push_back(m);
        // uvs that run to 2, so the texture repeats twice each way.
        addTexturedQuad(scene, {{{0, 0}, {2, 0}, {2, 2}, {0, 2}}});
        scene.settings.filter = filter;
        RenderPair r = renderBoth(scene);
        expectImagesMatch(r);
    }
}

// Wrapping left of and above the texture (u < 0, and v > 1, which samples at 1 - v < 0): a 5 x 3
// texture of distinct colours magnified over a quad whose uvs run from -1 to 1 and from 0 to 2,
// so a texel taken from the wrong column or row shows on many pixels. GLSL leaves % undefined for
// a negative operand (texture.glsl).
TEST(MeshTexture, TexelsLeftOfAndAboveTheTextureWrapAround) {
    std::vector<glm::vec3> texels;
    for (int i = 0; i < 15; ++i) texels.push_back(glm::vec3(float(i % 5) / 4.0f, float(i / 5) / 2.0f, float(i % 2)));
    for (TextureFilter filter : {TextureFilter::Bilinear, TextureFilter::Nearest}) {
        Scene scene;
        scene.camera = {.from = {0, 0, 3}, .at = {0, 0, 0}, .up = {0, 1, 0}, .fovY = 40, .width = 80, .height = 60};
        scene.lights = {{.position = {0, 0, 5}, .colour = glm::vec3(1.0f)}};
        scene.textures.push_back(Texture{"colours", 5, 3, texels});
        Material m;
        m.model = MaterialModel::Lambert;
        m.diffuseTexture = 0;
        scene.materials.push_back(m);
        addTexturedQuad(scene, {{{-1, 0}, {1, 0}, {1, 2}, {-1, 2}}});
        scene.settings.filter = filter;
        expectImagesMatch(renderBoth(scene));
    }
}

}  // namespace
}  // namespace vitrum::testing
