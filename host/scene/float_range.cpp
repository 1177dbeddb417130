#include "scene/float_range.h"

#include "scene/instances.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <glm/glm.hpp>

namespace vitrum {
namespace {

// A float vector's squared length must be a finite float for glm::normalize to work on it.
const double kLargestLength = std::sqrt(double(std::numeric_limits<float>::max()));

std::string shortNumber(double x) {
    std::ostringstream s;
    s.precision(3);
    s << x;
    return s.str();
}

std::string beyondFloat(double length) {
    return shortNumber(length) + ": the renderers' float arithmetic overflows beyond " + shortNumber(kLargestLength);
}

}  // namespace

std::string cameraProblem(const Camera& camera) {
    const glm::dvec3 view = glm::dvec3(camera.from) - glm::dvec3(camera.at);
    const double distance = glm::length(view);
    if (!(distance > 0.0)) return "\"at\" must differ from \"from\"";
    if (distance >= kLargestLength) return "\"from\" and \"at\" are apart by " + beyondFloat(distance);
    const double upLength = glm::length(glm::dvec3(camera.up));
    if (!(upLength > 0.0)) return "\"up\" must not be zero";
    if (upLength >= kLargestLength) return "\"up\" is as long as " + beyondFloat(upLength);
    if (glm::length(glm::cross(glm::dvec3(camera.up) / upLength, view / distance)) < 1e-6)
        return "\"up\" must not be parallel to from - at";
    return "";
}

std::optional<LightProblem> lightProblem(const Scene& scene) {
    if (scene.lights.empty()) return std::nullopt;
    const FloatBox box = worldBox(scene);  // the instances' boxes too
    const glm::dvec3 low(box.min), high(box.max);
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const glm::dvec3 light(scene.lights[i].position);
        const glm::dvec3 near = scene.triangles.empty() ? light : low, far = scene.triangles.empty() ? light : high;
        // The farthest corner of the box from the light: along each axis, the farther of the two ends.
        const double distance = glm::length(glm::max(glm::abs(light - near), glm::abs(light - far)));
        if (distance >= kLargestLength)
            return LightProblem{i, "the light is as far from the scene's triangles as " + beyondFloat(distance)};
    }
    return std::nullopt;
}

}  // namespace vitrum
