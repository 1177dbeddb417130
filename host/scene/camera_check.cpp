#include "scene/camera_check.h"

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

}  // namespace

std::string cameraProblem(const Camera& camera) {
    const glm::dvec3 view = glm::dvec3(camera.from) - glm::dvec3(camera.at);
    const double distance = glm::length(view);
    if (!(distance > 0.0)) return "\"at\" must differ from \"from\"";
    if (distance >= kLargestLength)
        return "\"from\" and \"at\" are " + shortNumber(distance) + " apart: the renderers' float arithmetic overflows " +
               "beyond " + shortNumber(kLargestLength);
    const double upLength = glm::length(glm::dvec3(camera.up));
    if (!(upLength > 0.0)) return "\"up\" must not be zero";
    if (upLength >= kLargestLength)
        return "\"up\" is " + shortNumber(upLength) + " long: the renderers' float arithmetic overflows beyond " +
               shortNumber(kLargestLength);
    if (glm::length(glm::cross(glm::dvec3(camera.up) / upLength, view / distance)) < 1e-6)
        return "\"up\" must not be parallel to from - at";
    return "";
}

}  // namespace vitrum
