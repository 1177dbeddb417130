#include "scene/gltf_materials.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <string_view>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "common/error.h"
#include "image/image.h"
#include "image/srgb8_codes.h"
#include "scene/mtl_material.h"
#include "scene/quote_input.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

// alphaMode BLEND: alpha below half the least step of an 8-bit alpha is no surface at all, which
// is cut away (render-model-decisions.md, "Partial coverage").
constexpr double kNoCoverage = 0.5 / 255.0;

const tinygltf::Value* materialExtension(const tinygltf::Material& g, const char* key) {
    auto found = g.extensions.find(key);
    return found == g.extensions.end() ? nullptr : &found->second;
}

glm::vec3 baseColourFactor(const tinygltf::Material& g) {
    const auto& factor = g.pbrMetallicRoughness.baseColorFactor;
    return factor.size() >= 3 ? glm::vec3(glm::make_vec3(factor.data())) : glm::vec3(1.0f);
}

// A textureInfo object inside an extension, which tinygltf passes on as a Value: index -1 where
// it names none.
tinygltf::TextureInfo textureInfo(const tinygltf::Value& t) {
    tinygltf::TextureInfo info;
    info.index = t.Has("index") && t.Get("index").IsNumber() ? t.Get("index").GetNumberAsInt() : -1;
    info.texCoord = t.Has("texCoord") && t.Get("texCoord").IsNumber() ? t.Get("texCoord").GetNumberAsInt() : 0;
    if (t.Has("extensions") && t.Get("extensions").IsObject())
        for (const std::string& key : t.Get("extensions").Keys()) info.extensions[key] = t.Get("extensions").Get(key);
    return info;
}

// A relative URI as a path: percent-escapes decoded (RFC 3986), '/' as separator.
fs::path uriPath(const std::string& uri) {
    std::string path;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            path += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            path += uri[i];
        }
    }
    return fs::path(path);
}

// RFC 4648 base64 (a data URI's payload); nothing where a character is not of its alphabet.
std::optional<std::vector<unsigned char>> base64Bytes(std::string_view text) {
    while (!text.empty() && text.back() == '=') text.remove_suffix(1);
    std::vector<unsigned char> bytes;
    bytes.reserve(text.size() * 3 / 4);
    std::uint32_t bits = 0;
    int count = 0;
    for (const char c : text) {
        const int value = c >= 'A' && c <= 'Z'   ? c - 'A'
                          : c >= 'a' && c <= 'z' ? c - 'a' + 26
                          : c >= '0' && c <= '9' ? c - '0' + 52
                          : c == '+'             ? 62
                          : c == '/'             ? 63
                                                 : -1;
        if (value < 0) return std::nullopt;
        bits = (bits << 6) | std::uint32_t(value);
        if ((count += 6) >= 8) bytes.push_back(static_cast<unsigned char>(bits >> (count -= 8)));
    }
    return bytes;
}

}  // namespace

bool isReadGltfExtension(const std::string& name) {
    static const std::set<std::string> read = {"KHR_materials_transmission", "KHR_materials_volume",
                                               "KHR_materials_ior",          "KHR_materials_specular",
                                               "KHR_materials_dispersion",   "KHR_lights_punctual",
                                               "KHR_texture_transform",      "KHR_materials_pbrSpecularGlossiness",
                                               "KHR_mesh_quantization",      "EXT_meshopt_compression",
                                               "KHR_draco_mesh_compression", "EXT_texture_webp",
                                               "KHR_materials_variants"};
    return read.count(name) != 0;
}

void GltfMaterials::fail(const std::string& message) const { throw inputError(file_, 0, message); }
void GltfMaterials::warnAbout(const std::string& message) const { warn(file_.string() + ": " + message); }

// tinygltf passes an extension's values on unchecked (it keeps only extensions that are objects):
// a "transmissionFactor": "1" read as absent would render glass as plastic without a word, so a
// value of the wrong type is refused.
double GltfMaterials::extensionNumber(const tinygltf::Value& extension, const char* name, const char* key,
                                      double fallback, const std::string& quoted) const {
    if (!extension.Has(key)) return fallback;
    if (!extension.Get(key).IsNumber()) fail(quoted + ": " + name + "'s " + key + " is not a number");
    return extension.Get(key).GetNumberAsDouble();
}

