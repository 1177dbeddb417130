// The scene as every backend sees it: geometry in world space, materials with linear colours,
// lights, camera, background and the render settings the scene asks for. Loading fills it
// (scene_loader.h); the BVH and the GPU packing read it. See ../shared/docs/render-model.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace vitrum {

enum class MaterialModel : std::uint32_t {
    Normal = 1,   // (n + 1) / 2
    Lambert = 2,
    Phong = 3,    // opaque dielectric: Phong + Schlick-weighted reflection
    Glass = 4,
    Mirror = 6,
    // A glass wall of no thickness (glTF's thin-walled transmission, MTL `thin_walled 1`): a sheet
    // with no inside that reflects and transmits as a thin pane does, the transmitted light tinted
    // by the diffuse colour (docs/render-model-decisions.md, "Thin-walled glass"). Not a course
    // shader number.
    ThinGlass = 7,
};

enum class FresnelModel : std::uint32_t { Schlick = 0, Exact = 1, SchlickExp2 = 2 };

struct Texture {
    std::filesystem::path path;
    int width = 0;
    int height = 0;
    std::vector<glm::vec3> texels;  // linear RGB, row 0 is the image's top row
};

struct Material {
    std::string name;
    MaterialModel model = MaterialModel::Phong;
    glm::vec3 ambient{0.0f};      // Ka, linear
    glm::vec3 diffuse{0.5f};      // Kd, linear
    glm::vec3 specular{0.0f};     // Ks, linear
    float shininess = 1.0f;       // Ns
    float ior = 1.5f;             // Ni
    glm::vec3 attenuation{0.0f};  // Tf of a glass: Beer-Lambert mu per channel, 1 / scene unit
    // Of a glass: where media overlap, the one of highest priority is the medium (MTL `priority`;
    // docs/render-model-decisions.md, "Overlapping media by priority").
    int priority = 0;
    // Of a glass: its Abbe number V_d (MTL `Vd`), with `ior` as n_d; 0 for none. Its index then
    // depends on the wavelength (render_model/dispersion.h).
    float abbe = 0.0f;
    // Of a glass: the colour light passing through its surface takes on, at every crossing of it
    // (glTF's base colour of a transmissive volume, KHR_materials_volume: "Base Color and
    // Absorption"); white for none. A thin glass's tint is its `diffuse`.
    glm::vec3 tint{1.0f};
    int diffuseTexture = -1;      // index into Scene::textures, -1 for none
    // Cut-out parts (glTF's alphaMode MASK): index into Scene::textures of a grey texture, read at
    // a hit's uv as map_Kd is, where the surface is not there when its value is below 1 (glTF's
    // alpha over alphaCutoff); -1 for none. A ray passes such a hit by (docs/render-model-decisions.md,
    // "Cut-out surfaces"). Not for glass volumes (hasCutouts).
    int cutout = -1;
    // Partial coverage (glTF's alphaMode BLEND): index into Scene::textures of a grey texture, read
    // at a hit's uv as map_Kd is, giving the share alpha of the surface that is there (glTF's alpha,
    // the texture's times the factor's); -1 for a surface that is all there. At a hit the surface's
    // shading takes alpha of the ray's weight and the ray passes on through it, undeviated, with
    // 1 - alpha (docs/render-model-decisions.md, "Partial coverage"). Only opaque models
    // (hasPartialCoverage).
    int coverage = -1;
    // Of a glass or thin glass: where it is glass (glTF's transmissionTexture): index into
    // Scene::textures of a grey texture, read at a hit's uv as map_Kd is, below 1 where the
    // surface is not glass but material `opaquePart` (glTF's transmission under 1/2: each texel
    // takes the nearer model, as the factor does); -1 for glass everywhere
    // (docs/render-model-decisions.md, "Transmission textures"; hasTransmissionTexture).
    int transmissionTexture = -1;
    // The material shown where transmissionTexture is below 1: an opaque model (Lambert, Phong,
    // mirror) with no cut-outs, coverage or transmission texture of its own; -1 for none.
    int opaquePart = -1;
};

// Whether rays pass by parts of the material's surfaces (Material::cutout): not a glass volume's,
// whose closed surface bounds its medium.
inline bool hasCutouts(const Material& m) { return m.cutout >= 0 && m.model != MaterialModel::Glass; }

// Whether surfaces of a model can be partly there (Material::coverage): Lambert, Phong and
// mirrors; a glass's or thin glass's coverage is not read (docs/render-model-decisions.md,
// "Partial coverage").
inline bool canBePartlyCovered(MaterialModel model) {
    return model == MaterialModel::Lambert || model == MaterialModel::Phong || model == MaterialModel::Mirror;
}
inline bool hasPartialCoverage(const Material& m) { return m.coverage >= 0 && canBePartlyCovered(m.model); }

