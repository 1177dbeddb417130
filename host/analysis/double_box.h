// An axis-aligned box in double precision, for the scene analysis's geometric tests (the scene's
// floats are exact in it).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <vector>

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

// Calls found(i, j), i < j, for every two of `boxes` that come within `margin` of each other.
// The boxes are swept in order of their lowest x, each compared only with those that begin
// within its x range (a scene of 20,000 objects spent 2.6 s comparing every two).
template <class Found>
void forEachBoxPairWithin(const std::vector<DoubleBox>& boxes, double margin, Found found) {
    std::vector<std::size_t> order(boxes.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    // A NaN (no loaded scene has one) sorts first, so that the order stays strict and weak.
    auto lowestX = [&](std::size_t i) { return std::isnan(boxes[i].min.x) ? -HUGE_VAL : boxes[i].min.x; };
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lowestX(a) < lowestX(b); });
    for (std::size_t a = 0; a < order.size(); ++a)
        for (std::size_t b = a + 1; b < order.size() && boxes[order[b]].min.x <= boxes[order[a]].max.x + margin; ++b)
            if (boxes[order[a]].within(boxes[order[b]], margin))
                found(std::min(order[a], order[b]), std::max(order[a], order[b]));
}

}  // namespace vitrum
