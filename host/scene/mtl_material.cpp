#include "scene/mtl_material.h"

#include <cmath>
#include <string>

#include "common/error.h"
#include "image/srgb.h"

namespace vitrum {
namespace {

glm::vec3 decodeSrgb(glm::vec3 c) { return {srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z)}; }

// `thin_walled 1` makes a glass a wall of no thickness (docs/render-model-decisions.md,
// "Thin-walled glass"): its transmitted light is tinted by Kd (map_Kd), clear without a Kd line;
// what only a medium has (Tf over a length, a priority among media, dispersion, which a pane's
// two parallel faces undo) does not apply and is named.
void thinWalled(const MtlEntry& entry, const std::filesystem::path& mtlFile, Material& m) {
    const std::string material = mtlFile.string() + ": material \"" + entry.name + "\"";
    if (m.model != MaterialModel::Glass) {
        warn(material + " has thin_walled 1 but is not glass; thin_walled ignored");
        return;
    }
    m.model = MaterialModel::ThinGlass;
    if (!entry.kd) m.diffuse = glm::vec3(1.0f);
    std::string ignored;
    if (m.attenuation != glm::vec3(0.0f)) ignored += " Tf";
    if (m.priority != 0) ignored += " priority";
    if (m.abbe > 0.0f) ignored += " Vd";
    if (entry.tint) ignored += " tint (a thin glass is tinted by Kd)";
    m.attenuation = glm::vec3(0.0f);
    m.priority = 0;
    m.abbe = 0.0f;
    m.tint = glm::vec3(1.0f);
    if (!ignored.empty()) warn(material + " is thin-walled glass, which has no medium; ignored:" + ignored);
}

}  // namespace

MaterialModel materialModelFor(std::optional<int> shader, std::optional<int> illum, bool* substituted) {
    if (substituted) *substituted = false;
    switch (shader.value_or(0)) {
        case 1: return MaterialModel::Normal;
        case 2: return MaterialModel::Lambert;
        case 3: return MaterialModel::Phong;
        case 4: return MaterialModel::Glass;
        case 5: return MaterialModel::Lambert;  // the course's path-traced Lambert: its direct-light term
        case 6: return MaterialModel::Mirror;
        default: break;
    }
    if (substituted) *substituted = true;
    // MTL illumination models (Wavefront MTL spec): 4, 6, 7 involve refraction, 3 and 5 are
    // reflective; everything else is a Phong-like surface.
    switch (illum.value_or(2)) {
        case 4:
        case 6:
        case 7: return MaterialModel::Glass;
        case 3:
        case 5: return MaterialModel::Mirror;
        default: return MaterialModel::Phong;
    }
}

Material defaultMaterial() {
    Material m;
    m.name = "default";
    m.model = MaterialModel::Lambert;
    return m;
}

Material materialFromMtl(const MtlEntry& entry, const std::filesystem::path& mtlFile) {
    Material m;  // defaults of scene.h: Ka 0, Kd 0.5 (linear), Ks 0, Ns 1, Ni 1.5, Tf 0
    m.name = entry.name;
    bool substituted = false;
    m.model = materialModelFor(entry.shader, entry.illum, &substituted);
    if (substituted) {
        static constexpr const char* kNames[] = {"", "normal", "Lambert", "Phong", "glass", "", "mirror", "thin glass"};
        std::string shader = entry.shader ? "unsupported shader " + std::to_string(*entry.shader) : "no shader line";
        std::string illum = entry.illum ? "illum " + std::to_string(*entry.illum) : "no illum line";
        int line = entry.shader ? entry.shaderLine : entry.line;
        warn(mtlFile.string() + ":" + std::to_string(line) + ": material \"" + entry.name + "\" has " + shader + "; " +
             illum + " makes it " + kNames[int(m.model)]);
    }
    // Negative coefficients would give negative radiance (../shared/docs/render-model.md: no negative pixel).
    auto clamped = [&](auto value, const char* key) {
        if (glm::all(glm::greaterThanEqual(glm::vec3(value), glm::vec3(0.0f)))) return value;
        warn(mtlFile.string() + ": material \"" + entry.name + "\" has a negative " + key + "; clamped to 0");
        return glm::max(value, decltype(value)(0.0f));
    };
    if (entry.ka) m.ambient = decodeSrgb(clamped(*entry.ka, "Ka"));
    if (entry.kd) m.diffuse = decodeSrgb(clamped(*entry.kd, "Kd"));
    if (entry.ks) m.specular = decodeSrgb(clamped(*entry.ks, "Ks"));
    if (entry.ns) m.shininess = clamped(*entry.ns, "Ns");
    if (entry.tf) m.attenuation = clamped(*entry.tf, "Tf");
    if (entry.priority) m.priority = *entry.priority;
    if (entry.vd) {
        // An Abbe number is positive; 0 is how some files say "none" (render-model-decisions.md,
        // "Dispersion").
        if (*entry.vd >= 0.0f && std::isfinite(*entry.vd))
            m.abbe = *entry.vd;
        else
            warn(mtlFile.string() + ": material \"" + entry.name + "\" has Vd " + std::to_string(*entry.vd) +
                 "; no dispersion");
    }
    if (entry.tint) {
        // A glass's surface tint (render-model-decisions.md, "Glass tint"), sRGB as Kd; it passes
        // light, so it lies within [0, 1].
        const std::string material = mtlFile.string() + ": material \"" + entry.name + "\"";
        if (m.model != MaterialModel::Glass)
            warn(material + " has a tint but is not glass; tint ignored");
        else if (glm::any(glm::lessThan(*entry.tint, glm::vec3(0.0f))) || glm::any(glm::greaterThan(*entry.tint, glm::vec3(1.0f))))
            warn(material + " has a tint outside [0, 1]; kept within it");
        if (m.model == MaterialModel::Glass) m.tint = decodeSrgb(glm::clamp(*entry.tint, 0.0f, 1.0f));
    }
    if (entry.thinWalled == 1) thinWalled(entry, mtlFile, m);
    if (entry.ni) {
        // Some exporters write Ni 0 for opaque materials; an IOR must be positive for the optics.
        if (*entry.ni > 0.0f)
            m.ior = *entry.ni;
        else
            warn(mtlFile.string() + ": material \"" + entry.name + "\" has Ni " + std::to_string(*entry.ni) +
                 "; using 1.5");
    }
    return m;
}

}  // namespace vitrum
