// Reading textures and environment maps on the CPU: texel centres at (i + 0.5) / size, bilinear
// or nearest, wrap or clamp per axis; the spherical and cube mappings of
// ../shared/docs/render-model.md ("Background"). shaders/background.glsl and shaders/texture.glsl
// do the same steps in float.
#pragma once

#include <cmath>
#include <numbers>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vitrum::sampling {

enum class Address { Wrap, Clamp };

template <class Real>
int addressTexel(int i, int size, Address mode) {
    if (mode == Address::Wrap) return ((i % size) + size) % size;
    return i < 0 ? 0 : (i >= size ? size - 1 : i);
}

// The texel value at (u, v) in [0, 1]^2 (v = 0 is the top row).
template <class Real>
glm::vec<3, Real> sampleTexture(const Texture& t, Real u, Real v, TextureFilter filter, Address addressU,
                                Address addressV) {
    using Color = glm::vec<3, Real>;
    const int w = t.width, h = t.height;
    if (w <= 0 || h <= 0 || t.texels.size() < std::size_t(w) * std::size_t(h) || !std::isfinite(u) ||
        !std::isfinite(v))
        return Color(0);
    auto texel = [&](int x, int y) {
        x = addressTexel<Real>(x, w, addressU);
        y = addressTexel<Real>(y, h, addressV);
        return Color(t.texels[std::size_t(y) * std::size_t(w) + std::size_t(x)]);
    };
    const Real x = u * Real(w);
    const Real y = v * Real(h);
    if (filter == TextureFilter::Nearest) return texel(int(std::floor(x)), int(std::floor(y)));
    const Real xc = x - Real(0.5), yc = y - Real(0.5);
    const Real x0 = std::floor(xc), y0 = std::floor(yc);
    const Real fx = xc - x0, fy = yc - y0;
    const int ix = int(x0), iy = int(y0);
    const Color top = glm::mix(texel(ix, iy), texel(ix + 1, iy), fx);
    const Color bottom = glm::mix(texel(ix, iy + 1), texel(ix + 1, iy + 1), fx);
    return glm::mix(top, bottom, fy);
}

// Render model: theta = acos(z), phi = atan2(y, x) + pi, u = 1 - phi / (2 pi), v = theta / pi.
template <class Real>
glm::vec<2, Real> sphericalUv(const glm::vec<3, Real>& d) {
    const Real pi = std::numbers::pi_v<Real>;
    const Real z = d.z < Real(-1) ? Real(-1) : (d.z > Real(1) ? Real(1) : d.z);
    const Real theta = std::acos(z);
    const Real phi = std::atan2(d.y, d.x) + pi;
    return {Real(1) - phi / (Real(2) * pi), theta / pi};
}

template <class Real>
struct CubeUv {
    int face;  // 0..5: +x, -x, +y, -y, +z, -z
    Real u, v;
};

// Render model: the face of the largest absolute component (ties: x, then y, then z), then
// u, v = (a + 1) / 2 of the components the table names, a = c / |max|.
template <class Real>
CubeUv<Real> cubeUv(const glm::vec<3, Real>& d) {
    const Real ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
    int face;
    Real m, au, av;
    if (ax >= ay && ax >= az) {
        m = ax;
        face = d.x > 0 ? 0 : 1;
        au = d.x > 0 ? -d.y : d.y;
        av = -d.z;
    } else if (ay >= az) {
        m = ay;
        face = d.y > 0 ? 2 : 3;
        au = d.y > 0 ? d.x : -d.x;
        av = -d.z;
    } else {
        m = az;
        face = d.z > 0 ? 4 : 5;
        au = d.x;
        av = d.z > 0 ? d.y : -d.y;
    }
    return {face, (au / m + Real(1)) / Real(2), (av / m + Real(1)) / Real(2)};
}

// A mesh texture (map_Kd, a cutout or coverage texture) at a surface's texture coordinates: read at
// (u, 1 - v), wrapping in both (render-model-decisions.md, "Texture coordinates"), as the kernel's
// sampleMeshTexture reads it.
template <class Real>
glm::vec<3, Real> sampleMeshTexture(const Scene& scene, int texture, const glm::vec<2, Real>& uv) {
    return sampleTexture<Real>(scene.textures[std::size_t(texture)], uv.x, Real(1) - uv.y, scene.settings.filter,
                               Address::Wrap, Address::Wrap);
}

// The background seen along the unit direction d.
template <class Real>
glm::vec<3, Real> backgroundRadiance(const Scene& scene, const glm::vec<3, Real>& d) {
    const Background& b = scene.background;
    const TextureFilter filter = scene.settings.filter;
    if (b.kind == BackgroundKind::Spherical && b.map >= 0) {
        const auto uv = sphericalUv(d);
        return sampleTexture<Real>(scene.textures[std::size_t(b.map)], uv.x, uv.y, filter, Address::Wrap,
                                   Address::Clamp);
    }
    if (b.kind == BackgroundKind::Cube && b.map >= 0) {
        const CubeUv<Real> c = cubeUv(d);
        return sampleTexture<Real>(scene.textures[std::size_t(b.map + c.face)], c.u, c.v, filter, Address::Clamp,
                                   Address::Clamp);
    }
    return glm::vec<3, Real>(b.colour);
}

}  // namespace vitrum::sampling
