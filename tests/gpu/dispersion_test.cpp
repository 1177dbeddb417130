// Dispersion on both backends (render-model-decisions.md, "Dispersion"): white light through a
// slab at normal incidence against the Fresnel series of each wavelength sample, a dispersive prism
// GPU against CPU, a glass of a huge Abbe number as the glass without dispersion, and the energy
// of every pixel under a white sky.
#include "gpu_test_support.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "render_model/dispersion.h"
#include "../support/scenes_in_code.h"

namespace vitrum::testing {
namespace {

constexpr float kFlintNd = 1.7f, kFlintAbbe = 20.0f;

// One pixel looking along +y through a slab 0.5 thick at normal incidence, under a spherical sky
// that is white where y > 0 (beyond the slab) and black where y < 0 (behind the camera).
Scene slabUnderHalfSky(float abbe, std::uint32_t wavelengths) {
    Scene scene;
    Material glass = makeMaterial(MaterialModel::Glass, glm::vec3(0), glm::vec3(0), glm::vec3(0), 1.0f, kFlintNd);
    glass.abbe = abbe;
    scene.materials = {glass};
    scene.objectNames = {"slab"};
    addBox(scene, {-1.0f, -0.25f, -1.0f}, {1.0f, 0.25f, 1.0f}, 0, 0);
    scene.camera.from = {0.0f, -5.0f, 0.0f};
    scene.camera.at = {0.0f, 0.0f, 0.0f};
    scene.camera.width = scene.camera.height = 1;
    // Spherical map (render model): u = 1 - (atan2(y, x) + pi) / (2 pi), so y > 0 is u < 1/2.
    Texture sky;
    sky.width = 8;
    sky.height = 4;
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 8; ++column) sky.texels.push_back(glm::vec3(column < 4 ? 1.0f : 0.0f));
    scene.textures = {sky};
    scene.background.kind = BackgroundKind::Spherical;
    scene.background.map = 0;
    scene.settings.wavelengths = wavelengths;
    scene.settings.maxDepth = 16;  // the slab's internal reflections to R^14
    return scene;
}

// Each sample k's light crosses the slab with (1 - R_k)^2 (R_k^2)^j over j internal round trips:
// (1 - R_k) / (1 + R_k), R_k = ((n_k - 1) / (n_k + 1))^2 (Schlick at normal incidence is F0); the
// light reflected back meets the black half. The pixel is the samples' weighted sum.
TEST(Dispersion, WhiteThroughASlabIsEachWavelengthsFresnelSeries) {
    constexpr std::uint32_t kSamples = 8;
    const RenderPair dispersive = renderBoth(slabUnderHalfSky(kFlintAbbe, kSamples));
    ASSERT_TRUE(dispersive.gpuStats.kernel->dispersion);
    const std::vector<WavelengthSample> samples = wavelengthSamples(kSamples);
    const float b = float(cauchyB(kFlintNd, kFlintAbbe));
    glm::dvec3 expected(0.0);
    double lowest = 1.0, highest = 0.0;
    for (const WavelengthSample& s : samples) {
        const double n = double(dispersedIor(kFlintNd, b, s.offset));
        const double r = std::pow((n - 1.0) / (n + 1.0), 2.0);
        expected += glm::dvec3(s.weight) * ((1.0 - r) / (1.0 + r));
        lowest = std::min(lowest, (1.0 - r) / (1.0 + r));
        highest = std::max(highest, (1.0 - r) / (1.0 + r));
    }
    for (const Image* image : {&dispersive.gpu, &dispersive.cpu}) {
        const glm::vec3 pixel = image->at(0, 0);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(pixel[c], expected[c], 2e-5) << c;
        // White up to the Fresnel terms' change with the wavelength: the channels lie closer
        // together than the samples' transmittances.
        EXPECT_LT(std::max({pixel.x, pixel.y, pixel.z}) - std::min({pixel.x, pixel.y, pixel.z}), highest - lowest);
    }
    // The pixel's one white ray splits where it meets the slab, once, and its samples do not.
    EXPECT_EQ(dispersive.gpuStats.dispersionSplits, 1u);
    EXPECT_EQ(dispersive.cpuStats.dispersionSplits, 1u);
    // Without dispersion: n_d for every channel.
    const RenderPair plain = renderBoth(slabUnderHalfSky(0.0f, kSamples));
    ASSERT_FALSE(plain.gpuStats.kernel->dispersion);
    EXPECT_EQ(plain.gpuStats.dispersionSplits, 0u);
    EXPECT_EQ(plain.cpuStats.dispersionSplits, 0u);
    const double r = std::pow((double(kFlintNd) - 1.0) / (double(kFlintNd) + 1.0), 2.0);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(plain.gpu.at(0, 0)[c], (1.0 - r) / (1.0 + r), 2e-6);
}

// scenes/prism.json with its prism of dense flint.
Scene dispersivePrism(float abbe, std::uint32_t wavelengths) {
    Scene scene = loadScene(sourcePath("scenes/prism.json"));
    scene.camera.width = 160;
    scene.camera.height = 120;
    for (Material& m : scene.materials)
        if (m.model == MaterialModel::Glass) {
            m.ior = kFlintNd;
            m.abbe = abbe;
        }
    scene.settings.wavelengths = wavelengths;
    return scene;
}

TEST(Dispersion, PrismRendersAsTheReferenceOnBothBackends) {
    const RenderPair r = renderBoth(dispersivePrism(kFlintAbbe, 8));
    ASSERT_TRUE(r.gpuStats.kernel->dispersion);
    expectImagesMatch(r);
    // Every ray that met the prism split into 8: far more refraction than without dispersion.
    const RenderPair plain = renderBoth(dispersivePrism(0.0f, 8));
    EXPECT_GT(r.gpuStats.refractionRays, 4 * plain.gpuStats.refractionRays);
    EXPECT_EQ(r.gpuStats.refractionRays, r.cpuStats.refractionRays);
}

// Crown glass glued to dispersive flint (tests/core's Dispersion.ARayEnteringADispersiveGlass...):
// rays cross from one into the other, splitting at the shared face on both backends alike.
TEST(Dispersion, GluedSlabsRenderAsTheReferenceOnBothBackends) {
    Scene scene = slabUnderHalfSky(kFlintAbbe, 8);
    scene.triangles.clear();
    const Material crown = makeMaterial(MaterialModel::Glass, glm::vec3(0), glm::vec3(0), glm::vec3(0), 1.0f, 1.5f);
    scene.materials.push_back(crown);
    scene.objectNames = {"flint", "crown"};
    addBox(scene, {-1.0f, -0.5f, -1.0f}, {1.0f, 0.0f, 1.0f}, 1, 1);
    addBox(scene, {-1.0f, 0.000001f, -1.0f}, {1.0f, 0.5f, 1.0f}, 0, 0);
    scene.camera.from = {-1.5f, -4.0f, 1.2f};
    scene.camera.width = 48;
    scene.camera.height = 32;
    scene.settings.maxDepth = 6;
    const RenderPair r = renderBoth(scene);
    ASSERT_TRUE(r.gpuStats.kernel->dispersion);
    ASSERT_TRUE(r.gpuStats.features.touchingMediaPossible);
    expectImagesMatch(r);
    EXPECT_EQ(r.gpuStats.refractionRays, r.cpuStats.refractionRays);
    EXPECT_GT(r.gpuStats.touchingInterfaces, 0u);
}

// The general kernel (--no-specialize) decides dispersion at run time: the same image, bit for
// bit, with a small iteration budget so that pixels are suspended and resumed mid-split.
TEST(Dispersion, GeneralKernelRendersTheSameImage) {
    const Scene scene = dispersivePrism(kFlintAbbe, 5);
    const Bvh bvh = buildSceneBvh(scene);
    RenderStats general, specialized;
    VulkanRenderOptions options{.iterationBudget = 200};
    options.specialize = false;
    const Image a = renderVulkan(testDevice(), scene, bvh, options, general);
    options.specialize = true;
    const Image b = renderVulkan(testDevice(), scene, bvh, options, specialized);
    ASSERT_TRUE(specialized.kernel->dispersion);
    EXPECT_EQ(general.refractionRays, specialized.refractionRays);
    EXPECT_EQ(general.rayStackOverflows, 0u);
    EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec3)), 0);
}