glm::dvec3 GltfMaterials::extensionColour(const tinygltf::Value& extension, const char* name, const char* key,
                                          glm::dvec3 fallback, const std::string& quoted) const {
    if (!extension.Has(key)) return fallback;
    const tinygltf::Value& c = extension.Get(key);
    if (!c.IsArray() || c.ArrayLen() != 3 || !c.Get(0).IsNumber() || !c.Get(1).IsNumber() || !c.Get(2).IsNumber())
        fail(quoted + ": " + name + "'s " + key + " is not three numbers");
    return {c.Get(0).GetNumberAsDouble(), c.Get(1).GetNumberAsDouble(), c.Get(2).GetNumberAsDouble()};
}

std::uint32_t GltfMaterials::defaultMaterial() {
    if (!defaultMaterial_) {
        defaultMaterial_ = std::uint32_t(scene_.materials.size());
        scene_.materials.push_back(vitrum::defaultMaterial());
    }
    return *defaultMaterial_;
}

std::uint32_t GltfMaterials::sceneMaterial(int index) {
    if (index < 0) return defaultMaterial();
    if (std::size_t(index) >= model_.materials.size())
        fail("a primitive names materials[" + std::to_string(index) + "], which does not exist");
    if (auto found = materials_.find(index); found != materials_.end()) return found->second;
    Material made = material(model_.materials[std::size_t(index)], index);  // may add its opaque part first
    const auto sceneIndex = std::uint32_t(scene_.materials.size());
    scene_.materials.push_back(std::move(made));
    return materials_[index] = sceneIndex;
}

