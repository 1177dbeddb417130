// `vitrum render SCENE -o OUT [options]`
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <new>
#include <iostream>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/arguments.h"
#include "app/commands.h"
#include "bvh/bvh.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/file_extension.h"
#include "common/progress.h"
#include "cpu/reference_renderer.h"
#include "gpu/gpu_buffer.h"
#include "gpu/tile_buffers.h"
#include "gpu/tile_size.h"
#include "gpu/vulkan_device.h"
#include "gpu/vulkan_renderer.h"
#include "image/image.h"
#include "scene/float_range.h"
#include "scene/scene_loader.h"
#include "shared/gpu_types.h"

namespace vitrum {
namespace {

// The ranges and defaults come from the constants the parser and the scene file use.
std::string renderHelp() {
    const VulkanRenderOptions gpuDefaults;
    const RenderSettings defaults;
    const std::string side = std::to_string(kMaxImageSide);
    return R"(usage: vitrum render SCENE -o OUT [options]

Renders SCENE (a .json scene file or a bare .obj) and writes OUT: .png (8-bit sRGB), .pfm,
.hdr or .exr (linear). Options override the scene's own settings.

  -o, --output FILE        the image to write (required)
  --backend vulkan|cpu     Vulkan compute (default) or the CPU reference renderer
  --device INDEX|NAME      the Vulkan device ('vitrum devices' lists them); default: first GPU,
                           else lavapipe
  --precision float|double CPU reference arithmetic (default float)
  --threads N              CPU reference threads (default: all)
  --width N, --height N    image size in pixels (1..)" +
           side + R"()
  --spp N                  samples per pixel (1..)" +
           std::to_string(kMaxSamplesPerPixel) + R"(): 1 = pixel centre, more = stratified jitter
  --max-depth N            rays are traced while their depth is below N (0..)" +
           std::to_string(kMaxRayDepth) + "; default " + std::to_string(defaults.maxDepth) + R"()
  --min-weight W           skip branches whose path weight is below W in every channel (default 0)
  --fresnel MODEL          schlick (default) | exact | schlick-exp2, for glass
  --filter MODE            bilinear (default) | nearest: textures and environment maps
  --camera-from X,Y,Z      camera position
  --camera-at X,Y,Z        camera target
  --camera-up X,Y,Z        camera up vector
  --fov DEG                vertical field of view, )" +
           kFovYRange + R"(
  --light X,Y,Z            a white point light; repeatable; replaces the scene's lights
  --background R,G,B       constant background colour, linear RGB
  --stats FILE.json        write device, times by phase, rays by kind and limits hit
  --iteration-budget N     GPU loop steps per subgroup (8 pixels on lavapipe) and dispatch
                           (default )" +
           std::to_string(gpuDefaults.iterationBudget) + R"(; lavapipe silently stops loops at 65,535)
  --tile N                 GPU tile size in pixels, 8..4096 (default )" +
           std::to_string(kCpuTileSize) + R"( on lavapipe; on a GPU the
                           largest whose buffers fit an eighth of its memory: 'vitrum devices')
  --no-specialize          GPU: the general kernel instead of one built for what the scene
                           needs (same image; for comparison, docs/specialization.md)
)";
}

enum class Backend { Vulkan, Cpu };

struct RenderCommand {
    std::string scenePath;
    std::string outputPath;
    std::string statsPath;
    Backend backend = Backend::Vulkan;
    std::string device;
    bool doublePrecision = false;
    unsigned threads = 0;
    VulkanRenderOptions gpu;
    // Overrides of the scene.
    std::optional<std::uint32_t> width, height, spp, maxDepth;
    std::optional<float> minWeight, fov;
    std::optional<FresnelModel> fresnel;
    std::optional<TextureFilter> filter;
    std::optional<glm::vec3> from, at, up, background;
    std::vector<glm::vec3> lights;
};

bool hasExtension(const std::string& path, std::initializer_list<const char*> extensions) {
    std::string ext = lowerCaseExtension(path);
    for (const char* e : extensions)
        if (ext == e) return true;
    return false;
}

