// What a scene can need from the renderer ("simulate only the effects a scene calls for"):
// found once at load, printed by `vitrum info`, recorded in --stats, used by both backends to skip
// work the scene cannot need and by the Vulkan backend to specialize its kernel
// (gpu_input/trace_specialization.h).
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "analysis/camera_surface.h"
#include "scene/scene.h"

namespace vitrum {

// Surfaces of two objects closer than this fraction of the scene's diagonal along a ray are one
// interface (both backends). Far above float rounding of coordinates (~1e-7), far below modelled gaps.
constexpr double kTouchingTolerance = 1e-5;

struct SceneFeatures {
    std::uint32_t materialModels = 0;    // bit (1 << model) for every MaterialModel a hit can show
    bool glass = false;                  // refraction and a medium stack
    bool absorbingMedia = false;         // some glass has Tf != 0 (Beer-Lambert)
    // Glass materials of different priorities (MTL `priority`): where their media overlap, the
    // highest is the medium, and surfaces inside it are false hits (render-model-decisions.md,
    // "Overlapping media by priority"). Equal priorities change nothing.
    bool mediumPriorities = false;
    // Some glass disperses (MTL `Vd`): a ray meeting it splits into wavelength samples
    // (render-model-decisions.md, "Dispersion").
    bool dispersion = false;
    // Some glass tints the light crossing its surface (Material::tint, glTF's base colour of a
    // volume; render-model-decisions.md, "Glass tint").
    bool glassTints = false;
    // Some surface has cut-out parts (Material::cutout, glTF's alphaMode MASK): both traversals
    // test its hits against its texture (render-model-decisions.md, "Cut-out surfaces").
    bool cutouts = false;
    // Some opaque surface is partly there (Material::coverage, glTF's alphaMode BLEND): its hits
    // send a ray on through it (render-model-decisions.md, "Partial coverage").
    bool partialCoverage = false;
    // Some glass is glass only where its transmission texture says so, and an opaque material
    // elsewhere (Material::transmissionTexture, glTF's transmissionTexture): both backends read it
    // at a hit to know which material the hit shows (render-model-decisions.md, "Transmission
    // textures").
    bool transmissionTextures = false;
    // Two triangles of different glass objects that may lie within twice the touching distance
    // of each other (analysis/glass_proximity.h): only then can a touching probe find anything, so
    // otherwise neither backend probes. Nested objects apart from each other need no probe.
    bool touchingMediaPossible = false;
    // A glass triangle that may lie within twice the touching distance of an opaque one (any
    // objects): only then can an opaque surface lie within the touching distance of a glass hit,
    // where both backends take the opaque one (glass resting on a table; render-model-decisions.md,
    // "Glass on an opaque surface"), so otherwise neither looks for it.
    bool opaqueContactPossible = false;
    // Opaque triangles of two different objects that may lie within twice the touching distance
    // of each other, one of the two objects one that a ray may meet from behind
    // (opaqueObjectsMetFromBehind): only then can a ray meet, within the touching distance, an
    // opaque surface from behind and another from the front, where both backends take the one it
    // leaves through (a box standing on another, seen from inside; render-model-decisions.md,
    // "Coincident opaque surfaces").
    bool coincidentOpaquePossible = false;
    bool reflection = false;             // some material spawns secondary rays (reflected, refracted, passing)
    bool shadowRays = false;             // lights and materials that use them (Lambert, Phong)
    bool textures = false;               // some material samples a texture at a hit (map_Kd, coverage, transmission)
    BackgroundKind background = BackgroundKind::Constant;
    std::uint32_t glassObjects = 0;
    // Surfaces of different objects closer than this along a ray touch: kTouchingTolerance times
    // the diagonal of the scene's box (both backends' touching probes use it).
    double touchingDistance = 0.0;
    // Glass objects that are not closed, consistently wound meshes (some edge is not shared by
    // exactly two triangles in opposite directions): rays can leave them without entering, or
    // enter them and never leave, so the medium stack can hold more than their nesting says.
    std::uint32_t openGlassObjects = 0;
    std::vector<std::uint32_t> openGlassNamed;  // the first few of them, for openGlassWarning
    // The most media a ray can be inside at once: 0 without glass; the GPU's whole stack
    // (gpu::kMaxMediumDepth) when some glass object is open; else 1 + the most other glass objects
    // whose boxes overlap one glass object's box (an upper bound on how deep they nest), capped
    // at the GPU's stack.
    std::uint32_t mediumStackDepth = 0;
    // The surface the camera lies on, if any (camera_surface.h): primary rays start off it, on
    // the side each goes to.
    CameraSurface cameraSurface;
    // The glass objects whose media the camera is inside, innermost last: every primary ray's
    // medium stack (camera_medium.h). Where the camera lies on a surface, those of the side its
    // normal points to, and cameraMediaBehind those of the other side; else the two are the same.
    std::vector<std::uint32_t> cameraMedia;
    std::vector<std::uint32_t> cameraMediaBehind;
    // Pending rays of a depth-first ray tree: only refractions and rays through partly covered
    // surfaces wait (the reflection of a hit is traced at once), so 0 without glass, thin glass or
    // partial coverage, else max_depth - 1 (docs/gpu-design.md shows why that
    // suffices), capped at gpu::kRayStackSize.
    std::uint32_t rayStackDepth = 0;
    // The max_depth beyond which nothing changes: 1 (primary rays only, a tree of depth 0) without
    // reflective or refractive materials, else the scene's max_depth.
    std::uint32_t usefulDepth = 1;

