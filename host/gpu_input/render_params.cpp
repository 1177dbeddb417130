#include "gpu_input/render_params.h"

#include <algorithm>
#include <cmath>

#include "render_model/ray_offset.h"
#include "render_model/sampling.h"

namespace vitrum {

gpu::RenderParams makeRenderParams(const Scene& scene, const SceneFeatures& features, std::uint32_t rootEntry,
                                   std::uint32_t iterationBudget, std::uint32_t firstInstanceNode) {
    const Camera& camera = scene.camera;
    const glm::vec3 z = glm::normalize(camera.from - camera.at);
    const glm::vec3 x = glm::normalize(glm::cross(camera.up, z));
    const glm::vec3 y = glm::cross(z, x);
    const float focal = float(camera.height) / (2.0f * std::tan(glm::radians(camera.fovY) / 2.0f));
    const RenderSettings& s = scene.settings;
    gpu::RenderParams p{};
    gpu::setCamera(p, camera.from, focal, x, y, z);
    gpu::setBackground(p, scene.background.colour, scene.airIor);
    gpu::setImage(p, camera.width, camera.height, s.samplesPerPixel, stratifiedColumns(s.samplesPerPixel));
    gpu::setLimits(p, s.maxDepth, iterationBudget);
    // Every primary ray's medium stack: the media around the camera, or where the camera lies on a
    // surface, those on the ray's side of it (analysis/camera_surface.h).
    const std::vector<std::uint32_t>& around = features.cameraMedia;
    const std::vector<std::uint32_t>& behind = features.cameraMediaBehind;
    gpu::setCounts(p, std::uint32_t(scene.lights.size()), std::uint32_t(scene.textures.size()),
                   std::uint32_t(around.size()), std::uint32_t(behind.size()));
    for (std::size_t i = 0; i < around.size(); ++i) p.cameraMedia[int(i)] = around[i];
    for (std::size_t i = 0; i < behind.size(); ++i) p.cameraMediaBehind[int(i)] = behind[i];
    p.cameraSurface = glm::vec4(features.cameraSurface.normal, 0.0f);
    gpu::setModels(p, std::uint32_t(s.fresnel), std::uint32_t(scene.background.kind), std::uint32_t(s.filter),
                   std::uint32_t(std::max(scene.background.map, 0)));
    // The probes at glass hits. The general kernel asks only whether the scene has two glass
    // objects; the specialized one has the analysis's answer compiled in (boxes that overlap), so
    // it skips probes that could find nothing. The other two are the analysis's answers in both.
    gpu::setSurfaceChecks(p, features.glassObjects >= 2, features.opaqueContactPossible,
                          features.coincidentOpaquePossible);
    const RayOffsetScale offsets = rayOffsetScale(scene);  // Waechter and Binder's, scaled to the scene
    gpu::setThresholds(p, s.minWeight, float(features.touchingDistance), offsets.origin, offsets.absolute);
    gpu::setBvhRoot(p, rootEntry, firstInstanceNode);
    return p;
}

}  // namespace vitrum