RenderCommand parse(int argc, char** argv, int first) {
    RenderCommand c;
    Arguments args(argc, argv, first);
    while (!args.empty()) {
        std::string flag = args.next();
        if (flag == "-o" || flag == "--output") c.outputPath = args.valueOf(flag);
        else if (flag == "--backend") {
            std::string v = args.valueOf(flag);
            if (v == "vulkan") c.backend = Backend::Vulkan;
            else if (v == "cpu") c.backend = Backend::Cpu;
            else throw InputError("--backend must be vulkan or cpu, got \"" + v + "\"");
        } else if (flag == "--device") c.device = args.valueOf(flag);
        else if (flag == "--precision") {
            std::string v = args.valueOf(flag);
            if (v != "float" && v != "double") throw InputError("--precision must be float or double, got \"" + v + "\"");
            c.doublePrecision = v == "double";
        } else if (flag == "--threads") c.threads = Arguments::toUint(flag, args.valueOf(flag), 1, 1024);
        else if (flag == "--width") c.width = Arguments::toUint(flag, args.valueOf(flag), 1, kMaxImageSide);
        else if (flag == "--height") c.height = Arguments::toUint(flag, args.valueOf(flag), 1, kMaxImageSide);
        else if (flag == "--spp") c.spp = Arguments::toUint(flag, args.valueOf(flag), 1, kMaxSamplesPerPixel);
        else if (flag == "--max-depth") c.maxDepth = Arguments::toUint(flag, args.valueOf(flag), 0, kMaxRayDepth);
        else if (flag == "--min-weight") {
            float w = Arguments::toFloat(flag, args.valueOf(flag));
            if (w < 0 || w > 1) throw InputError("--min-weight must be between 0 and 1");
            c.minWeight = w;
        } else if (flag == "--fresnel") {
            std::string v = args.valueOf(flag);
            if (v == "schlick") c.fresnel = FresnelModel::Schlick;
            else if (v == "exact") c.fresnel = FresnelModel::Exact;
            else if (v == "schlick-exp2") c.fresnel = FresnelModel::SchlickExp2;
            else throw InputError("--fresnel must be schlick, exact or schlick-exp2, got \"" + v + "\"");
        } else if (flag == "--filter") {
            std::string v = args.valueOf(flag);
            if (v == "bilinear") c.filter = TextureFilter::Bilinear;
            else if (v == "nearest") c.filter = TextureFilter::Nearest;
            else throw InputError("--filter must be bilinear or nearest, got \"" + v + "\"");
        } else if (flag == "--camera-from") c.from = Arguments::toVec3(flag, args.valueOf(flag));
        else if (flag == "--camera-at") c.at = Arguments::toVec3(flag, args.valueOf(flag));
        else if (flag == "--camera-up") c.up = Arguments::toVec3(flag, args.valueOf(flag));
        else if (flag == "--fov") {
            float f = Arguments::toFloat(flag, args.valueOf(flag));
            if (!validFovY(f)) throw InputError(std::string("--fov must be ") + kFovYRange);
            c.fov = f;
        } else if (flag == "--light") c.lights.push_back(Arguments::toVec3(flag, args.valueOf(flag)));
        else if (flag == "--background") {
            glm::vec3 b = Arguments::toVec3(flag, args.valueOf(flag));
            if (b.x < 0 || b.y < 0 || b.z < 0) throw InputError("--background must not be negative");
            c.background = b;
        } else if (flag == "--stats") c.statsPath = args.valueOf(flag);
        else if (flag == "--iteration-budget") c.gpu.iterationBudget = Arguments::toUint(flag, args.valueOf(flag), kMinIterationBudget, 1u << 24);
        else if (flag == "--tile") c.gpu.tileSize = Arguments::toUint(flag, args.valueOf(flag), kMinTileSize, kMaxTileSize);
        else if (flag == "--no-specialize") c.gpu.specialize = false;
        else if (flag.rfind("-", 0) == 0) throw InputError("unknown option " + flag + " (see vitrum render --help)");
        else if (c.scenePath.empty()) c.scenePath = flag;
        else throw InputError("more than one scene given: \"" + c.scenePath + "\" and \"" + flag + "\"");
    }
    if (c.scenePath.empty()) throw InputError("no scene given (see vitrum render --help)");
    if (c.outputPath.empty()) throw InputError("no output given: add -o OUT.png (or .pfm, .hdr, .exr)");
    if (!hasExtension(c.outputPath, {".png", ".pfm", ".hdr", ".exr"}))
        throw InputError(c.outputPath + ": the output must end in .png, .pfm, .hdr or .exr");
    for (const std::string& out : {c.outputPath, c.statsPath}) {
        // Fail before any long work when the output cannot be written where asked.
        if (out.empty()) continue;
        std::filesystem::path parent = std::filesystem::path(out).parent_path();
        std::error_code ec;
        if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
            throw InputError(out + ": cannot write the file: " + parent.string() + " is not a directory");
        checkWritable(out);
    }
    if (!c.statsPath.empty() && !hasExtension(c.statsPath, {".json"}))
        throw InputError(c.statsPath + ": --stats must name a .json file");
    return c;
}

