// Thin-walled glass (docs/render-model-decisions.md, "Thin-walled glass"): a pane of no thickness
// reflects R' = 2R / (1 + R) and transmits T' = (1 - R) / (1 + R) of the light, R one face's
// Fresnel reflectance, the transmission undeviated and tinted by its Kd; an index-matched pane only
// tints. Each value is worked out here from the Fresnel formulas in double, on both backends.
#include "gpu_test_support.h"

#include <cmath>
#include <numbers>

#include "../support/scenes_in_code.h"

namespace vitrum::testing {
namespace {

Material thinGlass(float ior, glm::vec3 tint) {
    return makeMaterial(MaterialModel::ThinGlass, {}, tint, {}, 1.0f, ior);
}

// baseScene's camera (from -y, looking at the origin) before a pane of `material` through the
// origin, turned `degrees` about z from facing the camera, filling the view; a white background,
// so that whatever the pane reflects or transmits returns 1.
Scene paneScene(const Material& material, double degrees) {
    Scene scene = baseScene();
    scene.materials.push_back(material);
    scene.objectNames = {"pane"};
    const double a = degrees * std::numbers::pi / 180.0;
    const glm::vec3 u(float(std::cos(a)), float(std::sin(a)), 0.0f), v(0.0f, 0.0f, 1.0f);
    const float h = 6.0f;
    scene.triangles.push_back(makeTriangle(-h * u - h * v, h * u - h * v, h * u + h * v, 0, 0));
    scene.triangles.push_back(makeTriangle(-h * u - h * v, h * u + h * v, -h * u + h * v, 0, 0));
    scene.background.colour = glm::vec3(1.0f);
    scene.settings.maxDepth = 2;
    return scene;
}

// One face's reflectance from n1 to n2 at incidence cosI, as the render model defines the models
// (the lecture's formulas, written again here in double).
double faceReflectance(FresnelModel model, double n1, double n2, double cosI) {
    const double sin2t = (n1 / n2) * (n1 / n2) * (1.0 - cosI * cosI);
    if (sin2t > 1.0) return 1.0;
    const double cosT = std::sqrt(1.0 - sin2t);
    if (model == FresnelModel::Exact) {
        const double rs = (n2 * cosT - n1 * cosI) / (n2 * cosT + n1 * cosI);
        const double rp = (n2 * cosI - n1 * cosT) / (n2 * cosI + n1 * cosT);
        return 0.5 * (rs * rs + rp * rp);
    }
    const double f0 = std::pow((n1 - n2) / (n1 + n2), 2.0);
    return f0 + (1.0 - f0) * std::pow(1.0 - (n1 <= n2 ? cosI : cosT), 5.0);
}

// Head-on, a pane of Ni 1.5 reflects R' = 0.08 / 1.04 (one face: 0.04) and transmits T' = 0.96 /
// 1.04 tinted: every pixel of the white background seen through it is R' + T' Kd, channel by
// channel (one face's values, 0.04 + 0.96 Kd, differ by 0.0185 at Kd 0.5). One reflection and
// one transmission a pixel.
TEST(ThinGlass, APaneHeadOnReflectsAndTransmitsWhatItsTwoFacesSum) {
    const glm::dvec3 tint(1.0, 0.5, 0.25);
    Scene scene = paneScene(thinGlass(1.5f, glm::vec3(tint)), 0.0);
    scene.camera.fovY = 1.0f;  // every ray within a degree of normal incidence: R within 1e-6 of R0
    scene.settings.fresnel = FresnelModel::Exact;
    const RenderPair r = renderBoth(scene);
    const double reflected = 0.08 / 1.04, transmitted = 0.96 / 1.04;
    for (const Image* image : {&r.gpu, &r.cpu})
        for (const glm::vec3& pixel : image->pixels)
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(pixel[c], reflected + transmitted * tint[c], 1e-5) << c;
    for (const RenderStats* stats : {&r.gpuStats, &r.cpuStats}) {
        EXPECT_EQ(stats->reflectionRays, 81u);
        EXPECT_EQ(stats->refractionRays, 81u);
        EXPECT_EQ(stats->totalInternalReflections, 0u);
    }
}

// The pane's values are those of a real slab of its glass, its inner reflections traced: head-on
// under a white sky, with a black wall behind the camera taking every reflection, a clear slab
// 0.01 thick at max_depth 30 shows its Fresnel series (1 - R)^2 (1 + R^2 + R^4 + ...) =
// (1 - R) / (1 + R), the pane T' at once, a pane of index 2.4 too (R 0.17).
TEST(ThinGlass, APaneTransmitsWhatASlabOfItsGlassTransmitsThroughItsInnerReflections) {
    for (const float ior : {1.5f, 2.4f}) {
        SCOPED_TRACE(ior);
        Scene pane = paneScene(thinGlass(ior, glm::vec3(1.0f)), 0.0);
        Scene slab = pane;
        slab.triangles.clear();
        slab.materials = {makeMaterial(MaterialModel::Glass, {}, {}, {}, 1.0f, ior)};
        slab.objectNames = {"slab"};
        addBox(slab, glm::vec3(-6.0f, -0.005f, -6.0f), glm::vec3(6.0f, 0.005f, 6.0f), 0, 0);
        for (Scene* scene : {&pane, &slab}) {
            scene->camera.fovY = 1.0f;
            scene->settings.maxDepth = 30;
            scene->settings.fresnel = FresnelModel::Exact;
            scene->materials.push_back(makeMaterial(MaterialModel::Lambert, {}, glm::vec3(0.0f)));
            scene->objectNames.push_back("black wall");
            addSquareY(*scene, {0, -10, 0}, 50.0f, false, std::uint32_t(scene->materials.size() - 1),
                       std::uint32_t(scene->objectNames.size() - 1));
        }
        const RenderPair p = renderBoth(pane);
        const RenderPair s = renderBoth(slab);
        const double r = std::pow((ior - 1.0) / (ior + 1.0), 2.0), expected = (1.0 - r) / (1.0 + r);
        for (const Image* image : {&p.gpu, &p.cpu, &s.gpu, &s.cpu})
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(image->at(4, 4)[c], expected, 2e-5);
        EXPECT_GT(s.gpuStats.maxRayDepth, 10u);  // the slab's series, traced
        EXPECT_LE(p.gpuStats.maxRayDepth, 2u);   // the pane's, at once
    }
}

// At 0 to 80 degrees, the centre pixel of a black pane (its transmission tinted away) is R' of
// the face's R, with each Fresnel model; in a medium of index 1.5 around a pane of index 1 the
// face reflects totally beyond 41.8 degrees: R' = 1, nothing transmitted, the reflection counted
// as total internal reflection.
TEST(ThinGlass, ACentrePixelIsThePanesReflectanceAtEveryAngleAndModel) {
    struct Case {
        double degrees;
        FresnelModel model;
        float paneIor, mediumIor;
    };
    for (const Case& c : {Case{0, FresnelModel::Schlick, 1.5f, 1.0f}, Case{30, FresnelModel::Schlick, 1.5f, 1.0f},
                          Case{60, FresnelModel::Schlick, 1.5f, 1.0f}, Case{80, FresnelModel::Schlick, 2.4f, 1.0f},
                          Case{60, FresnelModel::Exact, 1.5f, 1.0f}, Case{80, FresnelModel::Exact, 1.33f, 1.0f},
                          Case{30, FresnelModel::Exact, 1.0f, 1.5f}, Case{60, FresnelModel::Exact, 1.0f, 1.5f},
                          Case{60, FresnelModel::Schlick, 1.0f, 1.5f}}) {
        SCOPED_TRACE(std::to_string(c.degrees) + " degrees, pane " + std::to_string(c.paneIor) + " in " +
                     std::to_string(c.mediumIor));
        Scene scene = paneScene(thinGlass(c.paneIor, glm::vec3(0.0f)), c.degrees);
        scene.settings.fresnel = c.model;
        scene.camera.fovY = 1.0f;  // every ray within half a degree of the centre's
        scene.airIor = c.mediumIor;
        const RenderPair r = renderBoth(scene);
        const double face =
            faceReflectance(c.model, c.mediumIor, c.paneIor, std::cos(c.degrees * std::numbers::pi / 180.0));
        const double pane = 2.0 * face / (1.0 + face);
        for (const Image* image : {&r.gpu, &r.cpu})
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(image->at(4, 4)[k], pane, 2e-5);
        const bool total = face == 1.0;
        EXPECT_EQ(r.gpuStats.totalInternalReflections > 0, total);
        EXPECT_EQ(r.cpuStats.totalInternalReflections > 0, total);
        EXPECT_EQ(r.gpuStats.refractionRays, r.cpuStats.refractionRays);
    }
}

// A pane of the index of the medium around it has no optical interface: the ray goes on at its
// depth (render model, "Index-matched interface"), through the tint, so at max_depth 1, where no
// child is traced, it shows the background times Kd; a pane of another index shows black there,
// its children cut by the depth limit.
TEST(ThinGlass, AnIndexMatchedPaneOnlyTintsAndCostsNoDepth) {
    const glm::vec3 tint(0.2f, 0.6f, 1.0f);
    Scene matched = paneScene(thinGlass(1.0f, tint), 25.0);
    matched.settings.maxDepth = 1;
    const RenderPair m = renderBoth(matched);
    for (const Image* image : {&m.gpu, &m.cpu})
        for (const glm::vec3& pixel : image->pixels)
            for (int c = 0; c < 3; ++c) ASSERT_EQ(pixel[c], tint[c]) << c;
    EXPECT_EQ(m.gpuStats.depthLimitHits, 0u);
    EXPECT_EQ(m.cpuStats.depthLimitHits, 0u);

    Scene other = paneScene(thinGlass(1.5f, tint), 25.0);
    other.settings.maxDepth = 1;
    const RenderPair o = renderBoth(other);
    for (const Image* image : {&o.gpu, &o.cpu})
        for (const glm::vec3& pixel : image->pixels) ASSERT_EQ(pixel, glm::vec3(0.0f));
    EXPECT_EQ(o.gpuStats.depthLimitHits, 2u * 81u);  // its reflection and its transmission
    EXPECT_EQ(o.cpuStats.depthLimitHits, 2u * 81u);
}

// Thin glass has no medium: a ray through a hollow thin-glass box keeps the air's stack (the
// box's Ni never becomes the medium), so a solid glass block inside it looks as it does without
// the box, up to the box's panes' R' and tint, which an index-matched box (Ni 1, white) removes
// entirely: the image is the block's alone, bit for bit (under a constant background, where a
// ray's colour depends on its directions, not on where the box's faces moved its origin).
TEST(ThinGlass, AHollowThinGlassBoxIsNoMedium) {
    Scene alone = baseScene();
    alone.materials = {makeMaterial(MaterialModel::Glass, {}, {}, {}, 1.0f, 1.5f), thinGlass(1.0f, glm::vec3(1.0f))};
    alone.objectNames = {"block"};
    // Off the camera's axis, so that no ray meets an edge of the block exactly: a reflection off
    // the top face there starts beyond the side face and travels outside with the block's medium,
    // which the thin box's walls would then show (measured with the box centred).
    addBox(alone, glm::vec3(-1.0f, -0.9f, -0.8f), glm::vec3(0.9f, 1.1f, 1.2f), 0, 0);
    alone.background.colour = glm::vec3(0.3f, 0.6f, 0.9f);
    Scene boxed = alone;
    boxed.objectNames.push_back("box");
    addBox(boxed, glm::vec3(-2.0f), glm::vec3(2.0f), 1, 1);
    const RenderPair a = renderBoth(alone);
    const RenderPair b = renderBoth(boxed);
    EXPECT_EQ(differingPixels(a.gpu, b.gpu), 0u);
    EXPECT_EQ(differingPixels(a.cpu, b.cpu), 0u);
    EXPECT_EQ(b.gpuStats.inconsistentMedia, 0u);
    EXPECT_EQ(b.cpuStats.inconsistentMedia, 0u);
    // The block's medium alone: were the box a medium (of the air's index, so the same image), a
    // ray in the block would be two deep.
    EXPECT_EQ(b.gpuStats.maxMediumDepth, 1u);
    EXPECT_EQ(b.cpuStats.maxMediumDepth, 1u);
}

}  // namespace
}  // namespace vitrum::testing
