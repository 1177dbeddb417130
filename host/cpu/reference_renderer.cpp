// The CPU reference renderer: ../shared/docs/render-model.md as a recursive Whitted-style ray
// tree, one function per material model, in float or double. The decisions the render model
// leaves open are made the way shaders/trace.comp makes them, so that the two backends can be
// compared pixel by pixel:
//   - the hit point is interpolated from the barycentrics (Waechter and Binder recommend it over
//     o + t d: its error scales with the triangle, not with the ray's length);
//   - new rays start at offsetRayOrigin(p, n_g) on the side they go to, with tMin = 0, with the
//     offsets scaled to the scene exactly as makeRenderParams scales the GPU's (rayOffsetScale);
//   - Beer-Lambert's length runs from the un-offset point a ray leaves from: t plus the offset's
//     share along the ray (the GPU puts that share's factor into the new ray's weight);
//   - a shadow ray runs from the offset point to the light as o + t (light - o), 0 < t < 1, any hit;
//   - the ambient term of a light is not attenuated by inverse-square fall-off, the direct term is;
//   - a light's shadow ray is traced only when its direct term is not zero.
#include "cpu/reference_renderer.h"
#include "cpu/texture_sampling.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "bvh/bvh_traversal.h"
#include "cpu/optics.h"
#include "render_model/dispersion.h"
#include "render_model/ray_offset.h"
#include "render_model/medium_materials.h"
#include "render_model/sampling.h"
#include "analysis/scene_features.h"

namespace vitrum {
namespace {

// Counters of one worker thread, summed at the end: those of trace_statistics.h that the CPU
// measures (the GPU-only ones stay 0 and are not reported), and the traversal's.
struct TraceCounters : TraceCounts {
    TraversalCounters traversal;
    std::vector<TracedRay>* tracedRays = nullptr;  // this thread's log, when one is asked for
    std::uint32_t pixel = 0;                        // the pixel being traced, for the log

    template <class Real>
    void logRay(const Ray<Real>& ray, bool anyHit) {
        if (tracedRays)
            tracedRays->push_back({glm::vec3(ray.origin), float(ray.tMin), glm::vec3(ray.direction),
                                   float(std::min<Real>(ray.tMax, Real(std::numeric_limits<float>::max()))), anyHit,
                                   pixel});
    }

    void addTo(RenderStats& stats) const {
        TraceCounts counts = *this;
        counts.nodeVisits = traversal.nodeVisits;
        stats += counts;
    }
};

// The triangles in BVH order as both traversals read them, marked (gpu_types.h, "Triangles").
std::vector<gpu::TriangleVertices> markedVertices(const Scene& scene, const Bvh& bvh) {
    std::vector<gpu::TriangleVertices> vertices = packTriangleVertices(bvh, scene.triangles);
    for (std::size_t i = 0; i < vertices.size(); ++i)
        vertices[i].v2.w =
            std::bit_cast<float>(traversalMark(scene.materials[scene.triangles[bvh.triangleOrder[i]].material]));
    return vertices;
}

// A triangle's texture coordinates at barycentrics (u, v) of its corners v1 and v2, interpolated
// as the hit point is (the kernels' interpolatedUv).
template <class Real>
glm::vec<2, Real> uvAt(const Triangle& tri, Real u, Real v) {
    const Real w0 = Real(1) - u - v;
    return w0 * glm::vec<2, Real>(tri.uv[0]) + u * glm::vec<2, Real>(tri.uv[1]) + v * glm::vec<2, Real>(tri.uv[2]);
}

// Where a marked triangle is cut away (Material::cutout): its texture at the hit's uv, read as
// map_Kd is (diffuseColour), below 1.
class ReferenceCutouts final : public Cutouts {
public:
    ReferenceCutouts(const Scene& scene, const Bvh& bvh) : scene_(scene), bvh_(bvh) {}
    bool cutAway(std::uint32_t triangle, std::uint32_t mark, float u, float v) const override {
        return cut<float>(triangle, mark, u, v);
    }
    bool cutAway(std::uint32_t triangle, std::uint32_t mark, double u, double v) const override {
        return cut<double>(triangle, mark, u, v);
    }

private:
    template <class Real>
    bool cut(std::uint32_t triangle, std::uint32_t mark, Real u, Real v) const {
        const glm::vec<2, Real> uv = uvAt(scene_.triangles[bvh_.triangleOrder[triangle]], u, v);
        return sampling::sampleMeshTexture<Real>(scene_, int(mark & gpu::kTriangleCutoutTexture), uv).x < Real(1);
    }

    const Scene& scene_;
    const Bvh& bvh_;
};

template <class Real>
class ReferenceTracer {
public:
    using Vec3 = glm::vec<3, Real>;
    using Color = glm::vec<3, Real>;
    using MediumStack = std::vector<std::uint32_t>;  // objects the ray is inside, innermost last

