// An axis-aligned box in double precision, for the scene analysis's geometric tests (the scene's
// floats are exact in it).
#pragma once

#include <limits>

#include <glm/glm.hpp>

namespace vitrum {

struct DoubleBox {
    glm::dvec3 min{std::numeric_limits<double>::max()};
    glm::dvec3 max{std::numeric_limits<double>::lowest()};

    void grow(const glm::dvec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    // Whether the two boxes come within `margin` of each other on every axis.
    bool within(const DoubleBox& o, double margin) const {
        return glm::all(glm::lessThanEqual(min - margin, o.max)) && glm::all(glm::lessThanEqual(o.min - margin, max));
    }
};

}  // namespace vitrum
