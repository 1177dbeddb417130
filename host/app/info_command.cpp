// `vitrum info SCENE`, `vitrum diff A B`, `vitrum devices`: the small commands.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>

#include "app/arguments.h"
#include "app/commands.h"
#include "bvh/bvh.h"
#include "common/error.h"
#include "gpu/gpu_buffer.h"
#include "gpu/tile_size.h"
#include "gpu/trace_pipeline.h"
#include "gpu/vulkan_device.h"
#include "image/image_diff.h"
#include "render/scene_features.h"
#include "render/trace_specialization.h"
#include "scene/scene_names.h"
#include "shared/gpu_types.h"
#include "scene/scene_loader.h"

namespace vitrum {
namespace {

bool wantsHelp(int argc, char** argv, int first) {
    for (int i = first; i < argc; ++i)
        if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) return true;
    return false;
}

// "glass (4)": the model and its MTL `shader` number.
std::string modelName(MaterialModel model) {
    return std::string(materialModelName(model)) + " (" + std::to_string(std::uint32_t(model)) + ")";
}

}  // namespace

int infoCommand(int argc, char** argv, int first) {
    if (wantsHelp(argc, argv, first) || argc - first != 1) {
        std::cout << "usage: vitrum info SCENE\n\nPrints the triangles, objects, materials, lights, camera and BVH "
                     "statistics of SCENE (.json or .obj).\n";
        return argc - first == 1 ? 0 : 1;
    }
    Scene scene = loadScene(argv[first]);
    Bvh bvh = buildBvh(scene.triangles);
    std::map<std::uint32_t, std::size_t> trianglesPerMaterial;
    for (const Triangle& t : scene.triangles) ++trianglesPerMaterial[t.material];

    std::printf("scene: %s\n", scene.source.string().c_str());
    std::printf("triangles: %zu in %zu objects\n", scene.triangles.size(), scene.objectNames.size());
    std::printf("materials: %zu\n", scene.materials.size());
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        std::printf("  %-28s %-22s %7zu triangles", m.name.c_str(), modelName(m.model).c_str(), trianglesPerMaterial[i]);
        if (m.model == MaterialModel::Glass || m.model == MaterialModel::Phong) std::printf("  Ni %.3g", m.ior);
        if (m.model == MaterialModel::Glass)
            std::printf("  Tf %.3g %.3g %.3g", m.attenuation.x, m.attenuation.y, m.attenuation.z);
        if (m.diffuseTexture >= 0) std::printf("  map_Kd %s", scene.textures[m.diffuseTexture].path.filename().c_str());
        std::printf("\n");
    }
    // What the scene can need (render/scene_features.h).
    SceneFeatures features = analyseScene(scene);
    std::printf("features:\n");
    for (const std::string& line : features.describe()) std::printf("  %s\n", line.c_str());
    // The kernel `vitrum render` builds for it (render/trace_specialization.h).
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
    // The media every primary ray starts inside (render/camera_medium.h), on each side of the
    // surface the camera lies on, if any (render/camera_surface.h).
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
    std::printf("gpu memory: %.1f bytes per triangle (BVH, vertices, shading)\n",
                double((bvh.stats.nodeCount - bvh.stats.leafCount) * sizeof(gpu::TraversalNode) +
                       scene.triangles.size() * (sizeof(gpu::TriangleVertices) + sizeof(gpu::TriangleShading))) /
                    double(std::max<std::size_t>(1, scene.triangles.size())));
    return 0;
}