    ReferenceTracer(const Scene& scene, const Bvh& bvh, const SceneFeatures& features,
                    const RayIntersector* intersector)
        : scene_(scene),
          bvh_(bvh),
          intersector_(intersector),
          vertices_(markedVertices(scene, bvh)),
          cutouts_(scene, bvh),
          anyCutouts_(features.cutouts),
          mediumMaterials_(objectMediumMaterials(scene)),
          cameraMedia_(features.cameraMedia),
          cameraMediaBehind_(features.cameraMediaBehind),
          cameraSurface_(Vec3(features.cameraSurface.normal)),
          maxDepth_(scene.settings.maxDepth),
          touchTolerance_(Real(features.touchingDistance)),
          touchingPossible_(features.touchingMediaPossible),
          opaqueContactPossible_(features.opaqueContactPossible),
          coincidentOpaquePossible_(features.coincidentOpaquePossible),
          minWeight_(Real(scene.settings.minWeight)),
          offsetScale_(rayOffsetScale(scene)) {
        // Another traversal knows the triangles, not vitrum's instances (RayIntersector).
        if (intersector_ && !bvh.instances.empty())
            throw std::invalid_argument("a RayIntersector traces scenes without instances only");
        if (intersector_ && (features.cutouts || features.partialCoverage))
            throw std::invalid_argument(
                "a RayIntersector traces scenes without cut-out or partly covered surfaces only");
        // Each object's medium's Cauchy B (0 without dispersion), in float as the GPU gets it;
        // the wavelength samples only where some medium disperses.
        for (std::uint32_t material : mediumMaterials_) {
            const Material& m = scene.materials[material];
            mediumDispersion_.push_back(m.model == MaterialModel::Glass ? float(cauchyB(m.ior, m.abbe)) : 0.0f);
        }
        if (std::any_of(mediumDispersion_.begin(), mediumDispersion_.end(), [](float b) { return b != 0.0f; }))
            samples_ = wavelengthSamples(scene.settings.wavelengths);
        const Camera& c = scene.camera;
        cameraFrom_ = Vec3(c.from);
        cameraZ_ = glm::normalize(Vec3(c.from) - Vec3(c.at));
        cameraX_ = glm::normalize(glm::cross(Vec3(c.up), cameraZ_));
        cameraY_ = glm::cross(cameraZ_, cameraX_);
        focal_ = Real(c.height) / (Real(2) * std::tan(glm::radians(Real(c.fovY)) / Real(2)));
    }

    // Whether some medium disperses: rays split into wavelength samples.
    bool disperses() const { return !samples_.empty(); }

    // The averaged colour of pixel (x, y) over the scene's samples (box filter).
    Color renderPixel(std::uint32_t x, std::uint32_t y, TraceCounters& counters) const {
        const Camera& c = scene_.camera;
        const std::uint32_t n = std::max(1u, scene_.settings.samplesPerPixel);
        const std::uint32_t pixelIndex = y * c.width + x;  // wraps like the GPU's uint arithmetic
        Color sum(0);
        for (std::uint32_t k = 0; k < n; ++k) {
            const glm::vec2 offset = stratifiedSample(pixelIndex, k, n);
            const Real sx = Real(x) + Real(offset.x);
            const Real sy = Real(y) + Real(offset.y);
            const Vec3 d = glm::normalize((sx - Real(c.width) / Real(2)) * cameraX_ +
                                          (Real(c.height) / Real(2) - sy) * cameraY_ - focal_ * cameraZ_);
            if (maxDepth_ == 0) {
                counters.depthLimitHits += 1;  // not even the primary ray may be traced
                continue;
            }
            counters.primaryRays += 1;
            // Off the surface the camera lies on, if any, on the ray's side (analysis/camera_surface.h).
            const bool behind = glm::dot(d, cameraSurface_) < Real(0);
            sum += trace(cameraFrom_, primaryRayOrigin(cameraFrom_, cameraSurface_, d, offsetScale_), d, 0,
                         behind ? cameraMediaBehind_ : cameraMedia_, Color(1), kWhite, counters);
        }
        return sum / Real(n);
    }

private:
    struct Hit {
        Real t;
        Vec3 position;
        Vec3 geometricNormal;  // unit, as wound (outward for a closed mesh)
        Vec3 shadingNormal;    // unit, interpolated
        glm::vec<2, Real> uv;
        const Material* material;
        std::uint32_t object;
    };

    // A ray of every wavelength, before it meets a dispersive glass; else the index of its
    // wavelength sample (render_model/dispersion.h).
    static constexpr int kWhite = -1;

    // Radiance arriving at the ray's origin along direction d (unit). `start` is the un-offset point
    // the ray leaves from (`origin` is offset off its surface); `weight` is the product of the path
    // factors so far, used only for min_weight; `sample` the ray's wavelength sample, or kWhite;
    // `passCovered` the t below which a ray going on through a partly covered surface passes such
    // surfaces by (Ray::passCoveredBelow).
    Color trace(const Vec3& start, const Vec3& origin, const Vec3& d, std::uint32_t depth, const MediumStack& media,
                const Color& weight, int sample, TraceCounters& counters, Real passCovered = Real(0)) const {
        Ray<Real> ray{origin, d, Real(0), std::numeric_limits<Real>::max(), passCovered};
        counters.logRay(ray, false);
        counters.maxRayDepth = std::max<std::uint64_t>(counters.maxRayDepth, depth);
        auto found = closest(ray, counters);
        if (found) found = hitWhereSurfacesMeet(ray, *found, counters);
        const Color mu = mediumAttenuation(media);
        if (!found) {
            // Constant colour or environment map (render model, "Background").
            Color escaped = sampling::backgroundRadiance<Real>(scene_, d);
            if (glm::any(glm::greaterThan(mu, Color(0)))) {
                // Only an open mesh lets a ray leave the scene inside an absorbing medium: the
                // infinite segment absorbs everything in those channels (render model, "Media").
                for (int i = 0; i < 3; ++i)
                    if (mu[i] > Real(0)) escaped[i] = Real(0);
                counters.absorbedEscapes += 1;
            }
            return escaped;
        }
        const Hit hit = describeHit(*found, d);
        if (sample == kWhite && splitsHere(hit, origin, d, media)) {
            // A white ray meeting a dispersive glass splits into its wavelength samples, each
            // traced again from this ray's origin with its share of the weight, as the GPU does
            // (render-model-decisions.md, "Dispersion").
            counters.dispersionSplits += 1;
            Color sum(0);
            for (int k = 0; k < int(samples_.size()); ++k) {
                const Color share(samples_[std::size_t(k)].weight);
                sum += share * trace(start, origin, d, depth, media, weight * share, k, counters, passCovered);
            }
            return sum;
        }
        // Beer-Lambert over the segment just travelled, from un-offset point to un-offset point
        // (docs/render-model-decisions.md, "Absorption lengths"); air (mu = 0) gives 1 (lecture: l = 0
        // in air).
        const Color transmittance = optics::beerLambert(mu, hit.t + glm::dot(origin - start, d));
        const Color w = weight * transmittance;
        Color colour;
        switch (hit.material->model) {
            case MaterialModel::Glass: colour = shadeGlass(hit, origin, d, depth, media, w, sample, counters); break;
            case MaterialModel::ThinGlass: colour = shadeThinGlass(hit, d, depth, media, w, sample, counters); break;
            default: colour = shadeOpaque(hit, d, depth, media, w, sample, counters); break;
        }
        return colour * transmittance;
    }

