// `vitrum render`'s options: read from the command line, checked, and applied to the scene.
#include "app/render_options.h"

#include <algorithm>
#include <filesystem>
#include <initializer_list>

#include "app/arguments.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/file_extension.h"
#include "gpu/tile_size.h"
#include "render_model/dispersion.h"
#include "scene/environment_map.h"
#include "scene/float_range.h"

namespace vitrum {
namespace {

// The images an environment map may be (image/image_io.h reads them).
constexpr std::initializer_list<const char*> kBackgroundMapExtensions = {
    ".hdr", ".exr", ".pfm", ".png", ".jpg", ".jpeg", ".webp", ".ppm", ".pgm", ".pnm"};

bool hasExtension(const std::string& path, std::initializer_list<const char*> extensions) {
    std::string ext = lowerCaseExtension(path);
    for (const char* e : extensions)
        if (ext == e) return true;
    return false;
}

}  // namespace

// The ranges and defaults come from the constants the parser and the scene file use.
std::string renderHelp() {
    const VulkanRenderOptions gpuDefaults;
    const RenderSettings defaults;
    const std::string side = std::to_string(kMaxImageSide);
    return R"(usage: vitrum render SCENE -o OUT [options]

Renders SCENE (a .json scene file, a bare .obj, or a glTF .gltf or .glb) and writes OUT: .png (8-bit sRGB), .pfm,
.hdr or .exr (linear). Options override the scene's own settings. Under mpirun, the
processes share one image, rank 0 writing it ('mpirun -np N vitrum render ...',
docs/distributed.md).

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
  --wavelengths N          wavelength samples a ray splits into at a dispersive glass (1..)" +
           std::to_string(kMaxWavelengths) + "; default " + std::to_string(defaults.wavelengths) + R"()
  --min-weight W           skip branches whose path weight is below W in every channel (default 0)
  --fresnel MODEL          schlick (default) | exact | schlick-exp2, for glass
  --filter MODE            bilinear (default) | nearest: textures and environment maps
  --camera NAME            a glTF scene's camera (default: its first perspective camera)
  --variant NAME           a glTF scene's material variant (KHR_materials_variants; default: none)
  --camera-from X,Y,Z      camera position
  --camera-at X,Y,Z        camera target
  --camera-up X,Y,Z        camera up vector
  --fov DEG                vertical field of view, )" +
           kFovYRange + R"(
  --light X,Y,Z            a white point light; repeatable; replaces the scene's lights
  --background R,G,B|FILE  constant background colour, linear RGB, or an environment map: an
                           equirectangular image (.hdr, .exr, .pfm, .png, .jpg, .webp), as a
                           scene's "spherical" background
  --stats FILE.json        write device, times by phase, rays by kind and limits hit
  --iteration-budget N     GPU loop steps per subgroup (8 pixels on lavapipe) and dispatch
                           (default )" +
           std::to_string(gpuDefaults.iterationBudget) + R"(; lavapipe silently stops loops at 65,535)
  --tile N                 GPU tile size in pixels, 8..4096 (default )" +
           std::to_string(kCpuTileSize) + R"( on lavapipe; on a GPU the
                           largest whose buffers fit an eighth of its memory: 'vitrum devices')
  --no-specialize          GPU: the general kernel instead of one built for what the scene
                           needs (same image; for comparison, docs/specialization.md)
  --no-instancing          store every copy of a mesh that the scene places more than once
                           (more memory, faster tracing; docs/scene-format.md, "Instancing")
)";
}


