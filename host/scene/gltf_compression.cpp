#include "scene/gltf_compression.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "common/error.h"

namespace vitrum {
namespace {

constexpr const char* kMeshopt = "EXT_meshopt_compression";
constexpr const char* kDraco = "KHR_draco_mesh_compression";
// A fallback buffer's uri: a name no file has (a control character), with the buffer's index.
constexpr std::string_view kFallbackUri = "\x01meshopt-fallback-";

// A decoded view is at most this many times its compressed bytes (and 64 KiB), four times what the
// codecs reach (docs/scene-format.md, "glTF 2.0"): a file cannot ask for memory far beyond its size.
constexpr std::size_t kMaxExpansion = 256;
constexpr std::size_t kExpansionSlack = std::size_t(1) << 16;

bool isFallbackUri(const std::string& path) { return path.find(kFallbackUri) != std::string::npos; }

bool fileExists(const std::string& path, void*) { return isFallbackUri(path) || tinygltf::FileExists(path, nullptr); }

std::string expandFilePath(const std::string& path, void*) {
    return isFallbackUri(path) ? path : tinygltf::ExpandFilePath(path, nullptr);
}

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
    if (!isFallbackUri(path)) return tinygltf::ReadWholeFile(out, err, path, nullptr);
    out->assign(1, 0);  // its byteLength in the prepared JSON; decode() gives it its own
    return true;
}

std::uint32_t readU32(const std::vector<unsigned char>& bytes, std::size_t at) {
    std::uint32_t value;
    std::memcpy(&value, bytes.data() + at, 4);
    return value;
}

void appendU32(std::vector<unsigned char>& bytes, std::uint32_t value) {
    const auto* p = reinterpret_cast<const unsigned char*>(&value);
    bytes.insert(bytes.end(), p, p + 4);
}

}  // namespace

void GltfCompression::fail(const std::string& message) const { throw inputError(file_, 0, message); }

bool GltfCompression::markFallbackBuffers(nlohmann::json& doc) {
    if (!doc.contains("buffers") || !doc["buffers"].is_array()) return false;
    nlohmann::json& buffers = doc["buffers"];
    for (std::size_t i = 0; i < buffers.size(); ++i) {
        nlohmann::json& buffer = buffers[i];
        if (!buffer.is_object() || buffer.contains("uri") || !buffer.contains("byteLength") ||
            !buffer["byteLength"].is_number_unsigned())
            continue;
        const nlohmann::json* extension = nullptr;
        if (buffer.contains("extensions") && buffer["extensions"].is_object() &&
            buffer["extensions"].contains(kMeshopt))
            extension = &buffer["extensions"][kMeshopt];
        if (!extension || !extension->is_object() || extension->value("fallback", false) != true) continue;
        fallbackLengths_[int(i)] = buffer["byteLength"].get<std::size_t>();
        buffer["uri"] = std::string(kFallbackUri) + std::to_string(i);
        buffer["byteLength"] = 1;
    }
    return !fallbackLengths_.empty();
}

// Each indices accessor of a Draco primitive that has no buffer view gets one of one byte in the
// buffer of the primitive's compressed data (or buffer 0): tinygltf refuses indices without one.
bool GltfCompression::giveDracoIndicesAView(nlohmann::json& doc) {
    if (!doc.contains("meshes") || !doc["meshes"].is_array() || !doc.contains("accessors") ||
        !doc["accessors"].is_array() || !doc.contains("bufferViews") || !doc["bufferViews"].is_array())
        return false;
    nlohmann::json& accessors = doc["accessors"];
    nlohmann::json& views = doc["bufferViews"];
    bool given = false;
    for (nlohmann::json& mesh : doc["meshes"]) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        for (nlohmann::json& primitive : mesh["primitives"]) {
            if (!primitive.is_object() || !primitive.contains("indices") ||
                !primitive["indices"].is_number_unsigned() || !primitive.contains("extensions") ||
                !primitive["extensions"].is_object() || !primitive["extensions"].contains(kDraco))
                continue;
            const std::size_t indices = primitive["indices"].get<std::size_t>();
            if (indices >= accessors.size() || !accessors[indices].is_object() ||
                accessors[indices].contains("bufferView"))
                continue;
            const nlohmann::json& draco = primitive["extensions"][kDraco];
            std::size_t buffer = 0;
            if (draco.is_object() && draco.contains("bufferView") && draco["bufferView"].is_number_unsigned() &&
                draco["bufferView"].get<std::size_t>() < views.size()) {
                const nlohmann::json& view = views[draco["bufferView"].get<std::size_t>()];
                if (view.is_object() && view.contains("buffer") && view["buffer"].is_number_unsigned())
                    buffer = view["buffer"].get<std::size_t>();
            }
            views.push_back({{"buffer", buffer}, {"byteLength", 1}});
            accessors[indices]["bufferView"] = views.size() - 1;
            given = true;
        }
    }
    return given;
}