void applyOverrides(const RenderCommand& c, Scene& scene) {
    if (c.width) scene.camera.width = *c.width;
    if (c.height) scene.camera.height = *c.height;
    if (c.spp) scene.settings.samplesPerPixel = *c.spp;
    if (c.maxDepth) scene.settings.maxDepth = *c.maxDepth;
    if (c.minWeight) scene.settings.minWeight = *c.minWeight;
    if (c.fresnel) scene.settings.fresnel = *c.fresnel;
    if (c.filter) scene.settings.filter = *c.filter;
    if (c.from) scene.camera.from = *c.from;
    if (c.at) scene.camera.at = *c.at;
    if (c.up) scene.camera.up = *c.up;
    if (c.fov) scene.camera.fovY = *c.fov;
    if (c.background) {
        scene.background.kind = BackgroundKind::Constant;
        scene.background.colour = *c.background;
    }
    if (!c.lights.empty()) {
        scene.lights.clear();
        for (const glm::vec3& p : c.lights) scene.lights.push_back({.position = p, .colour = glm::vec3(1.0f)});
    }
    const Camera& cam = scene.camera;
    if (const std::string problem = cameraProblem(cam); !problem.empty())
        throw InputError("the camera (--camera-from, --camera-at, --camera-up or the scene's): " + problem);
    if (const auto problem = lightProblem(scene))
        throw InputError("light " + std::to_string(problem->light + 1) + " (--light or the scene's): " + problem->message);
    if (std::uint64_t(cam.width) * cam.height > (1ull << 28))
        throw InputError("the image is too large: " + std::to_string(cam.width) + "x" + std::to_string(cam.height));
}

// Said before a render whose work (pixels x samples x depth) is far beyond the usual (a 16384 x
// 16384 image at 4096 samples was accepted without a word, and took about 15 hours): its size, and
// a lower bound on its time at the fastest rate lavapipe traces primary rays alone here
// (docs/performance.md, about 20 Mrays/s).
std::string largeRenderNote(const Scene& scene) {
    constexpr double kLargeWork = 1e10;
    constexpr double kFastestRaysPerSecond = 20e6;
    const Camera& c = scene.camera;
    const RenderSettings& s = scene.settings;
    const double primary = double(c.width) * c.height * s.samplesPerPixel;
    if (primary * std::max(s.maxDepth, 1u) < kLargeWork) return "";
    const double seconds = primary / kFastestRaysPerSecond;
    char time[64];
    if (seconds < 90.0) std::snprintf(time, sizeof(time), "a minute");
    else if (seconds < 3600.0) std::snprintf(time, sizeof(time), "%.0f minutes", seconds / 60.0);
    else std::snprintf(time, sizeof(time), "%.1f hours", seconds / 3600.0);
    char text[320];
    std::snprintf(text, sizeof(text),
                  "a large render: %.3g primary rays (%u x %u pixels x %u samples), each a tree of up to %u levels; "
                  "at 20 Mrays/s, lavapipe's fastest for primary rays alone, it takes at least %s",
                  primary, c.width, c.height, s.samplesPerPixel, s.maxDepth, time);
    return text;
}

// The files of the scene's largest textures, for an error about their buffer: "a.png (4096 x
// 4096, 192 MiB)" and the next two.
std::string largestTextures(const Scene& scene) {
    std::vector<const Texture*> bySize;
    for (const Texture& texture : scene.textures) bySize.push_back(&texture);
    std::sort(bySize.begin(), bySize.end(),
              [](const Texture* a, const Texture* b) { return a->texels.size() > b->texels.size(); });
    std::string list = bySize.size() == 1 ? "the texture: " : "the largest textures: ";
    for (std::size_t i = 0; i < std::min<std::size_t>(bySize.size(), 3); ++i) {
        const Texture& t = *bySize[i];
        list += (i ? ", " : "") + t.path.string() + " (" + std::to_string(t.width) + " x " + std::to_string(t.height) +
                ", " + describeBytes(t.texels.size() * 3 * sizeof(float)) + ")";
    }
    return list;
}

