// Where in a glTF file the error tinygltf reports lies. tinygltf names a property ("'count'
// property is not a positive integer.") or a file ("File not found : tri.bin"), not the element
// it belongs to; a file of hundreds of accessors needs the element to be mended.
#pragma once

#include <filesystem>
#include <string>

namespace vitrum {

// tinygltf's `errors` on one line, the first headed by the JSON path of the element it is about
// ("accessors[3]: 'count' property is missing."), found in the file's JSON (a .gltf's text, a
// .glb's JSON chunk), where it names a property or a file this can find; the parent tinygltf
// names ("... missing in Accessor.") is dropped then, since the path says more (and tinygltf
// names some wrongly). Never a guess: where a property may be a number or an array (a node's
// "scale", a texture's) a value of either shape is not named.
std::string describeGltfErrors(const std::filesystem::path& file, const std::string& errors);

}  // namespace vitrum
