// The CPU reference renderer and its optics against numbers from the lecture
// (../shared/seed/dielectrics-lecture.txt) and from hand calculation, on scenes built in code.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <set>
#include <vector>

#include "bvh/bvh.h"
#include "cpu/optics.h"
#include "render_model/ray_offset.h"
#include "cpu/reference_renderer.h"
#include "gpu_input/packed_scene.h"
#include "gpu_input/render_params.h"
#include "render_model/sampling.h"
#include "scene/scene_loader.h"

#include "../support/scenes_in_code.h"

namespace vitrum {
namespace {

using Vec3d = glm::dvec3;
using namespace vitrum::testing;

// ---- Optics: the lecture's worked example ---------------------------------------------------

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

// The lecture prints d = (-0.429, -0.903, 0) rounded; it comes from theta1 = 25.391 deg, which
// the example also prints. Using the angle keeps the rounding of d out of the 3-decimal checks.
Vec3d lectureDirection() {
    const double theta1 = 25.391 / kDegrees;
    return Vec3d(-std::sin(theta1), -std::cos(theta1), 0.0);
}

TEST(Optics, RefractionMatchesLectureExample) {
    // n1 = 1.5, n2 = 1, d = (-0.429, -0.903, 0), n = (0, 1, 0): l = (-0.643, -0.766, 0),
    // theta2 = 40.03 deg. n faces the incoming ray (d.n < 0), as in our convention.
    const Vec3d d = lectureDirection();
    EXPECT_NEAR(d.x, -0.429, 5e-4);
    EXPECT_NEAR(d.y, -0.903, 5e-4);
    const Vec3d n(0.0, 1.0, 0.0);
    const auto l = optics::refract(d, n, 1.5 / 1.0);
    ASSERT_TRUE(l.has_value());
    EXPECT_NEAR(l->x, -0.643, 5e-4);
    EXPECT_NEAR(l->y, -0.766, 5e-4);
    EXPECT_NEAR(l->z, 0.0, 1e-12);
    EXPECT_NEAR(glm::length(*l), 1.0, 1e-12);
    EXPECT_NEAR(std::acos(-l->y) * kDegrees, 40.03, 5e-3);
    // Snell: n1 sin(theta1) = n2 sin(theta2) = 0.643.
    EXPECT_NEAR(1.5 * std::sqrt(1.0 - d.y * d.y), 1.0 * std::sqrt(1.0 - l->y * l->y), 1e-12);
}

TEST(Optics, ReflectionMatchesLectureExample) {
    const Vec3d d = lectureDirection();
    const Vec3d r = optics::reflect(d, Vec3d(0.0, 1.0, 0.0));
    EXPECT_NEAR(r.x, -0.429, 5e-4);
    EXPECT_NEAR(r.y, 0.903, 5e-4);
    EXPECT_NEAR(r.z, 0.0, 1e-12);
    // "Note that the orientation of n is not important here."
    const Vec3d r2 = optics::reflect(d, Vec3d(0.0, -1.0, 0.0));
    EXPECT_NEAR(glm::length(r - r2), 0.0, 1e-15);
}

TEST(Optics, FresnelExactMatchesLectureExample) {
    const double cosI = -lectureDirection().y;  // 0.903
    const auto cosT = optics::cosTransmitted(1.5, 1.0, cosI);
    ASSERT_TRUE(cosT.has_value());
    EXPECT_NEAR(*cosT, 0.766, 5e-4);
    const auto terms = optics::fresnelTerms(1.5, 1.0, cosI, *cosT);
    EXPECT_NEAR(terms.rs, 0.077, 5e-4);
    EXPECT_NEAR(terms.rp, 0.014, 5e-4);
    EXPECT_NEAR(optics::fresnelExact(1.5, 1.0, cosI), 0.046, 5e-4);
    EXPECT_NEAR(1.0 - optics::fresnelExact(1.5, 1.0, cosI), 0.954, 5e-4);
}

TEST(Optics, TotalInternalReflectionGivesFullReflectance) {
    // From glass to air beyond the critical angle (41.8 deg): sin(theta1) = 0.8.
    const Vec3d d(0.8, -0.6, 0.0);
    const Vec3d n(0.0, 1.0, 0.0);
    EXPECT_FALSE(optics::refract(d, n, 1.5).has_value());
    EXPECT_LT(optics::cosSquaredTransmitted(d, n, 1.5), 0.0);
    EXPECT_EQ(optics::fresnelExact(1.5, 1.0, 0.6), 1.0);
    EXPECT_EQ(optics::fresnelSchlick(1.5, 1.0, 0.6), 1.0);
    EXPECT_EQ(optics::fresnelSchlickExp2(1.5, 1.0, 0.6), 1.0);
    EXPECT_EQ(optics::fresnel(FresnelModel::Schlick, 1.5, 1.0, 0.6), 1.0);
}

TEST(Optics, ReversedRefractionReturnsTheIncomingDirection) {
    // Lecture: "What happens when we reverse the direction ... it doesn't matter". Refract d from
    // n1 into n2 to get l; then -l refracted from n2 into n1 gives -d.
    const Vec3d d = lectureDirection();
    const Vec3d n(0.0, 1.0, 0.0);
    const auto l = optics::refract(d, n, 1.5 / 1.0);
    ASSERT_TRUE(l);
    const auto back = optics::refract(-*l, -n, 1.0 / 1.5);
    ASSERT_TRUE(back);
    EXPECT_NEAR(glm::length(*back + d), 0.0, 1e-12);
}

TEST(Optics, RefractionAtNormalIncidenceGoesStraight) {
    // The final formula has no division by sin(theta1), which is 0 here.
    const auto l = optics::refract(Vec3d(0, 0, -1), Vec3d(0, 0, 1), 1.0 / 1.5);
    ASSERT_TRUE(l);
    EXPECT_EQ(*l, Vec3d(0, 0, -1));
    const auto lf = optics::refract(glm::vec3(0, 0, -1), glm::vec3(0, 0, 1), 1.0f / 1.5f);
    ASSERT_TRUE(lf);
    EXPECT_TRUE(std::isfinite(lf->x) && std::isfinite(lf->y));
}

TEST(Optics, SchlickMatchesExactAtNormalIncidence) {
    // F0 = ((1 - 1.5) / (1 + 1.5))^2 = 0.04.
    EXPECT_NEAR(optics::schlickF0(1.0, 1.5), 0.04, 1e-15);
    EXPECT_NEAR(optics::fresnelExact(1.0, 1.5, 1.0), 0.04, 1e-15);
    EXPECT_NEAR(optics::fresnelSchlick(1.0, 1.5, 1.0), 0.04, 1e-15);
    EXPECT_NEAR(optics::fresnelExact(1.5, 1.0, 1.0), 0.04, 1e-15);
    EXPECT_NEAR(optics::fresnelSchlick(1.5, 1.0, 1.0), 0.04, 1e-15);
    // Exp2 variant: 2^((-5.55473 - 6.98316) * 1) = 2^-12.538 ~ 1.7e-4, so R ~ F0.
    EXPECT_NEAR(optics::fresnelSchlickExp2(1.0, 1.5, 1.0), 0.04 + 0.96 * std::exp2(-12.53789), 1e-12);
    // At grazing incidence every model goes to 1.
    EXPECT_NEAR(optics::fresnelSchlick(1.0, 1.5, 0.0), 1.0, 1e-15);
    EXPECT_NEAR(optics::fresnelExact(1.0, 1.5, 0.0), 1.0, 1e-15);
}

TEST(Optics, IndexMatchedInterfaceReflectsNothing) {
    for (FresnelModel m : {FresnelModel::Schlick, FresnelModel::Exact, FresnelModel::SchlickExp2})
        EXPECT_EQ(optics::fresnel(m, 1.5, 1.5, 0.3), 0.0);
}

TEST(Optics, BeerLambertIsExponential) {
    const auto t = optics::beerLambert(Vec3d(0.0, 1.0, 0.5), 2.0);
    EXPECT_EQ(t.x, 1.0);
    EXPECT_NEAR(t.y, std::exp(-2.0), 1e-15);
    EXPECT_NEAR(t.z, std::exp(-1.0), 1e-15);
}

TEST(Optics, RayOffsetMovesToTheRequestedSide) {
    for (float scale : {1e-3f, 1.0f, 1e3f}) {
        const glm::vec3 p = glm::vec3(0.3f, -1.7f, 2.2f) * scale;
        const glm::vec3 n = glm::normalize(glm::vec3(1.0f, 2.0f, -0.5f));
        const glm::vec3 up = offsetRayOrigin(p, n);
        const glm::vec3 down = offsetRayOrigin(p, -n);
        EXPECT_GT(glm::dot(up - p, n), 0.0f);
        EXPECT_LT(glm::dot(down - p, n), 0.0f);
        EXPECT_LT(glm::length(up - p), 1e-3f * scale + 2e-5f);  // small: a few hundred ulps
        const glm::dvec3 upd = offsetRayOrigin(glm::dvec3(p), glm::dvec3(n));
        EXPECT_GT(glm::dot(upd - glm::dvec3(p), glm::dvec3(n)), 0.0);
    }
}

// ---- Sampling -------------------------------------------------------------------------------

TEST(ReferenceSampling, OneSampleIsThePixelCentre) { EXPECT_EQ(stratifiedSample(17, 0, 1), glm::vec2(0.5f)); }

TEST(ReferenceSampling, GridIsAsSquareAsTheCountAllows) {
    EXPECT_EQ(stratifiedColumns(1), 1u);
    EXPECT_EQ(stratifiedColumns(4), 2u);
    EXPECT_EQ(stratifiedColumns(8), 2u);
    EXPECT_EQ(stratifiedColumns(16), 4u);
    EXPECT_EQ(stratifiedColumns(7), 1u);
    EXPECT_EQ(stratifiedColumns(12), 3u);
}

// Every count a scene may ask for: the columns divide n, and the next divisor of n above them is
// above sqrt(n) (no squarer grid exists).
TEST(ReferenceSampling, GridColumnsAreTheLargestDivisorUpToTheSquareRoot) {
    for (std::uint32_t n = 1; n <= kMaxSamplesPerPixel; ++n) {
        const std::uint32_t columns = stratifiedColumns(n);
        ASSERT_GE(columns, 1u) << "n = " << n;
        ASSERT_EQ(n % columns, 0u) << "n = " << n;
        ASSERT_LE(std::uint64_t(columns) * columns, n) << "n = " << n;
        std::uint32_t next = columns + 1;  // n + 1 where n has no larger divisor (n = 1)
        while (next <= n && n % next != 0) ++next;
        ASSERT_GT(std::uint64_t(next) * next, n) << "n = " << n << ": " << next << " divides it too";
    }
}

// From n = 65535^2 on, c * c in 32 bits would wrap (65536^2 = 2^32) before it passed n: such a
// guard would loop on past sqrt(n) and divide by a wrapped c = 0.
TEST(ReferenceSampling, GridColumnsOfCountsNear2To32) {
    EXPECT_EQ(stratifiedColumns(0x80000000u), 32768u);  // 2^31: 2^15 x 2^16
    EXPECT_EQ(stratifiedColumns(65535u * 65535u), 65535u);
    EXPECT_EQ(stratifiedColumns(65535u * 65536u), 65535u);
    EXPECT_EQ(stratifiedColumns(0xFFFFFFFFu), 65535u);  // 3 * 5 * 17 * 257 * 65537
    EXPECT_EQ(stratifiedColumns(4294967291u), 1u);      // the largest prime below 2^32
}

// The GPU's render parameters carry the same grid as the CPU reference's samples use.
TEST(ReferenceSampling, TheGpuGetsTheSameGrid) {
    Scene scene;
    for (std::uint32_t n : {1u, 2u, 7u, 8u, 12u, 16u, 4095u, 4096u}) {
        scene.settings.samplesPerPixel = n;
        EXPECT_EQ(gpu::sampleGridColumns(makeRenderParams(scene, analyseScene(scene), gpu::kLeafEntryFlag, 1000)),
                  stratifiedColumns(n))
            << "n = " << n;
    }
}

TEST(ReferenceSampling, StratifiedSamplesCoverEachCellOnce) {
    for (std::uint32_t n : {2u, 4u, 6u, 7u, 9u, 16u, 64u}) {
        const std::uint32_t columns = stratifiedColumns(n), rows = n / columns;
        for (std::uint32_t pixel : {0u, 1u, 12345u, 0xFFFFFFFFu}) {
            std::set<std::pair<std::uint32_t, std::uint32_t>> cells;
            for (std::uint32_t k = 0; k < n; ++k) {
                const glm::vec2 o = stratifiedSample(pixel, k, n);
                const std::uint32_t cx = k % columns, cy = k / columns;
                // Inside its cell (closed: float rounding may land on the far edge).
                EXPECT_GE(o.x, float(cx) / float(columns));
                EXPECT_LE(o.x, float(cx + 1) / float(columns));
                EXPECT_GE(o.y, float(cy) / float(rows));
                EXPECT_LE(o.y, float(cy + 1) / float(rows));
                cells.insert({std::min(columns - 1, std::uint32_t(o.x * float(columns))),
                              std::min(rows - 1, std::uint32_t(o.y * float(rows)))});
            }
            EXPECT_EQ(cells.size(), n) << "n = " << n;
        }
    }
}

TEST(ReferenceSampling, JitterUsesTheSharedHash) {
    // Sample 3 of 4 at pixel 10: cell (1, 1) of a 2 x 2 grid, jitter from pcgHash as documented.
    const std::uint32_t seed = 10u * 2654435761u;
    const float jx = gpu::hashToUnit(gpu::pcgHash(seed ^ gpu::pcgHash(6u)));
    const float jy = gpu::hashToUnit(gpu::pcgHash(seed ^ gpu::pcgHash(7u)));
    EXPECT_EQ(stratifiedSample(10, 3, 4), glm::vec2((1.0f + jx) / 2.0f, (1.0f + jy) / 2.0f));
}

// ---- Scenes built in code -------------------------------------------------------------------

Image render(const Scene& scene, bool doublePrecision = false, RenderStats* statsOut = nullptr, unsigned threads = 2) {
    const Bvh bvh = buildSceneBvh(scene);
    RenderStats stats;
    ReferenceOptions options;
    options.doublePrecision = doublePrecision;
    options.threads = threads;
    Image image = renderReference(scene, bvh, options, stats);
    if (statsOut) *statsOut = stats;
    return image;
}

void expectColour(const glm::vec3& actual, const glm::dvec3& expected, double tolerance = 1e-5) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(ReferenceRenderer, LambertCentrePixelMatchesHandCalculation) {
    Scene scene = wallOf(makeMaterial(MaterialModel::Lambert, {0.05f, 0.1f, 0.02f}, {0.8f, 0.5f, 0.3f}));
    scene.lights.push_back({{1, -3, 2}, {0.9f, 1.0f, 0.7f}, false});
    for (bool dp : {false, true}) {
        RenderStats stats;
        const Image image = render(scene, dp, &stats);
        // p = (0, 0, 0), n = (0, -1, 0), l = (1, -3, 2) / sqrt(14): n.l = 3 / sqrt(14).
        const double nl = 3.0 / std::sqrt(14.0);
        const glm::dvec3 lc(0.9, 1.0, 0.7), ka(0.05, 0.1, 0.02), kd(0.8, 0.5, 0.3);
        expectColour(image.at(4, 4), lc * (ka + kd * nl));
        EXPECT_EQ(stats.backend, "cpu");
        EXPECT_EQ(stats.primaryRays, 81u);
        EXPECT_EQ(stats.shadowRays, 81u);
        EXPECT_EQ(stats.reflectionRays + stats.refractionRays, 0u);
        EXPECT_GT(stats.seconds("render"), 0.0);
    }
}

TEST(ReferenceRenderer, InverseSquareFallOffDimsTheDirectTerm) {
    Scene scene = wallOf(makeMaterial(MaterialModel::Lambert, {0.1f, 0.1f, 0.1f}, {1, 1, 1}));
    scene.lights.push_back({{0, -2, 0}, {1, 1, 1}, true});
    // Ambient is not attenuated (as in trace.comp); the direct term is divided by d^2 = 4.
    expectColour(render(scene).at(4, 4), glm::dvec3(0.1 + 1.0 / 4.0));
}

TEST(ReferenceRenderer, NormalMaterialShowsTheFacingNormal) {
    Scene scene = baseScene();
    scene.materials.push_back(makeMaterial(MaterialModel::Normal, {}, {}));
    scene.objectNames = {"wall"};
    // Wound facing away from the camera: the normal is flipped to face the ray, (0, -1, 0).
    addSquareY(scene, {0, 0, 0}, 3.0f, false, 0, 0);
    expectColour(render(scene).at(4, 4), {0.5, 0.0, 0.5});
}

TEST(ReferenceRenderer, MissReturnsTheBackground) {
    Scene scene = baseScene();
    scene.materials.push_back(makeMaterial(MaterialModel::Lambert, {1, 1, 1}, {1, 1, 1}));
    scene.objectNames = {"small"};
    addSquareY(scene, {0, 0, 0}, 0.1f, true, 0, 0);
    const Image image = render(scene);
    const glm::vec3 background(0.1f, 0.2f, 0.3f);
    EXPECT_EQ(image.at(0, 0), background);
    EXPECT_EQ(image.at(8, 8), background);
    // An empty scene renders the background everywhere.
    Scene empty = baseScene();
    for (const glm::vec3& p : render(empty).pixels) EXPECT_EQ(p, background);
}

TEST(ReferenceRenderer, OccluderLeavesOnlyTheAmbientTerm) {
    Scene scene = baseScene();
    scene.materials.push_back(makeMaterial(MaterialModel::Lambert, {0.05f, 0.05f, 0.05f}, {0.8f, 0.8f, 0.8f}));
    scene.objectNames = {"wall", "occluder"};
    addSquareY(scene, {0, 0, 0}, 3.0f, true, 0, 0);
    scene.lights.push_back({{0, -3, 3}, {1, 1, 1}, false});
    const double lit = render(scene).at(4, 4).x;
    EXPECT_NEAR(lit, 0.05 + 0.8 * (3.0 / std::sqrt(18.0)), 1e-5);
    // A small square half-way to the light, out of the camera ray's way (z = 1.5, the ray is at z = 0).
    addSquareY(scene, {0, -1.5f, 1.5f}, 0.2f, true, 0, 1);
    expectColour(render(scene).at(4, 4), glm::dvec3(0.05));
    // A glass occluder blocks too (binary shadows, glass included).
    scene.materials.push_back(makeMaterial(MaterialModel::Glass, {}, {}));
    for (std::size_t i = 2; i < scene.triangles.size(); ++i) scene.triangles[i].material = 1;
    expectColour(render(scene).at(4, 4), glm::dvec3(0.05));
}

TEST(ReferenceRenderer, LightBehindTheSurfaceGivesAmbientOnly) {
    Scene scene = wallOf(makeMaterial(MaterialModel::Lambert, {0.05f, 0.05f, 0.05f}, {0.8f, 0.8f, 0.8f}));
    scene.lights.push_back({{0, 2, 0}, {1, 1, 1}, false});
    RenderStats stats;
    expectColour(render(scene, false, &stats).at(4, 4), glm::dvec3(0.05));
    EXPECT_EQ(stats.shadowRays, 0u);  // direct term zero: no shadow ray needed
}

// A direct term below the smallest normal float is a denormal, which a device may flush to 0: no
// shadow ray is traced for it, so that every device traces the same rays (render-model-decisions.md,
// "Skipped"). Kd 0.5 head-on under a light of 2e-38 gives 1e-38, below FLT_MIN (1.18e-38); under
// 4e-38 it gives 2e-38, above it: a shadow ray for each of the 81 pixels.
TEST(ReferenceRenderer, ADenormalDirectTermSendsNoShadowRay) {
    for (bool doublePrecision : {false, true}) {
        SCOPED_TRACE(doublePrecision ? "double" : "float");
        for (const auto& [light, rays] : {std::pair{2e-38f, 0u}, std::pair{4e-38f, 81u}}) {
            Scene scene = wallOf(makeMaterial(MaterialModel::Lambert, {0.0f, 0.0f, 0.0f}, {0.5f, 0.5f, 0.5f}));
            scene.lights.push_back({{0, -5, 0}, glm::vec3(light), false});
            RenderStats stats;
            render(scene, doublePrecision, &stats);
            EXPECT_EQ(stats.shadowRays, rays) << light;
        }
    }
}

TEST(ReferenceRenderer, DiffuseTextureIsSampledBilinearly) {
    Material m = makeMaterial(MaterialModel::Lambert, {0, 0, 0}, {1, 1, 1});
    m.diffuseTexture = 0;
    Scene scene = wallOf(m);
    Texture texture;
    texture.width = 2;
    texture.height = 2;
    texture.texels = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    scene.textures.push_back(texture);
    scene.lights.push_back({{0, -5, 0}, {1, 1, 1}, false});
    // The centre hit has uv = (0.5, 0.5): exactly between the four texel centres.
    expectColour(render(scene).at(4, 4), {0.5, 0.5, 0.5});
}

TEST(ReferenceRenderer, MirrorReflectsTheWallBehindTheCamera) {
    Scene scene = baseScene();
    scene.materials.push_back(makeMaterial(MaterialModel::Mirror, {}, {}, {0.9f, 0.8f, 0.7f}));
    scene.materials.push_back(makeMaterial(MaterialModel::Lambert, {0.1f, 0.1f, 0.1f}, {0.5f, 0.6f, 0.7f}));
    scene.objectNames = {"mirror", "wall"};
    addSquareY(scene, {0, 0, 0}, 3.0f, true, 0, 0);
    addSquareY(scene, {0, -10, 0}, 30.0f, false, 1, 1);  // behind the camera, facing it (+y)
    scene.lights.push_back({{0, -5, 0}, {1, 1, 1}, false});
    RenderStats stats;
    const Image image = render(scene, false, &stats);
    // The reflected ray hits the wall head-on; the light is straight in front of it: n.l = 1.
    expectColour(image.at(4, 4), glm::dvec3(0.9, 0.8, 0.7) * (glm::dvec3(0.1) + glm::dvec3(0.5, 0.6, 0.7)));
    EXPECT_EQ(stats.reflectionRays, 81u);
    // With max_depth 1 only primary rays run: the mirror is black and the cut is counted.
    scene.settings.maxDepth = 1;
    const Image shallow = render(scene, false, &stats);
    expectColour(shallow.at(4, 4), glm::dvec3(0.0), 0.0);
    EXPECT_EQ(stats.depthLimitHits, 81u);
}

TEST(ReferenceRenderer, PhongAddsSchlickWeightedReflection) {
    Scene scene = plasticBeforeWall();
    scene.lights.push_back({{0, -5, 0}, {1, 1, 1}, false});
    // Head-on: n.l = 1, l_r = v so the highlight is 1; R = F0 = 0.04 for air -> 1.5.
    const glm::dvec3 phong = glm::dvec3(0.01) + glm::dvec3(0.3, 0.2, 0.1) + glm::dvec3(0.5);
    const glm::dvec3 wall = glm::dvec3(0.1) + glm::dvec3(0.5, 0.6, 0.7);
    expectColour(render(scene).at(4, 4), phong + 0.04 * wall);
    expectColour(render(scene, true).at(4, 4), phong + 0.04 * wall, 1e-7);
}

// Value of the centre pixel for a thin slab head-on in front of a constant background of 1, with
// no lights: the ray tree of the render model written out. A(k) is a ray of depth k reaching the
// front face from outside, B(k) a ray of depth k inside reaching a face; children of depth
// k + 1 exist only while k + 1 < maxDepth. e = exp(-mu L) per crossing of the slab.
double slabTree(double r, double e, unsigned maxDepth) {
    const double t = 1.0 - r;
    auto inside = [&](auto&& self, unsigned k) -> double {
        if (k + 1 >= maxDepth) return 0.0;
        return t * 1.0 + r * e * self(self, k + 1);
    };
    if (maxDepth <= 1) return 0.0;
    return r * 1.0 + t * e * inside(inside, 1);
}

TEST(ReferenceRenderer, GlassSlabMatchesTheRayTree) {
    for (FresnelModel fresnel : {FresnelModel::Exact, FresnelModel::Schlick}) {
        for (unsigned maxDepth : {1u, 2u, 3u, 4u, 10u, 30u}) {
            for (float mu : {0.0f, 2.0f}) {
                Scene scene = baseScene();
                scene.background.colour = glm::vec3(1.0f);
                scene.settings.fresnel = fresnel;
                scene.settings.maxDepth = maxDepth;
                Material glass = makeMaterial(MaterialModel::Glass, {}, {});
                glass.attenuation = glm::vec3(mu);
                scene.materials.push_back(glass);
                scene.objectNames = {"slab"};
                addBox(scene, {-2, 0, -2}, {2, 0.1f, 2}, 0, 0);
                const double expected = slabTree(0.04, std::exp(-double(mu) * 0.1), maxDepth);
                for (bool dp : {false, true}) {
                    // The image is float either way. In float, the ray offsets (a few hundred
                    // ulps, Waechter and Binder) shorten the 0.1 long segments inside measurably.
                    const glm::vec3 c = render(scene, dp).at(4, 4);
                    expectColour(c, glm::dvec3(expected), dp ? 1e-7 : (mu > 0.0f ? 1e-4 : 2e-6));
                }
            }
        }
    }
    // Without absorption and with enough depth, all the light comes back out: R + T = 1.
    EXPECT_NEAR(slabTree(0.04, 1.0, 200), 1.0, 1e-12);
}

TEST(ReferenceRenderer, TouchingIndexMatchedBoxesActLikeOneSlab) {
    // Two boxes of the same glass sharing the face y = 0.05: leaving the first enters the second
    // at the same point. Rendered with the cluster of crossings treated as one interface, the
    // pixel equals the single slab's.
    Scene one = baseScene();
    one.background.colour = glm::vec3(1.0f);
    one.settings.fresnel = FresnelModel::Exact;
    Material glass = makeMaterial(MaterialModel::Glass, {}, {});
    glass.attenuation = glm::vec3(1.0f);
    one.materials.push_back(glass);
    one.objectNames = {"slab"};
    addBox(one, {-2, 0, -2}, {2, 0.1f, 2}, 0, 0);
    Scene two = one;
    two.triangles.clear();
    two.objectNames = {"front", "back"};
    addBox(two, {-2, 0, -2}, {2, 0.05f, 2}, 0, 0);
    addBox(two, {-2, 0.05f, -2}, {2, 0.1f, 2}, 0, 1);
    for (bool dp : {false, true}) {
        const glm::vec3 a = render(one, dp).at(4, 4);
        const glm::vec3 b = render(two, dp).at(4, 4);
        expectColour(b, glm::dvec3(a), 1e-5);
    }
}

TEST(ReferenceRenderer, TotalInternalReflectionIsCounted) {
    // A ray entering a glass prism-like box at an angle and hitting a side face past the critical
    // angle: set up with a camera looking down into a thin, wide block from above at 60 degrees.
    Scene scene = baseScene();
    scene.camera.from = {0, -5, 5};
    scene.camera.at = {0, 0, 0};
    scene.background.colour = glm::vec3(1.0f);
    scene.materials.push_back(makeMaterial(MaterialModel::Glass, {}, {}));
    scene.objectNames = {"block"};
    addBox(scene, {-3, -3, -1}, {3, 3, 0}, 0, 0);
    RenderStats stats;
    const Image image = render(scene, false, &stats);
    for (const glm::vec3& p : image.pixels) {
        EXPECT_TRUE(std::isfinite(p.x) && p.x >= 0.0f);
        EXPECT_LE(p.x, 1.0f + 1e-5f);  // energy: a non-absorbing glass never adds light
    }
    EXPECT_GT(stats.refractionRays, 0u);
    EXPECT_GT(stats.totalInternalReflections, 0u);
}

// A small scene with every material, for comparisons between renders.
Scene mixedScene() {
    Scene scene = baseScene();
    scene.camera.width = 48;
    scene.camera.height = 36;
    scene.camera.from = {1.5f, -6, 2};
    scene.camera.at = {0, 0, 0};
    scene.background.colour = {0.3f, 0.4f, 0.5f};
    scene.materials.push_back(makeMaterial(MaterialModel::Lambert, {0.05f, 0.05f, 0.05f}, {0.7f, 0.6f, 0.5f}));
    scene.materials.push_back(makeMaterial(MaterialModel::Phong, {0.01f, 0.01f, 0.01f}, {0.2f, 0.3f, 0.8f},
                                           {0.6f, 0.6f, 0.6f}, 30.0f, 1.46f));
    scene.materials.push_back(makeMaterial(MaterialModel::Mirror, {}, {}, {0.9f, 0.9f, 0.9f}));
    Material glass = makeMaterial(MaterialModel::Glass, {}, {});
    glass.attenuation = {0.4f, 0.01f, 0.4f};
    scene.materials.push_back(glass);
    scene.objectNames = {"floor", "plastic", "mirror", "glass"};
    Triangle f1 = makeTriangle({-10, -10, -1}, {10, -10, -1}, {10, 10, -1}, 0, 0);
    Triangle f2 = makeTriangle({-10, -10, -1}, {10, 10, -1}, {-10, 10, -1}, 0, 0);
    scene.triangles.push_back(f1);
    scene.triangles.push_back(f2);
    // The boxes float just above the floor: a face coplanar with another surface makes the closest
    // hit a coin toss that float and double may call differently.
    addBox(scene, {-2.5f, 0.5f, -0.9f}, {-1.0f, 2.0f, 0.5f}, 1, 1);
    addSquareY(scene, {0, 4, 1}, 3.0f, true, 2, 2);
    addBox(scene, {-0.5f, -1.0f, -0.9f}, {1.0f, 0.5f, 1.0f}, 3, 3);
    scene.lights.push_back({{3, -4, 5}, {0.8f, 0.8f, 0.8f}, false});
    scene.lights.push_back({{-4, -2, 3}, {0.3f, 0.3f, 0.4f}, false});
    return scene;
}

TEST(ReferenceRenderer, FloatAndDoubleImagesNearlyAgree) {
    Scene scene = mixedScene();
    scene.settings.samplesPerPixel = 4;
    const Image f = render(scene, false);
    const Image d = render(scene, true);
    double sum = 0.0;
    int large = 0;
    for (std::size_t i = 0; i < f.pixels.size(); ++i) {
        const glm::vec3 diff = glm::abs(f.pixels[i] - d.pixels[i]);
        sum += diff.x + diff.y + diff.z;
        if (std::max({diff.x, diff.y, diff.z}) > 1e-3f) ++large;
    }
    const double mean = sum / (3.0 * f.pixels.size());
    std::cout << "    mean |float - double| = " << mean << ", pixels off by > 1e-3: " << large << "\n";
    EXPECT_LT(mean, 1e-4);
    EXPECT_LE(large, int(f.pixels.size() / 100));  // edges may pick another triangle
}

TEST(ReferenceRenderer, ThreadCountDoesNotChangeTheImage) {
    const Scene scene = mixedScene();
    RenderStats one, many;
    const Image a = render(scene, false, &one, 1);
    const Image b = render(scene, false, &many, 3);
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_EQ(one.totalRays(), many.totalRays());
    EXPECT_EQ(one.depthLimitHits, many.depthLimitHits);
    EXPECT_EQ(many.device, "CPU reference (float), 3 threads");
}

TEST(ReferenceRenderer, TracedRayLogHoldsEveryRayOfTheTree) {
    // The log is what bench/whitted_bench.cpp replays with Embree: it must hold exactly the rays
    // the counters count, each the kind it claims, the primary rays from the camera; and, for its
    // model of ray schedules (bench/ray_schedules.h), each pixel's rays together, the first its
    // primary ray.
    const Scene scene = mixedScene();
    const Bvh bvh = buildSceneBvh(scene);
    RenderStats stats;
    std::vector<TracedRay> rays;
    ReferenceOptions options;
    options.threads = 2;
    options.tracedRays = &rays;
    const Image logged = renderReference(scene, bvh, options, stats);
    EXPECT_EQ(rays.size(), stats.totalRays());
    std::uint64_t shadow = 0, fromCamera = 0;
    for (const TracedRay& r : rays) {
        shadow += r.anyHit;
        if (r.anyHit)
            EXPECT_EQ(r.tMax, 1.0f);  // o + t d reaches the light at t = 1
        else
            EXPECT_NEAR(glm::length(r.direction), 1.0f, 1e-5f);
        fromCamera += !r.anyHit && r.origin == scene.camera.from;
    }
    EXPECT_GT(stats.shadowRays, 0u);
    EXPECT_GT(stats.refractionRays, 0u);
    EXPECT_EQ(shadow, stats.shadowRays);
    EXPECT_EQ(fromCamera, stats.primaryRays);
    const std::uint32_t pixels = scene.camera.width * scene.camera.height;
    ASSERT_EQ(stats.primaryRays, std::uint64_t(pixels) * scene.settings.samplesPerPixel);
    std::vector<std::uint32_t> runs(pixels, 0u);  // runs of consecutive rays of each pixel
    for (std::size_t i = 0; i < rays.size(); ++i) {
        ASSERT_LT(rays[i].pixel, pixels);
        if (i == 0 || rays[i].pixel != rays[i - 1].pixel) {
            ++runs[rays[i].pixel];
            EXPECT_TRUE(!rays[i].anyHit && rays[i].origin == scene.camera.from) << "ray " << i;
        }
    }
    EXPECT_EQ(std::count(runs.begin(), runs.end(), 1u), std::ptrdiff_t(pixels));
    // Logging changes nothing else.
    EXPECT_EQ(logged.pixels, render(scene).pixels);
}

Scene scaledScene(Scene scene, float scale) {
    scene.camera.from *= scale;
    scene.camera.at *= scale;
    for (Triangle& t : scene.triangles)
        for (auto& p : t.position) p *= scale;
    for (PointLight& l : scene.lights) l.position *= scale;
    for (Material& m : scene.materials) m.attenuation /= scale;
    return scene;
}

int pixelsDiffering(const Image& a, const Image& b, float tolerance) {
    int differing = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        if (glm::length(a.pixels[i] - b.pixels[i]) > tolerance) ++differing;
    return differing;
}

TEST(ReferenceRenderer, ImageDoesNotChangeWhenTheSceneIsScaled) {
    // Double: the offsets are a few hundred double ulps, far below anything visible, at any scale.
    const Scene scene = mixedScene();
    const Image reference = render(scene, true);
    for (float scale : {1e-3f, 1e3f}) {
        const Image image = render(scaledScene(scene, scale), true);
        EXPECT_LE(pixelsDiffering(image, reference, 1e-3f), int(image.pixels.size() / 100)) << "scale " << scale;
    }
    // Float with Waechter and Binder's constants (as the GPU uses them): offsets are relative
    // (256 ulps) except within 1/32 of the origin, where they are an absolute 1/65536. Scaling up
    // is therefore invariant; scaling a scene down to millimetres is not (documented limit).
    const Image referenceFloat = render(scene, false);
    const Image up = render(scaledScene(scene, 1e3f), false);
    EXPECT_LE(pixelsDiffering(up, referenceFloat, 1e-3f), int(up.pixels.size() / 100));
}

TEST(ReferenceRenderer, MinWeightCutsWeakBranches) {
    Scene scene = mixedScene();
    RenderStats exact, cut;
    const Image a = render(scene, false, &exact);
    scene.settings.minWeight = 0.05f;
    const Image b = render(scene, false, &cut);
    EXPECT_EQ(exact.weightCuts, 0u);
    EXPECT_GT(cut.weightCuts, 0u);
    EXPECT_LT(cut.totalRays(), exact.totalRays());
    double sum = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) sum += glm::length(a.pixels[i] - b.pixels[i]);
    EXPECT_LT(sum / a.pixels.size(), 0.02);  // only weak branches were dropped
}

// 0 as tracing begins, then a call a row, one at a time though two threads render: in order.
TEST(ReferenceRenderer, ProgressReachesOne) {
    const Scene scene = mixedScene();
    const Bvh bvh = buildSceneBvh(scene);
    std::vector<double> fractions;
    ReferenceOptions options;
    options.threads = 2;
    options.progress = [&](double f) { fractions.push_back(f); };
    RenderStats stats;
    renderReference(scene, bvh, options, stats);
    ASSERT_EQ(fractions.size(), std::size_t(scene.camera.height) + 1);
    EXPECT_EQ(fractions.front(), 0.0);
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
    EXPECT_EQ(fractions.back(), 1.0);
}

}  // namespace
}  // namespace vitrum