// glTF's metallic-roughness materials on the render model's (docs/scene-format.md, "glTF
// materials"): transmission is glass, metal a mirror, the rest the opaque dielectric.
Material GltfMaterials::material(const tinygltf::Material& g, int index) {
    const std::string name = g.name.empty() ? "material" + std::to_string(index) : g.name;
    const std::string quoted = "materials[" + std::to_string(index) + "] (" + quoteInput(name) + ")";
    std::vector<std::string> ignored;
    Material m;
    m.name = name;
    // Of KHR_materials_pbrSpecularGlossiness: its diffuse texture and factor's alpha, which
    // replace the base colour's.
    std::optional<std::pair<tinygltf::TextureInfo, double>> sgColour;
    const auto& pbr = g.pbrMetallicRoughness;
    const glm::vec3 base = baseColourFactor(g);
    auto extension = [&](const char* key) { return materialExtension(g, key); };
    const tinygltf::Value* transmission = extension("KHR_materials_transmission");
    const tinygltf::Value* volume = extension("KHR_materials_volume");
    const tinygltf::Value* iorExtension = extension("KHR_materials_ior");
    const double transmissionFactor =
        transmission ? extensionNumber(*transmission, "KHR_materials_transmission", "transmissionFactor", 0.0, quoted)
                     : 0.0;
    const double ior = iorExtension ? extensionNumber(*iorExtension, "KHR_materials_ior", "ior", 1.5, quoted) : 1.5;
    // KHR_materials_ior allows 0 (an infinite index) and values from 1 up; a refracting
    // medium needs a finite one.
    if (ior >= 1.0 && ior <= 10.0)
        m.ior = float(ior);
    else
        warnAbout(quoted + " has ior " + std::to_string(ior) + "; using 1.5");
    const double thickness = transmissionFactor >= 0.5 && volume
                                 ? extensionNumber(*volume, "KHR_materials_volume", "thicknessFactor", 0.0, quoted)
                                 : 0.0;
    if (transmissionFactor >= 0.5 && !(thickness > 0.0)) {
        // Thin-walled (no volume, or thicknessFactor 0: KHR_materials_volume): a wall of no
        // thickness whose transmitted light the base colour tints (KHR_materials_transmission).
        m.model = MaterialModel::ThinGlass;
        m.diffuse = glm::clamp(base, 0.0f, 1.0f);  // a tint: the light it passes, never more
        if (pbr.baseColorTexture.index >= 0)
            m.diffuseTexture = baseColorTexture(pbr.baseColorTexture, m.diffuse, index, quoted, ignored);
        if (transmissionFactor < 1.0)
            ignored.push_back("transmissionFactor " + std::to_string(transmissionFactor) + " (rendered as 1)");
        if (const tinygltf::Value* dispersion = extension("KHR_materials_dispersion");
            dispersion && extensionNumber(*dispersion, "KHR_materials_dispersion", "dispersion", 0.0, quoted) > 0.0)
            ignored.push_back("KHR_materials_dispersion (a thin wall's two faces undo each other's dispersion)");
        if (extension("KHR_materials_pbrSpecularGlossiness")) ignored.push_back("KHR_materials_pbrSpecularGlossiness");
    } else if (transmissionFactor >= 0.5) {
        m.model = MaterialModel::Glass;
        // KHR_materials_dispersion: dispersion = 20 / V_d, 0 for none.
        if (const tinygltf::Value* dispersion = extension("KHR_materials_dispersion")) {
            const double value = extensionNumber(*dispersion, "KHR_materials_dispersion", "dispersion", 0.0, quoted);
            if (value > 0.0 && std::isfinite(value)) m.abbe = float(20.0 / value);
        }
        if (transmissionFactor < 1.0)
            ignored.push_back("transmissionFactor " + std::to_string(transmissionFactor) + " (rendered as 1)");
        // The base colour tints the light passing through the volume's boundary, at every
        // crossing (KHR_materials_volume, "Base Color and Absorption").
        m.tint = glm::clamp(base, 0.0f, 1.0f);
        const double distance = extensionNumber(*volume, "KHR_materials_volume", "attenuationDistance",
                                                std::numeric_limits<double>::infinity(), quoted);
        if (std::isfinite(distance) && distance > 0.0) {
            const glm::dvec3 colour =
                extensionColour(*volume, "KHR_materials_volume", "attenuationColor", glm::dvec3(1.0), quoted);
            // mu = -ln(colour) / distance (KHR_materials_volume); a colour of 0 would be an
            // infinite mu: the smallest normal float keeps it finite and black.
            for (int i = 0; i < 3; ++i)
                m.attenuation[i] =
                    float(-std::log(std::clamp(colour[i], double(std::numeric_limits<float>::min()), 1.0)) / distance);
        }
        if (pbr.baseColorTexture.index >= 0)
            ignored.push_back("baseColorTexture (a glass volume is tinted by its baseColorFactor alone)");
        if (extension("KHR_materials_pbrSpecularGlossiness")) ignored.push_back("KHR_materials_pbrSpecularGlossiness");
    } else {
        sgColour = opaqueMaterial(g, index, quoted, m, ignored);
        if (transmissionFactor > 0.0)
            ignored.push_back("transmissionFactor " + std::to_string(transmissionFactor) + " (rendered as 0)");
    }
    if (pbr.metallicRoughnessTexture.index >= 0) ignored.push_back("metallicRoughnessTexture");
    if (g.normalTexture.index >= 0) ignored.push_back("normalTexture");
    if (g.occlusionTexture.index >= 0) ignored.push_back("occlusionTexture");
    if (g.emissiveTexture.index >= 0 ||
        (g.emissiveFactor.size() == 3 &&
         (g.emissiveFactor[0] > 0 || g.emissiveFactor[1] > 0 || g.emissiveFactor[2] > 0)))
        ignored.push_back("emission");
    // The base colour's alpha: its texture's and its factor's (the specular-glossiness diffuse's
    // where that replaces the base colour).
    const tinygltf::TextureInfo& alphaSource = sgColour ? sgColour->first : pbr.baseColorTexture;
    const double alphaFactor =
        sgColour ? sgColour->second : (pbr.baseColorFactor.size() >= 4 ? pbr.baseColorFactor[3] : 1.0);
    if (g.alphaMode == "MASK") {
        if (m.model == MaterialModel::Glass) {
            // Said only where it would cut something (exporters write MASK and BLEND on glass
            // whose alpha is 1).
            if (alphaBelow(alphaSource, alphaFactor, g.alphaCutoff, quoted))
                ignored.push_back("alphaMode MASK (a glass volume's surface is closed: it bounds its medium)");
        } else
            m.cutout = alphaTexture(alphaSource, alphaFactor, g.alphaCutoff, "alpha", index, quoted, ignored);
    } else if (g.alphaMode == "BLEND") {
        // Partial coverage (render-model-decisions.md, "Partial coverage"): alpha of the surface
        // is there; where none of it is (alpha 0, below half the least 8-bit step), it is cut away.
        if (!canBePartlyCovered(m.model)) {
            if (alphaBelow(alphaSource, alphaFactor, 1.0, quoted))
                ignored.push_back("alphaMode BLEND (a glass is all there: its transmission is what passes)");
        } else {
            m.coverage = alphaTexture(alphaSource, alphaFactor, 1.0, "alpha", index, quoted, ignored);
            m.cutout = alphaTexture(alphaSource, alphaFactor, kNoCoverage, "where alpha is 0", index, quoted, ignored);
        }
    } else if (g.alphaMode != "OPAQUE" && !g.alphaMode.empty()) {
        ignored.push_back("alphaMode " + g.alphaMode);
    }
    // A factor below 1/2 makes the material opaque whatever its texture says (red is at most 1).
    if (transmission && transmission->Has("transmissionTexture") && transmissionFactor >= 0.5)
        transmissionTexture(g, *transmission, transmissionFactor, index, quoted, m, ignored);
    for (const auto& [key, value] : g.extensions)
        if (!isReadGltfExtension(key)) ignored.push_back(key);
    if (!ignored.empty()) {
        std::string list;
        for (const std::string& item : ignored) list += (list.empty() ? "" : ", ") + item;
        warnAbout(quoted + ": ignored: " + list);
    }
    return m;
}

