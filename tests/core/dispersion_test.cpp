// Dispersion (render-model-decisions.md, "Dispersion"): Cauchy's fit to n_d and V_d, the
// wavelength samples and their weights, the scene keys, and the prism's deviation per wavelength
// in the CPU reference's own rays against the minimum-deviation formula.
#include "render_model/dispersion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "analysis/scene_features.h"
#include "bvh/bvh.h"
#include "cpu/reference_renderer.h"
#include "scene/scene_loader.h"
#include "../support/scenes_in_code.h"
#include "../support/temporary_folder_test.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

// n(lambda) = A + B / lambda^2 with A = n_d - B / lambda_d^2.
double cauchy(double nd, double b, double micrometres) {
    return nd - b / (kLambdaD * kLambdaD) + b / (micrometres * micrometres);
}

// The fit gives back what it was fitted to: n_d at the d line, and (n_d - 1) / (n_F - n_C) = V_d
// (Schott's N-BK7: n_d 1.5168, V_d 64.17; a dense flint: 1.7847, 25.7).
TEST(Dispersion, CauchyFitGivesBackNdAndTheAbbeNumber) {
    for (const auto& [nd, abbe] : {std::pair{1.5168, 64.17}, std::pair{1.7847, 25.7}}) {
        const double b = cauchyB(nd, abbe);
        EXPECT_GT(b, 0.0);
        EXPECT_NEAR(cauchy(nd, b, kLambdaD), nd, 1e-15);
        EXPECT_NEAR((nd - 1.0) / (cauchy(nd, b, kLambdaF) - cauchy(nd, b, kLambdaC)), abbe, 1e-9);
        // The renderers' form: n_d plus B times the sample's offset; n_d where lambda = lambda_d.
        EXPECT_EQ(dispersedIor(float(nd), float(b), 0.0f), float(nd));
    }
    EXPECT_EQ(cauchyB(1.5, 0.0), 0.0);  // no V_d: no dispersion
}

// The weights of the samples sum to white in every channel (an equal-energy spectrum is white),
// each sample carries a positive luminance, the samples run up the visible range, and three
// samples are a blue, a green and a red band.
TEST(Dispersion, WavelengthSamplesSumToWhite) {
    for (std::uint32_t n : {1u, 2u, 3u, 8u, 16u, 64u}) {
        SCOPED_TRACE(n);
        const std::vector<WavelengthSample> samples = wavelengthSamples(n);
        ASSERT_EQ(samples.size(), n);
        glm::dvec3 sum(0.0);
        float previous = 380.0f;
        for (const WavelengthSample& s : samples) {
            sum += glm::dvec3(s.weight);
            EXPECT_GT(s.nanometres, previous);
            EXPECT_LT(s.nanometres, 780.0f);
            previous = s.nanometres;
            EXPECT_GT(0.2126 * s.weight.x + 0.7152 * s.weight.y + 0.0722 * s.weight.z, 0.0);
            const double micrometres = double(s.nanometres) * 1e-3;
            EXPECT_NEAR(s.offset, 1.0 / (micrometres * micrometres) - 1.0 / (kLambdaD * kLambdaD), 1e-6);
        }
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], 1.0, 1e-6);
    }
    EXPECT_EQ(wavelengthSamples(1)[0].weight, glm::vec3(1.0f));
    const std::vector<WavelengthSample> three = wavelengthSamples(3);
    EXPECT_GT(three[0].weight.z, std::max(three[0].weight.x, three[0].weight.y));  // blue
    EXPECT_GT(three[1].weight.y, std::max(three[1].weight.x, three[1].weight.z));  // green
    EXPECT_GT(three[2].weight.x, std::max(three[2].weight.y, three[2].weight.z));  // red
}

class DispersionScene : public testing::TemporaryFolderTest {};

// MTL `Vd` is the Abbe number; glTF's KHR_materials_dispersion is 20 / V_d.
TEST_F(DispersionScene, AbbeNumberFromMtlAndGltf) {
    std::ofstream(dir_ / "prism.obj") << "mtllib prism.mtl\nusemtl flint\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(dir_ / "prism.mtl") << "newmtl flint\nNi 1.75\nVd 25\nshader 4\n";
    const Scene obj = loadScene(dir_ / "prism.obj");
    EXPECT_EQ(obj.materials[0].abbe, 25.0f);
    EXPECT_EQ(obj.materials[0].ior, 1.75f);
    std::ofstream(dir_ / "prism.gltf") << R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
      "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
      "materials": [{"extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                                    "KHR_materials_volume": {"thicknessFactor": 1},
                                    "KHR_materials_dispersion": {"dispersion": 0.5}}}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
      "nodes": [{"mesh": 0}]})";
    const Scene gltf = loadScene(dir_ / "prism.gltf");
    EXPECT_EQ(gltf.materials[0].abbe, 40.0f);
}

