// What a scene can need from the renderer (the start of "simulate only the effects a scene calls
// for"): found once at load, printed by `vitrum info`, used to skip work the scene cannot need.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace vitrum {

struct SceneFeatures {
    bool glass = false;              // refraction and a medium stack
    bool absorbingMedia = false;     // some glass has Tf != 0 (Beer-Lambert)
    bool touchingMediaPossible = false;  // two or more glass objects: surfaces may touch or nest
    bool reflection = false;         // opaque dielectrics, mirrors or glass spawn reflected rays
    bool shadowRays = false;         // lights and materials that use them (Lambert, Phong)
    bool textures = false;           // some material samples map_Kd
    BackgroundKind background = BackgroundKind::Constant;
    std::uint32_t glassObjects = 0;
    // The deepest a ray tree can usefully go: 1 (primary rays only) without reflective or
    // refractive materials, else the scene's max_depth.
    std::uint32_t usefulDepth = 1;

    std::vector<std::string> describe() const;  // one line a feature, for `vitrum info`
};

SceneFeatures analyseScene(const Scene& scene);

}  // namespace vitrum
