#include "scene/gltf_errors.h"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <regex>
#include <set>

#include <nlohmann/json.hpp>

#include "common/file_extension.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// The file's JSON: a .gltf's text, or the first chunk of a .glb (glTF 2.0, 4.4.3: it must be the
// JSON chunk). Nothing where it does not parse.
std::optional<json> readDocument(const fs::path& file) {
    try {
        std::ifstream in(file, std::ios::binary);
        if (lowerCaseExtension(file) != ".glb") return json::parse(in);
        std::uint32_t header[5] = {};
        if (!in.read(reinterpret_cast<char*>(header), sizeof header) || header[4] != 0x4E4F534Au) return std::nullopt;
        std::error_code ec;
        const std::uintmax_t size = fs::file_size(file, ec);
        if (ec || header[3] > size - sizeof header) return std::nullopt;
        std::string text(header[3], '\0');
        if (!in.read(text.data(), std::streamsize(text.size()))) return std::nullopt;
        return json::parse(text);
    } catch (const json::exception&) {
        return std::nullopt;
    }
}

// The properties glTF 2.0's schema requires of an object, by its path without indices
// ("meshes.primitives" for meshes[0].primitives[1]).
const std::map<std::string, std::set<std::string>>& requiredProperties() {
    static const std::map<std::string, std::set<std::string>> required = {
        {"asset", {"version"}},
        {"accessors", {"componentType", "count", "type"}},
        {"accessors.sparse", {"count", "indices", "values"}},
        {"accessors.sparse.indices", {"bufferView", "componentType"}},
        {"accessors.sparse.values", {"bufferView"}},
        {"animations", {"channels", "samplers"}},
        {"animations.channels", {"sampler", "target"}},
        {"animations.channels.target", {"path"}},
        {"animations.samplers", {"input", "output"}},
        {"buffers", {"byteLength"}},
        {"bufferViews", {"buffer", "byteLength"}},
        {"cameras", {"type"}},
        {"cameras.orthographic", {"xmag", "ymag", "zfar", "znear"}},
        {"cameras.perspective", {"yfov", "znear"}},
        {"meshes", {"primitives"}},
        {"meshes.primitives", {"attributes"}},
        {"skins", {"joints"}},
        {"extensions.KHR_lights_punctual.lights", {"type"}},
    };
    return required;
}

// An object of the document, with its path ("meshes[0].primitives[1]") and that path without
// indices ("meshes.primitives").
struct Element {
    const json& object;
    std::string path;
    std::string kind;
};

// The first object of the document, in its order, that `wrong` picks; `extras` (an
// application's own data) are not looked into.
std::string firstElement(const json& doc, const std::function<bool(const Element&)>& wrong) {
    std::string found;
    std::function<bool(const json&, const std::string&, const std::string&)> visit =
        [&](const json& value, const std::string& path, const std::string& kind) {
            if (value.is_object()) {
                if (!path.empty() && wrong(Element{value, path, kind})) {
                    found = path;
                    return true;
                }
                for (const auto& [key, member] : value.items())
                    if (key != "extras" &&
                        visit(member, path.empty() ? key : path + "." + key, kind.empty() ? key : kind + "." + key))
                        return true;
            } else if (value.is_array()) {
                for (std::size_t i = 0; i < value.size(); ++i)
                    if (visit(value[i], path + "[" + std::to_string(i) + "]", kind)) return true;
            }
            return false;
        };
    visit(doc, "", "");
    return found;
}

bool allOf(const json& value, bool (json::*is)() const noexcept) {
    if (!value.is_array()) return false;
    for (const json& v : value)
        if (!(v.*is)()) return false;
    return true;
}

// Whether `value` is of the kind an error of tinygltf's says it is not ("a positive integer",
// "an integer type", ...). A scalar kind accepts an array of that kind, and an array accepts a
// number, since the same property is one in one place and the other in another (a node's "scale"
// and a texture's): a value of either shape is not named.
bool isOfKind(const json& value, const std::string& kind) {
    if (kind == "a positive integer") return value.is_number_unsigned() || allOf(value, &json::is_number_unsigned);
    if (kind == "an integer type") return value.is_number_integer() || allOf(value, &json::is_number_integer);
    if (kind == "a number type" || kind == "a number") return value.is_number() || allOf(value, &json::is_number);
    if (kind == "an array") return value.is_array() || value.is_number();
    if (kind == "a bool type") return value.is_boolean();
    if (kind == "a string type") return value.is_string();
    return value.is_object();  // "an object", "a JSON object"
}

