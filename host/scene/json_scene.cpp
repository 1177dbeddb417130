#include "scene/json_scene.h"
#include "scene/environment_map.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <initializer_list>
#include <limits>
#include <map>
#include <stdexcept>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/error.h"
#include "common/input_file.h"
#include "scene/float_range.h"
#include "scene/json_lines.h"
#include "render_model/dispersion.h"
#include "scene/gltf_loader.h"
#include "scene/instances.h"
#include "scene/obj_loader.h"
#include "scene/scene_loader.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct ObjectSpec {
    fs::path file;
    bool gltf = false;  // a glTF file, else an OBJ file
    ObjOptions options;
};

// nlohmann's what() reads "[json.exception.parse_error.101] parse error at line 3, column 5: syntax
// error ..."; the file and line come first in our messages, so keep only the explanation.
std::string jsonReason(std::string what) {
    if (what.starts_with("[json.exception") && what.find("] ") != std::string::npos) what.erase(0, what.find("] ") + 2);
    if (what.starts_with("parse error") && what.find(": ") != std::string::npos) what.erase(0, what.find(": ") + 2);
    return what;
}

class JsonSceneReader {
public:
    JsonSceneReader(fs::path file, std::string text, SceneLoadOptions options)
        : file_(std::move(file)), text_(std::move(text)), options_(std::move(options)) {}

