// What loading a scene may be told: the limit on its textures of the device it will be rendered
// on, a check of its triangle count, where to report progress, and a glTF file's camera.
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
};

}  // namespace vitrum