    Hit describeHit(const TriangleHit<Real>& found, const Vec3& direction) const {
        const gpu::TriangleVertices& tv = vertices_[found.triangle];
        const Triangle& tri = scene_.triangles[bvh_.triangleOrder[found.triangle]];
        const Vec3 v0(tv.v0), v1(tv.v1), v2(tv.v2);
        const Real w0 = Real(1) - found.u - found.v;
        Hit hit;
        hit.t = found.t;
        hit.position = pointToWorld(found.instance, w0 * v0 + found.u * v1 + found.v * v2);
        const Vec3 edgeCross = windingNormal(found);
        const Real crossLength = glm::length(edgeCross);
        const Vec3 interpolated = normalToWorld(
            found.instance, w0 * Vec3(tri.normal[0]) + found.u * Vec3(tri.normal[1]) + found.v * Vec3(tri.normal[2]));
        const Real length = glm::length(interpolated);
        const bool shadingValid = length > Real(0) && std::isfinite(length);
        // A triangle whose corners are collinear has no geometric normal but can still be hit by
        // rounding: fall back to the shading normal, else to facing the ray (hard-cases.md).
        hit.geometricNormal = crossLength > Real(0) && std::isfinite(crossLength)
                                  ? edgeCross / crossLength
                                  : (shadingValid ? interpolated / length : -direction);
        hit.shadingNormal = shadingValid ? interpolated / length : hit.geometricNormal;
        hit.uv = uvAt(tri, found.u, found.v);
        hit.material = &shownMaterial(scene_.materials[tri.material], hit.uv);
        hit.object = objectOf(found);
        return hit;
    }

    // A glass with a transmission texture is glass only where the texture at the hit's uv is 1 or
    // more, and its opaque part elsewhere (render-model-decisions.md, "Transmission textures"): the
    // material a hit of `m` at `uv` shows.
    const Material& shownMaterial(const Material& m, const glm::vec<2, Real>& uv) const {
        if (!hasTransmissionTexture(m)) return m;
        const bool opaque = sampling::sampleMeshTexture<Real>(scene_, m.transmissionTexture, uv).x < Real(1);
        return opaque ? scene_.materials[std::size_t(m.opaquePart)] : m;
    }

    // Instances (gpu_types.h, "Instances"): a hit's point and normals move to the world, the
    // normals by the inverse transpose (the world-to-object matrix's transpose), as the kernel's
    // finishTrace moves them; its object is its instance's.
    Vec3 pointToWorld(std::uint32_t instance, const Vec3& p) const {
        if (instance == gpu::kNoInstance) return p;
        const gpu::GpuInstance& g = bvh_.instances[instance];
        const glm::vec4* rows[3] = {&g.toWorld0, &g.toWorld1, &g.toWorld2};
        Vec3 world;
        for (int a = 0; a < 3; ++a) world[a] = glm::dot(Vec3(*rows[a]), p) + Real(rows[a]->w);
        return world;
    }
    Vec3 normalToWorld(std::uint32_t instance, const Vec3& n) const {
        if (instance == gpu::kNoInstance) return n;
        const gpu::GpuInstance& g = bvh_.instances[instance];
        return n.x * Vec3(g.toObject0) + n.y * Vec3(g.toObject1) + n.z * Vec3(g.toObject2);
    }
    std::uint32_t objectOf(const TriangleHit<Real>& h) const {
        const std::uint32_t object = scene_.triangles[bvh_.triangleOrder[h.triangle]].object;
        return h.instance == gpu::kNoInstance ? object : object + bvh_.instances[h.instance].info.z;
    }

    // ---- Opaque materials: normal, Lambert, Phong (opaque dielectric), mirror ----------------

