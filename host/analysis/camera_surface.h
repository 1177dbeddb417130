// The surface the camera lies on, if any. A ray never re-hits the surface it starts on (render
// model), and a primary ray starts at the camera: where the camera lies on a surface (a floor at
// eye level zero, a pane of glass), every primary ray would meet it at a distance of about 0 that
// rounding alone makes positive or negative, and the image would be speckled with hits of it. So,
// as a secondary ray leaves its hit point, a primary ray starts off that plane on the side it goes
// to: offsetRayOrigin(from, +-normal) (render_model/ray_offset.h), with the media of that side
// (camera_medium.h).
//
// The camera lies on a triangle when its distance to it is at most the offset a ray starting
// there would get along the triangle's normal (32 float ulps of its coordinates, or the absolute
// offset near the origin): closer than rounding can tell apart.
#pragma once

#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "render_model/ray_offset.h"
#include "scene/scene.h"

namespace vitrum {

struct CameraSurface {
    glm::vec3 normal{0.0f};       // unit geometric normal of the plane the camera lies on; 0: none
    std::uint32_t triangles = 0;  // the triangles the camera lies on
    // Some of those triangles lie in another plane (the camera is on an edge or a corner where
    // surfaces meet at an angle): primary rays start off the first plane only.
    bool otherPlanes = false;
};

// Among `triangles` (in the world), for a camera at `from`; `scale`: the scene's ray offsets
// (rayOffsetScale), as the renderers use them.
CameraSurface cameraSurface(std::span<const Triangle> triangles, const glm::vec3& from, const RayOffsetScale& scale);

// Where a primary ray of direction `d` starts: off the camera's surface (`normal`, from
// CameraSurface) on the side `d` goes to, along +normal where d is parallel to it; `from` itself
// where the normal is 0. shaders/ray_tree.glsl's startPrimaryRay does the same.
template <class Real>
glm::vec<3, Real> primaryRayOrigin(const glm::vec<3, Real>& from, const glm::vec<3, Real>& normal,
                                   const glm::vec<3, Real>& d, const RayOffsetScale& scale) {
    return offsetRayOrigin(from, glm::dot(d, normal) < Real(0) ? -normal : normal, scale);
}

}  // namespace vitrum