// A prism of apex angle A with its edge along x, turned so that a ray along +y passes it
// symmetrically at the index n: at minimum deviation, 2 asin(n sin(A / 2)) - A (Born and Wolf,
// "Principles of Optics", 4.7.2). The CPU reference's rays (in double) of a 1-pixel camera looking
// along +y: the ray leaving the second face, one a wavelength sample in the samples' order, is
// deviated by exactly that for its sample's index, and the other samples' by more.
TEST(Dispersion, PrismDeviatesEachWavelengthByTheMinimumDeviationFormula) {
    constexpr double kApex = std::numbers::pi / 3.0, kNd = 1.7, kAbbe = 20.0;
    constexpr std::uint32_t kSamples = 5;
    const std::vector<WavelengthSample> samples = wavelengthSamples(kSamples);
    const double b = double(float(cauchyB(kNd, kAbbe)));
    auto indexOf = [&](std::uint32_t k) { return double(dispersedIor(float(kNd), float(b), samples[k].offset)); };
    auto minimumDeviation = [&](double n) { return 2.0 * std::asin(n * std::sin(kApex / 2.0)) - kApex; };
    for (std::uint32_t symmetric = 0; symmetric < kSamples; symmetric += 2) {
        SCOPED_TRACE(symmetric);
        // In the y-z plane: the prism's base faces -z, its apex +z; turned about x by the angle
        // that makes sample `symmetric`'s ray inside run parallel to the base.
        const double incidence = (minimumDeviation(indexOf(symmetric)) + kApex) / 2.0;
        const double turn = kApex / 2.0 - incidence;  // unturned, a ray along +y meets face 1 at A / 2
        auto rotate = [&](glm::dvec2 p) {             // (y, z) about the origin
            return glm::dvec2(p.x * std::cos(turn) - p.y * std::sin(turn), p.x * std::sin(turn) + p.y * std::cos(turn));
        };
        const double h = 1.0;
        const glm::dvec2 apex = rotate({0.0, h}), left = rotate({-h * std::tan(kApex / 2.0) * 2.0, -h}),
                         right = rotate({h * std::tan(kApex / 2.0) * 2.0, -h});
        Scene scene;
        Material glass = testing::makeMaterial(MaterialModel::Glass, glm::vec3(0), glm::vec3(0), glm::vec3(0), 1.0f, float(kNd));
        glass.abbe = float(kAbbe);
        scene.materials = {glass};
        scene.objectNames = {"prism"};
        const double x0 = -5.0, x1 = 5.0;
        auto at = [](double x, glm::dvec2 yz) { return glm::vec3(float(x), float(yz.x), float(yz.y)); };
        const glm::dvec2 corners[3] = {left, apex, right};
        for (int f = 0; f < 3; ++f) {  // the three side faces, two triangles each, outward wound
            const glm::dvec2 a = corners[f], c = corners[(f + 1) % 3];
            const glm::dvec2 mid = (a + c) / 2.0, centre = (left + apex + right) / 3.0;
            std::array<glm::vec3, 4> q = {at(x0, a), at(x1, a), at(x1, c), at(x0, c)};
            Triangle t1 = testing::makeTriangle(q[0], q[1], q[2], 0, 0), t2 = testing::makeTriangle(q[0], q[2], q[3], 0, 0);
            const glm::vec3 out = at(0.0, mid - centre);
            for (Triangle* t : {&t1, &t2})
                if (glm::dot(t->normal[0], out) < 0.0f) {
                    std::swap(t->position[1], t->position[2]);
                    for (auto& n : t->normal) n = -n;
                }
            scene.triangles.push_back(t1);
            scene.triangles.push_back(t2);
        }
        for (double x : {x0, x1}) {  // the two ends
            Triangle t = testing::makeTriangle(at(x, left), at(x, apex), at(x, right), 0, 0);
            if ((t.normal[0].x > 0.0f) != (x > 0.0)) {
                std::swap(t.position[1], t.position[2]);
                for (auto& n : t.normal) n = -n;
            }
            scene.triangles.push_back(t);
        }
        scene.camera.from = {0.0f, -20.0f, 0.0f};
        scene.camera.at = {0.0f, 0.0f, 0.0f};
        scene.camera.width = scene.camera.height = 1;
        scene.lights.clear();
        scene.settings.wavelengths = kSamples;
        scene.settings.maxDepth = 3;  // primary, into the prism, out of it
        const Bvh bvh = buildSceneBvh(scene);
        std::vector<TracedRay> rays;
        RenderStats stats;
        renderReference(scene, bvh, {.doublePrecision = true, .threads = 1, .tracedRays = &rays}, stats);
        // Leaving the second face: rays that start on the far side of the prism (y > 0 of the
        // apex's line) heading away from it, in the order traced: sample 0's first.
        std::vector<glm::dvec3> leaving;
        for (const TracedRay& r : rays)
            if (r.origin.y > 0.05f && r.direction.y > 0.0f && !r.anyHit) leaving.push_back(glm::normalize(glm::dvec3(r.direction)));
        ASSERT_EQ(leaving.size(), kSamples);
        for (std::uint32_t k = 0; k < kSamples; ++k) {
            const double deviation = std::acos(std::clamp(leaving[k].y, -1.0, 1.0));
            EXPECT_LT(leaving[k].z, 0.0);  // towards the base
            if (k == symmetric) {
                EXPECT_NEAR(deviation, minimumDeviation(indexOf(k)), 2e-6) << k;
            } else {
                EXPECT_GT(deviation, minimumDeviation(indexOf(k)) - 2e-6) << k;
            }
            if (k > 0) {
                EXPECT_LT(std::acos(leaving[k].y), std::acos(leaving[k - 1].y)) << "red bends less than blue";
            }
        }
    }
}

