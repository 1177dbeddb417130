#include "scene/scene_fingerprint.h"

#include <cstring>
#include <span>
#include <type_traits>

namespace vitrum {
namespace {

// FNV-1a over 64-bit words (Fowler, Noll and Vo): not a cryptographic hash, a check that two
// loads of the same files agree. Each value is added by its bytes, never a struct's padding.
class Digest {
public:
    void add(const void* data, std::size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (; bytes >= 8; bytes -= 8, p += 8) {
            std::uint64_t word;
            std::memcpy(&word, p, 8);
            mix(word);
        }
        std::uint64_t tail = 0;
        std::memcpy(&tail, p, bytes);
        mix(tail ^ (std::uint64_t(bytes) << 56));
    }
    template <class T>
    void add(const T& value) requires std::has_unique_object_representations_v<T> || std::is_floating_point_v<T> {
        add(&value, sizeof(value));
    }
    template <int N, class T>
    void add(const glm::vec<N, T>& v) {
        for (int i = 0; i < N; ++i) add(v[i]);
    }
    void add(const std::string& s) {
        add(s.size());
        add(s.data(), s.size());
    }
    std::uint64_t value() const { return hash_; }

private:
    void mix(std::uint64_t word) {
        hash_ ^= word;
        hash_ *= 0x100000001b3ull;
    }
    std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

}  // namespace

std::uint64_t sceneFingerprint(const Scene& scene) {
    Digest d;
    d.add(scene.triangles.size());
    for (const Triangle& t : scene.triangles) {
        for (int i = 0; i < 3; ++i) {
            d.add(t.position[i]);
            d.add(t.normal[i]);
            d.add(t.uv[i]);
        }
        d.add(t.material);
        d.add(t.object);
    }
    if (!scene.instances.empty()) {
        for (const Mesh& m : scene.meshes) {
            d.add(m.first);
            d.add(m.count);
            d.add(m.objects);
        }
        for (const Instance& instance : scene.instances) {
            d.add(instance.mesh);
            d.add(instance.firstObject);
            for (int c = 0; c < 4; ++c) d.add(glm::vec4(instance.objectToWorld[c]));
        }
    }
    d.add(scene.materials.size());
    for (const Material& m : scene.materials) {
        d.add(std::uint32_t(m.model));
        d.add(m.ambient);
        d.add(m.diffuse);
        d.add(m.specular);
        d.add(m.shininess);
        d.add(m.ior);
        d.add(m.attenuation);
        d.add(m.priority);
        d.add(m.abbe);
        d.add(m.tint);
        d.add(m.diffuseTexture);
        d.add(m.cutout);
        d.add(m.coverage);
        d.add(m.transmissionTexture);
        d.add(m.opaquePart);
    }
    d.add(scene.textures.size());
    for (const Texture& t : scene.textures) {
        d.add(t.width);
        d.add(t.height);
        d.add(t.texels.data(), t.texels.size() * sizeof(glm::vec3));
    }
    d.add(scene.lights.size());
    for (const PointLight& l : scene.lights) {
        d.add(l.position);
        d.add(l.colour);
        d.add(std::uint32_t(l.inverseSquare));
    }
    const Camera& c = scene.camera;
    d.add(c.from);
    d.add(c.at);
    d.add(c.up);
    d.add(c.fovY);
    d.add(c.width);
    d.add(c.height);
    d.add(std::uint32_t(scene.background.kind));
    d.add(scene.background.colour);
    d.add(scene.background.map);
    const RenderSettings& s = scene.settings;
    d.add(s.samplesPerPixel);
    d.add(s.maxDepth);
    d.add(std::uint32_t(s.fresnel));
    d.add(s.minWeight);
    d.add(std::uint32_t(s.filter));
    d.add(s.wavelengths);
    d.add(scene.airIor);
    d.add(scene.objectNames.size());  // which triangles make one object is in Triangle::object
    return d.value();
}

}  // namespace vitrum
