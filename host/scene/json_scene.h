// The JSON scene file (docs/scene-format.md): camera, lights, background, render settings and
// the OBJ files with their transforms. Every error names the file and, where it can, the line.
#pragma once

#include <filesystem>

#include "scene/scene.h"
#include "scene/load_options.h"

namespace vitrum {

// Throws InputError for a missing or malformed file, a value of the wrong type or out of range,
// and for errors in the OBJ/MTL files it names, the images beyond the options' texel limit
// included. Unknown keys only warn.
Scene readJsonScene(const std::filesystem::path& file, const SceneLoadOptions& options = {});

}  // namespace vitrum