// What a glTF material is where it is not glass: metal a mirror, else the opaque dielectric (Lambert
// without a specular layer), or KHR_materials_pbrSpecularGlossiness's model where it has that.
// Sets m's model, colours and diffuse texture (m.ior already set); returns the specular-glossiness
// diffuse texture and alpha where they replace the base colour's.
std::optional<std::pair<tinygltf::TextureInfo, double>> GltfMaterials::opaqueMaterial(
    const tinygltf::Material& g, int index, const std::string& quoted, Material& m, std::vector<std::string>& ignored) {
    const auto& pbr = g.pbrMetallicRoughness;
    const glm::vec3 base = baseColourFactor(g);
    auto extension = [&](const char* key) { return materialExtension(g, key); };
    if (const tinygltf::Value* specularGlossiness = extension("KHR_materials_pbrSpecularGlossiness"))
        return specularGlossinessMaterial(*specularGlossiness, index, quoted, m, ignored);
    if (pbr.metallicFactor >= 0.5) {
        m.model = MaterialModel::Mirror;
        m.specular = base;
        if (pbr.metallicFactor < 1.0)
            ignored.push_back("metallicFactor " + std::to_string(pbr.metallicFactor) + " (rendered as 1)");
        if (pbr.roughnessFactor > 0.0) ignored.push_back("roughnessFactor (a metal is a perfect mirror)");
        if (pbr.baseColorTexture.index >= 0) ignored.push_back("baseColorTexture");
    } else if (const tinygltf::Value* specular = extension("KHR_materials_specular");
               specular && extensionNumber(*specular, "KHR_materials_specular", "specularFactor", 1.0, quoted) == 0.0) {
        // No specular layer at all (KHR_materials_specular): the diffuse base alone, Lambert.
        m.model = MaterialModel::Lambert;
        m.diffuse = base;
        if (pbr.baseColorTexture.index >= 0)
            m.diffuseTexture = baseColorTexture(pbr.baseColorTexture, base, index, quoted, ignored);
    } else {
        m.model = MaterialModel::Phong;
        m.diffuse = base;
        // Ks: the highlight's peak is the specular layer's reflectance at normal incidence,
        // min(F0(ior) * specularColorFactor, 1) * specularFactor (KHR_materials_specular), F0
        // against air. Ns from roughness by Walter et al. 2007 ("Microfacet Models for
        // Refraction", eq. 30): Ns = 2 / alpha^2 - 2, alpha = roughness^2, within [1, 10000].
        const float f0 = (m.ior - 1.0f) * (m.ior - 1.0f) / ((m.ior + 1.0f) * (m.ior + 1.0f));
        glm::vec3 colour(1.0f);
        float factor = 1.0f;
        if (const tinygltf::Value* specular = extension("KHR_materials_specular")) {
            factor = float(extensionNumber(*specular, "KHR_materials_specular", "specularFactor", 1.0, quoted));
            colour =
                extensionColour(*specular, "KHR_materials_specular", "specularColorFactor", glm::dvec3(1.0), quoted);
            if (specular->Has("specularTexture") || specular->Has("specularColorTexture"))
                ignored.push_back("KHR_materials_specular's textures");
        }
        m.specular = glm::max(glm::min(f0 * colour, glm::vec3(1.0f)) * factor, glm::vec3(0.0f));
        const double alpha = pbr.roughnessFactor * pbr.roughnessFactor;
        m.shininess = alpha > 0.0 ? float(std::clamp(2.0 / (alpha * alpha) - 2.0, 1.0, 10000.0)) : 10000.0f;
        if (pbr.metallicFactor > 0.0)
            ignored.push_back("metallicFactor " + std::to_string(pbr.metallicFactor) + " (rendered as 0)");
        if (pbr.baseColorTexture.index >= 0)
            m.diffuseTexture = baseColorTexture(pbr.baseColorTexture, base, index, quoted, ignored);
    }
    return std::nullopt;
}

