// The GPU against the CPU reference, and the kernel specialized for a scene against the general
// one, on random scenes: differential tests. The named scenes of the other tests hold each
// decision to a worked-out answer; these hold the renderers to each other where nobody thought to
// look: random materials (all five models, absorbing glass, indices 1 to 2.5), boxes and spheres
// placed at random, some nested in or touching one another or coinciding with a copy of
// themselves, a floor, up to two lights, smooth normals, a texture, a spherical or cube map as
// the background, nearest filtering, air denser than 1, the camera outside, inside an object or
// on one of its faces, objects of two materials, the scene turned, scaled by 1e-3 or 1e3 or moved
// 5000 units away, and the GPU's tiles and step budgets varied. Differential runs of this kind
// found that a camera on a surface speckled the image, that rays seeming to enter an object twice
// overflowed the specialized medium stack, and that glass standing on an opaque surface was
// speckled (docs/hard-cases.md). VITRUM_RANDOM_SCENES=N runs N seeds instead of 24, for a longer hunt.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "../support/scenes_in_code.h"
#include "../support/test_meshes.h"
#include "gpu_test_support.h"

namespace vitrum::testing {
namespace {

using glm::vec3;

class RandomScene {
public:
    explicit RandomScene(std::uint32_t seed) : rng_(seed) {}

