// A 64-bit digest of everything in a scene that decides its image: geometry, materials, textures,
// lights, camera, background and settings (not its file names). Ranks of a distributed render
// compare theirs, so that a host with other copies of the files fails the job instead of
// rendering its tiles of another scene (docs/distributed.md).
#pragma once

#include <cstdint>

#include "scene/scene.h"

namespace vitrum {

std::uint64_t sceneFingerprint(const Scene& scene);

}  // namespace vitrum