// KHR_materials_transmission's transmissionTexture: the share transmitted is its red channel (as
// stored, not sRGB) times transmissionFactor, and each texel takes the nearer model, as the factor
// does (render-model-decisions.md, "Transmission textures"): the glass `m` where that is 1/2 or more,
// its opaque model elsewhere, added to the scene as m.opaquePart. The texture is read at the
// triangles' coordinates, which are the base colour's where that is read: one named at others
// is ignored, with a word in `ignored`.
void GltfMaterials::transmissionTexture(const tinygltf::Material& g, const tinygltf::Value& transmission, double factor,
                                        int index, const std::string& quoted, Material& m,
                                        std::vector<std::string>& ignored) {
    const tinygltf::Value& value = transmission.Get("transmissionTexture");
    if (!value.IsObject() || !value.Has("index") || !value.Get("index").IsInt() || value.Get("index").Get<int>() < 0)
        fail(quoted + ": KHR_materials_transmission's transmissionTexture has no texture index");
    const tinygltf::TextureInfo info = textureInfo(value);
    const std::optional<glm::dmat3> transform = textureCoordinates(info, "transmissionTexture", quoted, ignored);
    const int source = imageSource(info, quoted, "transmissionTexture");
    if (source < 0) return;  // glass everywhere, as the factor says (warned)
    const auto key = std::make_pair(source, factor);
    std::optional<Texture> made;  // the texture, where this material is the first to need it
    auto found = transmissionTextures_.find(key);
    if (found == transmissionTextures_.end()) {
        const Image decoded = decodeSource(source, quoted, "transmissionTexture");
        // Glass where red times the factor is 1/2 or more: over 1/2, 1 or more. The 8-bit code
        // undoes the decoder's sRGB curve exactly (a 16-bit image keeps 8 bits, ample for 1/2).
        made = Texture{imageName(source).string() + " (transmission)", int(decoded.width), int(decoded.height), {}};
        made->texels.reserve(decoded.pixels.size());
        for (const glm::vec3& texel : decoded.pixels)
            made->texels.emplace_back(float(double(srgb8Code(texel.r)) / 255.0 * factor / 0.5));
        if (std::all_of(made->texels.begin(), made->texels.end(), [](glm::vec3 t) { return t.x >= 1.0f; })) {
            transmissionTextures_[key] = -1;  // glass everywhere: no texture
            return;
        }
    } else if (found->second < 0) {
        return;
    }
    Material opaque;
    opaque.name = m.name + " (where not glass)";
    opaque.ior = m.ior;
    std::vector<std::string> opaqueIgnored;
    opaqueMaterial(g, index, quoted, opaque, opaqueIgnored);
    // The triangles carry the base colour's coordinates where the glass or its opaque part reads
    // that texture; else this texture's transform becomes theirs.
    if (auto base = sources_.find(index); base != sources_.end() && base->second >= 0) {
        const glm::dmat3* baseTransform = uvTransform(index);
        if ((baseTransform ? *baseTransform : glm::dmat3(1.0)) != transform.value_or(glm::dmat3(1.0))) {
            ignored.push_back("transmissionTexture (its KHR_texture_transform is not the baseColorTexture's)");
            return;
        }
    } else if (transform) {
        uvTransforms_[index] = *transform;
    }
    if (made) {
        // Its own texture on the device: it must fit what the opaque part's colour left.
        try {
            texelLimit_.leftAfter(scene_).check(made->path, "its transmission", std::uint64_t(made->width),
                                                std::uint64_t(made->height));
        } catch (const ImageTooLarge& e) {
            fail(quoted + ": transmissionTexture " + e.what());
        }
        transmissionTextures_[key] = int(scene_.textures.size());
        scene_.textures.push_back(std::move(*made));
    }
    for (const std::string& item : opaqueIgnored)
        if (std::find(ignored.begin(), ignored.end(), item) == ignored.end())
            ignored.push_back("where not glass, " + item);
    m.transmissionTexture = transmissionTextures_[key];
    m.opaquePart = int(scene_.materials.size());
    scene_.materials.push_back(std::move(opaque));
}

