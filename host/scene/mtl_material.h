// From an MTL record to a Material of the render model (../shared/docs/render-model.md,
// "Materials"): the course's `shader N` picks the model, `illum` decides when there is no usable
// shader line, Ka Kd Ks are decoded from sRGB, Tf is kept linear. The table is in
// docs/scene-format.md.
#pragma once

#include <filesystem>

#include "scene/mtl_parser.h"
#include "scene/scene.h"

namespace vitrum {

// The model for a shader number (or none) and an illum number (or none); `substituted` tells
// whether the shader line was missing or unsupported so that illum decided.
MaterialModel materialModelFor(std::optional<int> shader, std::optional<int> illum, bool* substituted = nullptr);

// Warns once per material when illum had to decide. Leaves diffuseTexture at -1: textures are
// the loader's (it loads each file once).
Material materialFromMtl(const MtlEntry& entry, const std::filesystem::path& mtlFile);

// What a face without a (known) material gets: a grey Lambert named "default".
Material defaultMaterial();

}  // namespace vitrum
