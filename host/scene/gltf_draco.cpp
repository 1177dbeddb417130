#include "scene/gltf_draco.h"

#include <memory>
#include <stdexcept>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>

namespace vitrum {

PrimitiveVertices decodeDracoPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                       const tinygltf::Value& extension, const std::string& where) {
    const std::string at = where + ": KHR_draco_mesh_compression";
    auto fail = [&](const std::string& message) { throw std::invalid_argument(at + message); };
    auto index = [&](const tinygltf::Value& object, const char* key) -> int {
        if (!object.Has(key) || !object.Get(key).IsInt() || object.Get(key).Get<int>() < 0)
            fail("'s " + std::string(key) + " is not an index");
        return object.Get(key).Get<int>();
    };
    // The compressed bytes, within their buffer.
    const int viewIndex = index(extension, "bufferView");
    if (std::size_t(viewIndex) >= model.bufferViews.size())
        fail(" names bufferViews[" + std::to_string(viewIndex) + "], which does not exist");
    const tinygltf::BufferView& view = model.bufferViews[std::size_t(viewIndex)];
    if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size())
        fail(": its buffer view names a buffer that does not exist");
    const std::vector<unsigned char>& buffer = model.buffers[std::size_t(view.buffer)].data;
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
        fail(": its buffer view reaches beyond its buffer");
    draco::DecoderBuffer bytes;
    bytes.Init(reinterpret_cast<const char*>(buffer.data() + view.byteOffset), view.byteLength);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&bytes);
    if (!decoded.ok()) fail(": its data does not decode (Draco: " + decoded.status().error_msg_string() + ")");
    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();

    // The primitive's attributes that vitrum reads, each the Draco attribute the extension names.
    if (!extension.Has("attributes") || !extension.Get("attributes").IsObject()) fail(" has no attributes");
    const tinygltf::Value& attributes = extension.Get("attributes");
    PrimitiveVertices out;
    auto read = [&](const char* name, int components, std::vector<double>& values) {
        if (!primitive.attributes.count(name) || !attributes.Has(name)) return;
        const draco::PointAttribute* attribute = mesh->GetAttributeByUniqueId(std::uint32_t(index(attributes, name)));
        if (!attribute || attribute->num_components() < components)
            fail("'s " + std::string(name) + " is not an attribute of " + std::to_string(components) +
                 " components in its data");
        values.reserve(std::size_t(mesh->num_points()) * std::size_t(components));
        float value[4];
        for (draco::PointIndex p(0); p < mesh->num_points(); ++p) {
            if (!attribute->ConvertValue<float>(attribute->mapped_index(p), std::int8_t(components), value))
                fail("'s " + std::string(name) + " cannot be read as numbers");
            values.insert(values.end(), value, value + components);
        }
    };
    read("POSITION", 3, out.positions);
    read("NORMAL", 3, out.normals);
    read("TEXCOORD_0", 2, out.uvs);
    out.corners.reserve(std::size_t(mesh->num_faces()) * 3);
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
        for (int c = 0; c < 3; ++c) {
            const std::size_t corner = mesh->face(f)[c].value();
            if (corner >= mesh->num_points()) fail(": a triangle uses a vertex its data does not have");
            out.corners.push_back(corner);
        }
    return out;
}

}  // namespace vitrum
