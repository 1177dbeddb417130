// An Embree 3 scene of one triangle geometry, three vertices a triangle in the order given (so
// that Embree's primID is the caller's triangle index), and Embree's ray from vitrum's: what the
// Whitted-workload comparison (whitted_bench.cpp) and the Embree renderer (embree_renderer.cpp)
// both trace against.
#pragma once

#include <embree3/rtcore.h>

#include <cstddef>
#include <glm/glm.hpp>
#include <stdexcept>

namespace vitrum::bench {

class EmbreeTriangles {
public:
    struct Options {
        const char* config = nullptr;  // rtcNewDevice's, e.g. "threads=2"; null: Embree's defaults
        RTCBuildQuality quality = RTC_BUILD_QUALITY_MEDIUM;  // Embree's default
        RTCSceneFlags flags = RTC_SCENE_FLAG_NONE;
    };

    // `corner(i, c)`: corner c (0..2) of triangle i, a glm::vec3 or vec4 (its xyz).
    template <class Corner>
    EmbreeTriangles(std::size_t count, Corner corner, const Options& options) {
        device_ = rtcNewDevice(options.config);
        if (!device_) throw std::runtime_error("Embree: rtcNewDevice failed");
        scene_ = rtcNewScene(device_);
        rtcSetSceneBuildQuality(scene_, options.quality);
        rtcSetSceneFlags(scene_, options.flags);
        RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * count));
        auto* indices = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), count));
        for (std::size_t i = 0; i < count; ++i)
            for (int c = 0; c < 3; ++c) {
                const auto p = corner(i, c);
                for (int a = 0; a < 3; ++a) vertices[9 * i + 3 * c + a] = p[a];
                indices[3 * i + c] = unsigned(3 * i + c);
            }
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(scene_, geometry);
        rtcReleaseGeometry(geometry);
        rtcCommitScene(scene_);
        if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw std::runtime_error("Embree: building the scene failed");
    }
    ~EmbreeTriangles() {
        rtcReleaseScene(scene_);
        rtcReleaseDevice(device_);
    }
    EmbreeTriangles(const EmbreeTriangles&) = delete;
    EmbreeTriangles& operator=(const EmbreeTriangles&) = delete;

    RTCScene scene() const { return scene_; }

private:
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
};

// Embree's ray over (tMin, tMax), every geometry mask bit set.
inline RTCRay embreeRay(const glm::vec3& origin, const glm::vec3& direction, float tMin, float tMax) {
    RTCRay ray{};
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.tnear = tMin;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tfar = tMax;
    ray.mask = 0xFFFFFFFFu;
    return ray;
}

}  // namespace vitrum::bench
