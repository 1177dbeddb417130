// Appending glTF 2.0 files (.gltf with its buffers and images, or .glb) to a Scene, read with
// tinygltf: every mesh instance of the node tree is one object, glTF's +Y up becomes vitrum's +Z
// up, and glTF's PBR materials map onto the render model's (docs/scene-format.md, "glTF 2.0").
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/load_options.h"
#include "scene/scene.h"

namespace vitrum {

// One place of the file's scene in the world: vitrum's z-up world to the scene's world, and who
// placed it there for messages (a JSON scene's entry, "/objects/3"; empty for a file of its own).
struct GltfPlacement {
    glm::mat4 transform{1.0f};
    std::string by;
};

struct GltfOptions {
    // The file's scene is placed once a placement: a JSON scene that names the file several times
    // loads it once, and each of its meshes is stored once (docs/scene-format.md, "Instancing").
    std::vector<GltfPlacement> placements{GltfPlacement{}};
    // Take the file's camera (the one named, else the first perspective camera in node order)
    // into scene.camera, and its image size from the camera's aspect ratio. One placement only.
    bool takeCamera = false;
};

struct GltfResult {
    bool camera = false;     // the scene's camera came from the file
    std::size_t lights = 0;  // point lights appended to scene.lights
};

// glTF's y-up to vitrum's z-up: (x, y, z) becomes (x, -z, y), a rotation of +90 degrees about x.
glm::mat4 gltfToZUp();

// Throws InputError naming the file: unreadable or malformed, an extension it requires that
// vitrum does not read, accessors out of their buffers, non-finite positions, an unreadable
// texture, an orthographic or missing named camera, no triangles. Warns once per
// skipped primitive, light or ignored material property.
GltfResult loadGltf(Scene& scene, const std::filesystem::path& file, const SceneLoadOptions& loadOptions,
                    const GltfOptions& options = {});

}  // namespace vitrum