    Scene make() {
        Scene scene;
        scene.camera.up = {0, 0, 1};
        scene.camera.fovY = uniform(25.0f, 90.0f);
        scene.camera.width = 40;
        scene.camera.height = 30;
        scene.background.colour = vec3(uniform(0.0f, 0.5f), uniform(0.0f, 0.5f), uniform(0.0f, 0.5f));
        scene.settings.samplesPerPixel = pick({1u, 1u, 2u, 4u});
        scene.settings.maxDepth = pick({1u, 2u, 5u, 10u, 10u});
        scene.settings.fresnel = pick({FresnelModel::Schlick, FresnelModel::Exact, FresnelModel::SchlickExp2});
        if (chance(0.2)) scene.settings.minWeight = pick({0.001f, 0.01f});
        const int materials = int(uniform(1.0f, 4.99f));
        for (int i = 0; i < materials; ++i) scene.materials.push_back(material());
        for (int i = int(uniform(0.0f, 2.99f)); i > 0; --i)
            scene.lights.push_back({.position = vec3(uniform(-6, 6), uniform(-6, 6), uniform(1, 8)),
                                    .colour = vec3(uniform(0.2f, 1.0f)),
                                    .inverseSquare = chance(0.3)});
        // Objects: the first is a box (so that the camera can stand on its top face); a smaller
        // copy of it inside it, or a box on top of it sharing its face, sometimes.
        const vec3 centre(uniform(-1, 1), uniform(-1, 1), uniform(0, 1));
        const vec3 half(uniform(0.3f, 1.2f), uniform(0.3f, 1.2f), uniform(0.3f, 1.2f));
        addObject(scene, [&](std::uint32_t m, std::uint32_t o) { addBox(scene, centre - half, centre + half, m, o); });
        if (chance(0.3))
            addObject(scene, [&](std::uint32_t m, std::uint32_t o) {
                addBox(scene, centre - 0.5f * half, centre + 0.5f * half, m, o);
                drawn_ += ", a box in it";
            });
        if (chance(0.3)) {
            const vec3 top = centre + vec3(0, 0, half.z);
            addObject(scene, [&](std::uint32_t m, std::uint32_t o) {
                addBox(scene, top - vec3(half.x, half.y, 0), top + vec3(half.x, half.y, 2 * half.z), m, o);
                drawn_ += ", a box on its top face";
            });
        }
        for (int i = int(uniform(0.0f, 2.99f)); i > 0; --i) {
            const vec3 c(uniform(-2.5f, 2.5f), uniform(-2.5f, 2.5f), uniform(-0.5f, 2.0f));
            const float r = uniform(0.2f, 1.2f);
            addObject(scene, [&](std::uint32_t m, std::uint32_t o) {
                addSphere(scene, c, r, m, o);
                drawn_ += ", a sphere";
            });
        }
        if (chance(0.5))
            addObject(scene, [&](std::uint32_t m, std::uint32_t o) {
                scene.triangles.push_back(makeTriangle({-8, -8, -1}, {8, -8, -1}, {8, 8, -1}, m, o));
                scene.triangles.push_back(makeTriangle({-8, -8, -1}, {8, 8, -1}, {-8, 8, -1}, m, o));
                drawn_ += ", a floor";
            });
        // The camera: around the scene, inside the first box, or on its top face.
        const float where = uniform(0, 1);
        if (where < 0.2f) {
            scene.camera.from = centre + vec3(0.1f * half.x, 0.0f, 0.0f);
            drawn_ += ", the camera inside the first box";
        } else if (where < 0.4f) {
            scene.camera.from = centre + vec3(uniform(-0.9f, 0.9f) * half.x, uniform(-0.9f, 0.9f) * half.y, half.z);
            drawn_ += ", the camera on its top face";
        } else {
            const float angle = uniform(0.0f, 6.2832f), elevation = uniform(-0.3f, 1.2f), distance = uniform(3, 10);
            scene.camera.from = distance * vec3(std::cos(angle) * std::cos(elevation),
                                                std::sin(angle) * std::cos(elevation), std::sin(elevation));
        }
        scene.camera.at = vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 0.5f));
        const float scale = pick({1.0f, 1.0f, 1e-3f, 1e3f});
        // Light that falls off with the square of the distance is not the same image at another
        // scale (1e-3 makes it 1e6 times brighter, beyond what absolute thresholds can judge), and
        // its ambient term does not fall off: a scaled scene's lights do not fall off.
        for (PointLight& light : scene.lights) {
            light.inverseSquare = light.inverseSquare && scale == 1.0f;
            drawn_ += light.inverseSquare ? ", an inverse-square light" : ", a light";
        }
        // Drawn last, so that the scenes of earlier seeds stay as they were where these do not
        // apply: a copy of an object in the same place (its triangles coincide with the
        // object's), and the scene moved far from the origin, where the ray offsets are 32 ulps
        // of large coordinates.
        if (chance(0.15)) {
            const auto original = std::uniform_int_distribution<std::uint32_t>(0, scene.objectNames.size() - 1)(rng_);
            std::vector<Triangle> copy;
            for (const Triangle& t : scene.triangles)
                if (t.object == original) copy.push_back(t);
            addObject(scene, [&](std::uint32_t m, std::uint32_t o) {
                drawn_ += ", a copy of object " + std::to_string(original) + " in its place";
                for (Triangle t : copy) {
                    t.material = m;
                    t.object = o;
                    scene.triangles.push_back(t);
                }
            });
        }
        const vec3 shift = scale == 1.0f && chance(0.3) ? vec3(5000.0f, -3000.0f, 2000.0f) : vec3(0.0f);
        // What the shading reads besides the materials' colours: interpolated normals on the
        // spheres, a texture, a map for a background, nearest filtering, air denser than 1.
        if (chance(0.4)) smoothSpheres(scene);
        if (chance(0.3)) addTexture(scene);
        const float background = uniform(0, 1);
        if (background < 0.2f) addBackgroundMap(scene, BackgroundKind::Spherical);
        else if (background < 0.35f) addBackgroundMap(scene, BackgroundKind::Cube);
        if (chance(0.3)) scene.settings.filter = TextureFilter::Nearest;
        if (chance(0.15)) scene.airIor = uniform(1.0f, 1.4f);
        if (scale != 1.0f) drawn_ += ", scaled by " + std::to_string(scale);
        if (shift != vec3(0.0f)) drawn_ += ", moved 5000 units away";
        if (scene.airIor != 1.0f) drawn_ += ", air of index " + std::to_string(scene.airIor);
        // Turned about a random axis, so that faces that meet or coincide lie in no coordinate
        // plane and meet only up to rounding.
        if (chance(0.3)) turn(scene, glm::normalize(vec3(uniform(-1, 1), uniform(-1, 1), uniform(0.1f, 1))),
                              uniform(0.1f, 6.2f));
        // One object of two materials: every third of its triangles another's (glass beside
        // opaque triangles in one mesh, or glass of two indices).
        if (chance(0.1)) {
            const auto object = std::uniform_int_distribution<std::uint32_t>(0, scene.objectNames.size() - 1)(rng_);
            const auto other = std::uniform_int_distribution<std::uint32_t>(0, scene.materials.size() - 1)(rng_);
            drawn_ += ", every third triangle of object " + std::to_string(object) + " " +
                      modelName(scene.materials[other].model);
            std::uint32_t n = 0;
            for (Triangle& t : scene.triangles)
                if (t.object == object && n++ % 3 == 0) t.material = other;
        }
        // Thin-walled glass of a material of its own: a pane across the scene (sometimes through
        // the other objects) or a hollow sphere, tinted, sometimes textured.
        if (chance(0.25)) addThinGlass(scene);
        // Glass whose surfaces tint what crosses them (glTF's base colour of a volume).
        if (chance(0.25))
            for (std::size_t i = 0; i < scene.materials.size(); ++i)
                if (scene.materials[i].model == MaterialModel::Glass) {
                    scene.materials[i].tint = vec3(uniform(0.2f, 1), uniform(0.2f, 1), uniform(0.2f, 1));
                    drawn_ += ", the glass of material " + std::to_string(i) + " tinted";
                }
        // Surfaces cut out where a texture is below 1 (glTF's alphaMode MASK), about half of
        // them: an opaque or thin-glass material's.
        if (chance(0.25)) addCutout(scene);
        // Opaque surfaces partly there (glTF's alphaMode BLEND), drawn after everything else.
        if (chance(0.25)) addCoverage(scene);
        // A glass that is glass only where a texture says, an opaque material elsewhere (glTF's
        // transmissionTexture), drawn last.
        if (chance(0.25)) addTransmissionTexture(scene);
        return transformed(scene, scale, shift);
    }