std::vector<unsigned char> GltfCompression::prepare(std::vector<unsigned char> document, bool binary) {
    // A .glb's JSON is its first chunk (glTF 2.0, 4.4.3); one that is malformed is left for
    // tinygltf to name.
    std::size_t jsonBegin = 0, jsonLength = document.size();
    if (binary) {
        if (document.size() < 20 || readU32(document, 16) != 0x4E4F534Au) return document;
        jsonBegin = 20;
        jsonLength = readU32(document, 12);
        if (jsonLength > document.size() - 20) return document;
    }
    const std::string_view text(reinterpret_cast<const char*>(document.data()) + jsonBegin, jsonLength);
    if (text.find(kMeshopt) == std::string_view::npos && text.find(kDraco) == std::string_view::npos) return document;
    nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
    if (doc.is_discarded() || !doc.is_object()) return document;
    const bool marked = markFallbackBuffers(doc);
    const bool given = giveDracoIndicesAView(doc);
    if (!marked && !given) return document;
    std::string json = doc.dump();
    if (!binary) return std::vector<unsigned char>(json.begin(), json.end());
    while (json.size() % 4) json += ' ';
    const std::size_t rest = jsonBegin + jsonLength;  // the chunks after the JSON (the BIN chunk)
    std::vector<unsigned char> glb;
    glb.reserve(20 + json.size() + document.size() - rest);
    appendU32(glb, readU32(document, 0));  // "glTF"
    appendU32(glb, readU32(document, 4));  // its version
    appendU32(glb, std::uint32_t(20 + json.size() + document.size() - rest));
    appendU32(glb, std::uint32_t(json.size()));
    appendU32(glb, 0x4E4F534Au);  // "JSON"
    glb.insert(glb.end(), json.begin(), json.end());
    glb.insert(glb.end(), document.begin() + std::ptrdiff_t(rest), document.end());
    return glb;
}

tinygltf::FsCallbacks GltfCompression::fileCallbacks() {
    return tinygltf::FsCallbacks{&fileExists, &expandFilePath, &readWholeFile, &tinygltf::WriteWholeFile, nullptr};
}

