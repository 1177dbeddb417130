// tinygltf as vitrum uses it: without its own image decoding and without reading image files,
// so that every glTF image goes through vitrum's decoder (texel limit, sRGB rule, refusal of
// truncated images) as MTL textures do. Every file that includes tinygltf includes it through here:
// the options change its classes' defaults.
#pragma once

#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