// KHR_materials_pbrSpecularGlossiness (archived, but what assimp writes), which replaces the
// metallic-roughness model where present: the opaque dielectric with Kd = diffuseFactor (times
// diffuseTexture), Ks = specularFactor (the reflectance at normal incidence, the highlight's
// peak) and Ns from roughness = 1 - glossinessFactor as the metallic-roughness mapping takes it;
// Lambert where specularFactor is 0 (no specular layer).
std::pair<tinygltf::TextureInfo, double> GltfMaterials::specularGlossinessMaterial(const tinygltf::Value& sg, int index,
                                                                                   const std::string& quoted,
                                                                                   Material& m,
                                                                                   std::vector<std::string>& ignored) {
    auto factor = [&](const char* key, int count, glm::vec4 fallback) {
        const tinygltf::Value& v = sg.Get(key);
        if (!sg.Has(key)) return fallback;
        if (!v.IsArray() || v.ArrayLen() != std::size_t(count))
            fail(quoted + ": KHR_materials_pbrSpecularGlossiness's " + key + " is not " + std::to_string(count) +
                 " numbers");
        glm::vec4 out = fallback;
        for (int i = 0; i < count; ++i) {
            if (!v.Get(i).IsNumber())
                fail(quoted + ": KHR_materials_pbrSpecularGlossiness's " + key + " is not numbers");
            out[i] = float(std::clamp(v.Get(i).GetNumberAsDouble(), 0.0, 1.0));
        }
        return out;
    };
    const glm::vec4 diffuseFactor = factor("diffuseFactor", 4, glm::vec4(1.0f));
    const glm::vec3 diffuse(diffuseFactor);
    const glm::vec3 specular(factor("specularFactor", 3, glm::vec4(1.0f)));
    const double glossiness = std::clamp(
        extensionNumber(sg, "KHR_materials_pbrSpecularGlossiness", "glossinessFactor", 1.0, quoted), 0.0, 1.0);
    m.diffuse = diffuse;
    if (specular == glm::vec3(0.0f)) {
        m.model = MaterialModel::Lambert;
    } else {
        m.model = MaterialModel::Phong;
        m.specular = specular;
        const double roughness = 1.0 - glossiness, alpha = roughness * roughness;
        m.shininess = alpha > 0.0 ? float(std::clamp(2.0 / (alpha * alpha) - 2.0, 1.0, 10000.0)) : 10000.0f;
    }
    tinygltf::TextureInfo info;  // index -1: none
    if (sg.Has("diffuseTexture")) {
        info = textureInfo(sg.Get("diffuseTexture"));
        m.diffuseTexture = baseColorTexture(info, diffuse, index, quoted, ignored);
    }
    if (sg.Has("specularGlossinessTexture")) ignored.push_back("specularGlossinessTexture");
    return {info, diffuseFactor.w};
}

// The image a material's base colour texture reads (-1 where it has none it can read, with a
// warning), its KHR_texture_transform kept for the material's triangles (uvTransforms_). Once a
// material: its colour and its cut-outs read the same texture.
int GltfMaterials::baseColorSource(const tinygltf::TextureInfo& info, int material, const std::string& quoted,
                                   std::vector<std::string>& ignored) {
    if (info.index < 0) return -1;
    if (auto found = sources_.find(material); found != sources_.end()) return found->second;
    if (const auto transform = textureCoordinates(info, "baseColorTexture", quoted, ignored))
        uvTransforms_[material] = *transform;
    return sources_[material] = imageSource(info, quoted, "baseColorTexture");
}

// How a texture (`role`) is read: its KHR_texture_transform, if it has one, at TEXCOORD_0 (another
// set, and other extensions of the texture, go into `ignored`).
std::optional<glm::dmat3> GltfMaterials::textureCoordinates(const tinygltf::TextureInfo& info, const char* role,
                                                            const std::string& quoted,
                                                            std::vector<std::string>& ignored) {
    std::optional<glm::dmat3> transform;
    int texCoord = info.texCoord;
    for (const auto& [key, value] : info.extensions) {
        if (key != "KHR_texture_transform") {
            ignored.push_back(std::string(role) + "'s " + key);
            continue;
        }
        transform = textureTransform(value, quoted);
        if (value.Has("texCoord") && value.Get("texCoord").IsNumber())
            texCoord = value.Get("texCoord").GetNumberAsInt();
    }
    if (texCoord != 0)
        ignored.push_back(std::string(role) + "'s TEXCOORD_" + std::to_string(texCoord) + " (TEXCOORD_0 used)");
    return transform;
}

