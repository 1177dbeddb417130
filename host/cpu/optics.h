// Reflection, refraction, Fresnel and absorption for the CPU reference, in float or double.
// Every formula is the lecture's (../shared/seed/dielectrics-lecture.txt, "Dielectric Transparent
// Materials"); shaders/optics.glsl is the GPU's copy, with the same operations in the same order.
// Conventions: `d` is the unit incoming direction, `n` the unit normal on the incoming side
// (d.n <= 0), n1 the IOR the ray comes from, n2 the IOR it goes into, eta = n1 / n2.
#pragma once

#include <cmath>
#include <optional>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vitrum::optics {

template <class Real>
using Vec3 = glm::vec<3, Real>;

// Law of reflection: r = d - 2 (d.n) n (lecture, "Geometry of Reflection and Refraction"); the
// orientation of n does not matter.
template <class Real>
Vec3<Real> reflect(const Vec3<Real>& d, const Vec3<Real>& n) {
    return d - Real(2) * glm::dot(d, n) * n;
}

// cos^2(theta_2) = 1 - eta^2 (1 - (d.n)^2), from Snell's law; negative means total internal
// reflection.
template <class Real>
Real cosSquaredTransmitted(const Vec3<Real>& d, const Vec3<Real>& n, Real eta) {
    const Real dn = glm::dot(d, n);
    return Real(1) - eta * eta * (Real(1) - dn * dn);
}

// The lecture's final refraction formula
//   l = eta d - (eta (d.n) + sqrt(1 - eta^2 (1 - (d.n)^2))) n,
// which never divides by sin(theta_1) (the intermediate q = (d + cos theta_1 n) / sin theta_1 would
// at normal incidence). Empty at total internal reflection.
template <class Real>
std::optional<Vec3<Real>> refract(const Vec3<Real>& d, const Vec3<Real>& n, Real eta) {
    const Real cos2t = cosSquaredTransmitted(d, n, eta);
    if (cos2t < Real(0)) return std::nullopt;
    const Real dn = glm::dot(d, n);
    return eta * d - (eta * dn + std::sqrt(cos2t)) * n;
}

// cos(theta_2) for cos(theta_1) = cosI, or empty at total internal reflection.
template <class Real>
std::optional<Real> cosTransmitted(Real n1, Real n2, Real cosI) {
    const Real eta = n1 / n2;
    const Real cos2t = Real(1) - eta * eta * (Real(1) - cosI * cosI);
    if (cos2t < Real(0)) return std::nullopt;
    return std::sqrt(cos2t);
}

// Fresnel equations for unpolarised light (lecture, "Amount of Refraction and Reflection"):
//   Rs = ((n2 cos t2 - n1 cos t1) / (n2 cos t2 + n1 cos t1))^2,
//   Rp = ((n2 cos t1 - n1 cos t2) / (n2 cos t1 + n1 cos t2))^2.
template <class Real>
struct FresnelTerms {
    Real rs;
    Real rp;
};

template <class Real>
FresnelTerms<Real> fresnelTerms(Real n1, Real n2, Real cosI, Real cosT) {
    const Real s = (n2 * cosT - n1 * cosI) / (n2 * cosT + n1 * cosI);
    const Real p = (n2 * cosI - n1 * cosT) / (n2 * cosI + n1 * cosT);
    return {s * s, p * p};
}

// R = (Rs + Rp) / 2; 1 at total internal reflection.
template <class Real>
Real fresnelExact(Real n1, Real n2, Real cosI) {
    const auto cosT = cosTransmitted(n1, n2, cosI);
    if (!cosT) return Real(1);
    const FresnelTerms<Real> terms = fresnelTerms(n1, n2, cosI, *cosT);
    return Real(0.5) * (terms.rs + terms.rp);
}

// Reflectance at normal incidence, F0 = ((n1 - n2) / (n1 + n2))^2 (lecture, Schlick).
template <class Real>
Real schlickF0(Real n1, Real n2) {
    const Real r = (n1 - n2) / (n1 + n2);
    return r * r;
}

// Schlick: R = F0 + (1 - F0)(1 - cos theta)^5 with theta = theta_i if n1 <= n2 else theta_t;
// "when TIR occurs we should return 1" (lecture).
template <class Real>
Real fresnelSchlick(Real n1, Real n2, Real cosI) {
    const auto cosT = cosTransmitted(n1, n2, cosI);
    if (!cosT) return Real(1);
    const Real c = Real(1) - (n1 <= n2 ? cosI : *cosT);
    const Real c2 = c * c;
    const Real f0 = schlickF0(n1, n2);
    return f0 + (Real(1) - f0) * (c2 * c2 * c);
}

// The lecture's alternative approximation: R = F0 + (1 - F0) 2^((-5.55473 cos - 6.98316) cos),
// with the same choice of angle and 1 at total internal reflection.
template <class Real>
Real fresnelSchlickExp2(Real n1, Real n2, Real cosI) {
    const auto cosT = cosTransmitted(n1, n2, cosI);
    if (!cosT) return Real(1);
    const Real c = n1 <= n2 ? cosI : *cosT;
    const Real f0 = schlickF0(n1, n2);
    return f0 + (Real(1) - f0) * std::exp2((Real(-5.55473) * c - Real(6.98316)) * c);
}

// R for the chosen model. An index-matched interface (n1 == n2) is no optical interface at all:
// R = 0 whatever the model (render model, "The ray tree").
template <class Real>
Real fresnel(FresnelModel model, Real n1, Real n2, Real cosI) {
    if (n1 == n2) return Real(0);
    switch (model) {
        case FresnelModel::Exact: return fresnelExact(n1, n2, cosI);
        case FresnelModel::SchlickExp2: return fresnelSchlickExp2(n1, n2, cosI);
        case FresnelModel::Schlick: break;
    }
    return fresnelSchlick(n1, n2, cosI);
}

// A thin pane (render-model-decisions.md, "Thin-walled glass"): the light reflected back and forth
// between its two parallel faces, each reflecting R, summed (pbrt-v4, ThinDielectricBxDF):
// R' = R + (1 - R)^2 R / (1 - R^2) = 2R / (1 + R), T' = (1 - R) / (1 + R).
template <class Real>
struct PaneTerms {
    Real reflectance;
    Real transmittance;
};

template <class Real>
PaneTerms<Real> thinPane(Real r) {
    return {Real(2) * r / (Real(1) + r), (Real(1) - r) / (Real(1) + r)};
}

// Beer-Lambert transmittance exp(-mu t) over a segment of length t in a medium of attenuation mu
// per channel (lecture, "Attenuation of Refracted Ray"); mu = 0 (air) gives exactly 1.
template <class Real>
Vec3<Real> beerLambert(const Vec3<Real>& mu, Real t) {
    return glm::exp(-mu * t);
}

}  // namespace vitrum::optics
