// Texture filtering and the background mappings of ../shared/docs/render-model.md, on the CPU
// reference's functions: hand-computed values, the axes and poles, and seams.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "cpu/texture_sampling.h"

namespace vitrum {
namespace {

using sampling::Address;
using Vec3 = glm::vec3;

Texture twoByTwo() {
    // a b
    // c d
    return Texture{"2x2", 2, 2, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}};
}

TEST(TextureSampling, BilinearEqualsHandComputationOn2x2) {
    Texture t = twoByTwo();
    auto at = [&](float u, float v) {
        return sampling::sampleTexture<float>(t, u, v, TextureFilter::Bilinear, Address::Clamp, Address::Clamp);
    };
    // Texel centres are at (i + 0.5) / 2: 0.25 and 0.75.
    EXPECT_EQ(at(0.25f, 0.25f), Vec3(0, 0, 0));
    EXPECT_EQ(at(0.75f, 0.75f), Vec3(0, 0, 1));
    // The centre of the image weighs all four by 1/4.
    glm::vec3 centre = at(0.5f, 0.5f);
    EXPECT_FLOAT_EQ(centre.x, 0.25f);
    EXPECT_FLOAT_EQ(centre.y, 0.25f);
    EXPECT_FLOAT_EQ(centre.z, 0.25f);
    // (u, v) = (0.375, 0.25): a quarter of the way from a to b: fx = 0.375 * 2 - 0.5 = 0.25.
    glm::vec3 q = at(0.375f, 0.25f);
    EXPECT_FLOAT_EQ(q.x, 0.25f);
    EXPECT_FLOAT_EQ(q.y, 0.0f);
    // (0.6, 0.4): fx = 0.7, fy = 0.3 -> a(0.3*0.7) + b(0.7*0.7) + c(0.3*0.3) + d(0.7*0.3).
    glm::vec3 g = at(0.6f, 0.4f);
    EXPECT_NEAR(g.x, 0.7f * 0.7f, 1e-6f);
    EXPECT_NEAR(g.y, 0.3f * 0.3f, 1e-6f);
    EXPECT_NEAR(g.z, 0.7f * 0.3f, 1e-6f);
    // Clamp: beyond the last texel centre the edge texel holds.
    EXPECT_EQ(at(0.0f, 0.0f), Vec3(0, 0, 0));
    EXPECT_EQ(at(1.0f, 1.0f), Vec3(0, 0, 1));
}

TEST(TextureSampling, WrapBlendsAcrossTheEdge) {
    Texture t = twoByTwo();
    // At u = 0 with wrapping, the sample lies halfway between the last and the first column.
    glm::vec3 w = sampling::sampleTexture<float>(t, 0.0f, 0.25f, TextureFilter::Bilinear, Address::Wrap, Address::Clamp);
    EXPECT_FLOAT_EQ(w.x, 0.5f);
    glm::vec3 c = sampling::sampleTexture<float>(t, 0.0f, 0.25f, TextureFilter::Bilinear, Address::Clamp, Address::Clamp);
    EXPECT_FLOAT_EQ(c.x, 0.0f);
}

TEST(TextureSampling, NearestPicksTheTexelContainingTheSample) {
    Texture t = twoByTwo();
    auto at = [&](float u, float v) {
        return sampling::sampleTexture<float>(t, u, v, TextureFilter::Nearest, Address::Clamp, Address::Clamp);
    };
    EXPECT_EQ(at(0.49f, 0.1f), Vec3(0, 0, 0));
    EXPECT_EQ(at(0.51f, 0.1f), Vec3(1, 0, 0));
    EXPECT_EQ(at(0.1f, 0.51f), Vec3(0, 1, 0));
    EXPECT_EQ(at(0.99f, 0.99f), Vec3(0, 0, 1));
}

TEST(SphericalMapping, AxesAndPolesHaveTheRenderModelsUv) {
    auto uv = [](Vec3 d) { return sampling::sphericalUv<float>(d); };
    // phi = atan2(y, x) + pi, u = 1 - phi / 2 pi, v = theta / pi.
    EXPECT_NEAR(uv({1, 0, 0}).x, 0.5f, 1e-6f);
    EXPECT_NEAR(uv({1, 0, 0}).y, 0.5f, 1e-6f);
    EXPECT_NEAR(uv({0, 1, 0}).x, 0.25f, 1e-6f);
    EXPECT_NEAR(uv({0, -1, 0}).x, 0.75f, 1e-6f);
    EXPECT_NEAR(uv({0, 0, 1}).y, 0.0f, 1e-6f);   // the top row
    EXPECT_NEAR(uv({0, 0, -1}).y, 1.0f, 1e-6f);  // the bottom row
    // -x is the seam: u = 0 from one side, 1 from the other.
    EXPECT_NEAR(uv(glm::normalize(Vec3(-1, 1e-4f, 0))).x, 0.0f, 1e-4f);
    EXPECT_NEAR(uv(glm::normalize(Vec3(-1, -1e-4f, 0))).x, 1.0f, 1e-4f);
}

// A map painted from a smooth function of direction must read back that function everywhere,
// to within the texel size, and show no seam at u = 0 / 1.
Vec3 smoothWorld(Vec3 d) { return 0.5f * d + 0.5f; }

TEST(SphericalMapping, MapReadsBackTheWorldItWasPaintedFromWithoutSeam) {
    const int w = 128, h = 64;
    Texture map{"world", w, h, {}};
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            double theta = (j + 0.5) / h * std::numbers::pi, phi = (1.0 - (i + 0.5) / w) * 2 * std::numbers::pi - std::numbers::pi;
            map.texels.push_back(smoothWorld(Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                                  std::cos(theta))));
        }
    std::mt19937 random(7);
    std::normal_distribution<float> gauss;
    for (int k = 0; k < 2000; ++k) {
        Vec3 d = glm::normalize(Vec3(gauss(random), gauss(random), gauss(random)));
        glm::vec2 uv = sampling::sphericalUv<float>(d);
        Vec3 value = sampling::sampleTexture<float>(map, uv.x, uv.y, TextureFilter::Bilinear, Address::Wrap, Address::Clamp);
        // One texel spans 2 pi / 128 = 0.05 rad; the function changes by at most 0.5 per radian.
        // Near the poles the clamped first/last row is half a texel (0.025 rad) away.
        EXPECT_NEAR(value.x, smoothWorld(d).x, 0.02f) << d.x << " " << d.y << " " << d.z;
        EXPECT_NEAR(value.y, smoothWorld(d).y, 0.02f);
        EXPECT_NEAR(value.z, smoothWorld(d).z, 0.02f);
    }
    // Just either side of the seam the two samples agree (wrapping, not clamping).
    for (float z : {-0.6f, 0.0f, 0.7f}) {
        Vec3 a = glm::normalize(Vec3(-1, 1e-5f, z)), b = glm::normalize(Vec3(-1, -1e-5f, z));
        auto sample = [&](Vec3 d) {
            glm::vec2 uv = sampling::sphericalUv<float>(d);
            return sampling::sampleTexture<float>(map, uv.x, uv.y, TextureFilter::Bilinear, Address::Wrap, Address::Clamp);
        };
        EXPECT_LT(glm::length(sample(a) - sample(b)), 1e-3f);
    }
}