std::string findElement(const fs::path& file, const json& doc, const std::string& line) {
    std::smatch m;
    if (std::regex_search(line, m, std::regex("^File not found : (.*)$"))) {
        const std::string missing = m[1];
        return firstElement(doc, [&](const Element& e) {
            if ((e.kind != "buffers" && e.kind != "images") || !e.object.contains("uri") ||
                !e.object["uri"].is_string())
                return false;
            const std::string uri = e.object["uri"].get<std::string>();
            return uri == missing ||
                   (file.parent_path() / uri).lexically_normal() == fs::path(missing).lexically_normal();
        });
    }
    if (std::regex_search(line, m, std::regex("^'([^']+)' property is missing"))) {
        const std::string property = m[1];
        return firstElement(doc, [&](const Element& e) {
            const auto required = requiredProperties().find(e.kind);
            return required != requiredProperties().end() && required->second.count(property) &&
                   !e.object.contains(property);
        });
    }
    if (std::regex_search(line, m,
                          std::regex("^'([^']+)' (?:property|value) is not (a positive integer|an integer type|"
                                     "a number type|a number|an array|a bool type|a string type|an object|"
                                     "a JSON object)"))) {
        const std::string property = m[1];
        const std::string kind = m[2];
        return firstElement(
            doc, [&](const Element& e) { return e.object.contains(property) && !isOfKind(e.object[property], kind); });
    }
    if (std::regex_search(line, std::regex("^Unsupported `type` for accessor object"))) {
        static const std::set<std::string> types = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
        return firstElement(doc, [&](const Element& e) {
            return e.kind == "accessors" && e.object.contains("type") &&
                   !(e.object["type"].is_string() && types.count(e.object["type"].get<std::string>()));
        });
    }
    if (std::regex_search(line, std::regex("^Invalid `componentType` in accessor"))) {
        return firstElement(doc, [&](const Element& e) {
            const json* type = e.object.contains("componentType") ? &e.object["componentType"] : nullptr;
            return e.kind == "accessors" && type &&
                   !(type->is_number_unsigned() && type->get<std::uint64_t>() >= 5120 &&
                     type->get<std::uint64_t>() <= 5126 && type->get<std::uint64_t>() != 5124);
        });
    }
    if (std::regex_search(line, std::regex("^Invalid `byteStride' value"))) {
        return firstElement(doc, [&](const Element& e) {
            if (e.kind != "bufferViews" || !e.object.contains("byteStride")) return false;
            const json& stride = e.object["byteStride"];
            return !(stride.is_number_unsigned() && stride.get<std::uint64_t>() % 4 == 0 &&
                     stride.get<std::uint64_t>() >= 4 && stride.get<std::uint64_t>() <= 252);
        });
    }
    if (std::regex_search(line, std::regex("^'uri' is missing from non binary glTF file buffer"))) {
        return firstElement(doc, [&](const Element& e) { return e.kind == "buffers" && !e.object.contains("uri"); });
    }
    return "";
}

}  // namespace

std::string describeGltfErrors(const fs::path& file, const std::string& errors) {
    const std::size_t begin = errors.find_first_not_of(" \n");
    if (begin == std::string::npos) return "unreadable glTF";
    const std::size_t end = std::min(errors.find('\n', begin), errors.size());
    std::string first = errors.substr(begin, end - begin);
    std::string rest = errors.substr(std::min(errors.size(), end + 1));
    std::replace(rest.begin(), rest.end(), '\n', ' ');
    rest.erase(rest.find_last_not_of(' ') + 1);
    const std::optional<json> doc = readDocument(file);
    const std::string path = doc ? findElement(file, *doc, first) : "";
    if (!path.empty()) first = path + ": " + std::regex_replace(first, std::regex(" in (`\\w+'|\\w+)\\.$"), ".");
    return rest.empty() ? first : first + " " + rest;
}

}  // namespace vitrum