    // What make() drew, for a failure's message: "a box, a sphere, a floor, the camera on its top
    // face, ...". Materials are listed object by object.
    std::string drawn() const { return drawn_; }

private:
    float uniform(float a, float b) { return std::uniform_real_distribution<float>(a, b)(rng_); }
    bool chance(double p) { return std::uniform_real_distribution<double>(0, 1)(rng_) < p; }
    template <class T>
    T pick(std::initializer_list<T> values) {
        return values.begin()[std::uniform_int_distribution<std::size_t>(0, values.size() - 1)(rng_)];
    }

    Material material() {
        const MaterialModel model =
            pick({MaterialModel::Normal, MaterialModel::Lambert, MaterialModel::Lambert, MaterialModel::Phong,
                  MaterialModel::Glass, MaterialModel::Glass, MaterialModel::Mirror});
        Material m = materialOf(model);
        if (model == MaterialModel::Glass && chance(0.5))
            m.attenuation = vec3(uniform(0, 2), uniform(0, 2), uniform(0, 2));
        return m;
    }

    // A material of `model` with random colours, exponent and index.
    Material materialOf(MaterialModel model) {
        return makeMaterial(model, vec3(uniform(0, 0.2f)), vec3(uniform(0, 1), uniform(0, 1), uniform(0, 1)),
                            vec3(uniform(0, 1)), pick({1.0f, 20.0f, 1000.0f}), uniform(1.0f, 2.5f));
    }

