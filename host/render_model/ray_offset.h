// Moving a new ray's origin off the surface it starts on: Waechter and Binder, "A Fast and Robust
// Method for Avoiding Self-Intersection", Ray Tracing Gems (2019), ch. 6. The offset is a fixed
// number of ulps of each coordinate (scale-invariant), with a small absolute offset near the
// origin where ulps vanish. `n` is the geometric normal on the side the new ray goes to.
//
// The chapter's two absolute constants (origin region 1/32, offset there 1/65536) assume a scene
// of about unit size: a scene 1e-3 across lies wholly inside the origin region and gets offsets of
// 1.5% of its size, one 1e3 across gets offsets below the rounding of its hit points. So both are
// scaled with the scene's extent E (the longest side of the bounding box of its triangles):
//   - origin region E / 32: the chapter's for E = 1;
//   - outside it the offset is 32 ulps of each coordinate (the chapter uses 256): at least
//     2^-19 |p| >= 2^-24 E, 8x the error of an interpolated hit point along the normal
//     (about 4 float roundings, <= 2^-22 |p|), and 8x closer to the surface than the chapter's,
//     which matters far from the origin: a scene moved 1e4 units away (ulps of 1e-3) would
//     otherwise restart its rays 0.25 units off the surface (docs/hard-cases.md);
//   - absolute offset E / 2^23: exactly 32 ulps of E / 32 when E is a power of two, so the offset
//     does not jump at the region's edge.
// Both are exact scalings of E, so a scene scaled by s gets offsets scaled by s (exactly for a
// power of two). The host passes the same two numbers to the GPU in RenderParams.offsets
// (makeRenderParams). RayOffsetScale{} keeps the chapter's own constants.
//
// float: the chapter's method, the same arithmetic as shaders/ray_offset.glsl.
// double: the same method on the double's bits. The hit point of a double render carries errors of
// double ulps, so the offset is 32 double ulps (and the near-origin offset is scaled down by the
// 2^29 between the two mantissas) instead of 32 float ulps: the double render stays the closer
// approximation of the exact image rather than inheriting float's offsets.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>

#include <glm/glm.hpp>

#include "scene/instances.h"
#include "scene/scene.h"

namespace vitrum {

// The absolute part of the offset (see above); the default is the chapter's constants.
struct RayOffsetScale {
    float origin = 1.0f / 32.0f;         // radius of the region around the origin with absolute offsets
    float absolute = 1.0f / 65536.0f;    // the offset there, in float renders
};

// The scale for a scene whose box has sides `size` (E, the longest; E = 1 for an empty or
// single-point scene, or one with non-finite coordinates).
inline RayOffsetScale rayOffsetScaleOfBox(const glm::vec3& size, bool empty) {
    float extent = std::max(size.x, std::max(size.y, size.z));
    if (empty || !(extent > 0.0f) || !std::isfinite(extent)) extent = 1.0f;
    return {extent / 32.0f, extent / 8388608.0f};
}

// E = the longest side of the triangles' bounding box.
inline RayOffsetScale rayOffsetScale(std::span<const Triangle> triangles) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const Triangle& t : triangles)
        for (const glm::vec3& p : t.position) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    return rayOffsetScaleOfBox(hi - lo, triangles.empty());
}

// The scene's: its triangles' where it has no instances, else E of the box around the world
// triangles and its instances' boxes (scene/instances.h).
inline RayOffsetScale rayOffsetScale(const Scene& scene) {
    if (scene.instances.empty()) return rayOffsetScale(scene.triangles);
    const FloatBox box = worldBox(scene);
    return rayOffsetScaleOfBox(box.max - box.min, false);
}

namespace detail {

inline float offsetComponent(float p, float n, const RayOffsetScale& scale) {
    const float kOrigin = scale.origin;
    const float kFloatScale = scale.absolute;
    constexpr float kIntScale = 32.0f;
    const auto offsetInt = static_cast<std::int32_t>(kIntScale * n);
    const std::int32_t bits = std::bit_cast<std::int32_t>(p);
    // Unsigned arithmetic: the bit pattern is an integer that may wrap, not a signed overflow.
    const auto moved = static_cast<std::uint32_t>(bits) + static_cast<std::uint32_t>(p < 0.0f ? -offsetInt : offsetInt);
    const float pInt = std::bit_cast<float>(moved);
    return std::fabs(p) < kOrigin ? p + kFloatScale * n : pInt;
}

inline double offsetComponent(double p, double n, const RayOffsetScale& scale) {
    const double kOrigin = double(scale.origin);
    const double kFloatScale = double(scale.absolute) / 536870912.0;  // float's offset / 2^29
    constexpr double kIntScale = 32.0;
    const auto offsetInt = static_cast<std::int64_t>(kIntScale * n);
    const std::int64_t bits = std::bit_cast<std::int64_t>(p);
    const auto moved = static_cast<std::uint64_t>(bits) + static_cast<std::uint64_t>(p < 0.0 ? -offsetInt : offsetInt);
    const double pInt = std::bit_cast<double>(moved);
    return std::fabs(p) < kOrigin ? p + kFloatScale * n : pInt;
}

}  // namespace detail

template <class Real>
glm::vec<3, Real> offsetRayOrigin(const glm::vec<3, Real>& p, const glm::vec<3, Real>& n,
                                  const RayOffsetScale& scale = {}) {
    return {detail::offsetComponent(p.x, n.x, scale), detail::offsetComponent(p.y, n.y, scale),
            detail::offsetComponent(p.z, n.z, scale)};
}

}  // namespace vitrum
