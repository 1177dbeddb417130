// EXT_meshopt_compression (the Khronos registry's vendor extension, which gltfpack -c writes):
// buffer views stored compressed by meshoptimizer's vertex and index codecs, decoded with
// Debian's libmeshoptimizer (docs/scene-format.md, "glTF 2.0").
//
// The decoded views usually live in a "fallback" buffer that has no data in the file (no uri),
// which tinygltf 2.7 refuses to load. So a file that uses the extension is handed to tinygltf with
// each fallback buffer given a uri that this class's file callbacks answer with one byte, and
// once loaded, each compressed view is decoded into a buffer made for it.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "scene/tinygltf.h"

namespace vitrum {

class GltfMeshopt {
public:
    explicit GltfMeshopt(std::filesystem::path file) : file_(std::move(file)) {}

    // `document` (a .gltf's text or a .glb's bytes) as tinygltf should read it: the same bytes
    // unless its JSON uses EXT_meshopt_compression and has fallback buffers.
    std::vector<unsigned char> prepare(std::vector<unsigned char> document, bool binary);
    // tinygltf's own file callbacks, with the fallback buffers' uris answered. Pass to
    // TinyGLTF::SetFsCallbacks; valid while this object lives.
    tinygltf::FsCallbacks fileCallbacks();
    // Decodes every compressed view of the loaded `model` into its buffer (fallback buffers get
    // their declared length first). Throws InputError naming the file and the view.
    void decode(tinygltf::Model& model) const;

private:
    [[noreturn]] void fail(const std::string& message) const;

    std::filesystem::path file_;
    std::map<int, std::size_t> fallbackLengths_;  // fallback buffer -> its declared byteLength
};

}  // namespace vitrum