    void addThinGlass(Scene& scene) {
        Material m = makeMaterial(MaterialModel::ThinGlass, vec3(0.0f), vec3(uniform(0.3f, 1), uniform(0.3f, 1), 1.0f),
                                  vec3(0.0f), 1.0f, pick({1.0f, 1.33f, 1.5f, 2.4f, uniform(1.0f, 2.5f)}));
        if (!scene.textures.empty() && chance(0.3)) m.diffuseTexture = 0;
        const auto material = std::uint32_t(scene.materials.size());
        scene.materials.push_back(m);
        const auto object = std::uint32_t(scene.objectNames.size());
        scene.objectNames.push_back("object " + std::to_string(object));
        const vec3 at(uniform(-1, 1), uniform(-1, 1), uniform(-0.5f, 1));
        if (chance(0.5)) {
            addSphere(scene, at, uniform(0.3f, 1.5f), material, object);
            drawn_ += "; a hollow sphere of thin glass of index " + std::to_string(m.ior);
            return;
        }
        const vec3 n = glm::normalize(vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)));
        const vec3 u = glm::normalize(glm::cross(n, std::abs(n.z) < 0.9f ? vec3(0, 0, 1) : vec3(1, 0, 0)));
        const vec3 v = glm::cross(n, u);
        const float size = uniform(1.0f, 4.0f);
        const vec3 a = at - size * u - size * v, b = at + size * u - size * v, c = at + size * u + size * v,
                   d = at - size * u + size * v;
        scene.triangles.push_back(makeTriangle(a, b, c, material, object));
        scene.triangles.push_back(makeTriangle(a, c, d, material, object));
        drawn_ +=
            "; a pane of thin glass of index " + std::to_string(m.ior) + (m.diffuseTexture >= 0 ? ", textured" : "");
    }

    // Adds one object of a random material of the scene's.
    template <class Add>
    void addObject(Scene& scene, Add add) {
        const auto material = std::uniform_int_distribution<std::uint32_t>(0, scene.materials.size() - 1)(rng_);
        const auto object = std::uint32_t(scene.objectNames.size());
        scene.objectNames.push_back("object " + std::to_string(object));
        drawn_ += (object == 0 ? "" : "; ") + std::string("object ") + std::to_string(object) + " (" +
                  modelName(scene.materials[material].model) + ")";
        add(material, object);
    }

    void addSphere(Scene& scene, vec3 centre, float radius, std::uint32_t material, std::uint32_t object) {
        const IndexedMesh mesh = icosphere(2, radius, centre);
        for (const glm::uvec3& f : mesh.faces)
            scene.triangles.push_back(
                makeTriangle(mesh.vertices[f.x], mesh.vertices[f.y], mesh.vertices[f.z], material, object));
        sphereCentres_.push_back({object, centre});
    }

    // Vertex normals pointing away from each sphere's centre instead of the faces' normals.
    void smoothSpheres(Scene& scene) {
        drawn_ += ", smooth normals";
        for (Triangle& t : scene.triangles)
            for (const auto& [object, centre] : sphereCentres_)
                if (t.object == object)
                    for (int k = 0; k < 3; ++k) t.normal[k] = glm::normalize(t.position[k] - centre);
    }

    // A random texture of 2 to 5 texels a side, on one material; the triangles' texture
    // coordinates follow their positions, so that it repeats a few times across an object.
    void addTexture(Scene& scene) {
        const int side = int(uniform(2.0f, 5.99f));
        drawn_ += ", a texture";
        scene.materials[std::uniform_int_distribution<std::size_t>(0, scene.materials.size() - 1)(rng_)]
            .diffuseTexture = int(scene.textures.size());
        scene.textures.push_back(randomTexture(side, side));
        uvsFromPositions(scene);
    }

    // Texture coordinates that follow the triangles' positions, so that a texture repeats a few
    // times across an object.
    static void uvsFromPositions(Scene& scene) {
        for (Triangle& t : scene.triangles)
            for (int k = 0; k < 3; ++k) t.uv[k] = 0.7f * glm::vec2(t.position[k].x + t.position[k].z, t.position[k].y);
    }

    // A random grey texture of 2 to 5 texels a side, from 0 to 2, cutting one material that is
    // not a glass volume (if there is one); the triangles' texture coordinates as addTexture gives them.
    void addCutout(Scene& scene) {
        const auto material =
            randomMaterialWhere(scene, [](const Material& m) { return m.model != MaterialModel::Glass; });
        if (!material) return;
        scene.materials[*material].cutout = addGreyTexture(scene, "cutout", 0.0f, 2.0f);
        drawn_ += ", material " + std::to_string(*material) + " cut out";
    }

    // One of the scene's materials that `accepts` takes, at random; none where it takes none.
    template <class Accepts>
    std::optional<std::size_t> randomMaterialWhere(const Scene& scene, Accepts accepts) {
        std::vector<std::size_t> candidates;
        for (std::size_t i = 0; i < scene.materials.size(); ++i)
            if (accepts(scene.materials[i])) candidates.push_back(i);
        if (candidates.empty()) return std::nullopt;
        return candidates[std::uniform_int_distribution<std::size_t>(0, candidates.size() - 1)(rng_)];
    }

    // A random grey texture of 2 to 5 texels a side, its values in [low, high), added to the
    // scene with the triangles' texture coordinates as addTexture gives them: its index.
    int addGreyTexture(Scene& scene, const char* name, float low, float high) {
        const int side = int(uniform(2.0f, 5.99f));
        Texture texture{name, side, side, {}};
        for (int i = 0; i < side * side; ++i) texture.texels.push_back(vec3(uniform(low, high)));
        scene.textures.push_back(std::move(texture));
        uvsFromPositions(scene);
        return int(scene.textures.size()) - 1;
    }

    // A random grey texture of 2 to 5 texels a side, from -1/4 to 3/2 (taken within [0, 1]), the
    // share of one Lambert, Phong or mirror material that is there (if there is one).
    void addCoverage(Scene& scene) {
        const auto material = randomMaterialWhere(scene, [](const Material& m) { return canBePartlyCovered(m.model); });
        if (!material) return;
        scene.materials[*material].coverage = addGreyTexture(scene, "coverage", -0.25f, 1.5f);
        drawn_ += ", material " + std::to_string(*material) + " partly there";
    }

    // A random grey texture of 2 to 5 texels a side, from 0 to 2, where one glass or thin glass
    // material (if there is one) is glass where it is 1 or more, and a new Lambert, Phong or
    // mirror material elsewhere.
    void addTransmissionTexture(Scene& scene) {
        const auto material = randomMaterialWhere(scene, [](const Material& m) {
            return m.model == MaterialModel::Glass || m.model == MaterialModel::ThinGlass;
        });
        if (!material) return;
        const MaterialModel model = pick({MaterialModel::Lambert, MaterialModel::Phong, MaterialModel::Mirror});
        scene.materials[*material].transmissionTexture = addGreyTexture(scene, "transmission", 0.0f, 2.0f);
        scene.materials[*material].opaquePart = int(scene.materials.size());
        scene.materials.push_back(materialOf(model));
        drawn_ +=
            ", material " + std::to_string(*material) + " glass only where a texture says, else " + modelName(model);
    }

    // Every position, normal and direction of the scene turned by `angle` about `axis`.
    void turn(Scene& scene, vec3 axis, float angle) {
        drawn_ += ", turned";
        const glm::mat3 r(glm::rotate(glm::mat4(1.0f), angle, axis));
        for (Triangle& t : scene.triangles)
            for (int k = 0; k < 3; ++k) {
                t.position[k] = r * t.position[k];
                t.normal[k] = r * t.normal[k];
            }
        scene.camera.from = r * scene.camera.from;
        scene.camera.at = r * scene.camera.at;
        scene.camera.up = r * scene.camera.up;
        for (PointLight& light : scene.lights) light.position = r * light.position;
    }

    // An equirectangular map of 8x4 texels, or a cube of six faces of 3x3.
    void addBackgroundMap(Scene& scene, BackgroundKind kind) {
        drawn_ += kind == BackgroundKind::Spherical ? ", a spherical map" : ", a cube map";
        scene.background.kind = kind;
        scene.background.map = int(scene.textures.size());
        if (kind == BackgroundKind::Spherical) scene.textures.push_back(randomTexture(8, 4));
        else
            for (int face = 0; face < 6; ++face) scene.textures.push_back(randomTexture(3, 3));
    }

    Texture randomTexture(int width, int height) {
        Texture texture{"random", width, height, {}};
        for (int i = 0; i < width * height; ++i)
            texture.texels.push_back(vec3(uniform(0, 1), uniform(0, 1), uniform(0, 1)));
        return texture;
    }

    static const char* modelName(MaterialModel model) {
        switch (model) {
        case MaterialModel::Normal: return "normal";
        case MaterialModel::Lambert: return "Lambert";
        case MaterialModel::Phong: return "opaque dielectric";
        case MaterialModel::Glass: return "glass";
        case MaterialModel::Mirror: return "mirror";
        case MaterialModel::ThinGlass: return "thin glass";
        }
        return "?";
    }

    std::mt19937 rng_;
    std::string drawn_;
    std::vector<std::pair<std::uint32_t, vec3>> sphereCentres_;  // (object, centre) of each sphere
};