    bool uses(MaterialModel model) const { return (materialModels >> std::uint32_t(model) & 1u) != 0; }
    std::vector<std::string> describe() const;  // one line a feature, for `vitrum info`
};

// An instanced scene whose copies, placed in the world, make at most this many triangles is
// examined triangle by triangle, as its flattened scene is (a temporary copy of the placed
// triangles, about 100 bytes each); a larger one by its copies' boxes, which finds every surface
// that may touch another and more (docs/gpu-design.md, "Instances crossed outside the node loop").
inline constexpr std::size_t kFlatAnalysisTriangles = 1'000'000;

// `flatAnalysisTriangles`: kFlatAnalysisTriangles, but for the tests of both ways.
SceneFeatures analyseScene(const Scene& scene, std::size_t flatAnalysisTriangles = kFlatAnalysisTriangles);

// The glass objects whose glass triangles are not a closed, consistently wound mesh: some
// directed edge does not appear exactly once with its reverse exactly once.
std::set<std::uint32_t> openGlassObjects(const Scene& scene);

// What a user is told when the scene has open glass objects (`features.openGlassObjects`), naming
// `features.openGlassNamed`: a ray that enters such a medium may never leave it, and a pane or sheet of glass is
// thin-walled glass (render-model-decisions.md, "Thin-walled glass"). Empty without any.
std::string openGlassWarning(const Scene& scene, const SceneFeatures& features);

// The objects with opaque triangles that a ray may meet from behind (render-model-decisions.md,
// "Coincident opaque surfaces"): those whose opaque triangles are not a closed, consistently wound
// mesh with outward normals (an open sheet, a mesh wound inward), those that also have glass
// triangles, are of thin glass or have cut-out or partly covered surfaces (rays come in through
// them; thin glass counts as opaque in the rules), and those around one of `rayStarts` (where
// primary rays start). A ray meets the opaque triangles of any other object from the front only.
std::set<std::uint32_t> opaqueObjectsMetFromBehind(const Scene& scene, const std::vector<glm::dvec3>& rayStarts);

// Length of the diagonal of the box around every triangle (0 for an empty scene).
double sceneDiagonal(const std::vector<Triangle>& triangles);
// The scene's: with instances, of the box around the world triangles and the instances' boxes.
double sceneDiagonal(const Scene& scene);

nlohmann::json toJson(const SceneFeatures& features);

// The names of the models in a SceneFeatures::materialModels mask, in MaterialModel order.
std::vector<std::string> materialModelNames(std::uint32_t mask);

}  // namespace vitrum
