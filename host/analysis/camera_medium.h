// The media around the camera, which every primary ray starts inside (render model: "Primary rays
// start with the camera's medium").
//
// A glass object holds the camera when its glass triangles make a closed, consistently wound mesh
// (scene_features.h) whose winding number at the camera's position is above 1/2: +1 inside a
// mesh wound counterclockwise seen from outside, as the renderers' "entering" test assumes, 0
// outside; an open object holds no medium. Where the camera lies on a surface, the media are
// those of the points off it where primary rays start (camera_surface.h), one side each. The media
// are ordered as a ray's stack is, innermost last: by the volume of their boxes, the largest
// first (of two nested closed meshes the inner one has the smaller box). The GPU's stack holds
// gpu::kMaxMediumDepth media, so only that many innermost ones are kept, with a warning; both
// backends start from this list (SceneFeatures::cameraMedia, computed once by analyseScene).
#pragma once

#include <cstdint>
#include <set>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vitrum {

// The media of `triangles` (in the world; `materials` the scene's) around `point` (the camera,
// or where primary rays start off the surface it lies on, camera_surface.h): object indices
// (Triangle::object), innermost last; empty: air. `open` are the glass objects that are not
// closed meshes (openGlassObjects in scene_features.h).
std::vector<std::uint32_t> cameraMedia(std::span<const Triangle> triangles, const std::vector<Material>& materials,
                                       const std::set<std::uint32_t>& open, const glm::dvec3& point);

// The winding number of the triangles at `point` (the sum of their signed solid angles over 4 pi).
double windingNumber(const std::vector<const Triangle*>& triangles, const glm::dvec3& point);

}  // namespace vitrum
