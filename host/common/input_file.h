// Files a user names (the scene, OBJ, MTL, textures, backgrounds): each is checked to be a
// regular file before it is read, without blocking, so that a FIFO, a device or a directory is
// refused at once by name; and it is read with its size limit checked while reading, never
// after (docs/scene-format.md, "Size limits").
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace vitrum {

// The largest files vitrum reads: a JSON scene or an MTL file; an OBJ file; an image.
inline constexpr std::uint64_t kMaxSceneFileBytes = std::uint64_t(64) << 20;
inline constexpr std::uint64_t kMaxObjFileBytes = std::uint64_t(4) << 30;
inline constexpr std::uint64_t kMaxImageFileBytes = (std::uint64_t(2) << 30) - 1;
// A .gltf or .glb file (tinygltf reads a document of up to 2^32 - 1 bytes; a .glb's header
// cannot give more); its .bin files are tinygltf's to read.
inline constexpr std::uint64_t kMaxGltfFileBytes = (std::uint64_t(4) << 30) - 1;

// Throws InputError "PATH: cannot open WHAT (no such file)", "... (not a regular file: a FIFO)"
// and the like unless `path` names a regular file. `what`: "the OBJ file", "the image", ...
void requireRegularFile(const std::filesystem::path& path, const std::string& what);

// The whole of a regular file of at most `maxBytes`, read without blocking on a FIFO or a device
// and without reading more than `maxBytes` + 1 bytes of anything. Throws InputError naming it.
std::vector<unsigned char> readInputFile(const std::filesystem::path& path, const std::string& what,
                                         std::uint64_t maxBytes);
std::string readInputText(const std::filesystem::path& path, const std::string& what, std::uint64_t maxBytes);

// readInputText for the line-based text formats (OBJ, MTL): a UTF-8 byte order mark is dropped
// (tinyobjloader read "<BOM>v 0 0 5" as an unknown statement and lost the vertex, so every face
// used the wrong vertices, without an error), and UTF-16 or UTF-32 text is refused by name. Lines
// end at "\n", "\r\n" or a lone "\r", as tinyobjloader reads them (a file of classic Mac lines was
// one line to the MTL reader), and come back ending in "\n"; a NUL byte, where tinyobjloader
// ends a line without a word (a quad became a triangle), is refused with its line.
std::string readInputLines(const std::filesystem::path& path, const std::string& what, std::uint64_t maxBytes);

}  // namespace vitrum
