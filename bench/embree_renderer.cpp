// A complete CPU Whitted renderer built on Embree 3, the yardstick of issues 51 and 52: what a user
// with only a CPU would get from a CPU renderer. The render model is vitrum's (the CPU reference's
// shading, in float, on all hardware threads); the closest hits, shadow rays and the short probes
// where surfaces meet are Embree's (rtcIntersect1, rtcOccluded1, and an intersection filter that
// collects every hit), over a BVH of Embree's high-quality build. A bare OBJ is read the way such a
// renderer reads it, with tinyobjloader and none of vitrum's checks (its MTL by vitrum's parser, so
// that the materials are the same); a JSON scene by vitrum's loader. Prints the time of each phase,
// the whole time and the peak resident memory, like `vitrum render`, and with --stats writes them.
//
//   vitrum_bench_embree_render SCENE -o OUT [--width W --height H] [--threads N] [--stats FILE.json]
#include <embree3/rtcore.h>
#include <sys/resource.h>
#include <tiny_obj_loader.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_support.h"
#include "embree_triangles.h"
#include "analysis/scene_features.h"
#include "bvh/bvh.h"
#include "common/error.h"
#include "cpu/reference_renderer.h"
#include "image/image.h"
#include "scene/mtl_material.h"
#include "scene/mtl_parser.h"
#include "scene/scene_loader.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// A bare OBJ as tinyobjloader reads it, fanned into triangles like vitrum's loader, with vitrum's
// automatic camera and light (scene_loader.h), so that the image is vitrum's.
Scene loadObjPlainly(const fs::path& path) {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warning, error;
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, path.c_str(),
                          path.parent_path().c_str(), true))
        throw std::runtime_error(path.string() + ": " + error);
    Scene scene;
    scene.source = path;
    // The materials tinyobjloader found, as vitrum's parser reads their MTL files.
    std::map<std::string, Material> byName;
    std::ifstream obj(path);
    for (std::string line; std::getline(obj, line);)
        if (line.rfind("mtllib ", 0) == 0)
            for (const MtlEntry& entry : parseMtlFile(path.parent_path() / line.substr(7)))
                byName[entry.name] = materialFromMtl(entry, path.parent_path() / line.substr(7));
    for (const tinyobj::material_t& m : materials) {
        auto found = byName.find(m.name);
        scene.materials.push_back(found != byName.end() ? found->second : defaultMaterial());
    }
    scene.materials.push_back(defaultMaterial());
    const std::uint32_t fallback = std::uint32_t(scene.materials.size() - 1);
    std::size_t corners = 0;
    for (const auto& shape : shapes) corners += shape.mesh.indices.size();
    scene.triangles.reserve(corners / 3);
    for (std::size_t s = 0; s < shapes.size(); ++s) {
        const tinyobj::mesh_t& mesh = shapes[s].mesh;
        for (std::size_t f = 0; f < mesh.indices.size() / 3; ++f) {
            Triangle t;
            const int material = mesh.material_ids[f];
            t.material = material >= 0 ? std::uint32_t(material) : fallback;
            t.object = std::uint32_t(s);
            for (int i = 0; i < 3; ++i) {
                const tinyobj::index_t& idx = mesh.indices[3 * f + i];
                const float* p = &attrib.vertices[3 * std::size_t(idx.vertex_index)];
                t.position[i] = glm::vec3(p[0], p[1], p[2]);
                t.uv[i] = idx.texcoord_index >= 0 ? glm::vec2(attrib.texcoords[2 * std::size_t(idx.texcoord_index)],
                                                              attrib.texcoords[2 * std::size_t(idx.texcoord_index) + 1])
                                                  : glm::vec2(0.0f);
            }
            glm::vec3 geometric = glm::cross(t.position[1] - t.position[0], t.position[2] - t.position[0]);
            const float length = glm::length(geometric);
            geometric = length > 0.0f ? geometric / length : glm::vec3(0.0f, 0.0f, 1.0f);
            for (int i = 0; i < 3; ++i) {
                const int n = mesh.indices[3 * f + i].normal_index;
                t.normal[i] = n >= 0 ? glm::normalize(glm::vec3(attrib.normals[3 * std::size_t(n)],
                                                                attrib.normals[3 * std::size_t(n) + 1],
                                                                attrib.normals[3 * std::size_t(n) + 2]))
                                     : geometric;
            }
            scene.triangles.push_back(t);
        }
        scene.objectNames.push_back(shapes[s].name);
    }
    frameAutomatically(scene);
    return scene;
}

// Embree's scene over the triangles in their own order (the reference's "BVH order" is then the
// identity): one triangle geometry, three vertices a triangle as the reference keeps them.
class EmbreeIntersector final : public RayIntersector {
public:
    EmbreeIntersector(const std::vector<Triangle>& triangles, unsigned threads)
        : config_("threads=" + std::to_string(threads)),
          triangles_(triangles.size(), [&](std::size_t i, int c) { return triangles[i].position[c]; },
                     {.config = config_.c_str(),
                      .quality = RTC_BUILD_QUALITY_HIGH,
                      .flags = RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION}) {}  // all()'s filter

    std::optional<TriangleHit<float>> closest(const Ray<float>& r) const override {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit hit;
        hit.ray = makeRay(r);
        hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(triangles_.scene(), &context, &hit);
        if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
        return TriangleHit<float>{hit.ray.tfar, hit.hit.u, hit.hit.v, hit.hit.primID};
    }

