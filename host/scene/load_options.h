// What loading a scene may be told: the limit on its textures of the device it will be rendered
// on, and where to report progress.
#pragma once

#include "common/progress.h"
#include "scene/texel_limit.h"

namespace vitrum {

struct SceneLoadOptions {
    TexelLimit texelLimit;
    PhaseCallback progress;  // may be empty
};

}  // namespace vitrum
