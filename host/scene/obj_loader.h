// Appending Wavefront OBJ files to a Scene: triangles in world space (after an optional
// transform), one object per OBJ shape ("o"/"g"), materials from the MTL files with textures.
// The OBJ is parsed on every core, as tinyobjloader 2.0 parsed it on one (obj_loader.cpp).
// Material libraries and textures are loaded once per path however many OBJ files use them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "image/image.h"
#include "scene/load_options.h"
#include "scene/scene.h"

namespace vitrum {

struct MtlEntry;

struct ObjOptions {
    std::optional<std::filesystem::path> mtlOverride;  // replaces the OBJ's own mtllib
    glm::mat4 transform{1.0f};                         // object to world; must be invertible
    // The text is read in this many parts at once (0: one a core, of 16 MiB at least); tests
    // split small files with it.
    std::size_t parts = 0;
};

class ObjLoader {
public:
    explicit ObjLoader(Scene& scene, SceneLoadOptions options = {}) : scene_(scene), options_(std::move(options)) {}

    // Throws InputError naming the file: missing, unparsable, non-finite coordinates, face indices
    // out of range, no triangles, a texture beyond the texel limit (with its MTL line). Missing MTL
    // files and unreadable textures only warn. Reports the parsing and the triangles as two phases.
    void load(const std::filesystem::path& objFile, const ObjOptions& options = {});

private:
    using Library = std::map<std::string, std::uint32_t>;  // material name -> index in scene_.materials
    const Library& library(const std::filesystem::path& mtlFile);
    int texture(const std::filesystem::path& imageFile, const std::filesystem::path& mtlFile, int line,
                const std::string& key, const std::string& what, const std::string& fallback,
                const std::function<std::vector<glm::vec3>(Image&)>& texels);
    int coverage(const MtlEntry& entry, const std::filesystem::path& mtlFile, const Material& material,
                 const std::function<std::filesystem::path(std::string)>& imageFile);
    std::uint32_t defaultMaterialIndex();

    Scene& scene_;
    SceneLoadOptions options_;
    std::map<std::filesystem::path, Library> libraries_;
    // By MTL key (map_Kd, map_d) and file: -1 where it could not be read (warned once).
    std::map<std::pair<std::string, std::filesystem::path>, int> textures_;
    std::optional<std::uint32_t> defaultMaterial_;
};

}  // namespace vitrum