    Scene read() {
        // Far beyond any scene's (objects, an entry, its transform, a vector: 4).
        constexpr int kMaxNesting = 64;
        if (const std::size_t at = offsetBeyondNesting(text_, kMaxNesting); at < text_.size())
            throw inputError(file_, lineOfOffset(text_, at),
                             "nesting deeper than " + std::to_string(kMaxNesting) + " levels");
        json root;
        try {
            root = json::parse(text_);
        } catch (const json::parse_error& e) {
            throw inputError(file_, lineOfOffset(text_, e.byte > 0 ? e.byte - 1 : 0),
                             "invalid JSON: " + jsonReason(e.what()));
        } catch (const json::exception& e) {
            throw inputError(file_, 0, "invalid JSON: " + jsonReason(e.what()));
        }
        lines_ = jsonValueLines(text_);
        if (!root.is_object()) fail("", "a scene must be a JSON object, got " + shown(root));
        checkKeys(root, "", {"camera", "lights", "background", "air_ior", "objects", "render"});

        Scene scene;
        scene.source = file_;
        if (const json* v = member(root, "render")) scene.settings = settings(*v, "/render");
        if (const json* v = member(root, "background")) background(*v, "/background", scene);
        if (const json* v = member(root, "air_ior"))
            scene.airIor = float(number(
                *v, "/air_ior", [](double x) { return x >= 1.0 && x <= 10.0; }, "a number from 1 to 10"));
        const json* lightList = member(root, "lights");
        if (lightList) scene.lights = lights(*lightList, "/lights");
        const json* cameraValue = member(root, "camera");
        if (cameraValue) scene.camera = camera(*cameraValue, "/camera");
        const json* objectList = member(root, "objects");
        if (!objectList) fail("", "a scene needs \"objects\": a non-empty list of OBJ or glTF files");
        std::vector<ObjectSpec> specs = objects(*objectList, "/objects");

        const std::size_t listedLights = scene.lights.size();
        ObjLoader loader(scene, options_);
        // An OBJ file that two or more entries name (with the same "mtl") is loaded once, as a
        // mesh that each entry places (docs/scene-format.md, "Instancing"); the others' triangles
        // come first, in the world.
        const std::vector<std::vector<std::size_t>> placings =
            options_.instancing ? repeatedFiles(specs, false) : std::vector<std::vector<std::size_t>>{};
        std::vector<bool> placed(specs.size(), false);
        for (const std::vector<std::size_t>& uses : placings)
            for (std::size_t i : uses) placed[i] = true;
        // A glTF file that two or more entries name is loaded once, at its first entry, and placed
        // by each (its meshes stored once).
        std::vector<std::vector<std::size_t>> gltfPlacings(specs.size());
        for (std::size_t i = 0; i < specs.size(); ++i)
            if (specs[i].gltf) gltfPlacings[i] = {i};
        if (options_.instancing)
            for (const std::vector<std::size_t>& uses : repeatedFiles(specs, true)) {
                for (std::size_t i : uses) gltfPlacings[i].clear();
                gltfPlacings[uses.front()] = uses;
            }
        for (std::size_t i = 0; i < specs.size(); ++i) {
            const ObjectSpec& spec = specs[i];
            // A glTF's punctual lights join the scene's; its cameras are not used (the scene's
            // camera rules: docs/scene-format.md, "glTF in a JSON scene").
            if (spec.gltf && !gltfPlacings[i].empty()) {
                GltfOptions gltf{.placements = {}};
                for (std::size_t j : gltfPlacings[i])
                    gltf.placements.push_back({specs[j].options.transform, "/objects/" + std::to_string(j)});
                loadGltf(scene, spec.file, options_, gltf);
            } else if (!spec.gltf && !placed[i]) {
                loader.load(spec.file, spec.options);
            }
        }
        for (const std::vector<std::size_t>& uses : placings) {
            const std::size_t firstTriangle = scene.triangles.size(), firstObject = scene.objectNames.size();
            loader.load(specs[uses.front()].file, {.mtlOverride = specs[uses.front()].options.mtlOverride});
            std::vector<std::string> names;
            const std::uint32_t mesh = makeMesh(scene, firstTriangle, firstObject, names);
            const FloatBox box = meshBox(scene, scene.meshes[mesh]);
            for (std::size_t i : uses) {
                const std::string at = "/objects/" + std::to_string(i) + "/transform";
                Instance instance;
                try {
                    instance = makeInstance(mesh, std::uint32_t(scene.objectNames.size()), specs[i].options.transform);
                } catch (const std::invalid_argument& e) {
                    fail(at, e.what());
                }
                const FloatBox placed = instanceBox(instance, box);
                const glm::vec3 size = placed.max - placed.min;
                if (!(std::isfinite(size.x) && std::isfinite(size.y) && std::isfinite(size.z)))
                    fail(at, "the transform moves the object's vertices beyond the range of float");
                scene.instances.push_back(instance);
                scene.objectNames.insert(scene.objectNames.end(), names.begin(), names.end());
            }
        }
        putMeshesLast(scene);  // a glTF file's meshes among the world's triangles
        if (const auto problem = lightProblem(scene)) {
            if (problem->light >= listedLights) throw inputError(file_, 0, "a light of its glTF files: " + problem->message);
            fail("/lights/" + std::to_string(problem->light) + "/position", problem->message);
        }
        if (!cameraValue) {
            // The automatic camera comes with its own light unless the scene has lights (listed,
            // or its glTF files').
            std::vector<PointLight> listed = scene.lights;
            frameAutomatically(scene);
            if (lightList || !listed.empty()) scene.lights = listed;
        }
        return scene;
    }

private:
    [[noreturn]] void fail(const std::string& path, const std::string& message) const {
        auto found = lines_.find(path);
        throw inputError(file_, found == lines_.end() ? 0 : found->second, message);
    }

    // "fov_y" for "/camera/fov_y", "objects[1]" for "/objects/1" (quoted).
    static std::string name(const std::string& path) {
        const std::size_t slash = path.rfind('/');
        const std::string last = path.substr(slash + 1);
        std::string result = "\"";
        if (slash != std::string::npos && slash > 0 && last.find_first_not_of("0123456789") == std::string::npos) {
            const std::size_t parent = path.rfind('/', slash - 1) + 1;
            result.append(path, parent, slash - parent).append("[").append(last).append("]");
        } else {
            result.append(last);
        }
        return result.append("\"");
    }

    static std::string shown(const json& v) {
        std::string s = v.dump();
        return s.size() > 60 ? s.substr(0, 57) + "..." : s;
    }

    [[noreturn]] void expected(const json& v, const std::string& path, const std::string& what) const {
        fail(path, name(path) + " must be " + what + ", got " + shown(v));
    }

    static const json* member(const json& object, const char* key) {
        auto found = object.find(key);
        return found == object.end() ? nullptr : &*found;
    }

    void requireObject(const json& v, const std::string& path) const {
        if (!v.is_object()) expected(v, path, "an object");
    }