    bool any(const Ray<float>& r) const override {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRay ray = makeRay(r);
        rtcOccluded1(triangles_.scene(), &context, &ray);
        return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
    }

    // Every hit in (tMin, tMax): a filter that records each hit and rejects it, so that Embree
    // goes on to the next.
    void all(const Ray<float>& r, std::vector<TriangleHit<float>>& hits) const override {
        struct Collecting {
            RTCIntersectContext context;
            std::vector<TriangleHit<float>>* hits;
        } collecting;
        rtcInitIntersectContext(&collecting.context);
        collecting.context.filter = [](const RTCFilterFunctionNArguments* args) {
            auto* self = reinterpret_cast<Collecting*>(args->context);
            const RTCRay ray = rtcGetRayFromRayN(args->ray, args->N, 0);
            const RTCHit hit = rtcGetHitFromHitN(args->hit, args->N, 0);
            self->hits->push_back({ray.tfar, hit.u, hit.v, hit.primID});
            args->valid[0] = 0;
        };
        collecting.hits = &hits;
        RTCRayHit hit;
        hit.ray = makeRay(r);
        hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(triangles_.scene(), &collecting.context, &hit);
    }

private:
    static RTCRay makeRay(const Ray<float>& r) { return bench::embreeRay(r.origin, r.direction, r.tMin, r.tMax); }

    std::string config_;
    bench::EmbreeTriangles triangles_;
};

double peakResidentBytes() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) * 1024.0;
}

int run(int argc, char** argv) {
    std::string scenePath, output, statsPath;
    std::uint32_t width = 0, height = 0;
    unsigned threads = std::thread::hardware_concurrency();
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(flag + " needs a value");
            return argv[++i];
        };
        if (flag == "-o") output = value();
        else if (flag == "--width") width = std::uint32_t(std::stoul(value()));
        else if (flag == "--height") height = std::uint32_t(std::stoul(value()));
        else if (flag == "--threads") threads = unsigned(std::stoul(value()));
        else if (flag == "--stats") statsPath = value();
        else if (scenePath.empty() && flag[0] != '-') scenePath = flag;
        else throw std::runtime_error("unknown argument " + flag);
    }
    if (scenePath.empty() || output.empty())
        throw std::runtime_error("usage: vitrum_bench_embree_render SCENE -o OUT [--width W --height H] [--threads N] "
                                 "[--stats FILE.json]");
    const auto start = Clock::now();
    auto phase = Clock::now();
    // Every copy of a repeated mesh in the world: Embree's scene is the triangle list.
    Scene scene = fs::path(scenePath).extension() == ".obj" ? loadObjPlainly(scenePath)
                                                             : loadScene(scenePath, SceneLoadOptions{.instancing = false});
    if (width) scene.camera.width = width;
    if (height) scene.camera.height = height;
    const double load = secondsSince(phase);

    // The scene's analysis (the render model's, analysis/scene_features.h) beside Embree's build,
    // as `vitrum render` runs it beside its own.
    std::future<std::pair<SceneFeatures, double>> analysis = std::async(std::launch::async, [&] {
        const auto analysisStart = Clock::now();
        SceneFeatures features = analyseScene(scene);
        return std::pair(std::move(features), secondsSince(analysisStart));
    });
    phase = Clock::now();
    const EmbreeIntersector embree(scene.triangles, threads);
    const double build = secondsSince(phase);
    const auto [features, analysisSeconds] = analysis.get();

    // The reference reads only the triangle order of its BVH when an intersector traces.
    Bvh identity;
    identity.triangleOrder.resize(scene.triangles.size());
    std::iota(identity.triangleOrder.begin(), identity.triangleOrder.end(), 0u);
    RenderStats stats;
    ReferenceOptions options{.threads = threads, .intersector = &embree, .features = &features};
    const Image image = renderReference(scene, identity, options, stats);

    phase = Clock::now();
    writeImage(image, output);
    const double write = secondsSince(phase);
    const double total = secondsSince(start);
    const double peak = peakResidentBytes();
    std::printf("Embree 3 renderer, %u threads: %zu triangles, %ux%u -> %s\n", threads, scene.triangles.size(),
                scene.camera.width, scene.camera.height, output.c_str());
    std::printf("load %.3f s, bvh %.3f s, analysis %.3f s, render %.3f s, write %.3f s; %.3f s in all; peak RSS %.0f MB\n",
                load, build, analysisSeconds, stats.seconds("render"), write, total, peak * 1e-6);
    if (!statsPath.empty()) {
        nlohmann::json json;
        json["triangles"] = scene.triangles.size();
        json["threads"] = threads;
        json["seconds"] = {{"load", load},     {"bvh", build}, {"analysis", analysisSeconds},
                           {"render", stats.seconds("render")}, {"write", write}, {"total", total}};
        json["peak_rss_bytes"] = peak;
        json["rays"] = {{"primary", stats.primaryRays}, {"shadow", stats.shadowRays},
                        {"reflection", stats.reflectionRays}, {"refraction", stats.refractionRays}};
        std::ofstream(statsPath) << json.dump(2) << "\n";
    }
    return 0;
}

}  // namespace
}  // namespace vitrum

int main(int argc, char** argv) {
    return vitrum::bench::guardedMain("vitrum_bench_embree_render", [&] { return vitrum::run(argc, argv); });
}
