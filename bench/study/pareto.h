// The Pareto front of (time, error) points: the points no other point beats on both, i.e. for
// which every faster point has a larger error. Ties count as beaten only by a point that is no
// worse on both and better on one.
#pragma once

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace vitrum::study {

struct TimeError {
    double time = 0;
    double error = 0;
};

// Indices of the front, fastest first.
inline std::vector<std::size_t> paretoFront(const std::vector<TimeError>& points) {
    std::vector<std::size_t> order(points.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return points[a].time != points[b].time ? points[a].time < points[b].time : points[a].error < points[b].error;
    });
    std::vector<std::size_t> front;
    for (std::size_t i : order) {
        // Sorted by time, then error: a point is on the front when its error is below every
        // earlier (faster or equally fast) point's error.
        if (front.empty() || points[i].error < points[front.back()].error) front.push_back(i);
    }
    return front;
}

}  // namespace vitrum::study
