// `vitrum render`'s options: what the command line asks for, before any file is read.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/vulkan_renderer.h"
#include "scene/scene.h"
#include "scene/texel_limit.h"

namespace vitrum {

enum class Backend { Vulkan, Cpu };

struct RenderCommand {
    std::string scenePath;
    std::string outputPath;
    std::string statsPath;
    Backend backend = Backend::Vulkan;
    std::string device;
    bool doublePrecision = false;
    unsigned threads = 0;
    VulkanRenderOptions gpu;
    // Overrides of the scene.
    std::optional<std::uint32_t> width, height, spp, maxDepth, wavelengths;
    std::optional<float> minWeight, fov;
    std::optional<FresnelModel> fresnel;
    std::optional<TextureFilter> filter;
    std::optional<glm::vec3> from, at, up, background;
    std::string backgroundMap;  // --background FILE: an equirectangular map in place of the scene's background
    std::vector<glm::vec3> lights;
    std::string camera;      // a glTF scene's camera by name
    std::string variant;     // a glTF scene's material variant by name
    bool instancing = true;  // repeated meshes stored once (SceneLoadOptions::instancing)
};

// The command's help, its ranges and defaults from the constants the parser and the scene use.
std::string renderHelp();

// argv[first..] as the render command's options. Touches no file; throws InputError naming the
// option that is wrong.
RenderCommand parseRenderCommand(int argc, char** argv, int first);

// Fails before any long work when the output or the statistics cannot be written where asked, or
// would overwrite the scene file.
void checkOutputs(const RenderCommand& command);
// Fails, once the scene is loaded and before it is rendered, when the output would overwrite a
// texture or environment map of the scene.
void checkOutputsSpareTheScenesImages(const RenderCommand& command, const Scene& scene);

// The command's overrides of the scene's own settings (a background map read within `limit`),
// then the checks of the camera, the lights and the image's size that a scene file's values pass
// too.
void applyOverrides(const RenderCommand& command, Scene& scene, const TexelLimit& limit = {});

}  // namespace vitrum