// The seeds to run: 1 to VITRUM_RANDOM_SCENES, 24 by default.
std::uint32_t lastSeed() {
    const char* value = std::getenv("VITRUM_RANDOM_SCENES");
    return value != nullptr && std::atoi(value) > 0 ? std::uint32_t(std::atoi(value)) : 24u;
}

// Tiles cut by the image's edges, and budgets that make the resumable kernel suspend pixels.
VulkanRenderOptions optionsFor(std::uint32_t seed) {
    return {.iterationBudget = seed % 3 == 0 ? 300u : 49152u, .tileSize = seed % 2 == 0 ? 16u : 256u};
}

// Runs check(seed, scene) on the scene of every seed, a failure naming the seed and what it drew.
template <class Check>
void forEachRandomScene(Check check) {
    for (std::uint32_t seed = 1; seed <= lastSeed(); ++seed) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        RandomScene random(seed);
        const Scene scene = random.make();
        SCOPED_TRACE(random.drawn());
        check(seed, scene);
    }
}

TEST(RandomScenes, GpuMatchesTheCpuReferenceOnEveryScene) {
    forEachRandomScene([](std::uint32_t seed, const Scene& scene) {
        const RenderPair p = renderBoth(scene, optionsFor(seed));
        // The thresholds of every GPU-against-CPU test (gpu_test_support.h): isolated pixels where
        // a ray passes within an ulp of an edge may differ, nothing more. Not its check that the
        // image varies: a camera inside a mirror box at depth 1 rightly sees black.
        expectImagesAgree(p);
        EXPECT_EQ(p.gpuStats.primaryRays, p.cpuStats.primaryRays);
    });
}