// A huge V_d is almost no dispersion: every sample sees n_d, and the weights sum to white.
TEST(Dispersion, HugeAbbeNumberRendersAsNoDispersion) {
    const RenderPair huge = renderBoth(dispersivePrism(1e9f, 8));
    const RenderPair none = renderBoth(dispersivePrism(0.0f, 8));
    for (const bool gpu : {true, false}) {
        SCOPED_TRACE(gpu ? "GPU" : "CPU");
        const ImageDiff d = diffImages(gpu ? huge.gpu : huge.cpu, gpu ? none.gpu : none.cpu);
        EXPECT_EQ(d.shareOver005, 0.0);
        EXPECT_LT(d.meanAbsError, 1e-5) << "rmse " << d.rmse;
    }
}

// Energy: under a white sky and no light, every path ends in the sky (1) or in black, and the
// samples' weights sum to the ray's: no pixel's luminance (CIE Y of linear sRGB) exceeds 1, though
// single channels may leave [0, 1] where the spectrum is narrow.
TEST(Dispersion, NoPixelIsBrighterThanAWhiteSky) {
    Scene scene = dispersivePrism(kFlintAbbe, 16);
    scene.lights.clear();
    scene.background = Background{};
    scene.background.colour = glm::vec3(1.0f);
    const RenderPair r = renderBoth(scene);
    for (const Image* image : {&r.gpu, &r.cpu}) {
        float brightest = 0.0f;
        for (const glm::vec3& p : image->pixels) brightest = std::max(brightest, 0.2126f * p.x + 0.7152f * p.y + 0.0722f * p.z);
        EXPECT_LE(brightest, 1.0f + 1e-5f);
        EXPECT_GT(brightest, 0.9f);
    }
    expectImagesMatch(r);
}

}  // namespace
}  // namespace vitrum::testing
