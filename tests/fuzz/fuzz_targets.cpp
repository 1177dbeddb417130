#include "fuzz_targets.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "app/render_options.h"
#include "common/error.h"
#include "image/image.h"
#include "analysis/scene_features.h"
#include "bvh/bvh.h"
#include "scene/scene_loader.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

// A folder of this process's own under the system's temporary folder, removed at exit (a crash
// leaves it behind: its name carries the process id).
class FuzzFolder {
public:
    FuzzFolder() : path_(fs::temp_directory_path() / ("vitrum-fuzz-" + std::to_string(::getpid()))) {
        fs::create_directories(path_);
    }
    ~FuzzFolder() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

const fs::path& folder() {
    static FuzzFolder folder;
    return folder.path();
}

fs::path writeFile(const std::string& name, std::string_view bytes) {
    fs::path file = folder() / name;
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    return file;
}

void removeFile(const std::string& name) {
    std::error_code ignored;
    fs::remove(folder() / name, ignored);
}

std::string_view asText(const std::uint8_t* data, std::size_t size) {
    return size ? std::string_view(reinterpret_cast<const char*>(data), size) : std::string_view();
}

}  // namespace

int fuzzObjMtl(const std::uint8_t* data, std::size_t size) {
    std::string_view bytes = asText(data, size);
    std::size_t split = bytes.find('\0');
    writeFile("fuzz.obj", bytes.substr(0, split));
    if (split == std::string_view::npos)
        removeFile("fuzz.mtl");
    else
        writeFile("fuzz.mtl", bytes.substr(split + 1));
    try {
        const Scene scene = loadScene(folder() / "fuzz.obj");
        openGlassWarning(scene, analyseScene(scene));  // names objects: their indices must hold
    } catch (const InputError&) {
    }
    return 0;
}

int fuzzGltf(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes = asText(data, size);
    const bool binary = bytes.substr(0, 4) == "glTF";
    const fs::path file = writeFile(binary ? "fuzz.glb" : "fuzz.gltf", bytes);
    try {
        // Its BVH too: two levels where nodes share a mesh (instancing).
        const Scene scene = loadScene(file);
        openGlassWarning(scene, analyseScene(scene));
        buildSceneBvh(scene);
    } catch (const InputError&) {
    }
    try {
        // A material variant's mappings (KHR_materials_variants), by the name the seeds use.
        SceneLoadOptions options;
        options.variant = "off";
        loadScene(file, options);
    } catch (const InputError&) {
    }
    return 0;
}

int fuzzSceneJson(const std::uint8_t* data, std::size_t size) {
    static const bool triangleWritten = [] {
        writeFile("tri.obj",
                  "mtllib tri.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nusemtl glass\nf 1/1/1 2/1/1 3/1/1\n");
        writeFile("tri.mtl", "newmtl glass\nshader 4\nNi 1.5\nTf 0.1 0.2 0.3\nKd 0.5\n");
        // Background maps: a 4x3 PFM (a valid cube cross and equirectangular map) and a 1x1 face.
        auto pfm = [](int width, int height) {
            std::string bytes = "PF\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
            const float grey = 0.5f;
            for (int i = 0; i < width * height * 3; ++i) bytes.append(reinterpret_cast<const char*>(&grey), 4);
            return bytes;
        };
        writeFile("sky.pfm", pfm(4, 3));
        writeFile("face.pfm", pfm(1, 1));
        return true;
    }();
    (void)triangleWritten;
    writeFile("scene.json", asText(data, size));
    try {
        // Its BVH too: two levels where it names tri.obj twice (instancing).
        const Scene scene = loadScene(folder() / "scene.json");
        analyseScene(scene);
        buildSceneBvh(scene);
    } catch (const InputError&) {
    }
    return 0;
}

int fuzzImage(const std::uint8_t* data, std::size_t size) {
    std::string_view bytes = asText(data, size);
    std::string name = "fuzz.png";
    if (bytes.starts_with("PF") || bytes.starts_with("Pf"))
        name = "fuzz.pfm";
    else if (bytes.starts_with("#?"))
        name = "fuzz.hdr";
    else if (bytes.starts_with(std::string_view("\x76\x2f\x31\x01", 4)))  // OpenEXR's magic number
        name = "fuzz.exr";
    fs::path file = writeFile(name, bytes);
    try {
        readImage(file);
    } catch (const InputError&) {
    }
    removeFile(name);
    return 0;
}

int fuzzRenderArguments(const std::uint8_t* data, std::size_t size) {
    constexpr std::size_t kMostArguments = 64;
    std::vector<std::string> pieces{"vitrum", "render"};
    std::string_view rest(reinterpret_cast<const char*>(data), size);
    while (!rest.empty() && pieces.size() < kMostArguments) {
        const std::size_t end = std::min(rest.find('\0'), rest.size());
        pieces.emplace_back(rest.substr(0, end));
        rest.remove_prefix(std::min(end + 1, rest.size()));
    }
    std::vector<char*> argv;
    for (std::string& piece : pieces) argv.push_back(piece.data());
    argv.push_back(nullptr);
    try {
        RenderCommand command = parseRenderCommand(int(pieces.size()), argv.data(), 2);
        command.backgroundMap.clear();  // a file to read, not an option: fuzz_image reads images
        Scene scene;
        scene.materials.push_back(Material{});
        scene.objectNames = {"triangle"};
        Triangle t{};
        t.position[1] = glm::vec3(1.0f, 0.0f, 0.0f);
        t.position[2] = glm::vec3(0.0f, 0.0f, 1.0f);
        for (glm::vec3& n : t.normal) n = glm::vec3(0.0f, -1.0f, 0.0f);
        scene.triangles.push_back(t);
        scene.lights.push_back({.position = glm::vec3(0.0f, -2.0f, 2.0f), .colour = glm::vec3(1.0f)});
        applyOverrides(command, scene);
        analyseScene(scene);
    } catch (const InputError&) {
    }
    return 0;
}

}  // namespace vitrum
