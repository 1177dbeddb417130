// Whether a camera can be rendered: from and at apart, up neither zero nor along the view, and
// every vector the renderers build from them (host/render/packed_scene.cpp's basis, the CPU
// reference's) within float range. Worked out in double, so that a camera far away is judged by
// its geometry, not by a float that overflowed: "from": [1e20, 1, 1] was refused as if up were
// parallel to the view, and from and at 6e38 apart rendered a black image (issue 48).
#pragma once

#include <string>

#include "scene/scene.h"

namespace vitrum {

// "" when the camera can be rendered, else what is wrong with it, naming "from", "at" and "up".
std::string cameraProblem(const Camera& camera);

}  // namespace vitrum
