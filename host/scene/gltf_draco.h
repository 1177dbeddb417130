// KHR_draco_mesh_compression: a glTF primitive's attributes and indices stored as one Draco
// mesh in a buffer view, decoded with Debian's libdraco (docs/scene-format.md, "glTF 2.0").
// tinygltf 2.7's own Draco support reads buffer views without checking them, so vitrum decodes
// the extension itself.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "scene/tinygltf.h"

namespace vitrum {

// A primitive's vertices as the loader reads an uncompressed one's: 3 numbers a vertex for
// positions and normals, 2 for texture coordinates (normals and uvs empty where the primitive has
// none), and 3 corners (vertex indices) a triangle.
struct PrimitiveVertices {
    std::vector<double> positions, normals, uvs;
    std::vector<std::size_t> corners;
};

// Decodes the primitive's KHR_draco_mesh_compression `extension` of `model`; `where` names the
// primitive. An attribute the extension does not name is left empty: the file stores it
// uncompressed, in its accessor. Throws std::invalid_argument with the reason (after `where`)
// where the extension or its data is wrong.
PrimitiveVertices decodeDracoPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                       const tinygltf::Value& extension, const std::string& where);

}  // namespace vitrum
