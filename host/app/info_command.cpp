// `vitrum info SCENE`: what a scene holds and what rendering it would take.
#include <cmath>
#include <cstdio>
#include <future>
#include <iostream>
#include <map>

#include "app/arguments.h"
#include "app/commands.h"
#include "bvh/bvh.h"
#include "common/byte_size.h"
#include "common/error.h"
#include "common/progress.h"
#include "analysis/scene_features.h"
#include "gpu_input/scene_geometry_bytes.h"
#include "gpu_input/trace_specialization.h"
#include "scene/instances.h"
#include "scene/scene_names.h"
#include "shared/gpu_types.h"
#include "scene/scene_loader.h"

namespace vitrum {
namespace {

// "glass (4)": the model and its MTL `shader` number (thin glass: shader 4 and `thin_walled 1`).
std::string modelName(MaterialModel model) {
    if (model == MaterialModel::ThinGlass) return std::string(materialModelName(model)) + " (4 thin_walled)";
    return std::string(materialModelName(model)) + " (" + std::to_string(std::uint32_t(model)) + ")";
}

}  // namespace

int infoCommand(int argc, char** argv, int first) {
    if (wantsHelp(argc, argv, first) || argc - first < 1) {
        std::cout << "usage: vitrum info SCENE [--camera NAME] [--variant NAME]\n\nPrints the triangles, objects, "
                     "materials, lights, camera and BVH statistics of SCENE (.json, .obj, .gltf or .glb); a glTF "
                     "file's camera and material variant by name, as `vitrum render` takes them.\n";
        return argc - first >= 1 ? 0 : 1;
    }
    PhaseProgress phases;
    SceneLoadOptions options{.progress = phases.callback()};
    Arguments args(argc, argv, first + 1);
    while (!args.empty()) {
        const std::string flag = args.next();
        if (flag == "--camera")
            options.camera = args.valueOf(flag);
        else if (flag == "--variant")
            options.variant = args.valueOf(flag);
        else
            throw InputError("unknown option " + flag + " (see vitrum info --help)");
    }
    Scene scene = loadScene(argv[first], options);
    // The analysis beside the BVH build, as `vitrum render` runs them (both read only the triangles).
    std::future<SceneFeatures> analysis = std::async(std::launch::async, [&] { return analyseScene(scene); });
    Bvh bvh = buildSceneBvh(scene, [&](double fraction) { phases.update("building the BVH", fraction); });
    phases.finish();
    const SceneFeatures features = analysis.get();
    if (const std::string open = openGlassWarning(scene, features); !open.empty()) warn(open);
    std::map<std::uint32_t, std::size_t> trianglesPerMaterial;
    for (const Triangle& t : scene.triangles) ++trianglesPerMaterial[t.material];

    std::printf("scene: %s\n", scene.source.string().c_str());
    std::printf("triangles: %zu in %zu objects\n", scene.triangles.size(), scene.objectNames.size());
    if (!scene.instances.empty()) {
        // What instancing saves (docs/gpu-design.md, "Instancing"): the triangles placed.
        const std::uint64_t placed = placedTriangleCount(scene);
        std::printf("instances: %zu of %zu meshes, %llu triangles placed (%zu stored)\n", scene.instances.size(),
                    scene.meshes.size(), static_cast<unsigned long long>(placed), scene.triangles.size());
    }
    std::printf("materials: %zu\n", scene.materials.size());
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        std::printf("  %-28s %-22s %7zu triangles", m.name.c_str(), modelName(m.model).c_str(), trianglesPerMaterial[i]);
        if (m.model == MaterialModel::Glass || m.model == MaterialModel::Phong || m.model == MaterialModel::ThinGlass)
            std::printf("  Ni %.3g", m.ior);
        if (m.model == MaterialModel::ThinGlass)  // the tint of what it transmits
            std::printf("  Kd %.3g %.3g %.3g", m.diffuse.x, m.diffuse.y, m.diffuse.z);
        if (m.model == MaterialModel::Glass)
            std::printf("  Tf %.3g %.3g %.3g", m.attenuation.x, m.attenuation.y, m.attenuation.z);
        if (m.model == MaterialModel::Glass && m.priority != 0) std::printf("  priority %d", m.priority);
        if (m.model == MaterialModel::Glass && m.abbe > 0.0f) std::printf("  Vd %.4g", m.abbe);
        if (m.model == MaterialModel::Glass && m.tint != glm::vec3(1.0f))  // at its surface (glTF's base colour)
            std::printf("  tint %.3g %.3g %.3g", m.tint.x, m.tint.y, m.tint.z);
        // Linear, as the renderers read them (a glTF's factors, an MTL's colours decoded).
        if (m.model == MaterialModel::Phong)
            std::printf("  Kd %.3g %.3g %.3g  Ks %.3g %.3g %.3g  Ns %.4g", m.diffuse.x, m.diffuse.y, m.diffuse.z,
                        m.specular.x, m.specular.y, m.specular.z, m.shininess);
        if (m.model == MaterialModel::Mirror) std::printf("  Ks %.3g %.3g %.3g", m.specular.x, m.specular.y, m.specular.z);
        if (m.diffuseTexture >= 0) std::printf("  map_Kd %s", scene.textures[m.diffuseTexture].path.filename().c_str());
        if (hasCutouts(m)) std::printf("  cutout %s", scene.textures[m.cutout].path.filename().c_str());
        if (hasPartialCoverage(m)) std::printf("  coverage %s", scene.textures[m.coverage].path.filename().c_str());
        if (hasTransmissionTexture(m))
            std::printf("  transmission %s (elsewhere %s)",
                        scene.textures[m.transmissionTexture].path.filename().c_str(),
                        scene.materials[m.opaquePart].name.c_str());
        std::printf("\n");
    }
    // What the scene can need (analysis/scene_features.h).
    std::printf("features:\n");
    for (const std::string& line : features.describe()) std::printf("  %s\n", line.c_str());
    // The kernel `vitrum render` builds for it (gpu_input/trace_specialization.h).
    std::printf("gpu kernel (--no-specialize: the general one, medium stack %u, pending-ray stack %u):\n",
                gpu::kMaxMediumDepth, gpu::kRayStackSize);
    for (const std::string& line : TraceSpecialization::forScene(scene, features).describe())
        std::printf("  %s\n", line.c_str());
    std::printf("lights: %zu\n", scene.lights.size());
    for (const PointLight& l : scene.lights)
        std::printf("  at (%g, %g, %g), colour (%g, %g, %g)%s\n", l.position.x, l.position.y, l.position.z, l.colour.x,
                    l.colour.y, l.colour.z, l.inverseSquare ? ", inverse-square" : "");
    const Camera& c = scene.camera;
    std::printf("camera: from (%g, %g, %g) at (%g, %g, %g) up (%g, %g, %g), fov_y %g deg, %ux%u\n", c.from.x,
                c.from.y, c.from.z, c.at.x, c.at.y, c.at.z, c.up.x, c.up.y, c.up.z, c.fovY, c.width, c.height);
    // The media every primary ray starts inside (analysis/camera_medium.h), on each side of the
    // surface the camera lies on, if any (analysis/camera_surface.h).
    auto mediaText = [&](const std::vector<std::uint32_t>& objects) {
        std::string media;
        for (std::uint32_t object : objects) media += (media.empty() ? "inside " : ", then ") + scene.objectNames[object];
        return media.empty() ? std::string("air") : media;
    };
    const CameraSurface& surface = features.cameraSurface;
    if (surface.triangles == 0) {
        std::printf("camera medium: %s\n", mediaText(features.cameraMedia).c_str());
    } else {
        std::printf("camera surface: the camera lies on %u triangle%s%s, normal (%g, %g, %g); primary rays start off "
                    "it on their side\n",
                    surface.triangles, surface.triangles == 1 ? "" : "s",
                    surface.otherPlanes ? " meeting at an angle" : " of one plane", surface.normal.x, surface.normal.y,
                    surface.normal.z);
        std::printf("camera medium: %s on the normal's side, %s behind it\n", mediaText(features.cameraMedia).c_str(),
                    mediaText(features.cameraMediaBehind).c_str());
    }
    std::printf("background: (%g, %g, %g), air IOR %g\n", scene.background.colour.x, scene.background.colour.y,
                scene.background.colour.z, scene.airIor);
    std::printf("render: %u spp, max depth %u, fresnel %s, min weight %g\n", scene.settings.samplesPerPixel,
                scene.settings.maxDepth, fresnelModelName(scene.settings.fresnel), scene.settings.minWeight);
    const BvhStats& s = bvh.stats;
    std::printf("bvh: %u nodes, %u leaves, depth %u, at most %u triangles a leaf, SAH cost %.2f, built in %.3f s\n",
                s.nodeCount, s.leafCount, s.maxDepth, s.maxLeafTriangles, s.sahCost, s.buildSeconds);
    const SceneGeometryBytes bytes = sceneGeometry(bvh, planShading(scene, bvh));
    std::printf("gpu memory: %.1f bytes per triangle (BVH, vertices, shading), %s in all\n",
                double(bytes.total()) / double(std::max<std::size_t>(1, scene.triangles.size())),
                describeBytes(bytes.total()).c_str());
    return 0;
}

}  // namespace vitrum
