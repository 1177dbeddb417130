// Scenes built in code for tests with answers worked out by hand: materials, triangles with their
// geometric normal, squares facing the camera, closed boxes, and a 9 x 9 camera whose centre
// pixel looks exactly along +y.
#pragma once

#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vitrum::testing {

inline Material makeMaterial(MaterialModel model, glm::vec3 ambient, glm::vec3 diffuse,
                             glm::vec3 specular = glm::vec3(0), float shininess = 1.0f, float ior = 1.5f) {
    Material m;
    m.model = model;
    m.ambient = ambient;
    m.diffuse = diffuse;
    m.specular = specular;
    m.shininess = shininess;
    m.ior = ior;
    return m;
}

// A grey texture of width x 1 texels (a cutout or coverage texture).
inline Texture greyRow(const std::vector<float>& values) {
    Texture t{"grey", int(values.size()), 1, {}};
    for (float v : values) t.texels.push_back(glm::vec3(v));
    return t;
}

// A triangle with its geometric normal as vertex normals.
inline Triangle makeTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, std::uint32_t material, std::uint32_t object) {
    Triangle t{};
    t.position[0] = a;
    t.position[1] = b;
    t.position[2] = c;
    const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
    for (auto& vn : t.normal) vn = n;
    t.material = material;
    t.object = object;
    return t;
}

// A square of half-size h centred at c in the plane y = c.y, facing -y (towards a camera on -y)
// or +y. Texture coordinates span [0, 1]^2 with u along +x and v along +z.
inline void addSquareY(Scene& scene, glm::vec3 c, float h, bool facingMinusY, std::uint32_t material,
                       std::uint32_t object) {
    glm::vec3 p00 = c + glm::vec3(-h, 0, -h), p10 = c + glm::vec3(h, 0, -h), p11 = c + glm::vec3(h, 0, h),
              p01 = c + glm::vec3(-h, 0, h);
    Triangle a = makeTriangle(p00, p10, p11, material, object);  // normal -y
    Triangle b = makeTriangle(p00, p11, p01, material, object);
    a.uv[0] = {0, 0}, a.uv[1] = {1, 0}, a.uv[2] = {1, 1};
    b.uv[0] = {0, 0}, b.uv[1] = {1, 1}, b.uv[2] = {0, 1};
    if (!facingMinusY) {
        for (Triangle* t : {&a, &b}) {
            std::swap(t->position[1], t->position[2]);
            std::swap(t->uv[1], t->uv[2]);
            for (auto& n : t->normal) n = -n;
        }
    }
    scene.triangles.push_back(a);
    scene.triangles.push_back(b);
}

// A closed box, outward wound.
inline void addBox(Scene& scene, glm::vec3 lo, glm::vec3 hi, std::uint32_t material, std::uint32_t object) {
    const glm::vec3 centre = 0.5f * (lo + hi);
    glm::vec3 corner[8];
    for (int i = 0; i < 8; ++i) corner[i] = glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    const int faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
    for (const auto& f : faces)
        for (int tri = 0; tri < 2; ++tri) {
            glm::vec3 a = corner[f[0]], b = corner[f[1 + tri]], c = corner[f[2 + tri]];
            if (glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - centre) < 0.0f) std::swap(b, c);
            scene.triangles.push_back(makeTriangle(a, b, c, material, object));
        }
}

// Every position of the scene (triangles, camera, lights) times `scale` plus `shift`; absorption
// scaled by 1 / scale so that the image stays the same.
inline Scene transformed(Scene scene, float scale, glm::vec3 shift = glm::vec3(0.0f)) {
    for (Triangle& t : scene.triangles)
        for (glm::vec3& p : t.position) p = p * scale + shift;
    scene.camera.from = scene.camera.from * scale + shift;
    scene.camera.at = scene.camera.at * scale + shift;
    for (PointLight& l : scene.lights) l.position = l.position * scale + shift;
    for (Material& m : scene.materials) m.attenuation /= scale;
    return scene;
}

// Camera at (0, -5, 0) looking along +y, z up, 9 x 9 pixels: the centre pixel's ray is exactly +y.
inline Scene baseScene() {
    Scene scene;
    scene.camera.from = {0, -5, 0};
    scene.camera.at = {0, 0, 0};
    scene.camera.up = {0, 0, 1};
    scene.camera.fovY = 40.0f;
    scene.camera.width = 9;
    scene.camera.height = 9;
    scene.background.colour = {0.1f, 0.2f, 0.3f};
    scene.settings.maxDepth = 10;
    return scene;
}

// baseScene with a wall of `material` facing the camera, filling its view (half-size 3 at the
// origin); no lights.
inline Scene wallOf(const Material& material) {
    Scene scene = baseScene();
    scene.materials.push_back(material);
    scene.objectNames = {"wall"};
    addSquareY(scene, {0, 0, 0}, 3.0f, true, 0, 0);
    return scene;
}

// baseScene with a Phong plastic square facing the camera (Ka 0.01, Kd (0.3, 0.2, 0.1), Ks 0.5,
// Ns 20, Ni 1.5) and a large Lambert wall behind the camera (Ka 0.1, Kd (0.5, 0.6, 0.7)) for the
// plastic to reflect; no lights.
inline Scene plasticBeforeWall() {
    Scene scene = baseScene();
    scene.materials.push_back(
        makeMaterial(MaterialModel::Phong, {0.01f, 0.01f, 0.01f}, {0.3f, 0.2f, 0.1f}, {0.5f, 0.5f, 0.5f}, 20.0f, 1.5f));
    scene.materials.push_back(makeMaterial(MaterialModel::Lambert, {0.1f, 0.1f, 0.1f}, {0.5f, 0.6f, 0.7f}));
    scene.objectNames = {"plastic", "wall"};
    addSquareY(scene, {0, 0, 0}, 3.0f, true, 0, 0);
    addSquareY(scene, {0, -10, 0}, 30.0f, false, 1, 1);
    return scene;
}

}  // namespace vitrum::testing