    void checkKeys(const json& object, const std::string& path, std::initializer_list<const char*> known) const {
        for (const auto& item : object.items()) {
            if (std::find_if(known.begin(), known.end(), [&](const char* k) { return item.key() == k; }) != known.end())
                continue;
            auto found = lines_.find(path + "/" + item.key());
            std::string where = file_.string();
            if (found != lines_.end()) where.append(":").append(std::to_string(found->second));
            warn(where + ": unknown key \"" + item.key() + "\" ignored");
        }
    }

    // Finite also as a float: the scene is single precision (and 1e39 would not convert).
    static bool isFiniteFloat(double x) {
        return std::isfinite(x) && std::abs(x) <= double(std::numeric_limits<float>::max());
    }

    double number(const json& v, const std::string& path, const std::function<bool(double)>& ok,
                  const std::string& what) const {
        if (!v.is_number() || !isFiniteFloat(v.get<double>()) || !ok(v.get<double>())) expected(v, path, what);
        return v.get<double>();
    }

    std::uint32_t integer(const json& v, const std::string& path, int lo, int hi) const {
        auto ok = [&](double x) { return x == std::floor(x) && x >= lo && x <= hi; };
        return std::uint32_t(
            number(v, path, ok, "an integer from " + std::to_string(lo) + " to " + std::to_string(hi)));
    }

    glm::vec3 vector3(const json& v, const std::string& path, bool nonNegative = false) const {
        bool ok = v.is_array() && v.size() == 3;
        for (std::size_t i = 0; ok && i < 3; ++i)
            ok = v[i].is_number() && isFiniteFloat(v[i].get<double>()) && (!nonNegative || v[i].get<double>() >= 0.0);
        if (!ok) expected(v, path, nonNegative ? "an array of 3 non-negative numbers" : "an array of 3 finite numbers");
        return {v[0].get<float>(), v[1].get<float>(), v[2].get<float>()};
    }

    std::string string(const json& v, const std::string& path) const {
        if (!v.is_string()) expected(v, path, "a string");
        return v.get<std::string>();
    }

    template <typename T>
    T choice(const json& v, const std::string& path, std::initializer_list<std::pair<const char*, T>> options) const {
        std::string list;
        for (const auto& [text, value] : options) {
            if (v.is_string() && v.get<std::string>() == text) return value;
            list += std::string(list.empty() ? "" : ", ") + "\"" + text + "\"";
        }
        expected(v, path, "one of " + list);
    }

    RenderSettings settings(const json& v, const std::string& path) const {
        requireObject(v, path);
        checkKeys(v, path, {"spp", "max_depth", "fresnel", "min_weight", "filter", "wavelengths"});
        RenderSettings s;
        if (const json* x = member(v, "spp"))
            s.samplesPerPixel = integer(*x, path + "/spp", 1, int(kMaxSamplesPerPixel));
        if (const json* x = member(v, "wavelengths"))
            s.wavelengths = integer(*x, path + "/wavelengths", int(kMinWavelengths), int(kMaxWavelengths));
        if (const json* x = member(v, "max_depth")) s.maxDepth = integer(*x, path + "/max_depth", 0, int(kMaxRayDepth));
        if (const json* x = member(v, "fresnel"))
            s.fresnel = choice<FresnelModel>(*x, path + "/fresnel",
                                             {{"schlick", FresnelModel::Schlick},
                                              {"exact", FresnelModel::Exact},
                                              {"schlick-exp2", FresnelModel::SchlickExp2}});
        if (const json* x = member(v, "filter"))
            s.filter = choice<TextureFilter>(*x, path + "/filter",
                                             {{"bilinear", TextureFilter::Bilinear}, {"nearest", TextureFilter::Nearest}});
        if (const json* x = member(v, "min_weight"))
            s.minWeight = float(number(
                *x, path + "/min_weight", [](double w) { return w >= 0.0 && w <= 1.0; }, "a number from 0 to 1"));
        return s;
    }