// The image texture info.index reads, or -1 where it has none that can be read (with a warning
// that the texture `role` falls back to its factor).
int GltfMaterials::imageSource(const tinygltf::TextureInfo& info, const std::string& quoted, const char* role) {
    if (std::size_t(info.index) >= model_.textures.size())
        fail(quoted + " names textures[" + std::to_string(info.index) + "], which does not exist");
    // EXT_texture_webp names a WebP image in the texture's extension, beside or instead of its
    // source (a PNG or JPEG fallback); vitrum reads WebP, so the extension's image is taken.
    const tinygltf::Texture& texture = model_.textures[std::size_t(info.index)];
    int source = texture.source;
    if (const auto webp = texture.extensions.find("EXT_texture_webp"); webp != texture.extensions.end()) {
        if (!webp->second.Has("source") || !webp->second.Get("source").IsInt())
            fail(quoted + ": textures[" + std::to_string(info.index) + "]'s EXT_texture_webp has no source");
        source = webp->second.Get("source").Get<int>();
    }
    if (source < 0 || std::size_t(source) >= model_.images.size()) {
        warnAbout(quoted + ": its " + role + " has no image it can read; using its factor");
        source = -1;
    }
    return source;
}

// What messages call the file's images[source]: its file, or its place in the glTF.
fs::path GltfMaterials::imageName(int source) const {
    const tinygltf::Image& image = model_.images[std::size_t(source)];
    return image.uri.empty() || image.uri.starts_with("data:")
               ? fs::path(file_.string() + ": image " + std::to_string(source))
               : file_.parent_path() / uriPath(image.uri);
}

// The file's images[source], decoded within what the device leaves for textures; its alpha
// channel moves to lastAlpha_ (alphaOf), so that a masked or blended material decodes it once.
Image GltfMaterials::decodeSource(int source, const std::string& quoted, const char* role) {
    const tinygltf::Image& image = model_.images[std::size_t(source)];
    const fs::path name = imageName(source);
    try {
        // tinygltf 2.7 decodes the data URIs of PNG, JPEG, BMP and GIF only: an image/webp one
        // comes as its uri.
        std::optional<std::vector<unsigned char>> dataUri;
        if (!image.as_is && image.uri.starts_with("data:")) {
            const std::size_t payload = image.uri.find(";base64,");
            if (payload != std::string::npos) dataUri = base64Bytes(std::string_view(image.uri).substr(payload + 8));
            if (!dataUri) throw inputError(name, 0, "a data URI that is not base64");
        }
        Image decoded = image.as_is ? decodeImage(name, image.image, texelLimit_.leftAfter(scene_))
                        : dataUri   ? decodeImage(name, std::move(*dataUri), texelLimit_.leftAfter(scene_))
                                    : readImage(name, texelLimit_.leftAfter(scene_));
        lastAlpha_ = {source, decoded.width, decoded.height, std::move(decoded.alpha)};
        return decoded;
    } catch (const ImageTooLarge& e) {
        fail(quoted + ": " + role + " " + e.what());
    } catch (const InputError& e) {
        // Refused, unlike an MTL's map_Kd: a glTF's images are part of the asset, and a glass
        // set rendered without its labels is not what its author exported (issue 50).
        fail(quoted + ": its " + role + "'s image cannot be read: " + e.what());
    }
}

// The render model's opaque diffuse colour is the texel alone (Kd or map_Kd): a factor other
// than white is multiplied into a copy of the image, one per image and factor.
int GltfMaterials::baseColorTexture(const tinygltf::TextureInfo& info, glm::vec3 factor, int material,
                                    const std::string& quoted, std::vector<std::string>& ignored) {
    const int source = baseColorSource(info, material, quoted, ignored);
    if (source < 0) return -1;
    const auto key = std::make_tuple(source, factor.x, factor.y, factor.z);
    if (auto found = textures_.find(key); found != textures_.end()) return found->second;
    Image decoded = decodeSource(source, quoted);
    for (glm::vec3& texel : decoded.pixels) texel *= factor;
    const int index = int(scene_.textures.size());
    scene_.textures.push_back(
        Texture{imageName(source), int(decoded.width), int(decoded.height), std::move(decoded.pixels)});
    return textures_[key] = index;
}

