// Loading a scene: a JSON scene file (docs/scene-format.md), a bare OBJ (automatic camera and
// light) or a bare glTF file (its own camera and lights, else the automatic ones). Throws InputError naming the file and line on bad input.
#pragma once

#include <filesystem>

#include "scene/scene.h"
#include "scene/load_options.h"

namespace vitrum {

// A render passes its device's limit on textures, so that an image too large for it is refused
// before it is decoded, and a callback for the progress of long loads.
Scene loadScene(const std::filesystem::path& path, const SceneLoadOptions& options = {});

// The camera and light a bare OBJ gets: frames the bounding box of `scene.triangles`.
void frameAutomatically(Scene& scene);

// The automatic light: white, no fall-off, above the camera by the geometry's bounding radius.
PointLight automaticLight(const Scene& scene);

}  // namespace vitrum