    Color shadeOpaque(Hit hit, const Vec3& d, std::uint32_t depth, const MediumStack& media, const Color& weight,
                      int sample, TraceCounters& counters) const {
        // Both normals face the incoming ray (render model: "flipped to face the incoming ray").
        if (glm::dot(hit.geometricNormal, d) > Real(0)) hit.geometricNormal = -hit.geometricNormal;
        if (glm::dot(hit.shadingNormal, d) > Real(0)) hit.shadingNormal = -hit.shadingNormal;
        const Real alpha = coverage(*hit.material, hit.uv);
        if (alpha == Real(1)) return shadeSurface(hit, d, depth, media, weight, sample, counters);
        // Partly there (render-model-decisions.md, "Partial coverage"): alpha of the surface's
        // shading, and 1 - alpha of what lies beyond it, seen undeviated through it.
        const Color surface = alpha * shadeSurface(hit, d, depth, media, weight * alpha, sample, counters);
        // From the ray's side of the surface, so that a surface lying on it is met beyond it; it
        // passes partly covered surfaces by until twice where it crosses this one's plane.
        const Vec3 origin = offsetRayOrigin(hit.position, hit.geometricNormal, offsetScale_);
        const Real crossing = glm::dot(origin - hit.position, hit.geometricNormal) / -glm::dot(d, hit.geometricNormal);
        const Real rest = Real(1) - alpha;
        return surface + rest * traceChild(hit.position, origin, d, depth, media, weight * rest, Branch::PassThrough,
                                           sample, counters, Real(2) * crossing);
    }

    // The share of an opaque surface that is there at uv (Material::coverage), within [0, 1].
    Real coverage(const Material& m, const glm::vec<2, Real>& uv) const {
        if (!hasPartialCoverage(m)) return Real(1);
        return std::clamp(sampling::sampleMeshTexture<Real>(scene_, m.coverage, uv).x, Real(0), Real(1));
    }

    // An opaque surface where it is there, with normals facing the ray.
    Color shadeSurface(const Hit& hit, const Vec3& d, std::uint32_t depth, const MediumStack& media,
                       const Color& weight, int sample, TraceCounters& counters) const {
        const Material& m = *hit.material;
        switch (m.model) {
            case MaterialModel::Normal: return (hit.shadingNormal + Real(1)) / Real(2);
            case MaterialModel::Lambert: return directLight(hit, d, counters);
            case MaterialModel::Mirror: {
                // m_s * C_refl
                const Color ms(m.specular);
                return ms * traceReflection(hit, d, depth, media, weight * ms, sample, counters);
            }
            case MaterialModel::Phong:
            default: {
                // Lecture, "Composition": C = C_phong + R(theta_i) C_refl, R Schlick's with F0 from
                // the current medium's IOR and Ni; the reflection is not tinted.
                const Real n1 = mediumIor(media, sample);
                const Real n2 = Real(m.ior);
                const Real cosI = -glm::dot(d, hit.shadingNormal);
                const Real r = optics::fresnel(FresnelModel::Schlick, n1, n2, cosI);
                const Color phong = directLight(hit, d, counters);
                return phong + r * traceReflection(hit, d, depth, media, weight * r, sample, counters);
            }
        }
    }

    // sum over lights l_c (m_a + V(p, l_p) (m_d max(0, n.l) [+ m_s max(0, l_r.v)^Ns for Phong])).
    Color directLight(const Hit& hit, const Vec3& d, TraceCounters& counters) const {
        const Material& m = *hit.material;
        const Color diffuse = diffuseColour(m, hit.uv);
        const Vec3& n = hit.shadingNormal;
        Color sum(0);
        for (const PointLight& light : scene_.lights) {
            sum += Color(light.colour) * Color(m.ambient);
            const Vec3 toLight = Vec3(light.position) - hit.position;
            const Real distanceSquared = glm::dot(toLight, toLight);
            const Vec3 l = toLight / std::sqrt(distanceSquared);
            Color colour(light.colour);
            if (light.inverseSquare) colour /= distanceSquared;
            const Real nl = glm::dot(n, l);
            Color direct = diffuse * std::max(Real(0), nl);
            if (m.model == MaterialModel::Phong) {
                const Vec3 lr = Real(2) * nl * n - l;  // l reflected about n
                const Real c = std::max(Real(0), glm::dot(lr, -d));
                const Real ns = Real(m.shininess);
                // pow(0, 0) = 1 by convention; written out so the GPU's pow can match it.
                const Real highlight = c > Real(0) ? std::pow(c, ns) : (ns == Real(0) ? Real(1) : Real(0));
                direct += Color(m.specular) * highlight;
            }
            direct *= colour;
            // Nothing to shadow, or only a denormal a device may flush (gpu_types.h, kLeastShadowedTerm).
            if (glm::all(glm::lessThan(direct, Color(gpu::kLeastShadowedTerm)))) continue;
            if (visible(hit, Vec3(light.position), counters)) sum += direct;
        }
        return sum;
    }

    // V(p, l_p): no surface (glass included) strictly between the offset hit point and the light.
    bool visible(const Hit& hit, const Vec3& lightPosition, TraceCounters& counters) const {
        const Vec3 origin = offsetRayOrigin(hit.position, hit.geometricNormal, offsetScale_);
        counters.shadowRays += 1;
        // t in units of the whole segment: 0 < t < 1 excludes the light's own position.
        const Ray<Real> shadow{origin, lightPosition - origin, Real(0), Real(1)};
        counters.logRay(shadow, true);
        return !any(shadow, counters);
    }

    // m_d: Kd, or the texel of map_Kd at (u, 1 - v), wrapping in both directions (render model,
    // "Geometry and camera"); filtered as the scene asks (bilinear by default).
    Color diffuseColour(const Material& m, const glm::vec<2, Real>& uv) const {
        if (m.diffuseTexture < 0 || std::size_t(m.diffuseTexture) >= scene_.textures.size()) return Color(m.diffuse);
        return sampling::sampleMeshTexture<Real>(scene_, m.diffuseTexture, uv);
    }

