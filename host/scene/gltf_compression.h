// Compressed glTF geometry that tinygltf 2.7 cannot load by itself (docs/scene-format.md,
// "glTF 2.0"):
// - EXT_meshopt_compression (gltfpack -c): buffer views stored compressed by meshoptimizer's
//   codecs, decoded here with Debian's libmeshoptimizer. The decoded views usually live in a
//   "fallback" buffer without data (no uri), which tinygltf refuses; so such a buffer is given a
//   uri that this class's file callbacks answer with one byte, and decodeMeshopt() then makes it.
// - KHR_draco_mesh_compression: a primitive's accessors have no buffer views (its data is one
//   Draco mesh, gltf_draco.h), which tinygltf refuses for indices; so such an indices accessor is
//   given a view of one byte, which nothing reads.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "scene/tinygltf.h"

namespace vitrum {

class GltfCompression {
public:
    explicit GltfCompression(std::filesystem::path file) : file_(std::move(file)) {}

    // `document` (a .gltf's text or a .glb's bytes) as tinygltf should read it: the same bytes
    // unless its JSON uses EXT_meshopt_compression with fallback buffers or
    // KHR_draco_mesh_compression.
    std::vector<unsigned char> prepare(std::vector<unsigned char> document, bool binary);
    // tinygltf's own file callbacks, with the fallback buffers' uris answered (TinyGLTF::SetFsCallbacks).
    static tinygltf::FsCallbacks fileCallbacks();
    // Decodes every compressed view of the loaded `model` into its buffer (fallback buffers get
    // their declared length first). Throws InputError naming the file and the view.
    void decodeMeshopt(tinygltf::Model& model) const;

private:
    [[noreturn]] void fail(const std::string& message) const;
    // The rewrites of prepare(), each true where it changed `doc`.
    bool markFallbackBuffers(nlohmann::json& doc);
    static bool giveDracoIndicesAView(nlohmann::json& doc);

    std::filesystem::path file_;
    std::map<int, std::size_t> fallbackLengths_;  // fallback buffer -> its declared byteLength
};

}  // namespace vitrum
