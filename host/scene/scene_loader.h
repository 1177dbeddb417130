// Loading a scene: a JSON scene file (docs/scene-format.md) or a bare OBJ (automatic camera and
// light). Throws InputError naming the file and line on bad input.
#pragma once

#include <filesystem>

#include "scene/scene.h"

namespace vitrum {

Scene loadScene(const std::filesystem::path& path);

// The camera and light a bare OBJ gets: frames the bounding box of `scene.triangles`.
void frameAutomatically(Scene& scene);

}  // namespace vitrum