    // C_refl of an opaque surface: the reflected ray keeps the medium stack.
    Color traceReflection(const Hit& hit, const Vec3& d, std::uint32_t depth, const MediumStack& media,
                          const Color& weight, int sample, TraceCounters& counters) const {
        const Vec3 origin = offsetRayOrigin(hit.position, hit.geometricNormal, offsetScale_);
        return traceChild(hit.position, origin, optics::reflect(d, hit.shadingNormal), depth, media, weight,
                          Branch::Reflection, sample, counters);
    }

    // What a secondary ray is counted as.
    enum class Branch { Reflection, Refraction, PassThrough };

    // A secondary ray of depth + 1, unless max_depth or min_weight stops it (both counted).
    Color traceChild(const Vec3& start, const Vec3& origin, const Vec3& direction, std::uint32_t depth,
                     const MediumStack& media, const Color& weight, Branch branch, int sample, TraceCounters& counters,
                     Real passCovered = Real(0)) const {
        if (depth + 1 >= maxDepth_) {
            counters.depthLimitHits += 1;
            return Color(0);
        }
        // Its size: a wavelength sample's weight may be negative in a channel (render-model-
        // decisions.md, "Dispersion"); other weights are never negative.
        if (glm::all(glm::lessThan(glm::abs(weight), Color(minWeight_)))) {
            counters.weightCuts += 1;
            return Color(0);
        }
        if (branch == Branch::Reflection)
            counters.reflectionRays += 1;
        else if (branch == Branch::Refraction)
            counters.refractionRays += 1;
        else
            counters.passThroughRays += 1;
        return trace(start, origin, direction, depth + 1, media, weight, sample, counters, passCovered);
    }

    // ---- Glass -------------------------------------------------------------------------------

    // [R C_refl + (1 - R) C_refr] (lecture, "Attenuation of Refracted Ray in Glass"; T_BL is applied
    // by trace() to the segment that led here).
    Color shadeGlass(const Hit& hit, const Vec3& rayOrigin, const Vec3& d, std::uint32_t depth,
                     const MediumStack& media, const Color& weight, int sample, TraceCounters& counters) const {
        // Entering or leaving the object is decided by the geometric normal of the consistently
        // wound, closed mesh (lecture, "Problematic Cases", assumption 1).
        const bool entering = glm::dot(d, hit.geometricNormal) < Real(0);
        std::vector<Crossing> crossings{{hit.object, entering, hit.t}};
        Real farT = hit.t;
        if (touchingPossible_) findTouchingCrossings(hit, rayOrigin, d, crossings, farT, counters);
        if (crossings.size() > 1) counters.touchingInterfaces += 1;

        // The stack on the far side: leave, then enter (for touching objects the ray leaves one
        // and enters the other at the same point, whatever order the hits came in).
        MediumStack inside = media;
        for (const Crossing& c : crossings) {
            if (c.entering) continue;
            // Remove the innermost entry of the object (normally the top of the stack). A ray that
            // leaves an object it never entered (open mesh, inside-out winding, or a ray started
            // inside) keeps its stack, and that is counted, like trace.comp's inconsistent_media.
            const auto it = std::find(inside.rbegin(), inside.rend(), c.object);
            if (it != inside.rend()) inside.erase(std::next(it).base());
            else counters.inconsistentMedia += 1;
        }
        // Entering an object the ray is already inside (a closed mesh cannot be entered twice:
        // rounding, or an open mesh) keeps the stack too, and is counted the same way.
        for (const Crossing& c : crossings) {
            if (!c.entering) continue;
            if (std::find(inside.begin(), inside.end(), c.object) == inside.end()) inside.push_back(c.object);
            else counters.inconsistentMedia += 1;
        }
        counters.maxMediumDepth = std::max<std::uint64_t>(counters.maxMediumDepth, inside.size());
        const Real hitIor = dispersed(hit.material->ior, hit.object, sample);
        Real n1 = entering ? mediumIor(media, sample) : hitIor;
        Real n2 = entering && crossings.size() == 1 ? hitIor : mediumIor(inside, sample);
        // What the light crossing takes on: the tint of every surface it crosses, in order
        // (render-model-decisions.md, "Glass tint").
        Color tint(1);
        for (const Crossing& c : crossings) tint *= Color(objectTint(c.object));
        // A surface of a medium of lower priority than the one the ray is in, entered or left
        // from inside, is a false hit: no interface, the ray goes on through it (Schmidt and
        // Budge, JGT 2002; render-model-decisions.md, "Overlapping media by priority").
        if (crossings.size() == 1 && !media.empty() &&
            (entering || std::find(media.begin(), media.end(), hit.object) != media.end()) &&
            priority(hit.object) < priority(media[ruling(media)])) {
            n1 = n2 = mediumIor(media, sample);
            tint = Color(1);  // a false surface is no surface
            counters.falseHits += 1;
        }

        const Vec3 facing = entering ? hit.geometricNormal : -hit.geometricNormal;  // towards the incoming side
        Vec3 n = entering ? hit.shadingNormal : -hit.shadingNormal;
        if (glm::dot(n, d) >= Real(0)) n = facing;  // an interpolated normal on the wrong side: use the true one
        // The transmitted ray starts beyond every surface of the interface.
        const Vec3 through = crossings.size() == 1 ? hit.position : rayOrigin + farT * d;
        if (n1 == n2) {
            // Index-matched: no optical interface. The same ray goes on, at the same depth, with the
            // updated stack (render model, "The ray tree"), through the surfaces' tint.
            return tint * trace(through, offsetRayOrigin(through, -facing, offsetScale_), d, depth, inside,
                                weight * tint, sample, counters);
        }
        const Real eta = n1 / n2;
        const Real cosI = -glm::dot(d, n);
        const Real r = optics::fresnel(scene_.settings.fresnel, n1, n2, cosI);
        const auto refracted = optics::refract(d, n, eta);
        Color colour(0);
        if (refracted) {
            const Color wt = weight * (Real(1) - r) * tint;
            const Vec3 origin = offsetRayOrigin(through, -facing, offsetScale_);
            colour += (Real(1) - r) * tint *
                      traceChild(through, origin, *refracted, depth, inside, wt, Branch::Refraction, sample, counters);
        } else {
            counters.totalInternalReflections += 1;  // R = 1 (the Fresnel functions return it)
        }
        // The reflected ray stays in the medium it came from: it keeps the old stack.
        colour += r * traceChild(hit.position, offsetRayOrigin(hit.position, facing, offsetScale_),
                                 optics::reflect(d, n), depth, media, weight * r, Branch::Reflection, sample, counters);
        return colour;
    }