// Refuses a scene whose GPU buffers would not fit the device, from the scene's counts alone: before
// the BVH build, the packing and the upload (gpu/vulkan_renderer.cpp makes the buffers, and
// GpuBuffer checks each again then). The BVH has at most 2n - 1 nodes for n triangles.
void checkSceneFitsDevice(const VulkanDevice& device, const Scene& scene, const VulkanRenderOptions& options) {
    const VkDeviceSize triangles = scene.triangles.size();
    if (triangles > gpu::kMaxTriangles)
        throw InputError("the scene has " + std::to_string(triangles) + " triangles; the Vulkan backend traces at most " +
                         std::to_string(gpu::kMaxTriangles));
    VkDeviceSize texels = 0;
    for (const Texture& texture : scene.textures) texels += texture.texels.size();
    const std::uint32_t tile = tileSizeFor(device.description(), options.tileSize);
    const glm::uvec2 tilePixels(std::min(tile, scene.camera.width), std::min(tile, scene.camera.height));
    // As gpu/vulkan_renderer.cpp binds them: the scene's geometry and materials as texel buffers.
    constexpr BufferKind kTexel = BufferKind::Texel, kStorage = BufferKind::Storage;
    struct Buffer {
        const char* what;
        VkDeviceSize bytes;
        BufferKind kind;
        bool perTile = false;  // sized by --tile, not by the scene or the image
        bool textures = false;  // the scene's textures and environment maps, whose files the error names
    };
    std::vector<Buffer> buffers{
        {"BVH nodes", triangles * sizeof(gpu::TraversalNode), kTexel},  // at most triangles - 1 interior nodes
        {"triangle vertices", triangles * sizeof(gpu::TriangleVertices), kTexel},
        {"triangle normals and uvs", triangles * sizeof(gpu::TriangleShading), kTexel},
        {"materials", scene.materials.size() * sizeof(gpu::GpuMaterial), kTexel},
        {"lights", scene.lights.size() * sizeof(gpu::GpuLight), kTexel},
        {"texture texels", texels * 3 * sizeof(float), kStorage, false, true},
    };
    // The general kernel's: the scene's analysis, which may need fewer pending rays, comes later.
    for (const TileBuffer& buffer : kTileBuffers)
        buffers.push_back({buffer.what, tileBufferBytes(buffer, tilePixels, gpu::kRayStackSize), kStorage, true});
    VkDeviceSize total = 0;
    for (const auto& buffer : buffers) {
        if (buffer.bytes > bufferLimit(device, buffer.kind).bytes) {
            const InputError error = bufferTooLarge(device, buffer.what, buffer.bytes, buffer.kind);
            if (buffer.perTile) throw InputError(std::string(error.what()) + "; a smaller --tile needs less");
            if (buffer.textures) throw InputError(std::string(error.what()) + "; " + largestTextures(scene));
            throw error;
        }
        total += buffer.bytes;
    }
    // All of them live in device-local memory (gpu/gpu_buffer.h's MemoryUse) but the tile's pixels.
    const VkDeviceSize deviceLocal = device.description().deviceLocalBytes;
    if (deviceLocal > 0 && total > deviceLocal)
        throw InputError("the scene does not fit the device: its buffers need " + describeBytes(total) +
                         " in all, but the largest device-local memory heap of " + device.name() + " has " +
                         describeBytes(deviceLocal));
}

}  // namespace