// Two glass slabs glued face to face, crown (n 1.5, no dispersion) then flint (n_d 1.7, V_d 20),
// met at 30 degrees from air: the flint's medium begins at the shared face, so a white ray splits
// there (render-model-decisions.md, "Dispersion"), and every wavelength sample leaves the second
// slab parallel to the light that came in (Snell's law through parallel faces: sin theta_out =
// n_flint(lambda) sin theta_flint = n_crown sin theta_crown = sin theta_in), displaced sideways by
// its own index. Split at the flint's far face instead, the samples would leave fanned out. The
// flint's face lies 1e-6 beyond the crown's, within the touching distance, so that the ray's
// nearest hit at the interface is the crown's, as rounding may make it anywhere.
Scene gluedSlabs(std::uint32_t wavelengths) {
    Scene scene;
    const Material crown = testing::makeMaterial(MaterialModel::Glass, glm::vec3(0), glm::vec3(0), glm::vec3(0), 1.0f, 1.5f);
    Material flint = testing::makeMaterial(MaterialModel::Glass, glm::vec3(0), glm::vec3(0), glm::vec3(0), 1.0f, 1.7f);
    flint.abbe = 20.0f;
    scene.materials = {crown, flint};
    scene.objectNames = {"crown", "flint"};
    testing::addBox(scene, {-5.0f, 0.0f, -5.0f}, {5.0f, 1.0f, 5.0f}, 0, 0);
    testing::addBox(scene, {-5.0f, 1.000001f, -5.0f}, {5.0f, 2.0f, 5.0f}, 1, 1);
    const double angle = std::numbers::pi / 6.0;
    scene.camera.from = {0.0f, -3.0f, 0.0f};
    scene.camera.at = glm::vec3(0.0f, float(-3.0 + std::cos(angle)), float(std::sin(angle)));
    scene.camera.width = scene.camera.height = 1;
    scene.lights.clear();
    scene.settings.wavelengths = wavelengths;
    scene.settings.maxDepth = 4;
    return scene;
}

TEST(Dispersion, ARayEnteringADispersiveGlassThroughATouchingFaceSplitsThere) {
    constexpr std::uint32_t kSamples = 5;
    const Scene scene = gluedSlabs(kSamples);
    const SceneFeatures features = analyseScene(scene);
    ASSERT_TRUE(features.touchingMediaPossible);
    ASSERT_TRUE(features.dispersion);
    const Bvh bvh = buildSceneBvh(scene);
    std::vector<TracedRay> rays;
    RenderStats stats;
    renderReference(scene, bvh, {.doublePrecision = true, .threads = 1, .tracedRays = &rays}, stats);
    const glm::dvec3 in = glm::normalize(glm::dvec3(scene.camera.at) - glm::dvec3(scene.camera.from));
    std::set<float> exits;
    std::size_t leaving = 0;
    for (const TracedRay& r : rays)
        if (r.origin.y > 1.99f && r.direction.y > 0.0f && !r.anyHit) {
            ++leaving;
            const glm::dvec3 out = glm::normalize(glm::dvec3(r.direction));
            EXPECT_NEAR(out.y, in.y, 1e-6) << "a sample leaves at z = " << r.origin.z;
            EXPECT_NEAR(out.z, in.z, 1e-6) << "a sample leaves at z = " << r.origin.z;
            exits.insert(r.origin.z);
        }
    EXPECT_GE(leaving, kSamples);
    EXPECT_GE(exits.size(), kSamples);  // each sample's own sideways displacement
}

}  // namespace
}  // namespace vitrum