    // A wall of no thickness (render-model-decisions.md, "Thin-walled glass"): no medium, so the
    // stack stays; R' C_refl + T' Kd C_trans with the pane's R' and T' from the face's Fresnel R
    // between the ray's medium and Ni, the transmitted ray undeviated.
    Color shadeThinGlass(Hit hit, const Vec3& d, std::uint32_t depth, const MediumStack& media, const Color& weight,
                         int sample, TraceCounters& counters) const {
        // Both normals face the incoming ray, as on an opaque surface: a sheet has no inside.
        if (glm::dot(hit.geometricNormal, d) > Real(0)) hit.geometricNormal = -hit.geometricNormal;
        if (glm::dot(hit.shadingNormal, d) > Real(0)) hit.shadingNormal = -hit.shadingNormal;
        const Color tint = diffuseColour(*hit.material, hit.uv);
        const Vec3 through = offsetRayOrigin(hit.position, -hit.geometricNormal, offsetScale_);
        const Real n1 = mediumIor(media, sample);
        const Real n2 = Real(hit.material->ior);
        if (n1 == n2)  // index-matched: only the tint; the same ray goes on at its depth
            return tint * trace(hit.position, through, d, depth, media, weight * tint, sample, counters);
        const Real cosI = -glm::dot(d, hit.shadingNormal);
        const Real r = optics::fresnel(scene_.settings.fresnel, n1, n2, cosI);
        const optics::PaneTerms<Real> pane = optics::thinPane(r);
        Color colour(0);
        if (optics::cosSquaredTransmitted(d, hit.shadingNormal, n1 / n2) >= Real(0)) {  // as the kernel's cos2t
            const Color wt = weight * pane.transmittance * tint;
            colour += pane.transmittance * tint *
                      traceChild(hit.position, through, d, depth, media, wt, Branch::Refraction, sample, counters);
        } else {
            counters.totalInternalReflections += 1;  // R = 1: the pane reflects everything
        }
        return colour +
               pane.reflectance * traceReflection(hit, d, depth, media, weight * pane.reflectance, sample, counters);
    }

    struct Crossing {
        std::uint32_t object;
        bool entering;
        Real t;
    };

    // Touching objects (lecture, "Problematic Cases": "Two objects have one or more contact
    // points"): glass surfaces of other objects crossed within a scene-scale tolerance of the hit
    // form one interface with it (render model, "Media"), e.g. glass -> glass at P2, never
    // glass -> air -> glass. Appends one crossing per other object, at its nearest glass triangle
    // there, nearest first (ties: the lower object index first); farT becomes the farthest.
    void findTouchingCrossings(const Hit& hit, const Vec3& rayOrigin, const Vec3& d, std::vector<Crossing>& crossings,
                               Real& farT, TraceCounters& counters) const {
        thread_local std::vector<TriangleHit<Real>> hits;
        hits.clear();
        counters.touchingProbes += 1;
        const Ray<Real> probe{rayOrigin, d, std::max(Real(0), hit.t - touchTolerance_), hit.t + touchTolerance_};
        all(probe, hits, counters);
        const std::size_t first = crossings.size();
        for (const TriangleHit<Real>& h : hits) {
            const Triangle& tri = scene_.triangles[bvh_.triangleOrder[h.triangle]];
            const std::uint32_t object = objectOf(h);
            if (scene_.materials[tri.material].model != MaterialModel::Glass || object == hit.object) continue;
            const Crossing crossing{object, glm::dot(d, windingNormal(h)) < Real(0), h.t};
            const auto known = std::find_if(crossings.begin() + first, crossings.end(),
                                            [&](const Crossing& c) { return c.object == object; });
            if (known == crossings.end()) crossings.push_back(crossing);
            else if (h.t < known->t) *known = crossing;
        }
        std::sort(crossings.begin() + first, crossings.end(), [](const Crossing& a, const Crossing& b) {
            return a.t < b.t || (a.t == b.t && a.object < b.object);
        });
        for (auto it = crossings.begin() + first; it != crossings.end(); ++it) farT = std::max(farT, it->t);
    }

    bool isGlass(std::uint32_t triangle) const {
        return scene_.materials[scene_.triangles[bvh_.triangleOrder[triangle]].material].model == MaterialModel::Glass;
    }