namespace vitrum {
namespace {

// The CPU reference takes the scene's analysis too: it probes for touching surfaces only where
// two glass objects' boxes overlap, and the probe still finds the touching cubes' shared face.
TEST(ReferenceRenderer, ProbesForTouchingSurfacesOnlyWhereObjectsCanTouch) {
    auto render = [](const std::string& file) {
        Scene scene = loadScene(std::string(VITRUM_SOURCE_DIR) + "/" + file);
        scene.camera.width = 32;
        scene.camera.height = 24;
        RenderStats stats;
        renderReference(scene, buildSceneBvh(scene), ReferenceOptions{}, stats);
        return stats;
    };
    RenderStats spheres = render("scenes/course/geospheres_5x5_glass.json");  // 25 separate spheres
    EXPECT_GT(spheres.refractionRays, 0u);
    EXPECT_EQ(spheres.touchingProbes, 0u);
    EXPECT_FALSE(spheres.features.touchingMediaPossible);
    RenderStats cubes = render("scenes/touching_cubes.json");
    EXPECT_TRUE(cubes.features.touchingMediaPossible);
    EXPECT_GT(cubes.touchingProbes, 0u);
}

// Another traversal can stand in for the BVH's (bench/embree_renderer.cpp puts Embree there): one
// that is the same traversal, behind the interface, leaves the image as it was, bit for bit; each
// of its three queries is used where the scene needs it (touching cubes: the probes' all-hits);
// and the BVH's nodes are never read then.
TEST(ReferenceRenderer, AnIntersectorStandsInForTheBvh) {
    class SameTraversal final : public RayIntersector {
    public:
        SameTraversal(const Bvh& bvh, const Scene& scene)
            : nodes_(bvh.nodes), vertices_(packTriangleVertices(bvh, scene.triangles)) {}
        std::optional<TriangleHit<float>> closest(const Ray<float>& ray) const override {
            ++calls[0];
            return traceClosest<float>(nodes_, vertices_, ray);
        }
        bool any(const Ray<float>& ray) const override {
            ++calls[1];
            return traceAny<float>(nodes_, vertices_, ray);
        }
        void all(const Ray<float>& ray, std::vector<TriangleHit<float>>& hits) const override {
            ++calls[2];
            traceAll<float>(nodes_, vertices_, ray, hits);
        }
        mutable std::atomic<std::uint64_t> calls[3] = {};

    private:
        std::vector<gpu::BvhNode> nodes_;
        std::vector<gpu::TriangleVertices> vertices_;
    };
    Scene scene = loadScene(std::string(VITRUM_SOURCE_DIR) + "/scenes/touching_cubes.json");
    scene.camera.width = 48;
    scene.camera.height = 36;
    const Bvh bvh = buildSceneBvh(scene);
    RenderStats plain, through;
    std::vector<TracedRay> rays;  // every ray the tree traced, closest-hit and shadow
    const Image expected = renderReference(scene, bvh, ReferenceOptions{.tracedRays = &rays}, plain);
    const auto shadowRays = std::size_t(std::count_if(rays.begin(), rays.end(), [](const TracedRay& r) { return r.anyHit; }));
    const SameTraversal same(bvh, scene);
    Bvh orderOnly;
    orderOnly.triangleOrder = bvh.triangleOrder;  // no nodes: they must not be needed
    const Image image = renderReference(scene, orderOnly, ReferenceOptions{.intersector = &same}, through);
    EXPECT_EQ(image.pixels, expected.pixels);
    EXPECT_EQ(same.calls[0].load(), rays.size() - shadowRays);
    EXPECT_EQ(same.calls[1].load(), shadowRays);
    EXPECT_GT(same.calls[2].load(), 0u);
    EXPECT_THROW(renderReference(scene, orderOnly, ReferenceOptions{.doublePrecision = true, .intersector = &same}, through),
                 std::invalid_argument);
}

}  // namespace
}  // namespace vitrum