RenderCommand parseRenderCommand(int argc, char** argv, int first) {
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
        else if (flag == "--wavelengths") c.wavelengths = Arguments::toUint(flag, args.valueOf(flag), kMinWavelengths, kMaxWavelengths);
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
        } else if (flag == "--camera") c.camera = args.valueOf(flag);
        else if (flag == "--variant")
            c.variant = args.valueOf(flag);
        else if (flag == "--camera-from") c.from = Arguments::toVec3(flag, args.valueOf(flag));
        else if (flag == "--camera-at") c.at = Arguments::toVec3(flag, args.valueOf(flag));
        else if (flag == "--camera-up") c.up = Arguments::toVec3(flag, args.valueOf(flag));
        else if (flag == "--fov") {
            float f = Arguments::toFloat(flag, args.valueOf(flag));
            if (!validFovY(f)) throw InputError(std::string("--fov must be ") + kFovYRange);
            c.fov = f;
        } else if (flag == "--light") c.lights.push_back(Arguments::toVec3(flag, args.valueOf(flag)));
        else if (flag == "--background") {
            const std::string value = args.valueOf(flag);
            if (hasExtension(value, kBackgroundMapExtensions)) {
                c.backgroundMap = value;
                c.background.reset();
            } else {
                if (std::count(value.begin(), value.end(), ',') != 2)
                    throw InputError("--background takes a colour R,G,B or an image file (.hdr, .exr, .pfm, .png, "
                                     ".jpg, .webp, .ppm), got \"" + value + "\"");
                glm::vec3 b = Arguments::toVec3(flag, value);
                if (b.x < 0 || b.y < 0 || b.z < 0) throw InputError("--background must not be negative");
                c.background = b;
                c.backgroundMap.clear();
            }
        } else if (flag == "--stats") c.statsPath = args.valueOf(flag);
        else if (flag == "--iteration-budget") c.gpu.iterationBudget = Arguments::toUint(flag, args.valueOf(flag), kMinIterationBudget, 1u << 24);
        else if (flag == "--tile") c.gpu.tileSize = Arguments::toUint(flag, args.valueOf(flag), kMinTileSize, kMaxTileSize);
        else if (flag == "--no-specialize") c.gpu.specialize = false;
        else if (flag == "--no-instancing") c.instancing = false;
        else if (flag.rfind("-", 0) == 0) throw InputError("unknown option " + flag + " (see vitrum render --help)");
        else if (c.scenePath.empty()) c.scenePath = flag;
        else throw InputError("more than one scene given: \"" + c.scenePath + "\" and \"" + flag + "\"");
    }
    if (c.scenePath.empty()) throw InputError("no scene given (see vitrum render --help)");
    if (c.outputPath.empty()) throw InputError("no output given: add -o OUT.png (or .pfm, .hdr, .exr)");
    if (!hasExtension(c.outputPath, {".png", ".pfm", ".hdr", ".exr"}))
        throw InputError(c.outputPath + ": the output must end in .png, .pfm, .hdr or .exr");
    if (!c.statsPath.empty() && !hasExtension(c.statsPath, {".json"}))
        throw InputError(c.statsPath + ": --stats must name a .json file");
    return c;
}

void checkOutputs(const RenderCommand& c) {
    for (const std::string& out : {c.outputPath, c.statsPath}) {
        // Fail before any long work when the output cannot be written where asked.
        if (out.empty()) continue;
        std::filesystem::path parent = std::filesystem::path(out).parent_path();
        std::error_code ec;
        if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
            throw InputError(out + ": cannot write the file: " + parent.string() + " is not a directory");
        checkWritable(out);
        checkNotAnInput(out, c.scenePath, "the scene file");
        if (!c.backgroundMap.empty()) checkNotAnInput(out, c.backgroundMap, "the background map");
    }
}

void checkOutputsSpareTheScenesImages(const RenderCommand& c, const Scene& scene) {
    for (const std::string& out : {c.outputPath, c.statsPath})
        for (const Texture& texture : scene.textures)
            if (!out.empty()) checkNotAnInput(out, texture.path, "one of the scene's images");
}

void applyOverrides(const RenderCommand& c, Scene& scene, const TexelLimit& limit) {
    if (c.width) scene.camera.width = *c.width;
    if (c.height) scene.camera.height = *c.height;
    if (c.spp) scene.settings.samplesPerPixel = *c.spp;
    if (c.maxDepth) scene.settings.maxDepth = *c.maxDepth;
    if (c.wavelengths) scene.settings.wavelengths = *c.wavelengths;
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
    if (!c.backgroundMap.empty()) loadSphericalBackground(scene, c.backgroundMap, limit);
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

}  // namespace vitrum