// Whether the material is glass only where its transmission texture says so, and opaquePart
// elsewhere (Material::transmissionTexture).
inline bool hasTransmissionTexture(const Material& m) {
    return m.transmissionTexture >= 0 && m.opaquePart >= 0 &&
           (m.model == MaterialModel::Glass || m.model == MaterialModel::ThinGlass);
}

struct Triangle {
    glm::vec3 position[3];
    glm::vec3 normal[3];  // vertex normals, or the geometric normal three times
    glm::vec2 uv[3];      // (0, 0) where the file has none
    std::uint32_t material = 0;
    std::uint32_t object = 0;  // index into Scene::objectNames: one closed mesh
};

// A mesh stored once and placed by instances (issue 50; docs/gpu-design.md, "Instancing"): the
// triangles [first, first + count) of Scene::triangles, in the mesh's own space, their `object`
// numbering the mesh's own objects from 0 (its instances' objects are the scene's).
struct Mesh {
    std::uint32_t first = 0;
    std::uint32_t count = 0;
    std::uint32_t objects = 0;  // how many objects its triangles number
};

// A copy of a mesh placed in the world: its objects are Scene::objectNames [firstObject,
// firstObject + mesh's objects). worldToObject is objectToWorld's inverse, computed in double and
// rounded once (makeInstance), so that both backends transform rays with the same floats.
struct Instance {
    std::uint32_t mesh = 0;
    std::uint32_t firstObject = 0;
    glm::mat4 objectToWorld{1.0f};
    glm::mat4 worldToObject{1.0f};
};

struct PointLight {
    glm::vec3 position{0.0f};
    glm::vec3 colour{1.0f};  // linear
    bool inverseSquare = false;
};

// The vertical field of view a camera may have, in degrees, exclusive: wide enough to see through
// a keyhole, short of the 180 degrees at which the image plane would be infinitely large.
constexpr double kMinFovY = 0.5, kMaxFovY = 179.5;
inline bool validFovY(double degrees) { return degrees > kMinFovY && degrees < kMaxFovY; }
// The range as messages state it (tests/core/scene_loader_test.cpp holds it to the two numbers).
inline constexpr const char* kFovYRange = "between 0.5 and 179.5 degrees (exclusive)";

// The most a scene file or the command line may ask for: pixels along each side of the image,
// samples a pixel, and max_depth (the ray tree's depth, render model).
constexpr std::uint32_t kMaxImageSide = 16384, kMaxSamplesPerPixel = 4096, kMaxRayDepth = 64;

struct Camera {
    glm::vec3 from{0.0f, -5.0f, 0.0f};
    glm::vec3 at{0.0f};
    glm::vec3 up{0.0f, 0.0f, 1.0f};
    float fovY = 45.0f;  // degrees
    std::uint32_t width = 640;
    std::uint32_t height = 480;
};

enum class BackgroundKind : std::uint32_t { Constant = 0, Spherical = 1, Cube = 2 };

// How textures and environment maps are read between texel centres (render model: bilinear by
// default, nearest as an accuracy setting).
enum class TextureFilter : std::uint32_t { Bilinear = 0, Nearest = 1 };

struct Background {
    BackgroundKind kind = BackgroundKind::Constant;
    glm::vec3 colour{0.0f};  // linear; the Constant background
    // Spherical: the equirectangular map's index in Scene::textures. Cube: the +x face's; the
    // -x, +y, -y, +z and -z faces follow it (docs/scene-format.md shows their orientation).
    int map = -1;
};

struct RenderSettings {
    std::uint32_t samplesPerPixel = 1;
    std::uint32_t maxDepth = 10;
    FresnelModel fresnel = FresnelModel::Schlick;
    float minWeight = 0.0f;
    TextureFilter filter = TextureFilter::Bilinear;  // mesh textures and environment maps
    // Wavelength samples a ray splits into where it first meets a dispersive glass
    // (render_model/dispersion.h); unused without one.
    std::uint32_t wavelengths = 8;
};

struct Scene {
    std::filesystem::path source;  // the scene file (JSON or OBJ) it came from
    Camera camera;
    std::vector<PointLight> lights;
    Background background;
    RenderSettings settings;
    float airIor = 1.0f;
    // The world's triangles, then each mesh's (Mesh::first): without instances, all of them are
    // the world's.
    std::vector<Triangle> triangles;
    std::vector<Mesh> meshes;
    std::vector<Instance> instances;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<std::string> objectNames;
};

// The triangles in world space: all but the meshes' (which come after them).
inline std::uint32_t worldTriangleCount(const Scene& scene) {
    return scene.meshes.empty() ? std::uint32_t(scene.triangles.size()) : scene.meshes.front().first;
}

}  // namespace vitrum