    // Where surfaces meet, within e of the nearest hit along the ray (render-model-decisions.md,
    // "Coincident opaque surfaces" and "Glass on an opaque surface"): the nearest opaque triangle
    // the ray leaves through (hits from behind) is the hit; else, where the nearest hit is glass,
    // the nearest opaque one (ties: the lower index). Where two surfaces coincide, as under a
    // glass standing on a table or a box standing on another, rounding alone would otherwise
    // choose between them. Looks only where the scene's analysis says something can be found.
    TriangleHit<Real> hitWhereSurfacesMeet(const Ray<Real>& ray, const TriangleHit<Real>& nearest,
                                           TraceCounters& counters) const {
        const bool underGlass = opaqueContactPossible_ && isGlass(nearest.triangle);
        if (!coincidentOpaquePossible_ && !underGlass) return nearest;
        thread_local std::vector<TriangleHit<Real>> hits;
        hits.clear();
        const Real t = nearest.t;
        const Ray<Real> probe{ray.origin, ray.direction, std::max(Real(0), t - touchTolerance_), t + touchTolerance_,
                              ray.passCoveredBelow};
        all(probe, hits, counters);
        auto nearer = [](const TriangleHit<Real>& h, const std::optional<TriangleHit<Real>>& than) {
            return !than || h.t < than->t || (h.t == than->t && h.triangle < than->triangle);
        };
        std::optional<TriangleHit<Real>> opaque, leaving;
        for (const TriangleHit<Real>& h : hits) {
            if (isGlass(h.triangle)) continue;
            if (nearer(h, opaque)) opaque = h;
            // Met from behind: the ray leaves through it.
            const bool fromBehind = glm::dot(ray.direction, windingNormal(h)) > Real(0);
            if (coincidentOpaquePossible_ && fromBehind && nearer(h, leaving)) leaving = h;
        }
        if (leaving) return *leaving;
        if (underGlass && opaque) return *opaque;
        return nearest;
    }

    // What a ray hits: in the BVH, or by options.intersector where a benchmark gave one.
    std::optional<TriangleHit<Real>> closest(const Ray<Real>& ray, TraceCounters& counters) const {
        if constexpr (std::is_same_v<Real, float>)
            if (intersector_) return intersector_->closest(ray);
        return traceClosest<Real>(traversalInput(), ray, &counters.traversal);
    }
    bool any(const Ray<Real>& ray, TraceCounters& counters) const {
        if constexpr (std::is_same_v<Real, float>)
            if (intersector_) return intersector_->any(ray);
        return traceAny<Real>(traversalInput(), ray, &counters.traversal);
    }
    void all(const Ray<Real>& ray, std::vector<TriangleHit<Real>>& hits, TraceCounters& counters) const {
        if constexpr (std::is_same_v<Real, float>)
            if (intersector_) return intersector_->all(ray, hits);
        traceAll<Real>(traversalInput(), ray, hits, &counters.traversal);
    }
    TraversalInput traversalInput() const {
        return {bvh_.nodes, vertices_, bvh_.instances, anyCutouts_ ? &cutouts_ : nullptr};
    }

    // The hit triangle's normal as its corners wind (not unit length), in the world: a ray along
    // d meets the triangle from the front where dot(d, n) < 0. The kernels' windingNormal
    // (shaders/triangle_test.glsl) has the same operations. An instance's moves as normals do, so
    // that a mirroring instance's triangles face out as its flattened copy's do (whose winding
    // the loaders reverse).
    Vec3 windingNormal(const TriangleHit<Real>& h) const {
        const gpu::TriangleVertices& tv = vertices_[h.triangle];
        const Vec3 v0(tv.v0);
        return normalToWorld(h.instance, glm::cross(Vec3(tv.v1) - v0, Vec3(tv.v2) - v0));
    }

    // The place in a non-empty stack of the medium the ray is in: the innermost of those of the
    // highest priority; the innermost where all priorities are equal.
    std::size_t ruling(const MediumStack& media) const {
        std::size_t best = 0;
        for (std::size_t i = 1; i < media.size(); ++i)
            if (priority(media[i]) >= priority(media[best])) best = i;
        return best;
    }

    int priority(std::uint32_t object) const { return scene_.materials[mediumMaterials_[object]].priority; }
    // The tint of the object's surface, as packScene gives the kernel: its medium's glass's, white
    // for anything else.
    glm::vec3 objectTint(std::uint32_t object) const {
        const Material& m = scene_.materials[mediumMaterials_[object]];
        return m.model == MaterialModel::Glass ? m.tint : glm::vec3(1.0f);
    }

    // IOR of the medium a ray is in, or the scene's air.
    Real mediumIor(const MediumStack& media, int sample) const {
        if (media.empty()) return Real(scene_.airIor);
        const std::uint32_t object = media[ruling(media)];
        return dispersed(scene_.materials[mediumMaterials_[object]].ior, object, sample);
    }

    // An index n_d of object `object`'s glass at the ray's wavelength sample: n_d itself for a
    // white ray or a medium without dispersion (render_model/dispersion.h).
    Real dispersed(float nd, std::uint32_t object, int sample) const {
        if (sample == kWhite || mediumDispersion_[object] == 0.0f) return Real(nd);
        return Real(nd) + Real(mediumDispersion_[object]) * Real(samples_[std::size_t(sample)].offset);
    }

    // Whether a white ray splits at `hit`: a glass hit where the object's medium, the medium the
    // ray is in, or the medium of a glass touching the hit where the ray crosses it (which the ray
    // enters or leaves there) disperses. The probe for touching glass is not counted: the GPU
    // finds the same surfaces during its traversal.
    bool splitsHere(const Hit& hit, const Vec3& rayOrigin, const Vec3& d, const MediumStack& media) const {
        if (samples_.empty() || hit.material->model != MaterialModel::Glass) return false;
        if (mediumDispersion_[hit.object] != 0.0f || (!media.empty() && mediumDispersion_[media[ruling(media)]] != 0.0f))
            return true;
        if (!touchingPossible_) return false;
        std::vector<Crossing> crossings;
        Real farT = hit.t;
        TraceCounters uncounted;
        findTouchingCrossings(hit, rayOrigin, d, crossings, farT, uncounted);
        return std::any_of(crossings.begin(), crossings.end(),
                           [&](const Crossing& c) { return mediumDispersion_[c.object] != 0.0f; });
    }

