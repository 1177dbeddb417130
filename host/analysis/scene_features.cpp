#include "analysis/scene_features.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <set>
#include <unordered_map>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "analysis/camera_medium.h"
#include "analysis/double_box.h"
#include "analysis/glass_proximity.h"
#include "scene/scene_names.h"
#include "shared/gpu_types.h"

namespace vitrum {
namespace {

// Boxes of the objects that have glass triangles (all of each such object's triangles).
std::vector<DoubleBox> glassObjectBoxes(const Scene& scene) {
    std::set<std::uint32_t> glass;
    for (const Triangle& t : scene.triangles)
        if (scene.materials[t.material].model == MaterialModel::Glass) glass.insert(t.object);
    std::map<std::uint32_t, DoubleBox> boxes;
    for (const Triangle& t : scene.triangles)
        if (glass.count(t.object))
            for (const glm::vec3& p : t.position) boxes[t.object].grow(glm::dvec3(p));
    std::vector<DoubleBox> result;
    for (const auto& [object, box] : boxes) result.push_back(box);
    return result;
}

// A directed edge between two vertex positions, compared bit for bit (an OBJ's shared vertices
// have identical positions in every triangle that uses them).
struct Edge {
    std::uint32_t bits[6];
    bool operator==(const Edge& o) const { return std::memcmp(bits, o.bits, sizeof(bits)) == 0; }
};

struct EdgeHash {
    std::size_t operator()(const Edge& e) const {
        std::size_t h = 1469598103934665603ull;
        for (std::uint32_t b : e.bits) h = (h ^ b) * 1099511628211ull;
        return h;
    }
};

Edge edge(const glm::vec3& a, const glm::vec3& b) {
    Edge e;
    std::memcpy(e.bits, &a, 12);
    std::memcpy(e.bits + 3, &b, 12);
    return e;
}

Edge reversed(const Edge& e) {
    Edge r;
    std::memcpy(r.bits, e.bits + 3, 12);
    std::memcpy(r.bits + 3, e.bits, 12);
    return r;
}

}  // namespace

namespace {

// The objects whose triangles that `counts` are not a closed, consistently wound mesh.
template <class Counts>
std::set<std::uint32_t> openObjects(const Scene& scene, Counts counts) {
    std::map<std::uint32_t, std::unordered_map<Edge, int, EdgeHash>> edges;
    for (const Triangle& t : scene.triangles) {
        if (!counts(t)) continue;
        auto& objectEdges = edges[t.object];
        for (int i = 0; i < 3; ++i) objectEdges[edge(t.position[i], t.position[(i + 1) % 3])] += 1;
    }
    std::set<std::uint32_t> open;
    for (const auto& objectAndEdges : edges) {
        // Not a structured binding: C++20 lets a lambda capture one, but clang only from version
        // 16 on, and the fuzz build's clang is Debian 12's 14.
        const auto& objectEdges = objectAndEdges.second;
        const bool closed = std::all_of(objectEdges.begin(), objectEdges.end(), [&](const auto& entry) {
            const Edge reverse = reversed(entry.first);
            const auto found = objectEdges.find(reverse);
            return entry.second == 1 && !(reverse == entry.first) && found != objectEdges.end() && found->second == 1;
        });
        if (!closed) open.insert(objectAndEdges.first);
    }
    return open;
}

}  // namespace

std::set<std::uint32_t> openGlassObjects(const Scene& scene) {
    return openObjects(scene,
                       [&](const Triangle& t) { return scene.materials[t.material].model == MaterialModel::Glass; });
}

std::set<std::uint32_t> opaqueObjectsMetFromBehind(const Scene& scene, const std::vector<glm::dvec3>& rayStarts) {
    auto isGlass = [&](const Triangle& t) { return scene.materials[t.material].model == MaterialModel::Glass; };
    std::map<std::uint32_t, std::vector<const Triangle*>> opaque;
    std::set<std::uint32_t> withGlass;
    for (const Triangle& t : scene.triangles) {
        if (isGlass(t)) withGlass.insert(t.object);
        else opaque[t.object].push_back(&t);
    }
    const std::set<std::uint32_t> open = openObjects(scene, [&](const Triangle& t) { return !isGlass(t); });
    std::set<std::uint32_t> metFromBehind;
    for (const auto& [object, triangles] : opaque) {
        // Six times the enclosed volume, positive where the mesh is wound counterclockwise seen
        // from outside (its normals point out); taken about a corner, which keeps it exact enough
        // far from the origin.
        const glm::dvec3 corner(triangles.front()->position[0]);
        double volume = 0.0;
        for (const Triangle* t : triangles)
            volume += glm::dot(glm::dvec3(t->position[0]) - corner,
                               glm::cross(glm::dvec3(t->position[1]) - corner, glm::dvec3(t->position[2]) - corner));
        bool met = withGlass.count(object) || open.count(object) || !(volume > 0.0);
        for (const glm::dvec3& start : rayStarts) met = met || windingNumber(triangles, start) > 0.5;
        if (met) metFromBehind.insert(object);
    }
    return metFromBehind;
}

double sceneDiagonal(const std::vector<Triangle>& triangles) {
    DoubleBox box;
    for (const Triangle& t : triangles)
        for (const glm::vec3& p : t.position) box.grow(glm::dvec3(p));
    return triangles.empty() ? 0.0 : glm::length(box.max - box.min);
}

SceneFeatures analyseScene(const Scene& scene) {
    SceneFeatures f;
    for (const Triangle& t : scene.triangles) f.materialModels |= 1u << std::uint32_t(scene.materials[t.material].model);
    std::set<std::uint32_t> used;
    for (const Triangle& t : scene.triangles) used.insert(t.material);
    for (std::uint32_t index : used) {
        const Material& m = scene.materials[index];
        switch (m.model) {
            case MaterialModel::Glass:
                f.glass = f.reflection = true;
                if (m.attenuation != glm::vec3(0.0f)) f.absorbingMedia = true;
                break;
            case MaterialModel::Mirror: f.reflection = true; break;
            case MaterialModel::Phong: f.reflection = true; [[fallthrough]];
            case MaterialModel::Lambert:
                if (!scene.lights.empty()) f.shadowRays = true;
                if (m.diffuseTexture >= 0) f.textures = true;
                break;
            case MaterialModel::Normal: break;
        }
    }

    const std::vector<DoubleBox> boxes = glassObjectBoxes(scene);
    f.glassObjects = std::uint32_t(boxes.size());
    f.touchingDistance = kTouchingTolerance * sceneDiagonal(scene.triangles);
    // Boxes grown by twice the touching distance: a probe reaches that far on either side of a hit.
    const double margin = 2.0 * f.touchingDistance;
    std::vector<std::uint32_t> overlaps(boxes.size(), 0);
    forEachBoxPairWithin(boxes, margin, [&](std::size_t i, std::size_t j) {
        ++overlaps[i];
        ++overlaps[j];
    });
    const std::uint32_t mostOverlaps = overlaps.empty() ? 0 : *std::max_element(overlaps.begin(), overlaps.end());
    // Overlapping boxes say that two objects may touch or one lie in the other; only the
    // triangles tell which (a bubble in a block is nested, never touching).
    f.touchingMediaPossible = mostOverlaps > 0 && findCloseGlassTriangles(scene, margin).found;
    f.opaqueContactPossible = f.glass && findGlassNearOpaque(scene, margin).found;
    const std::set<std::uint32_t> open = openGlassObjects(scene);
    f.openGlassObjects = std::uint32_t(open.size());
    // A primary ray's media are those where it starts: off the camera's surface on its side.
    const RayOffsetScale offsets = rayOffsetScale(scene.triangles);
    f.cameraSurface = cameraSurface(scene, offsets);
    const glm::vec3 from = scene.camera.from;
    const glm::vec3 normal = f.cameraSurface.normal;
    // Where primary rays start: off the surface on each side of it, or at the camera.
    std::vector<glm::dvec3> primaryStarts = {glm::dvec3(offsetRayOrigin(from, normal, offsets))};
    if (f.cameraSurface.triangles != 0) primaryStarts.push_back(glm::dvec3(offsetRayOrigin(from, -normal, offsets)));
    f.cameraMedia = cameraMedia(scene, open, primaryStarts.front());
    f.cameraMediaBehind = primaryStarts.size() == 1 ? f.cameraMedia : cameraMedia(scene, open, primaryStarts.back());
    f.coincidentOpaquePossible =
        findCloseOpaqueTriangles(scene, margin, opaqueObjectsMetFromBehind(scene, primaryStarts)).found;
    if (f.cameraSurface.otherPlanes)
        warn(
            "the camera lies where surfaces meet at an angle (an edge or a corner): primary rays start off one "
            "of their planes, and may meet the others at distances that rounding decides; move the camera off them");
    f.mediumStackDepth = !f.glass ? 0
                         : f.openGlassObjects > 0 ? gpu::kMaxMediumDepth
                                                  : std::min<std::uint32_t>(gpu::kMaxMediumDepth, 1 + mostOverlaps);

    const std::uint32_t maxDepth = scene.settings.maxDepth;
    f.rayStackDepth = f.glass ? std::min<std::uint32_t>(gpu::kRayStackSize, maxDepth > 0 ? maxDepth - 1 : 0) : 0;
    f.textures = f.textures && !scene.textures.empty();
    f.background = scene.background.kind;
    f.usefulDepth = f.reflection ? maxDepth : std::min<std::uint32_t>(1, maxDepth);
    return f;
}

std::vector<std::string> materialModelNames(std::uint32_t mask) {
    std::vector<std::string> names;
    for (MaterialModel m : kMaterialModels)
        if (mask >> std::uint32_t(m) & 1u) names.emplace_back(materialModelName(m));
    return names;
}

std::vector<std::string> SceneFeatures::describe() const {
    auto yesNo = [](bool b) { return b ? "yes" : "no"; };
    std::string models;
    for (const std::string& name : materialModelNames(materialModels)) models += (models.empty() ? "" : ", ") + name;
    return {
        "materials: " + (models.empty() ? std::string("none") : models),
        std::string("glass (refraction, medium stack): ") + yesNo(glass) + ", " + std::to_string(glassObjects) +
            " objects" + (openGlassObjects ? ", " + std::to_string(openGlassObjects) + " of them open or badly wound" : ""),
        std::string("absorbing media (Beer-Lambert): ") + yesNo(absorbingMedia),
        std::string("touching glass surfaces possible: ") + yesNo(touchingMediaPossible),
        std::string("glass resting on opaque surfaces possible: ") + yesNo(opaqueContactPossible),
        std::string("coincident opaque surfaces of two objects possible: ") + yesNo(coincidentOpaquePossible),
        "medium stack depth needed: " + std::to_string(mediumStackDepth),
        std::string("reflected rays: ") + yesNo(reflection),
        "pending-ray stack needed: " + std::to_string(rayStackDepth),
        std::string("shadow rays: ") + yesNo(shadowRays),
        std::string("textures: ") + yesNo(textures),
        std::string("background: ") + backgroundKindName(background),
        "useful max_depth: " + std::to_string(usefulDepth) + (usefulDepth <= 1 ? " (primary rays only)" : ""),
    };
}

nlohmann::json toJson(const SceneFeatures& f) {
    return {
        {"materials", materialModelNames(f.materialModels)},
        {"glass", f.glass},
        {"glass_objects", f.glassObjects},
        {"open_glass_objects", f.openGlassObjects},
        {"absorbing_media", f.absorbingMedia},
        {"touching_media_possible", f.touchingMediaPossible},
        {"opaque_contact_possible", f.opaqueContactPossible},
        {"coincident_opaque_possible", f.coincidentOpaquePossible},
        {"medium_stack_depth", f.mediumStackDepth},
        {"camera_media", f.cameraMedia},
        {"camera_surface_triangles", f.cameraSurface.triangles},
        {"camera_media_behind_surface", f.cameraMediaBehind},
        {"reflection", f.reflection},
        {"ray_stack_depth", f.rayStackDepth},
        {"shadow_rays", f.shadowRays},
        {"textures", f.textures},
        {"background", backgroundKindName(f.background)},
        {"useful_max_depth", f.usefulDepth},
    };
}

}  // namespace vitrum
