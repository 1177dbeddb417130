#include "scene/scene_loader.h"

#include "scene/instances.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

#include "common/error.h"
#include "common/file_extension.h"
#include "scene/gltf_loader.h"
#include "scene/json_scene.h"
#include "scene/obj_loader.h"

namespace vitrum {

namespace {

// A folder given where a scene was expected (as the course's scenes come, one folder each): the
// error names the scenes inside, so the user can pick one.
[[noreturn]] void refuseFolder(const std::filesystem::path& path) {
    std::vector<std::string> scenes;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(path, error)) {
        std::string extension = lowerCaseExtension(entry.path());
        if (entry.is_regular_file(error) &&
            (extension == ".json" || extension == ".obj" || extension == ".gltf" || extension == ".glb")) {
            scenes.push_back(entry.path().filename().string());
        }
    }
    std::sort(scenes.begin(), scenes.end());
    std::string message = "is a folder, not a scene";
    if (scenes.empty()) {
        message += ", and holds no .json, .obj, .gltf or .glb scene";
    } else {
        message += "; the scenes in it:";
        for (const std::string& name : scenes) message += " " + name;
    }
    throw inputError(path, 0, message);
}

}  // namespace

Scene loadScene(const std::filesystem::path& path, const SceneLoadOptions& options) {
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) refuseFolder(path);
    std::string extension = lowerCaseExtension(path);
    if (!options.camera.empty() && extension != ".gltf" && extension != ".glb")
        throw inputError(path, 0, "--camera picks a camera of a glTF file (.gltf, .glb); this scene is none");
    if (!options.variant.empty() && extension != ".gltf" && extension != ".glb")
        throw inputError(path, 0,
                         "--variant picks a material variant of a glTF file (.gltf, .glb); this scene is none");
    // Running out of memory is the input's size, not a bug: say which scene (it was "internal
    // error: std::bad_alloc", naming nothing).
    try {
        if (extension == ".json") return readJsonScene(path, options);
        if (extension == ".obj") {
            Scene scene;
            scene.source = path;
            ObjLoader(scene, options).load(path);
            frameAutomatically(scene);
            return scene;
        }
        if (extension == ".gltf" || extension == ".glb") {
            Scene scene;
            scene.source = path;
            const GltfResult read = loadGltf(scene, path, options, {.takeCamera = true});
            // Without a camera of its own the file is framed as an OBJ is; without lights of its
            // own it gets the automatic light (docs/scene-format.md, "glTF 2.0").
            std::vector<PointLight> lights = scene.lights;
            if (!read.camera) frameAutomatically(scene);
            if (read.lights > 0) scene.lights = lights;
            else if (read.camera) scene.lights = {automaticLight(scene)};
            return scene;
        }
    } catch (const std::bad_alloc&) {
        throw inputError(path, 0, "not enough memory to load the scene (its files, textures and triangles)");
    } catch (const std::system_error& e) {
        // A thread of the OBJ loader that cannot start: no memory left for its stack.
        if (e.code() != std::errc::resource_unavailable_try_again) throw;
        throw inputError(path, 0, "not enough memory to load the scene (its files, textures and triangles)");
    }
    throw inputError(path, 0, "unknown scene format \"" + extension +
                                  "\": expected a .json scene, an .obj file or a glTF file (.gltf, .glb)");
}

// A z-up three-quarter view from the -y side, slightly above, that fits the bounding sphere of
// the geometry into the vertical field of view with a 10 % margin; one white light above the eye.
namespace {

struct BoundingSphere {
    glm::vec3 centre{0.0f};
    float radius = 1.0f;
};

// The sphere around the geometry's box; radius 1 for nothing or a single point.
BoundingSphere boundingSphere(const Scene& scene) {
    const FloatBox box = worldBox(scene);  // the instances' boxes too
    const glm::vec3 lo = box.min, hi = box.max;
    BoundingSphere sphere;
    if (scene.triangles.empty()) return sphere;
    sphere.centre = (lo + hi) * 0.5f;
    const float radius = glm::length(hi - lo) * 0.5f;
    if (radius > 0.0f && std::isfinite(radius)) sphere.radius = radius;
    return sphere;
}

}  // namespace

PointLight automaticLight(const Scene& scene) {
    return PointLight{scene.camera.from + scene.camera.up * boundingSphere(scene).radius, glm::vec3(1.0f), false};
}

void frameAutomatically(Scene& scene) {
    const auto [centre, radius] = boundingSphere(scene);

    Camera& camera = scene.camera;
    camera = Camera{};
    camera.up = glm::vec3(0.0f, 0.0f, 1.0f);
    camera.fovY = 45.0f;
    camera.width = 640;
    camera.height = 480;
    const float distance = 1.1f * radius / std::sin(glm::radians(camera.fovY) * 0.5f);
    camera.at = centre;
    camera.from = centre + glm::normalize(glm::vec3(1.0f, -2.0f, 1.0f)) * distance;
    scene.lights = {automaticLight(scene)};
}

}  // namespace vitrum
