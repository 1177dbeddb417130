// The material whose medium each object encloses, one rule for both backends: the CPU reference
// reads its IOR and Tf where a ray is inside the object, packScene hands it to the kernel.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace vitrum {

// One material index a Scene::objectNames entry (more where a triangle names a later object):
// the object's first glass triangle's material, else its first triangle's, else 0 for an object
// without triangles. Rays enter media only through glass, so only the first case is ever read;
// the others only give every object an index.
std::vector<std::uint32_t> objectMediumMaterials(const Scene& scene);

}  // namespace vitrum