    Color mediumAttenuation(const MediumStack& media) const {
        if (media.empty()) return Color(0);
        return Color(scene_.materials[mediumMaterials_[media[ruling(media)]]].attenuation);
    }

    const Scene& scene_;
    const Bvh& bvh_;
    const RayIntersector* intersector_;  // null: the BVH's nodes
    std::vector<gpu::TriangleVertices> vertices_;
    ReferenceCutouts cutouts_;
    bool anyCutouts_;
    std::vector<std::uint32_t> mediumMaterials_;
    std::vector<float> mediumDispersion_;          // an object's medium's Cauchy B, 0 without dispersion
    std::vector<WavelengthSample> samples_;        // empty where nothing disperses
    MediumStack cameraMedia_;  // every primary ray starts inside them (SceneFeatures::cameraMedia)
    MediumStack cameraMediaBehind_;  // or these, where it goes against cameraSurface_
    Vec3 cameraSurface_;  // the normal of the surface the camera lies on, 0 if none
    std::uint32_t maxDepth_;
    Real touchTolerance_;    // surfaces closer than this along a ray touch
    bool touchingPossible_;  // glass surfaces of two objects close enough to touch (scene_features.h)
    bool opaqueContactPossible_;  // glass close enough to an opaque surface to rest on it (scene_features.h)
    bool coincidentOpaquePossible_;  // opaque surfaces of two objects close enough to coincide (scene_features.h)
    Real minWeight_;
    RayOffsetScale offsetScale_;  // Waechter and Binder's absolute offsets, scaled to the scene
    Vec3 cameraFrom_, cameraX_, cameraY_, cameraZ_;
    Real focal_;
};

// Rows are handed out one at a time from an atomic counter, so threads stay busy whatever the
// cost of each row.
template <class Real>
void renderRows(const Scene& scene, const Bvh& bvh, unsigned threadCount, const ReferenceOptions& options,
                Image& image, RenderStats& stats) {
    const ReferenceTracer<Real> tracer(scene, bvh, stats.features, options.intersector);
    if (options.progress) options.progress(0.0);
    const std::uint32_t width = scene.camera.width, height = scene.camera.height;
    std::atomic<std::uint32_t> nextRow{0};
    std::uint32_t rowsDone = 0;  // guarded by progressMutex
    std::mutex statsMutex, progressMutex;
    std::vector<std::vector<TracedRay>> threadRays(options.tracedRays ? threadCount : 0);
    std::atomic<unsigned> nextThread{0};
    auto worker = [&]() {
        TraceCounters counters;
        const unsigned thread = nextThread++;
        if (options.tracedRays) counters.tracedRays = &threadRays[thread];
        for (std::uint32_t y = nextRow++; y < height; y = nextRow++) {
            for (std::uint32_t x = 0; x < width; ++x) {
                counters.pixel = y * width + x;
                const glm::vec<3, Real> c = tracer.renderPixel(x, y, counters);
                // The render model's invariant: no NaN, Inf or negative value in any pixel; but for
                // the negative channels of dispersion, kept (render-model-decisions.md, "Dispersion").
                glm::vec3 pixel(c);
                for (int i = 0; i < 3; ++i)
                    if (!std::isfinite(pixel[i]) || (pixel[i] < 0.0f && !tracer.disperses())) pixel[i] = 0.0f;
                image.at(x, y) = pixel;
            }
            if (options.progress) {
                // The callback draws: one thread at a time, and the count taken under the same
                // lock, so that the fractions it is given never go back.
                std::lock_guard lock(progressMutex);
                options.progress(double(++rowsDone) / double(height));
            }
        }
        std::lock_guard lock(statsMutex);
        counters.addTo(stats);
        if (options.tracedRays)
            options.tracedRays->insert(options.tracedRays->end(), threadRays[thread].begin(), threadRays[thread].end());
    };
    std::vector<std::thread> threads;
    for (unsigned i = 1; i < threadCount; ++i) threads.emplace_back(worker);
    worker();
    for (std::thread& t : threads) t.join();
}

}  // namespace

Image renderReference(const Scene& scene, const Bvh& bvh, const ReferenceOptions& options, RenderStats& stats) {
    if (options.features) {
        stats.features = *options.features;
    } else {
        const auto analysisStart = std::chrono::steady_clock::now();
        stats.features = analyseScene(scene);
        stats.addPhase("analysis",
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - analysisStart).count());
    }
    const auto start = std::chrono::steady_clock::now();
    unsigned threads = options.threads != 0 ? options.threads : std::thread::hardware_concurrency();
    threads = std::max(1u, std::min(threads, std::max(1u, scene.camera.height)));
    Image image(scene.camera.width, scene.camera.height);
    stats.backend = "cpu";
    stats.device = std::string("CPU reference (") + (options.doublePrecision ? "double" : "float") + "), " +
                   std::to_string(threads) + (threads == 1 ? " thread" : " threads");
    if (options.intersector && options.doublePrecision)
        throw std::invalid_argument("renderReference: an intersector traces float rays only");
    if (options.doublePrecision) renderRows<double>(scene, bvh, threads, options, image, stats);
    else renderRows<float>(scene, bvh, threads, options, image, stats);
    stats.addPhase("render", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return image;
}

}  // namespace vitrum