int diffCommand(int argc, char** argv, int first) {
    if (wantsHelp(argc, argv, first)) {
        std::cout << "usage: vitrum diff A B [--heatmap OUT.png] [--scale S]\n\n"
                     "Compares two images of the same size channel by channel on linear values (PNG is decoded\n"
                     "from sRGB) and prints RMSE, PSNR, the largest and mean absolute error and the share of\n"
                     "pixels whose largest channel error is over 1/255 and over 0.05. --heatmap writes the\n"
                     "per-pixel error as black-red-yellow-white, white at S (default 0.1).\n";
        return 0;
    }
    Arguments args(argc, argv, first);
    std::vector<std::string> images;
    std::string heatmap;
    float scale = 0.1f;
    while (!args.empty()) {
        std::string a = args.next();
        if (a == "--heatmap") heatmap = args.valueOf(a);
        else if (a == "--scale") {
            scale = Arguments::toFloat(a, args.valueOf(a));
            if (scale <= 0) throw InputError("--scale must be positive");
        } else if (a.rfind("--", 0) == 0) throw InputError("unknown option " + a + " (see vitrum diff --help)");
        else images.push_back(a);
    }
    if (images.size() != 2) throw InputError("diff needs two images (see vitrum diff --help)");
    Image a = readImage(images[0]);
    Image b = readImage(images[1]);
    ImageDiff d = diffImages(a, b);
    std::printf("rmse: %.6g\npsnr: %.2f dB\nmax abs error: %.6g\nmean abs error: %.6g\n", d.rmse, d.psnr,
                d.maxAbsError, d.meanAbsError);
    std::printf("pixels over 1/255: %.4f%%\npixels over 0.05: %.4f%%\n", 100.0 * d.shareOver1of255,
                100.0 * d.shareOver005);
    if (!heatmap.empty()) writeImage(diffHeatMap(a, b, scale), heatmap);
    return 0;
}

int devicesCommand(int argc, char** argv, int first) {
    if (wantsHelp(argc, argv, first)) {
        std::cout << "usage: vitrum devices\n\nLists the Vulkan devices, each with what decides how vitrum's kernel runs there: its\n"
                     "subgroups (which count the loop budget and sum the statistics) and its buffer limits.\n"
                     "'vitrum render --device' takes an index or part of a name.\n";
        return 0;
    }
    for (const DeviceDescription& d : VulkanDevice::listDevices()) {
        std::printf("%u: %s (%s, Vulkan %u.%u)\n", d.index, d.name.c_str(), d.type.c_str(),
                    VK_API_VERSION_MAJOR(d.apiVersion), VK_API_VERSION_MINOR(d.apiVersion));
        if (d.apiVersion < VK_API_VERSION_1_2) {
            std::printf("   not usable: vitrum needs Vulkan 1.2\n");
            continue;
        }
        std::printf("   driver: %s, %s\n", d.driverName.c_str(), d.driverInfo.c_str());
        // What decides how trace.comp runs there (docs/gpu-design.md): the subgroups, which
        // count the loop budget and sum the statistics, and the buffer limits the scene must fit.
        const SubgroupSupport& s = d.subgroups;
        std::printf("   subgroups of %u lanes, arithmetic and ballots: %s, full subgroups: %s; statistics summed by %s\n",
                    s.size, s.arithmeticAndBallot ? "yes" : "no", s.fullSubgroups ? "yes" : "no",
                    statisticsSumsName(statisticsSumsFor(s, StatisticsSums::shuffles)));
        // The kernel path needs the device opened: the self-check runs there (gpu/subgroup_self_check.h).
        std::printf("   kernel: %s\n", VulkanDevice(std::to_string(d.index)).kernelPath().c_str());
        std::printf("   storage buffers up to %llu MiB, texel buffers up to %u texels\n",
                    static_cast<unsigned long long>(d.maxStorageBufferRange >> 20), d.maxTexelBufferElements);
        // Without it the driver may assume no value is infinite or NaN (gpu/spirv_float_semantics.h).
        std::printf("   infinities and NaNs in kernels: %s\n", d.preservesInfNan ? "kept (IEEE)" : "the driver's choice");
        // Where the kernels' buffers and the scene go (gpu/gpu_buffer.h's MemoryUse), and the tile
        // that sizes the per-pixel ones (gpu/tile_size.h).
        std::printf("   device-local memory %s, of it mappable by the host %s; tiles of %u pixels a side\n",
                    describeBytes(d.deviceLocalBytes).c_str(), describeBytes(d.mappableDeviceLocalBytes).c_str(),
                    defaultTileSize(d));
    }
    return 0;
}

}  // namespace vitrum
