#include "analysis/scene_features.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <functional>
#include <map>
#include <set>
#include <span>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/parallel.h"
#include "analysis/camera_medium.h"
#include "analysis/double_box.h"
#include "analysis/glass_proximity.h"
#include "scene/instances.h"
#include "scene/scene_names.h"
#include "shared/gpu_types.h"

namespace vitrum {
namespace {

// Boxes of the objects among triangles [first, end) that have glass triangles (all of each such
// object's triangles), by object.
std::map<std::uint32_t, DoubleBox> glassObjectBoxes(const Scene& scene, std::uint32_t first, std::uint32_t end) {
    std::set<std::uint32_t> glass;
    for (std::uint32_t i = first; i < end; ++i)
        if (scene.materials[scene.triangles[i].material].model == MaterialModel::Glass) glass.insert(scene.triangles[i].object);
    std::map<std::uint32_t, DoubleBox> boxes;
    for (std::uint32_t i = first; i < end; ++i) {
        const Triangle& t = scene.triangles[i];
        if (glass.count(t.object))
            for (const glm::vec3& p : t.position) boxes[t.object].grow(glm::dvec3(p));
    }
    return boxes;
}

// The boxes of the scene's glass objects: an instance's are its mesh's objects' boxes moved to the
// world (scene/instances.h's instanceBox, which holds them).
std::vector<DoubleBox> glassObjectBoxes(const Scene& scene) {
    std::vector<DoubleBox> result;
    for (const auto& [object, box] : glassObjectBoxes(scene, 0, worldTriangleCount(scene))) result.push_back(box);
    std::vector<std::map<std::uint32_t, DoubleBox>> meshBoxes;
    for (const Mesh& mesh : scene.meshes) meshBoxes.push_back(glassObjectBoxes(scene, mesh.first, mesh.first + mesh.count));
    for (const Instance& instance : scene.instances)
        for (const auto& [object, box] : meshBoxes[instance.mesh]) {
            const FloatBox moved = instanceBox(instance, FloatBox{glm::vec3(box.min), glm::vec3(box.max)});
            result.push_back(DoubleBox{glm::dvec3(moved.min), glm::dvec3(moved.max)});
        }
    return result;
}

// An edge between two vertex positions, compared bit for bit (an OBJ's shared vertices have
// identical positions in every triangle that uses them): its ends' bits in a fixed order (the
// smaller first), packed into three words so that a comparison is three integer compares, and
// whether a triangle runs along it the other way.
struct Edge {
    std::array<std::uint64_t, 3> bits;
    bool backwards;
    bool operator<(const Edge& o) const {
        return std::tie(bits[0], bits[1], bits[2], backwards) < std::tie(o.bits[0], o.bits[1], o.bits[2], o.backwards);
    }
    bool isPoint() const {  // both ends the same position
        return bits[0] >> 32 == (bits[1] & 0xffffffffu) && (bits[0] & 0xffffffffu) == bits[2] >> 32 &&
               bits[1] >> 32 == (bits[2] & 0xffffffffu);
    }
};

Edge edge(const glm::vec3& a, const glm::vec3& b) {
    std::array<std::uint32_t, 3> from, to;
    std::memcpy(from.data(), &a, 12);
    std::memcpy(to.data(), &b, 12);
    const bool backwards = to < from;
    if (backwards) std::swap(from, to);
    auto pair = [](std::uint32_t high, std::uint32_t low) { return std::uint64_t(high) << 32 | low; };
    return Edge{{pair(from[0], from[1]), pair(from[2], to[0]), pair(to[1], to[2])}, backwards};
}

// Whether the edges of one object's triangles make a closed, consistently wound mesh: every edge
// between two different points run along exactly twice, once each way. Sorted, not hashed: a hash
// map of a million-triangle object's edges took seconds and twice the memory.
bool closedMesh(std::vector<Edge>& edges) {
    if (edges.size() % 2 != 0) return false;
    parallelSort(edges.begin(), edges.end(), std::less<>());
    for (std::size_t i = 0; i < edges.size(); i += 2) {
        const Edge& forwards = edges[i];
        const Edge& back = edges[i + 1];
        if (forwards.isPoint() || forwards.backwards || !back.backwards || forwards.bits != back.bits) return false;
        if (i + 2 < edges.size() && edges[i + 2].bits == forwards.bits) return false;  // a third time
    }
    return true;
}

// The objects among triangles [begin, end) whose triangles that `counts` are not a closed,
// consistently wound mesh.
template <class Counts>
std::set<std::uint32_t> openObjects(const Scene& scene, std::uint32_t begin, std::uint32_t end, Counts counts) {
    // The counted triangles object by object (a loader writes each object's triangles in a run,
    // which the stable sort keeps), so that one object's edges are held at a time.
    std::vector<std::uint32_t> order;
    order.reserve(end - begin);
    for (std::uint32_t i = begin; i < end; ++i)
        if (counts(scene.triangles[i])) order.push_back(i);
    auto byObject = [&](std::uint32_t a, std::uint32_t b) { return scene.triangles[a].object < scene.triangles[b].object; };
    if (!std::is_sorted(order.begin(), order.end(), byObject)) std::stable_sort(order.begin(), order.end(), byObject);
    std::set<std::uint32_t> open;
    std::vector<Edge> edges;
    for (std::size_t first = 0; first < order.size();) {
        const std::uint32_t object = scene.triangles[order[first]].object;
        std::size_t last = first;
        while (last < order.size() && scene.triangles[order[last]].object == object) ++last;
        edges.clear();
        edges.reserve(3 * (last - first));
        for (std::size_t k = first; k < last; ++k) {
            const Triangle& t = scene.triangles[order[k]];
            for (int i = 0; i < 3; ++i) edges.push_back(edge(t.position[i], t.position[(i + 1) % 3]));
        }
        if (!closedMesh(edges)) open.insert(object);
        first = last;
    }
    return open;
}

// The same over the whole scene: an instance's objects are open where its mesh's are (a transform
// keeps a mesh closed, and a mirroring one its winding consistent), each mesh examined once.
template <class Counts>
std::set<std::uint32_t> openObjects(const Scene& scene, Counts counts) {
    std::set<std::uint32_t> open = openObjects(scene, 0, worldTriangleCount(scene), counts);
    std::vector<std::set<std::uint32_t>> meshes;
    for (const Mesh& mesh : scene.meshes) meshes.push_back(openObjects(scene, mesh.first, mesh.first + mesh.count, counts));
    for (const Instance& instance : scene.instances)
        for (std::uint32_t object : meshes[instance.mesh]) open.insert(instance.firstObject + object);
    return open;
}

}  // namespace

std::set<std::uint32_t> openGlassObjects(const Scene& scene) {
    return openObjects(scene,
                       [&](const Triangle& t) { return scene.materials[t.material].model == MaterialModel::Glass; });
}

std::string openGlassWarning(const Scene& scene, const SceneFeatures& features) {
    if (features.openGlassObjects == 0) return "";
    std::string names;
    for (std::uint32_t object : features.openGlassNamed)
        names += std::string(names.empty() ? "" : ", ") + "\"" + scene.objectNames[object] + "\"";
    const std::size_t open = features.openGlassObjects;
    if (open > features.openGlassNamed.size())
        names += " and " + std::to_string(open - features.openGlassNamed.size()) + " more";
    return "glass object" + std::string(open == 1 ? " " : "s ") + names + (open == 1 ? " is" : " are") +
           " not a closed, consistently wound mesh: a ray that enters its medium may never leave it. A pane or "
           "sheet of glass is thin-walled glass: `thin_walled 1` in its MTL material, or glTF's "
           "KHR_materials_transmission without KHR_materials_volume";
}

std::set<std::uint32_t> opaqueObjectsMetFromBehind(const Scene& scene, const std::vector<glm::dvec3>& rayStarts) {
    auto isGlass = [&](const Triangle& t) { return scene.materials[t.material].model == MaterialModel::Glass; };
    std::map<std::uint32_t, std::vector<const Triangle*>> opaque;
    // Rays pass through the walls of an object with glass triangles, thin glass included (whose
    // triangles the rules take as opaque: a wall of no thickness has no inside), cut-out parts or
    // partly covered surfaces.
    std::set<std::uint32_t> passable;
    for (const Triangle& t : scene.triangles) {
        const Material& m = scene.materials[t.material];
        if (isGlass(t) || m.model == MaterialModel::ThinGlass || hasCutouts(m) || hasPartialCoverage(m))
            passable.insert(t.object);
        if (!isGlass(t)) opaque[t.object].push_back(&t);
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
        bool met = passable.count(object) || open.count(object) || !(volume > 0.0);
        for (const glm::dvec3& start : rayStarts) met = met || windingNumber(triangles, start) > 0.5;
        if (met) metFromBehind.insert(object);
    }
    return metFromBehind;
}

double sceneDiagonal(const Scene& scene) {
    if (scene.instances.empty()) return sceneDiagonal(scene.triangles);
    const FloatBox box = worldBox(scene);
    return glm::length(glm::dvec3(box.max) - glm::dvec3(box.min));
}

double sceneDiagonal(const std::vector<Triangle>& triangles) {
    DoubleBox box;
    for (const Triangle& t : triangles)
        for (const glm::vec3& p : t.position) box.grow(glm::dvec3(p));
    return triangles.empty() ? 0.0 : glm::length(box.max - box.min);
}

SceneFeatures analyseScene(const Scene& scene, std::size_t flatAnalysisTriangles) {
    SceneFeatures f;
    // The materials hits can show: the triangles', and the opaque parts of those glass only where
    // a transmission texture says so.
    std::set<std::uint32_t> used;
    for (const Triangle& t : scene.triangles) used.insert(t.material);
    for (const Triangle& t : scene.triangles)
        if (const Material& m = scene.materials[t.material]; hasTransmissionTexture(m))
            used.insert(std::uint32_t(m.opaquePart));
    std::set<int> glassPriorities;
    for (std::uint32_t index : used) {
        const Material& m = scene.materials[index];
        f.materialModels |= 1u << std::uint32_t(m.model);
        if (hasCutouts(m)) f.cutouts = true;
        // Which material a hit shows is read at its uv (render-model-decisions.md, "Transmission textures").
        if (hasTransmissionTexture(m)) f.transmissionTextures = f.textures = true;
        // A partly covered surface's rays go on through it as children, read at its uv.
        if (hasPartialCoverage(m)) f.partialCoverage = f.reflection = f.textures = true;
        switch (m.model) {
            case MaterialModel::Glass:
                f.glass = f.reflection = true;
                if (m.attenuation != glm::vec3(0.0f)) f.absorbingMedia = true;
                glassPriorities.insert(m.priority);
                if (m.abbe > 0.0f) f.dispersion = true;
                if (m.tint != glm::vec3(1.0f)) f.glassTints = true;
                break;
            case MaterialModel::Mirror: f.reflection = true; break;
            case MaterialModel::ThinGlass:  // no medium; its tint is the diffuse colour or texture
                f.reflection = true;
                if (m.diffuseTexture >= 0) f.textures = true;
                break;
            case MaterialModel::Phong: f.reflection = true; [[fallthrough]];
            case MaterialModel::Lambert:
                if (!scene.lights.empty()) f.shadowRays = true;
                if (m.diffuseTexture >= 0) f.textures = true;
                break;
            case MaterialModel::Normal: break;
        }
    }

    f.mediumPriorities = glassPriorities.size() > 1;
    const std::vector<DoubleBox> boxes = glassObjectBoxes(scene);
    f.glassObjects = std::uint32_t(boxes.size());
    f.touchingDistance = kTouchingTolerance * sceneDiagonal(scene);
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
    // An instanced scene's triangles are compared as placed in the world where they are few
    // enough (a scene of triangles and materials alone); beyond that, what the boxes allow is
    // taken as found, which costs probes, never images.
    Scene placed;
    const bool byBoxes = !scene.instances.empty() && placedTriangleCount(scene) > flatAnalysisTriangles;
    if (!scene.instances.empty() && !byBoxes) {
        placed.materials = scene.materials;
        placed.triangles = placedTriangles(scene, [](const Instance&) { return true; });
    }
    const Scene& compared = scene.instances.empty() || byBoxes ? scene : placed;
    const bool opaque = (f.materialModels & ~(1u << std::uint32_t(MaterialModel::Glass))) != 0;
    f.touchingMediaPossible = mostOverlaps > 0 && (byBoxes || findCloseGlassTriangles(compared, margin).found);
    f.opaqueContactPossible = f.glass && (byBoxes ? opaque : findGlassNearOpaque(compared, margin).found);
    const std::set<std::uint32_t> open = openGlassObjects(scene);
    f.openGlassObjects = std::uint32_t(open.size());
    for (auto it = open.begin(); it != open.end() && f.openGlassNamed.size() < 3; ++it) f.openGlassNamed.push_back(*it);
    // A primary ray's media are those where it starts: off the camera's surface on its side.
    const RayOffsetScale offsets = rayOffsetScale(scene);
    // What the camera can lie on or inside: the world's triangles and, where the scene has
    // instances, the copies whose boxes hold the camera, moved to the world (copied only then).
    std::span<const Triangle> cameraTriangles = std::span(scene.triangles).first(worldTriangleCount(scene));
    std::vector<Triangle> aroundCamera;
    const std::vector<FloatBox> meshes = meshBoxes(scene);
    const auto holdsCamera = [&](const Instance& instance) {
        const FloatBox box = instanceBox(instance, meshes[instance.mesh]);
        return glm::all(glm::lessThanEqual(box.min - glm::vec3(float(margin)), scene.camera.from)) &&
               glm::all(glm::lessThanEqual(scene.camera.from, box.max + glm::vec3(float(margin))));
    };
    if (std::any_of(scene.instances.begin(), scene.instances.end(), holdsCamera)) {
        aroundCamera = placedTriangles(scene, holdsCamera);
        cameraTriangles = aroundCamera;
    }
    f.cameraSurface = cameraSurface(cameraTriangles, scene.camera.from, offsets);
    const glm::vec3 from = scene.camera.from;
    const glm::vec3 normal = f.cameraSurface.normal;
    // Where primary rays start: off the surface on each side of it, or at the camera.
    std::vector<glm::dvec3> primaryStarts = {glm::dvec3(offsetRayOrigin(from, normal, offsets))};
    if (f.cameraSurface.triangles != 0) primaryStarts.push_back(glm::dvec3(offsetRayOrigin(from, -normal, offsets)));
    f.cameraMedia = cameraMedia(cameraTriangles, scene.materials, open, primaryStarts.front());
    f.cameraMediaBehind = primaryStarts.size() == 1
                              ? f.cameraMedia
                              : cameraMedia(cameraTriangles, scene.materials, open, primaryStarts.back());
    f.coincidentOpaquePossible =
        byBoxes ? opaque
                : findCloseOpaqueTriangles(compared, margin, opaqueObjectsMetFromBehind(compared, primaryStarts)).found;
    if (f.cameraSurface.otherPlanes)
        warn(
            "the camera lies where surfaces meet at an angle (an edge or a corner): primary rays start off one "
            "of their planes, and may meet the others at distances that rounding decides; move the camera off them");
    f.mediumStackDepth = !f.glass ? 0
                         : f.openGlassObjects > 0 ? gpu::kMaxMediumDepth
                                                  : std::min<std::uint32_t>(gpu::kMaxMediumDepth, 1 + mostOverlaps);

    const std::uint32_t maxDepth = scene.settings.maxDepth;
    // Dispersion: a split ray's samples wait as one pending entry below its subtree (trace.comp).
    // A partly covered surface's pass-through waits as a refraction does.
    const bool refracts = f.glass || f.uses(MaterialModel::ThinGlass) || f.partialCoverage;
    f.rayStackDepth = refracts ? std::min<std::uint32_t>(gpu::kRayStackSize,
                                                         (maxDepth > 0 ? maxDepth - 1 : 0) + (f.dispersion ? 1 : 0))
                               : 0;
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
            " objects" +
            (openGlassObjects ? ", " + std::to_string(openGlassObjects) + " of them open or badly wound" : ""),
        std::string("absorbing media (Beer-Lambert): ") + yesNo(absorbingMedia),
        std::string("overlapping media by priority: ") + yesNo(mediumPriorities),
        std::string("dispersion (wavelength samples): ") + yesNo(dispersion),
        std::string("tinted glass surfaces: ") + yesNo(glassTints),
        std::string("cut-out surfaces (alpha masks): ") + yesNo(cutouts),
        std::string("partly covered surfaces (alpha blending): ") + yesNo(partialCoverage),
        std::string("glass only where a transmission texture says: ") + yesNo(transmissionTextures),
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
        {"medium_priorities", f.mediumPriorities},
        {"dispersion", f.dispersion},
        {"glass_tints", f.glassTints},
        {"cutouts", f.cutouts},
        {"partial_coverage", f.partialCoverage},
        {"transmission_textures", f.transmissionTextures},
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
