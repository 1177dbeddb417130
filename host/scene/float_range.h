// Whether the renderers' float arithmetic can take a scene's camera and lights: every vector they
// normalize (from - at, up, a light's direction from a surface) must have a squared length within
// float range. Worked out in double, so that a camera or light far away is judged by its geometry,
// not by a float that overflowed: "from": [1e20, 1, 1] was refused as if up were parallel to the
// view, from and at 6e38 apart rendered a black image, and a light at 3e38 lit nothing, without a
// word (issue 48).
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "scene/scene.h"

namespace vitrum {

// "" when the camera can be rendered, else what is wrong with it, naming "from", "at" and "up":
// from and at apart, up neither zero nor along the view, and both within float range.
std::string cameraProblem(const Camera& camera);

struct LightProblem {
    std::size_t light = 0;  // index into Scene::lights
    std::string message;    // how far it is
};

// The first light that is not within float range of every triangle of the scene (of their
// bounding box, found once), if any.
std::optional<LightProblem> lightProblem(const Scene& scene);

}  // namespace vitrum
