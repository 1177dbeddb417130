// glTF's materials on the render model's (docs/scene-format.md, "Materials" under "glTF 2.0"): transmission
// with a volume is glass, metal a mirror, the rest the opaque dielectric (or Lambert without a
// specular layer); what a material has that the render model has no place for is listed in one
// warning a material. Base-colour textures are decoded as MTL textures are.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>

#include "image/image.h"
#include "scene/scene.h"
#include "scene/texel_limit.h"
#include "scene/tinygltf.h"

namespace vitrum {

// The extensions whose meaning vitrum renders (docs/scene-format.md, "glTF 2.0"): the materials'
// here, KHR_texture_transform, EXT_texture_webp, KHR_lights_punctual, and KHR_mesh_quantization,
// EXT_meshopt_compression and KHR_draco_mesh_compression (the loader's geometry). A file that requires any other is refused,
// one that only uses it is read without it, with a warning.
bool isReadGltfExtension(const std::string& name);

class GltfMaterials {
public:
    // Materials go into `scene` as primitives name them; `model` is the file `file` as tinygltf read it.
    GltfMaterials(Scene& scene, const tinygltf::Model& model, std::filesystem::path file, const TexelLimit& texelLimit)
        : scene_(scene), model_(model), file_(std::move(file)), texelLimit_(texelLimit) {}

    // The scene's material for the file's materials[index], added at its first use; for -1 (a
    // primitive that names none), the render model's default material. Throws InputError naming
    // the material where it cannot be rendered (an unreadable texture).
    std::uint32_t sceneMaterial(int index);
    // The KHR_texture_transform of materials[index]'s baseColorTexture (glTF's texture
    // coordinates, v down), once sceneMaterial(index) has made it; null where it has none.
    const glm::dmat3* uvTransform(int index) const {
        const auto found = uvTransforms_.find(index);
        return found == uvTransforms_.end() ? nullptr : &found->second;
    }

private:
    [[noreturn]] void fail(const std::string& message) const;
    void warnAbout(const std::string& message) const;
    double extensionNumber(const tinygltf::Value& extension, const char* name, const char* key, double fallback,
                           const std::string& quoted) const;
    glm::dvec3 extensionColour(const tinygltf::Value& extension, const char* name, const char* key, glm::dvec3 fallback,
                               const std::string& quoted) const;
    std::uint32_t defaultMaterial();
    Material material(const tinygltf::Material& g, int index);
    std::optional<std::pair<tinygltf::TextureInfo, double>> opaqueMaterial(const tinygltf::Material& g, int index,
                                                                           const std::string& quoted, Material& m,
                                                                           std::vector<std::string>& ignored);
    void transmissionTexture(const tinygltf::Material& g, const tinygltf::Value& transmission, double factor, int index,
                             const std::string& quoted, Material& m, std::vector<std::string>& ignored);
    // Returns its diffuse texture (index -1 for none) and diffuse factor's alpha.
    std::pair<tinygltf::TextureInfo, double> specularGlossinessMaterial(const tinygltf::Value& sg, int index,
                                                                        const std::string& quoted, Material& m,
                                                                        std::vector<std::string>& ignored);
    int baseColorSource(const tinygltf::TextureInfo& info, int material, const std::string& quoted,
                        std::vector<std::string>& ignored);
    std::optional<glm::dmat3> textureCoordinates(const tinygltf::TextureInfo& info, const char* role,
                                                 const std::string& quoted, std::vector<std::string>& ignored);
    int imageSource(const tinygltf::TextureInfo& info, const std::string& quoted, const char* role);
    std::filesystem::path imageName(int source) const;
    Image decodeSource(int source, const std::string& quoted, const char* role = "baseColorTexture");
    int baseColorTexture(const tinygltf::TextureInfo& info, glm::vec3 factor, int material, const std::string& quoted,
                         std::vector<std::string>& ignored);
    int alphaTexture(const tinygltf::TextureInfo& info, double alphaFactor, double over, const char* what, int material,
                     const std::string& quoted, std::vector<std::string>& ignored);
    bool alphaBelow(const tinygltf::TextureInfo& info, double alphaFactor, double level, const std::string& quoted);
    const std::vector<float>& alphaOf(int source, const std::string& quoted);
    glm::dmat3 textureTransform(const tinygltf::Value& transform, const std::string& quoted);

    Scene& scene_;
    const tinygltf::Model& model_;
    std::filesystem::path file_;
    const TexelLimit& texelLimit_;
    std::map<int, std::uint32_t> materials_;  // by glTF material
    std::map<int, glm::dmat3> uvTransforms_;  // by glTF material: its baseColorTexture's KHR_texture_transform
    std::map<int, int> sources_;              // by glTF material: its base colour's image, -1 for none
    std::map<std::tuple<int, float, float, float>, int> textures_;  // by image and factor
    std::map<std::pair<int, double>, int> alphaTextures_;           // by image and alpha factor over a divisor
    std::map<std::pair<int, double>, int> transmissionTextures_;    // by image and transmissionFactor; -1: none
    struct {
        int source = -1;
        std::uint32_t width = 0, height = 0;
        std::vector<float> alpha;
    } lastAlpha_;  // the alpha of the image decoded last (alphaOf)
    std::optional<std::uint32_t> defaultMaterial_;
};

}  // namespace vitrum