    // {"colour": [r, g, b]}, {"spherical": "sky.hdr"}, {"cube": [six faces +x -x +y -y +z -z]} or
    // {"cube_cross": "cross.png"}; a map may come with a "colour" (unused) but not with another map.
    void background(const json& v, const std::string& path, Scene& scene) const {
        requireObject(v, path);
        checkKeys(v, path, {"colour", "spherical", "cube", "cube_cross"});
        if (const json* c = member(v, "colour")) scene.background.colour = vector3(*c, path + "/colour", true);
        int maps = int(member(v, "spherical") != nullptr) + int(member(v, "cube") != nullptr) +
                   int(member(v, "cube_cross") != nullptr);
        if (maps > 1) fail(path, "a background has one map: \"spherical\", \"cube\" or \"cube_cross\", not several");
        auto imagePath = [&](const json& x, const std::string& at) {
            if (!x.is_string() || x.get<std::string>().empty()) expected(x, at, "an image file name");
            return file_.parent_path() / x.get<std::string>();
        };
        try {
            if (const json* x = member(v, "spherical")) {
                loadSphericalBackground(scene, imagePath(*x, path + "/spherical"), options_.texelLimit);
            } else if (const json* x = member(v, "cube_cross")) {
                loadCubeCrossBackground(scene, imagePath(*x, path + "/cube_cross"), options_.texelLimit);
            } else if (const json* x = member(v, "cube")) {
                if (!x->is_array() || x->size() != 6)
                    expected(*x, path + "/cube", "six image file names (+x, -x, +y, -y, +z, -z)");
                std::array<fs::path, 6> faces;
                for (std::size_t i = 0; i < 6; ++i) faces[i] = imagePath((*x)[i], path + "/cube/" + std::to_string(i));
                loadCubeBackground(scene, faces, options_.texelLimit);
            }
        } catch (const InputError& e) {
            fail(path, e.what());
        }
    }

    std::vector<PointLight> lights(const json& v, const std::string& path) const {
        if (!v.is_array()) expected(v, path, "an array of lights");
        std::vector<PointLight> result;
        for (std::size_t i = 0; i < v.size(); ++i) {
            const std::string at = path + "/" + std::to_string(i);
            requireObject(v[i], at);
            checkKeys(v[i], at, {"position", "colour", "falloff"});
            PointLight light;
            const json* position = member(v[i], "position");
            if (!position) fail(at, "a light needs a \"position\"");
            light.position = vector3(*position, at + "/position");
            if (const json* c = member(v[i], "colour")) light.colour = vector3(*c, at + "/colour", true);
            if (const json* f = member(v[i], "falloff"))
                light.inverseSquare = choice<bool>(*f, at + "/falloff", {{"none", false}, {"inverse_square", true}});
            result.push_back(light);
        }
        return result;
    }

    Camera camera(const json& v, const std::string& path) const {
        requireObject(v, path);
        checkKeys(v, path, {"from", "at", "up", "fov_y", "width", "height"});
        Camera c;
        for (const char* key : {"from", "at"})
            if (!member(v, key)) fail(path, std::string("the camera needs \"") + key + "\"");
        c.from = vector3(v["from"], path + "/from");
        c.at = vector3(v["at"], path + "/at");
        if (const json* x = member(v, "up")) c.up = vector3(*x, path + "/up");
        if (const json* x = member(v, "fov_y"))
            c.fovY = float(number(
                *x, path + "/fov_y", validFovY, std::string("a number ") + kFovYRange));
        if (const json* x = member(v, "width")) c.width = integer(*x, path + "/width", 1, int(kMaxImageSide));
        if (const json* x = member(v, "height")) c.height = integer(*x, path + "/height", 1, int(kMaxImageSide));
        if (const std::string problem = cameraProblem(c); !problem.empty()) {
            const json* up = member(v, "up");
            if (problem.rfind("\"up\"", 0) == 0)
                fail(up ? path + "/up" : path, problem + ", got " + (up ? shown(*up) : "the default [0,0,1]"));
            fail(path + "/at", problem);
        }
        return c;
    }

    // The entries of each glTF file, or each OBJ file with the same "mtl", that two or more entries
    // name, in the order of their first entries.
    static std::vector<std::vector<std::size_t>> repeatedFiles(const std::vector<ObjectSpec>& specs, bool gltf) {
        std::map<std::pair<fs::path, fs::path>, std::size_t> group;
        std::vector<std::vector<std::size_t>> groups;
        for (std::size_t i = 0; i < specs.size(); ++i) {
            if (specs[i].gltf != gltf) continue;
            const auto key = std::pair(fs::weakly_canonical(specs[i].file),
                                       specs[i].options.mtlOverride ? fs::weakly_canonical(*specs[i].options.mtlOverride)
                                                                    : fs::path());
            const auto [it, added] = group.try_emplace(key, groups.size());
            if (added) groups.emplace_back();
            groups[it->second].push_back(i);
        }
        std::erase_if(groups, [](const std::vector<std::size_t>& uses) { return uses.size() < 2; });
        return groups;
    }