TEST(CubeMapping, AxesPickTheirFacesAtTheCentre) {
    struct Case {
        Vec3 d;
        int face;
    } cases[] = {{{1, 0, 0}, 0}, {{-1, 0, 0}, 1}, {{0, 1, 0}, 2}, {{0, -1, 0}, 3}, {{0, 0, 1}, 4}, {{0, 0, -1}, 5}};
    for (const Case& c : cases) {
        auto cube = sampling::cubeUv<float>(c.d);
        EXPECT_EQ(cube.face, c.face);
        EXPECT_FLOAT_EQ(cube.u, 0.5f);
        EXPECT_FLOAT_EQ(cube.v, 0.5f);
    }
    // Ties go to x, then y (render model).
    EXPECT_EQ(sampling::cubeUv<float>({1, 1, 0}).face, 0);
    EXPECT_EQ(sampling::cubeUv<float>({0, -1, -1}).face, 3);
    // Orientation (render model table): on +x, u grows towards -y and v towards -z.
    auto px = sampling::cubeUv<float>(glm::normalize(Vec3(1, -0.5f, -0.25f)));
    EXPECT_FLOAT_EQ(px.u, 0.75f);
    EXPECT_FLOAT_EQ(px.v, 0.625f);
    // On +z (looking up while facing +y), v grows towards +y: the bottom row meets +y's top.
    auto pz = sampling::cubeUv<float>(glm::normalize(Vec3(0.5f, 0.5f, 1)));
    EXPECT_FLOAT_EQ(pz.u, 0.75f);
    EXPECT_FLOAT_EQ(pz.v, 0.75f);
}

TEST(CubeMapping, FacesMeetWithoutSeams) {
    // Six faces painted from the smooth world; samples on either side of each of the 12 edges must
    // agree to within one texel's change of the function.
    const int size = 16;
    Scene scene;
    scene.background.kind = BackgroundKind::Cube;
    scene.background.map = 0;
    auto direction = [](int face, float a, float b) {
        switch (face) {
            case 0: return Vec3(1, -a, -b);
            case 1: return Vec3(-1, a, -b);
            case 2: return Vec3(a, 1, -b);
            case 3: return Vec3(-a, -1, -b);
            case 4: return Vec3(a, b, 1);
            default: return Vec3(a, -b, -1);
        }
    };
    for (int face = 0; face < 6; ++face) {
        Texture t{"face", size, size, {}};
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i)
                t.texels.push_back(smoothWorld(glm::normalize(
                    direction(face, 2.0f * (i + 0.5f) / size - 1.0f, 2.0f * (j + 0.5f) / size - 1.0f))));
        scene.textures.push_back(t);
    }
    std::mt19937 random(11);
    std::uniform_real_distribution<float> along(-0.95f, 0.95f);
    int checked = 0;
    for (int k = 0; k < 3000; ++k) {
        // A point on an edge of the unit cube: two coordinates at +-1, one free.
        Vec3 p(along(random), along(random), along(random));
        int free = k % 3;
        for (int a = 0; a < 3; ++a)
            if (a != free) p[a] = (random() & 1) ? 1.0f : -1.0f;
        for (int a = 0; a < 3; ++a) {
            if (a == free) continue;
            Vec3 inside = p, outside = p;
            inside[a] *= 1.0f - 1e-4f;   // just onto the other face
            outside[a] *= 1.0f + 1e-4f;  // just onto this axis's face
            Vec3 x = sampling::backgroundRadiance<float>(scene, glm::normalize(inside));
            Vec3 y = sampling::backgroundRadiance<float>(scene, glm::normalize(outside));
            ASSERT_NE(sampling::cubeUv<float>(glm::normalize(inside)).face,
                      sampling::cubeUv<float>(glm::normalize(outside)).face);
            // Clamp to edge holds the edge texel for half a texel on each side: at most one texel
            // (2/16 of the face, 0.09 rad at the edge) of change, 0.5 per radian: 0.05.
            EXPECT_LT(glm::length(x - y), 0.05f) << p.x << " " << p.y << " " << p.z;
            ++checked;
        }
    }
    EXPECT_EQ(checked, 6000);
}

}  // namespace
}  // namespace vitrum