int renderCommand(int argc, char** argv, int first) {
    if (wantsHelp(argc, argv, first)) {
        std::cout << renderHelp();
        return 0;
    }
    RenderCommand command = parse(argc, argv, first);
    using Clock = std::chrono::steady_clock;
    auto start = Clock::now();
    Scene scene = loadScene(command.scenePath);
    applyOverrides(command, scene);
    if (const std::string note = largeRenderNote(scene); !note.empty()) warn(note);
    double loadSeconds = std::chrono::duration<double>(Clock::now() - start).count();

    // The device comes before the BVH build, so that a scene too large for it is refused before
    // any long work.
    std::optional<VulkanDevice> device;
    double deviceSeconds = 0.0;
    if (command.backend == Backend::Vulkan) {
        auto deviceStart = Clock::now();
        device.emplace(command.device);
        deviceSeconds = std::chrono::duration<double>(Clock::now() - deviceStart).count();
        checkSceneFitsDevice(*device, scene, command.gpu);
    }

    RenderStats stats;
    stats.addPhase("load", loadSeconds);
    Image image;
    Bvh bvh;
    try {
        bvh = buildBvh(scene.triangles);
        stats.addPhase("bvh", bvh.stats.buildSeconds);
        ProgressBar progress("rendering");
        auto onProgress = [&](double fraction) { progress.update(fraction); };
        if (command.backend == Backend::Vulkan) {
            stats.addPhase("device", deviceSeconds);
            command.gpu.progress = onProgress;
            image = renderVulkan(*device, scene, bvh, command.gpu, stats);
            if (device->validationMessages() > 0)
                throw std::runtime_error(std::to_string(device->validationMessages()) +
                                         " Vulkan validation messages (see above)");
        } else {
            ReferenceOptions options{.doublePrecision = command.doublePrecision,
                                     .threads = command.threads,
                                     .progress = onProgress};
            image = renderReference(scene, bvh, options, stats);
        }
    } catch (const std::bad_alloc&) {
        throw InputError(command.scenePath + ": not enough memory to render it (" + std::to_string(scene.triangles.size()) +
                         " triangles, " + std::to_string(scene.camera.width) + " x " +
                         std::to_string(scene.camera.height) + " pixels)");
    }
    auto writeStart = Clock::now();
    writeImage(image, command.outputPath);
    stats.addPhase("write", std::chrono::duration<double>(Clock::now() - writeStart).count());

    double renderSeconds = stats.seconds("render");
    double totalSeconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::printf("device: %s (%s)\n", stats.device.c_str(), stats.backend.c_str());
    std::printf("image: %ux%u, %u spp, max depth %u -> %s\n", scene.camera.width, scene.camera.height,
                scene.settings.samplesPerPixel, scene.settings.maxDepth, command.outputPath.c_str());
    if (stats.kernel)
        std::printf("kernel: %s (medium stack %u, pending rays %u), compiled in %.3f s\n",
                    stats.kernel->specialized ? "specialized for the scene" : "general", stats.kernel->mediumStackDepth,
                    stats.kernel->pendingRayCapacity, stats.seconds("pipeline") + stats.seconds("compile"));
    if (stats.restartedPixels > 0)
        std::printf("resumable kernel: %llu pixels needed more than one dispatch, restarted (%.3f s to build it)\n",
                    (unsigned long long)stats.restartedPixels, stats.seconds("resumable kernel"));
    std::printf("time: %.3f s rendering, %.3f s in all\n", renderSeconds, totalSeconds);
    std::printf("rays: %llu (%.2f Mrays/s): %llu primary, %llu shadow, %llu reflection, %llu refraction\n",
                (unsigned long long)stats.totalRays(),
                renderSeconds > 0 ? double(stats.totalRays()) / renderSeconds * 1e-6 : 0.0,
                (unsigned long long)stats.primaryRays, (unsigned long long)stats.shadowRays,
                (unsigned long long)stats.reflectionRays, (unsigned long long)stats.refractionRays);
    if (stats.loopLimitSuspected || stats.traversalStackOverflows || stats.rayStackOverflows ||
        stats.mediumStackOverflows)
        std::fprintf(stderr, "vitrum: warning: limits hit: see --stats (loop limit %llu, traversal stack %llu, "
                             "ray stack %llu, medium stack %llu)\n",
                     (unsigned long long)stats.loopLimitSuspected,
                     (unsigned long long)stats.traversalStackOverflows,
                     (unsigned long long)stats.rayStackOverflows,
                     (unsigned long long)stats.mediumStackOverflows);
    if (!command.statsPath.empty()) {
        nlohmann::json json = toJson(stats);
        json["scene"] = command.scenePath;
        json["image"] = {{"width", scene.camera.width}, {"height", scene.camera.height}};
        json["settings"] = {{"spp", scene.settings.samplesPerPixel},
                            {"max_depth", scene.settings.maxDepth},
                            {"min_weight", scene.settings.minWeight},
                            {"fresnel", int(scene.settings.fresnel)}};
        json["triangles"] = scene.triangles.size();
        writeFileAtomically(command.statsPath, json.dump(2) + "\n");
    }
    return 0;
}

}  // namespace vitrum
