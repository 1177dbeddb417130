// Moving a new ray's origin off the surface it starts on: Waechter and Binder, "A Fast and Robust
// Method for Avoiding Self-Intersection", Ray Tracing Gems (2019), ch. 6. The offset is a fixed
// number of ulps of each coordinate (scale-invariant), with a small absolute offset near the
// origin where ulps vanish. `n` is the geometric normal on the side the new ray goes to.
//
// float: the chapter's constants, the same arithmetic as shaders/ray_offset.glsl.
// double: the same method on the double's bits. The hit point of a double render carries errors of
// double ulps, so the offset is 256 double ulps (and the near-origin offset is scaled down by the
// 2^29 between the two mantissas) instead of 256 float ulps: the double render stays the closer
// approximation of the exact image rather than inheriting float's offsets.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

namespace vitrum {

namespace detail {

inline float offsetComponent(float p, float n) {
    constexpr float kOrigin = 1.0f / 32.0f;
    constexpr float kFloatScale = 1.0f / 65536.0f;
    constexpr float kIntScale = 256.0f;
    const auto offsetInt = static_cast<std::int32_t>(kIntScale * n);
    const std::int32_t bits = std::bit_cast<std::int32_t>(p);
    // Unsigned arithmetic: the bit pattern is an integer that may wrap, not a signed overflow.
    const auto moved = static_cast<std::uint32_t>(bits) + static_cast<std::uint32_t>(p < 0.0f ? -offsetInt : offsetInt);
    const float pInt = std::bit_cast<float>(moved);
    return std::fabs(p) < kOrigin ? p + kFloatScale * n : pInt;
}

inline double offsetComponent(double p, double n) {
    constexpr double kOrigin = 1.0 / 32.0;
    constexpr double kFloatScale = 1.0 / 65536.0 / 536870912.0;  // float's constant / 2^29
    constexpr double kIntScale = 256.0;
    const auto offsetInt = static_cast<std::int64_t>(kIntScale * n);
    const std::int64_t bits = std::bit_cast<std::int64_t>(p);
    const auto moved = static_cast<std::uint64_t>(bits) + static_cast<std::uint64_t>(p < 0.0 ? -offsetInt : offsetInt);
    const double pInt = std::bit_cast<double>(moved);
    return std::fabs(p) < kOrigin ? p + kFloatScale * n : pInt;
}

}  // namespace detail

template <class Real>
glm::vec<3, Real> offsetRayOrigin(const glm::vec<3, Real>& p, const glm::vec<3, Real>& n) {
    return {detail::offsetComponent(p.x, n.x), detail::offsetComponent(p.y, n.y), detail::offsetComponent(p.z, n.z)};
}

}  // namespace vitrum