    std::vector<ObjectSpec> objects(const json& v, const std::string& path) const {
        if (!v.is_array() || v.empty()) expected(v, path, "a non-empty array of objects");
        std::vector<ObjectSpec> specs;
        for (std::size_t i = 0; i < v.size(); ++i) {
            const std::string at = path + "/" + std::to_string(i);
            requireObject(v[i], at);
            checkKeys(v[i], at, {"obj", "mtl", "gltf", "transform"});
            ObjectSpec spec;
            const json* obj = member(v[i], "obj");
            const json* gltf = member(v[i], "gltf");
            if (!obj && !gltf) fail(at, "an object needs \"obj\" or \"gltf\": the path of an OBJ or glTF file");
            if (obj && gltf) fail(at + "/gltf", "an object has \"obj\" or \"gltf\", not both");
            spec.gltf = gltf != nullptr;
            spec.file = spec.gltf ? existingFile(*gltf, at + "/gltf") : existingFile(*obj, at + "/obj");
            if (const json* mtl = member(v[i], "mtl")) {
                if (spec.gltf) fail(at + "/mtl", "\"mtl\" belongs to OBJ files; a glTF file has its own materials");
                spec.options.mtlOverride = existingFile(*mtl, at + "/mtl");
            }
            if (const json* t = member(v[i], "transform")) spec.options.transform = transform(*t, at + "/transform");
            specs.push_back(std::move(spec));
        }
        return specs;
    }

    fs::path existingFile(const json& v, const std::string& path) const {
        fs::path file = string(v, path);
        if (file.is_relative()) file = file_.parent_path() / file;  // relative to the scene file
        std::error_code ec;
        const fs::file_status status = fs::status(file, ec);
        if (!fs::exists(status)) fail(path, name(path) + ": no such file \"" + file.string() + "\"");
        if (!fs::is_regular_file(status)) fail(path, name(path) + ": not a regular file \"" + file.string() + "\"");
        return file;
    }

    // Scale, then rotation about x, y, z (in that order), then translation.
    glm::mat4 transform(const json& v, const std::string& path) const {
        requireObject(v, path);
        checkKeys(v, path, {"scale", "rotate_deg", "translate"});
        glm::vec3 scale(1.0f), rotation(0.0f), translation(0.0f);
        if (const json* s = member(v, "scale")) {
            const std::string at = path + "/scale";
            if (!s->is_number() && !s->is_array())
                expected(*s, at, "a non-zero number or an array of 3 non-zero numbers");
            scale = s->is_number() ? glm::vec3(float(number(
                                         *s, at, [](double) { return true; }, "")))
                                   : vector3(*s, at);
            if (scale.x == 0.0f || scale.y == 0.0f || scale.z == 0.0f)
                expected(*s, at, "a non-zero number or an array of 3 non-zero numbers");
        }
        if (const json* r = member(v, "rotate_deg")) rotation = glm::radians(vector3(*r, path + "/rotate_deg"));
        if (const json* t = member(v, "translate")) translation = vector3(*t, path + "/translate");
        glm::mat4 m = glm::translate(glm::mat4(1.0f), translation);
        m = glm::rotate(m, rotation.z, glm::vec3(0, 0, 1));
        m = glm::rotate(m, rotation.y, glm::vec3(0, 1, 0));
        m = glm::rotate(m, rotation.x, glm::vec3(1, 0, 0));
        return glm::scale(m, scale);
    }

    fs::path file_;
    std::string text_;
    SceneLoadOptions options_;
    std::unordered_map<std::string, int> lines_;
};

}  // namespace

Scene readJsonScene(const fs::path& file, const SceneLoadOptions& options) {
    return JsonSceneReader(file, readInputText(file, "the scene file", kMaxSceneFileBytes), options).read();
}

}  // namespace vitrum