TEST(RandomScenes, SpecializedKernelMatchesTheGeneralOneBitForBit) {
    // The specialized kernel leaves out code the scene cannot reach and sizes its stacks to what
    // it can (trace_specialization.h): the same arithmetic on the same rays, so the same image in
    // every bit and the same counts, wherever the scene's features were judged right.
    forEachRandomScene([](std::uint32_t seed, const Scene& scene) {
        const Bvh bvh = buildSceneBvh(scene);
        RenderStats specializedStats, generalStats;
        VulkanRenderOptions options = optionsFor(seed);
        const std::uint32_t before = testDevice().validationMessages();
        const Image specialized = renderVulkan(testDevice(), scene, bvh, options, specializedStats);
        options.specialize = false;
        const Image general = renderVulkan(testDevice(), scene, bvh, options, generalStats);
        EXPECT_EQ(testDevice().validationMessages(), before) << "Vulkan validation messages while rendering";
        ASSERT_TRUE(specializedStats.kernel && generalStats.kernel);
        EXPECT_TRUE(specializedStats.kernel->specialized);
        EXPECT_EQ(differingPixels(specialized, general), 0u) << "pixels that differ in any bit";
        expectSameWork(specializedStats, generalStats);
    });
}

}  // namespace
}  // namespace vitrum::testing