void GltfCompression::decodeMeshopt(tinygltf::Model& model) const {
    struct View {
        int index;
        std::size_t source, sourceOffset, sourceLength, stride, count;
        std::string mode, filter;
    };
    std::vector<View> views;
    std::map<int, std::size_t> decodedInto;  // a fallback buffer -> the bytes its views decode to
    for (std::size_t i = 0; i < model.bufferViews.size(); ++i) {
        const tinygltf::BufferView& view = model.bufferViews[i];
        const auto found = view.extensions.find(kMeshopt);
        if (found == view.extensions.end()) continue;
        const tinygltf::Value& e = found->second;
        const std::string where = "bufferViews[" + std::to_string(i) + "]: " + kMeshopt;
        auto count = [&](const char* key, bool required) -> std::size_t {
            if (!e.Has(key)) {
                if (required) fail(where + " has no " + key);
                return 0;
            }
            const double value = e.Get(key).IsNumber() ? e.Get(key).GetNumberAsDouble() : -1.0;
            if (!(value >= 0.0 && value <= 9007199254740992.0 && std::floor(value) == value))
                fail(where + "'s " + key + " is not a count of bytes or elements");
            return std::size_t(value);
        };
        auto text = [&](const char* key, const char* fallback) -> std::string {
            if (!e.Has(key)) return fallback;
            if (!e.Get(key).IsString()) fail(where + "'s " + key + " is not a string");
            return e.Get(key).Get<std::string>();
        };
        View v{int(i),
               count("buffer", true),
               count("byteOffset", false),
               count("byteLength", true),
               count("byteStride", true),
               count("count", true),
               text("mode", ""),
               text("filter", "NONE")};
        if (v.source >= model.buffers.size())
            fail(where + " names buffers[" + std::to_string(v.source) + "], which does not exist");
        const std::size_t sourceSize = model.buffers[v.source].data.size();
        if (v.sourceOffset > sourceSize || v.sourceLength > sourceSize - v.sourceOffset)
            fail(where + "'s compressed bytes reach beyond buffers[" + std::to_string(v.source) + "]");
        const bool attributes = v.mode == "ATTRIBUTES";
        if (!attributes && v.mode != "TRIANGLES" && v.mode != "INDICES")
            fail(where + " has the mode \"" + v.mode + "\"; the extension has ATTRIBUTES, TRIANGLES and INDICES");
        if (attributes ? (v.stride == 0 || v.stride % 4 != 0 || v.stride > 256) : (v.stride != 2 && v.stride != 4))
            fail(where + " has a byteStride of " + std::to_string(v.stride) + ", which its mode does not allow");
        if (v.mode == "TRIANGLES" && v.count % 3 != 0)
            fail(where + " has " + std::to_string(v.count) + " indices of triangles, not a multiple of 3");
        if (v.count > (kMaxExpansion * v.sourceLength + kExpansionSlack) / v.stride)
            fail(where + " decodes " + std::to_string(v.count) + " elements from " + std::to_string(v.sourceLength) +
                 " bytes, more than the codecs can");
        const std::size_t decoded = v.count * v.stride;
        if (view.byteLength != decoded)
            fail(where + " decodes " + std::to_string(decoded) + " bytes into a view of " +
                 std::to_string(view.byteLength));
        if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size())
            fail("bufferViews[" + std::to_string(i) + "] names a buffer that does not exist");
        const auto fallback = fallbackLengths_.find(view.buffer);
        const std::size_t targetSize =
            fallback != fallbackLengths_.end() ? fallback->second : model.buffers[std::size_t(view.buffer)].data.size();
        if (view.byteOffset > targetSize || decoded > targetSize - view.byteOffset)
            fail("bufferViews[" + std::to_string(i) + "] reaches beyond its buffer");
        if (fallback != fallbackLengths_.end()) decodedInto[view.buffer] += decoded;
        views.push_back(std::move(v));
    }
    // A fallback buffer holds its views (and their alignment), no more: its length is made, not read.
    for (const auto& [buffer, length] : fallbackLengths_) {
        if (length > decodedInto[buffer] + 16 * views.size())
            fail("buffers[" + std::to_string(buffer) + "]: its byteLength of " + std::to_string(length) +
                 " is more than its compressed views decode to");
        model.buffers[std::size_t(buffer)].data.assign(length, 0);
    }
    std::vector<unsigned char> decoded;
    for (const View& v : views) {
        tinygltf::BufferView& view = model.bufferViews[std::size_t(v.index)];
        const std::string where = "bufferViews[" + std::to_string(v.index) + "]: " + kMeshopt;
        decoded.assign(v.count * v.stride, 0);
        const unsigned char* source = model.buffers[v.source].data.data() + v.sourceOffset;
        const int status = v.mode == "ATTRIBUTES"
                               ? meshopt_decodeVertexBuffer(decoded.data(), v.count, v.stride, source, v.sourceLength)
                           : v.mode == "TRIANGLES"
                               ? meshopt_decodeIndexBuffer(decoded.data(), v.count, v.stride, source, v.sourceLength)
                               : meshopt_decodeIndexSequence(decoded.data(), v.count, v.stride, source, v.sourceLength);
        if (status != 0)
            fail(where + ": its bytes do not decode (meshoptimizer's status " + std::to_string(status) + ")");
        if (v.filter != "NONE" && v.mode != "ATTRIBUTES") fail(where + ": a filter applies to ATTRIBUTES only");
        if (v.filter == "OCTAHEDRAL" && (v.stride == 4 || v.stride == 8))
            meshopt_decodeFilterOct(decoded.data(), v.count, v.stride);
        else if (v.filter == "QUATERNION" && v.stride == 8)
            meshopt_decodeFilterQuat(decoded.data(), v.count, v.stride);
        else if (v.filter == "EXPONENTIAL")
            meshopt_decodeFilterExp(decoded.data(), v.count, v.stride);
        else if (v.filter != "NONE")
            fail(where + " has the filter \"" + v.filter + "\" with a byteStride of " + std::to_string(v.stride) +
                 ", which the extension does not define");
        std::memcpy(model.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset, decoded.data(),
                    decoded.size());
    }
}

}  // namespace vitrum