// The base colour's alpha (glTF 2.0, "Alpha Coverage": the texture's times the factor's) over
// `over`, as a grey texture read at the base colour's coordinates: per texel of the image, or
// one texel where the image has no alpha channel; none where it is 1 or more everywhere. MASK's
// Material::cutout is alpha over alphaCutoff (cut below 1), BLEND's Material::coverage alpha
// itself and its cutout alpha over kNoCoverage. `what` names it after its image's name ("alpha").
int GltfMaterials::alphaTexture(const tinygltf::TextureInfo& info, double alphaFactor, double over, const char* what,
                                int material, const std::string& quoted, std::vector<std::string>& ignored) {
    if (!(over > 0.0)) return -1;  // alpha is never below 0
    const double scale = std::clamp(alphaFactor, 0.0, 1.0) / over;
    const int source = baseColorSource(info, material, quoted, ignored);
    const auto key = std::make_pair(source, scale);
    if (auto found = alphaTextures_.find(key); found != alphaTextures_.end()) return found->second;
    const std::vector<float>* alpha = source >= 0 ? &alphaOf(source, quoted) : nullptr;
    // Named for `vitrum info`: the image's alpha, or the factor's alone.
    Texture texture{file_.string() + ": " + quoted + "'s baseColorFactor alpha", 1, 1, {glm::vec3(float(scale))}};
    if (alpha && !alpha->empty()) {
        texture.path = imageName(source).string() + " (" + what + ")";
        texture.width = int(lastAlpha_.width);
        texture.height = int(lastAlpha_.height);
        texture.texels.resize(alpha->size());
        for (std::size_t i = 0; i < texture.texels.size(); ++i)
            texture.texels[i] = glm::vec3(float(double((*alpha)[i]) * scale));
    }
    if (std::all_of(texture.texels.begin(), texture.texels.end(), [](glm::vec3 t) { return t.x >= 1.0f; }))
        return alphaTextures_[key] = -1;  // 1 or more everywhere
    // A texture of its own on the device, beside the colour's: it must fit what is left, as a
    // decoded image must (alphaOf may not have decoded it again).
    try {
        texelLimit_.leftAfter(scene_).check(texture.path, "its alpha", std::uint64_t(texture.width),
                                            std::uint64_t(texture.height));
    } catch (const ImageTooLarge& e) {
        fail(quoted + ": baseColorTexture " + e.what());
    }
    const int index = int(scene_.textures.size());
    scene_.textures.push_back(std::move(texture));
    return alphaTextures_[key] = index;
}

// Whether the base colour's alpha (the texture's times the factor's) is below `level` anywhere.
bool GltfMaterials::alphaBelow(const tinygltf::TextureInfo& info, double alphaFactor, double level,
                               const std::string& quoted) {
    const double factor = std::clamp(alphaFactor, 0.0, 1.0);
    if (factor < level) return true;
    const int source = info.index >= 0 ? imageSource(info, quoted, "baseColorTexture") : -1;
    if (source < 0) return false;
    const std::vector<float>& alpha = alphaOf(source, quoted);
    return std::any_of(alpha.begin(), alpha.end(), [&](float a) { return double(a) * factor < level; });
}

// The alpha channel of image `source` (empty where it has none), decoding the image unless it
// was the last one decoded.
const std::vector<float>& GltfMaterials::alphaOf(int source, const std::string& quoted) {
    if (lastAlpha_.source != source) decodeSource(source, quoted);
    return lastAlpha_.alpha;
}

// KHR_texture_transform: uv' = T R S uv in glTF's texture coordinates (v down), with T the
// offset, R the rotation (radians, counter-clockwise seen on the image) and S the scale, as the
// extension's specification writes the matrix.
glm::dmat3 GltfMaterials::textureTransform(const tinygltf::Value& transform, const std::string& quoted) {
    auto pair = [&](const char* key, glm::dvec2 fallback) {
        const tinygltf::Value& v = transform.Get(key);
        if (!transform.Has(key)) return fallback;
        if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
            fail(quoted + ": KHR_texture_transform's " + key + " is not two numbers");
        return glm::dvec2(v.Get(0).GetNumberAsDouble(), v.Get(1).GetNumberAsDouble());
    };
    const glm::dvec2 offset = pair("offset", glm::dvec2(0.0)), scale = pair("scale", glm::dvec2(1.0));
    double rotation = 0.0;
    if (transform.Has("rotation")) {
        if (!transform.Get("rotation").IsNumber()) fail(quoted + ": KHR_texture_transform's rotation is not a number");
        rotation = transform.Get("rotation").GetNumberAsDouble();
    }
    if (!std::isfinite(offset.x + offset.y + scale.x + scale.y + rotation))
        fail(quoted + ": KHR_texture_transform has a number that is not finite");
    const double c = std::cos(rotation), s = std::sin(rotation);
    // Column-major: the specification's rows (1 0 ox; 0 1 oy), (c s 0; -s c 0), (sx 0; 0 sy).
    const glm::dmat3 t(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);
    const glm::dmat3 r(c, -s, 0, s, c, 0, 0, 0, 1);
    const glm::dmat3 sc(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
    return t * r * sc;
}

}  // namespace vitrum
