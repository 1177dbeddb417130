// What loading a scene may be told: the limit on its textures of the device it will be rendered
// on, a check of its triangle count, where to report progress, a glTF file's camera, and whether
// repeated meshes are instanced.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include "common/progress.h"
#include "scene/texel_limit.h"

namespace vitrum {

struct SceneLoadOptions {
    TexelLimit texelLimit;
    PhaseCallback progress;  // may be empty
    // Called with the scene's triangle count so far as soon as an OBJ's statements tell how many
    // it adds, before they are made (the long part of a big model's load), so that a render can
    // refuse a scene too large for its device there (by throwing). May be empty.
    std::function<void(std::size_t triangles)> checkTriangles;
    // The glTF camera to look through, by name (`--camera NAME`); empty: the file's first
    // perspective camera in node order.
    std::string camera;
    // The glTF material variant to render, by name (KHR_materials_variants, `--variant NAME`):
    // each primitive takes the material its mappings give that variant; empty: their default
    // materials.
    std::string variant;
    // A mesh that two or more entries of a JSON scene or nodes of a glTF file place is stored once
    // and placed by instances (Scene::instances); false: every copy in the world (`--no-instancing`).
    bool instancing = true;
};

}  // namespace vitrum
