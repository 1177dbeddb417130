// What happens at a hit (render model, the lecture's Whitted shading): the background or the hit's
// record, direct light and shadow rays, and the reflected and refracted children.
#ifndef VITRUM_SHADING_GLSL
#define VITRUM_SHADING_GLSL

#include "trace_state.glsl"
#include "counters.glsl"
#include "pending_rays.glsl"
#include "media.glsl"
#include "ray_tree.glsl"
#include "cutout.glsl"  // cutAway, which bvh.glsl calls
#include "bvh.glsl"
#include "optics.glsl"
#include "ray_offset.glsl"
#include "texture.glsl"
#include "background.glsl"
#include "touching.glsl"
#include "ieee_vector_math.glsl"

// What this round of shading (traceUnit's loop) adds to the pixel's colour: a float sum of a few
// terms, added to the fixed-point sum once at the round's end (colour_sum.glsl).
vec3 gRoundColour = vec3(0.0);

// A white ray that met a dispersive glass becomes its wavelength samples, each traced again from
// the ray's origin with its share of the weight (render-model-decisions.md, "Dispersion"): sample
// 0 at once; the others wait as one pending entry, the white ray marked with the next sample,
// which starts one sample each time it is read (startWaitingWavelength), so that no loop pushes
// them all and the stack holds one entry for them.
void splitIntoWavelengths() {
    uint depth = rayDepth(st.ray);
    if (wavelengthCount() > 1u) {
        if (st.pendingRays >= kPendingRayCapacity) {
            counters.rayStackOverflows += 1u;  // the other samples are dropped, never silently
        } else {
            PendingRay waiting = st.ray;
            waiting.origin.w = uintBitsToFloat(depth | (2u << kWavelengthShift) | kWavelengthsWaiting);
            storePendingRay(pendingRayIndex(st.pendingRays), waiting);
            st.pendingRays += 1u;
        }
    }
    st.ray.origin.w = uintBitsToFloat(depth | (1u << kWavelengthShift));
    st.ray.weight.xyz *= wavelengthSample(0u).xyz;
    beginClosestTraversal();
}

// A ray just read from the pending rays that stands for a split ray's waiting samples: the next
// of them starts now, the rest wait on in the entry it was read from.
void startWaitingWavelength() {
    uint bits = floatBitsToUint(st.ray.origin.w);
    if ((bits & kWavelengthsWaiting) == 0u) return;
    uint depth = bits & 0xFFu;
    uint code = (bits >> kWavelengthShift) & 0xFFu;
    if (code < wavelengthCount()) {
        if (st.pendingRays >= kPendingRayCapacity) {
            counters.rayStackOverflows += 1u;
        } else {
            PendingRay rest = st.ray;
            rest.origin.w = uintBitsToFloat(depth | ((code + 1u) << kWavelengthShift) | kWavelengthsWaiting);
            storePendingRay(pendingRayIndex(st.pendingRays), rest);
            st.pendingRays += 1u;
        }
    }
    st.ray.origin.w = uintBitsToFloat(depth | (code << kWavelengthShift));
    st.ray.weight.xyz *= wavelengthSample(code - 1u).xyz;
}

// Whether st.ray, white, splits at a glass hit on `object`: the medium of the object, the one the
// ray is in, or that of a touching glass the ray crosses there (`touching`, finishTrace's
// selection: the ray enters or leaves it at this hit) disperses (render-model-decisions.md,
// "Dispersion"; the CPU reference's splitsHere).
bool splitsAt(uint object, uvec4 touching) {
    if (!kDispersion || wavelengthCode(st.ray) != 0u || wavelengthCount() == 0u) return false;
    uint count = mediaCount(st.ray);
    if (objectDispersion(object) != 0.0 || (count > 0u && objectDispersion(st.ray.media[ruling(st.ray.media, count)]) != 0.0))
        return true;
    uvec3 objects = touching.xyz & 0x7FFFFFFFu;
    return (touching.w > 0u && objectDispersion(objects.x) != 0.0) || (touching.w > 1u && objectDispersion(objects.y) != 0.0) ||
           (touching.w > 2u && objectDispersion(objects.z) != 0.0);
}

// Whether a child of st.ray at `depth` with path weight `weight` is traced; a limit that stops
// it is counted.
bool admitChild(uint depth, vec3 weight) {
    if (depth >= maxDepth()) {
        counters.depthLimitHits += 1u;
        return false;
    }
    // A wavelength sample's weight may be negative in a channel (outside sRGB's gamut): its size
    // is what min_weight compares (render-model-decisions.md, "Dispersion").
    if (all(lessThan(kDispersion ? abs(weight) : weight, vec3(minWeight())))) {
        counters.weightCuts += 1u;
        return false;
    }
    return true;
}

PendingRay childRay(vec3 origin, vec3 direction, vec3 weight, uvec4 media, uint count, uint depth) {
    PendingRay r;
    // A child keeps its parent's wavelength (never the mark of samples waiting).
    r.origin = vec4(origin, uintBitsToFloat(depth | (wavelengthCode(st.ray) << kWavelengthShift)));
    r.direction = vec4(direction, uintBitsToFloat(count));
    r.weight = vec4(weight, 0.0);
    r.media = media;
    return r;
}

// Partial coverage (glTF's alphaMode BLEND; Material::coverage): at an opaque hit, alpha of the
// surface is there, read from its coverage texture as map_Kd is. Its shading takes alpha of the
// ray's weight; the rest goes on through it, undeviated, as a child at depth + 1 that waits on the
// pending rays as a thin glass's transmission does (render-model-decisions.md, "Partial
// coverage"; the CPU reference's shadeOpaque). The child starts on the ray's side of the surface,
// so that a surface lying on this one is met beyond it, and passes partly covered triangles by
// until twice where it crosses this one's plane (its weight.w, which bvh.glsl's traversal reads).
void coverSurface(GpuMaterial m) {
    uint texture = floatBitsToUint(m.parts.x);
    if (texture == kNoTexture) return;
    float alpha = min(max(sampleMeshTexture(texture, st.hit.uv).x, 0.0), 1.0);
    vec3 passing = st.ray.weight.xyz * (1.0 - alpha);
    uint depth = rayDepth(st.ray);
    if (alpha < 1.0 && admitChild(depth + 1u, passing)) {
        if (st.pendingRays >= kPendingRayCapacity) {
            counters.rayStackOverflows += 1u;  // dropped, never silently
        } else {
            vec3 d = st.ray.direction.xyz;
            vec3 n = st.hit.geometricNormal;  // facing the ray
            vec3 origin = offsetRayOrigin(st.hit.position, n);
            PendingRay through = childRay(origin, d, passing, st.ray.media, mediaCount(st.ray), depth + 1u);
            through.weight.w = 2.0 * (ieeeDot(origin - st.hit.position, n) / -ieeeDot(d, n));
            through.weight.xyz *= skippedTransmittance(through, st.hit.position);
            storePendingRay(pendingRayIndex(st.pendingRays), through);
            st.pendingRays += 1u;
            counters.passThroughRays += 1u;
        }
    }
    st.ray.weight.xyz *= alpha;
}

// A glass with a transmission texture (glTF's transmissionTexture; Material::transmissionTexture)
// is glass only where that grey texture, read at the hit's uv as map_Kd is, is 1 or more, and its
// opaque part elsewhere (render-model-decisions.md, "Transmission textures"; the CPU reference's
// describeHit): the material that a hit of `triangle` at `barycentrics` shows.
uint shownMaterial(uint material, uint triangle, vec2 barycentrics) {
    vec4 parts = fetchVec4(materialTexels, kGpuMaterialTexels * material, 4u);
    uint texture = floatBitsToUint(parts.y);
    if (texture == kNoTexture) return material;
    bool opaque = sampleMeshTexture(texture, interpolatedUv(triangle, barycentrics)).x < 1.0;
    return opaque ? floatBitsToUint(parts.z) : material;
}

// The closest-hit traversal of st.ray is over: record the hit (triangle `tri`, the material
// `material` it shows, `m`, all read by traceUnit) or take the background.
void finishTrace(TriangleVertices tri, uint material, GpuMaterial m) {
    uint triangle = st.traversal.closest;
    // Beer-Lambert over the segment just travelled (render model: "Media: the IOR stack").
    vec3 mu = mediumAttenuation(st.ray);
    if (triangle == kNoTriangle) {
        vec3 escaped = st.ray.weight.xyz * backgroundRadiance(st.ray.direction.xyz);
        if (any(greaterThan(mu, vec3(0.0)))) {
            // Only an open mesh lets a ray leave the scene inside an absorbing medium.
            escaped *= vec3(equal(mu, vec3(0.0)));
            counters.absorbedEscapes += 1u;
        }
        gRoundColour += escaped;
        st.phase = kPhaseNextRay;
        return;
    }
    // A hit in an instance's mesh (gpu_types.h, "Instances"): its object is the instance's, and
    // its point and normals move to the world (normals by the world-to-object rows' transpose),
    // as the CPU reference's describeHit moves them.
    uint instance = kInstancing ? st.traversal.closestInstance : kNoInstance;
    GpuInstance placed;
    uint object = floatBitsToUint(tri.v1.w);
    if (kInstancing && instance != kNoInstance) {
        placed = instanceNumbered(instance);
        object += placed.info.z;
    }
    float t = st.traversal.tMax;
    // Touching objects (lecture, "Problematic Cases"): at a glass hit, the other glass surfaces
    // within the touching distance of it along the ray, which the traversal collected; the split
    // below and the glass's shading both go by them.
    bool glass = usesMaterial(kMaterialGlass) && materialModel(m) == kMaterialGlass;
    bool probed = glass && kTouchingProbe && touchingProbeOn();
    float farthest = t;
    uvec4 touching = uvec4(0u);
    if (probed) touching = selectTouching(st.candidates.touchingObjects, st.candidates.touchingT, t + touchingDistance(), object, farthest);
    if (kDispersion && glass && splitsAt(object, touching)) {
        counters.dispersionSplits += 1u;
        splitIntoWavelengths();
        return;
    }
    if (kAbsorption) st.ray.weight.xyz *= beerLambert(mu, t);  // exp(-0 t) is 1 only for finite t: not folded

    mat3 normals = loadVertexNormals(triangle);
    vec2 bary = st.traversal.barycentrics;
    float w0 = 1.0 - bary.x - bary.y;
    vec3 edgeCross = windingNormal(tri);
    vec3 interpolated = w0 * normals[0] + bary.x * normals[1] + bary.y * normals[2];
    // The hit point from the barycentrics, not origin + t d: it lies on the triangle to within
    // rounding (Waechter and Binder).
    vec3 position = w0 * tri.v0.xyz + bary.x * tri.v1.xyz + bary.y * tri.v2.xyz;
    if (kInstancing && instance != kNoInstance) {
        edgeCross = edgeCross.x * placed.toObject0.xyz + edgeCross.y * placed.toObject1.xyz + edgeCross.z * placed.toObject2.xyz;
        interpolated = interpolated.x * placed.toObject0.xyz + interpolated.y * placed.toObject1.xyz +
                       interpolated.z * placed.toObject2.xyz;
        position = pointByRows(placed.toWorld0, placed.toWorld1, placed.toWorld2, position);
    }
    float crossLength = ieeeLength(edgeCross);
    float normalLength = ieeeLength(interpolated);
    bool shadingValid = normalLength > 0.0 && !isinf(normalLength);
    // A triangle whose corners are collinear has no geometric normal but can still be hit by
    // rounding: fall back to the shading normal, else to facing the ray (hard-cases.md).
    vec3 geometricNormal = crossLength > 0.0 && !isinf(crossLength)
                               ? edgeCross / crossLength
                               : (shadingValid ? interpolated / normalLength : -st.ray.direction.xyz);
    vec3 shadingNormal = shadingValid ? interpolated / normalLength : geometricNormal;
    st.hit.position = position;
    st.hit.t = t;
    st.hit.shadingNormal = shadingNormal;
    st.hit.material = material;
    st.hit.geometricNormal = geometricNormal;
    st.hit.object = object;
    if (kTextures) st.hit.uv = interpolatedUv(triangle, bary);  // only texture lookups read it

    uint model = materialModel(m);
    if (glass) {
        if (probed) counters.touchingProbes += 1u;
        st.touching = touching;
        st.farthestTouching = farthest;
        st.phase = kPhaseScatter;
        return;
    }
    // Opaque: both normals face the incoming ray.
    vec3 d = st.ray.direction.xyz;
    if (ieeeDot(geometricNormal, d) > 0.0) st.hit.geometricNormal = -geometricNormal;
    if (ieeeDot(shadingNormal, d) > 0.0) st.hit.shadingNormal = -shadingNormal;
    if (usesMaterial(kMaterialNormal) && model == kMaterialNormal) {
        gRoundColour += st.ray.weight.xyz * (0.5 * st.hit.shadingNormal + 0.5);
        st.phase = kPhaseNextRay;
        return;
    }
    if (kPartialCoverage) coverSurface(m);
    st.light = 0u;
    bool scatters = (usesMaterial(kMaterialMirror) && model == kMaterialMirror) ||
                    (usesMaterial(kMaterialThinGlass) && model == kMaterialThinGlass);  // neither is lit
    st.phase = scatters ? kPhaseScatter : kPhaseNextLight;
}

vec3 diffuseColour(GpuMaterial m) {
    uint texture = floatBitsToUint(m.diffuse.w);
    return !kTextures || texture == kNoTexture ? m.diffuse.xyz
                                 : sampleMeshTexture(texture, st.hit.uv);
}

// The visibility-weighted part of light `index` at the hit: m_d max(0, n.l) (+ Phong's
// m_s max(0, l_r.v)^Ns), times the light's colour and fall-off.
vec3 directLight(GpuMaterial m, GpuLight light) {
    vec3 p = st.hit.position;
    vec3 n = st.hit.shadingNormal;
    vec3 toLight = light.position.xyz - p;
    float distanceSquared = ieeeDot(toLight, toLight);
    vec3 l = toLight / sqrt(distanceSquared);  // as the CPU reference divides
    vec3 colour = light.colour.xyz;
    if (light.position.w != 0.0) colour /= distanceSquared;
    vec3 result = diffuseColour(m) * max(0.0, ieeeDot(n, l));
    if (usesMaterial(kMaterialPhong) && materialModel(m) == kMaterialPhong) {
        vec3 lr = 2.0 * ieeeDot(n, l) * n - l;
        float c = max(0.0, ieeeDot(lr, -st.ray.direction.xyz));
        float ns = m.specular.w;
        float highlight = c > 0.0 ? pow(c, ns) : (ns == 0.0 ? 1.0 : 0.0);
        result += m.specular.xyz * highlight;
    }
    return colour * result;
}

// Lambert and Phong: ambient from every light, then one shadow ray per light whose direct term
// reaches kLeastShadowedTerm in some channel; the shadow ray carries that term (st.shadowLight) to
// finishShadow.
void nextLight(GpuMaterial m) {
    uint index = st.light;
    if (!kShadowRays || index >= lightCount()) {
        st.phase = usesMaterial(kMaterialPhong) && materialModel(m) == kMaterialPhong ? kPhaseScatter : kPhaseNextRay;
        return;
    }
    GpuLight light = loadLight(index);
    gRoundColour += st.ray.weight.xyz * light.colour.xyz * m.ambient.xyz;
    vec3 direct = directLight(m, light);
    if (all(lessThan(direct, vec3(kLeastShadowedTerm)))) {
        st.light = index + 1u;
        return;
    }
    vec3 origin = offsetRayOrigin(st.hit.position, st.hit.geometricNormal);
    counters.shadowRays += 1u;
    st.shadowLight = direct;
    beginTraversal(origin, light.position.xyz - origin, 0.0, 1.0);
    st.phase = kPhaseShadow;
}

void finishShadow() {
    if (st.traversal.closest == kNoTriangle) gRoundColour += st.ray.weight.xyz * st.shadowLight;
    st.light += 1u;
    st.phase = kPhaseNextLight;
}

// Whether any material of this build spawns reflected or refracted rays.
bool spawnsRays() {
    return usesMaterial(kMaterialPhong) || usesMaterial(kMaterialMirror) || usesMaterial(kMaterialGlass) ||
           usesMaterial(kMaterialThinGlass);
}


// The hit's children. The one traced next goes on at once as st.ray: the reflection (of a
// mirror, a Phong surface with Schlick's weight, glass or thin glass), or through an
// index-matched glass interface the same ray with the new medium stack; only a glass hit's
// refraction (a thin glass's transmission) waits on the pending-ray stack, so it has one store
// site here (docs/gpu-design.md, "The ray tree"; the other is coverSurface's). The materials
// share one reflection, from the normals on the incoming ray's side: lavapipe runs every
// material's code every round (docs/gpu-design.md, "One shading round, fewer copies of its code").
void scatter(GpuMaterial m) {
    uint model = materialModel(m);
    bool glass = usesMaterial(kMaterialGlass) && model == kMaterialGlass;
    bool mirror = usesMaterial(kMaterialMirror) && model == kMaterialMirror;
    bool thin = usesMaterial(kMaterialThinGlass) && model == kMaterialThinGlass;  // n1 the ray's medium, n2 Ni
    vec3 d = st.ray.direction.xyz;
    vec3 w = st.ray.weight.xyz;
    uint depth = rayDepth(st.ray);
    vec3 p = st.hit.position;
    vec3 facing = st.hit.geometricNormal;
    vec3 n = st.hit.shadingNormal;
    float n1 = mediumIor(st.ray);
    float n2 = m.attenuation.w;
    uvec4 media = st.ray.media;
    uint count = mediaCount(st.ray);
    vec3 through = p;  // where a transmitted ray starts: beyond every surface of the interface
    // What the transmitted light takes on: a thin glass's Kd, a tinted glass's surfaces (below).
    bool tinted = thin || (kGlassTints && glass);
    vec3 tint = thin ? diffuseColour(m) : vec3(1.0);
    if (usesMaterial(kMaterialGlass) && glass) {
        bool falseSurface = falseHit(media, count, st.hit.object, ieeeDot(d, facing) < 0.0);
        bool entering = crossGlass(media, count);
        float hitIor = dispersedIor(m.attenuation.w, st.hit.object, wavelengthCode(st.ray));
        if (entering) n2 = hitIor;
        if (!entering) n1 = hitIor;
        if (!entering || (kTouchingProbe && st.touching.w > 0u)) n2 = ior(media, count, wavelengthCode(st.ray));
        if (falseSurface) {  // the medium stays the one of higher priority: the ray goes on
            n1 = mediumIor(st.ray);
            n2 = n1;
            counters.falseHits += 1u;
        }
        if (kGlassTints && !falseSurface) tint = crossingTint();  // a false surface is no surface
        if (!entering) facing = -facing;
        if (!entering) n = -n;
        if (ieeeDot(n, d) >= 0.0) n = facing;  // a shading normal on the wrong side: use the true one
        if (kTouchingProbe && st.touching.w > 0u) through = st.ray.origin.xyz + st.farthestTouching * d;
    }
    // Index-matched glass: no optical interface; the same ray goes on with the new stack (a thin
    // glass's: with its own, through its tint).
    bool matched = (glass || thin) && n1 == n2;
    float eta = n1 / n2;
    float cosI = -ieeeDot(d, n);
    float cos2t = cosSquaredTransmitted(d, n, eta);
    float r = fresnelReflectance(glass || thin ? fresnelModel() : kFresnelSchlick, n1, n2, cosI, cos2t);
    if ((glass || thin) && !matched && cos2t < 0.0) counters.totalInternalReflections += 1u;
    vec3 transmitted = w * (1.0 - r);
    if (thin) {  // a pane: its faces' reflections summed, the transmission undeviated
        vec2 pane = thinPane(r);
        transmitted = w * pane.y;
        r = pane.x;
    }
    if (tinted) transmitted *= tint;
    vec3 transmittedOrigin = offsetRayOrigin(through, -facing);
    // Each child passes the depth and weight limits (or is counted).
    if ((glass || thin) && !matched && cos2t >= 0.0 && admitChild(depth + 1u, transmitted)) {
        if (st.pendingRays >= kPendingRayCapacity) {
            counters.rayStackOverflows += 1u;  // the refraction is dropped, never silently
        } else {
            vec3 direction = thin ? d : refractDirection(d, n, eta, cos2t);  // a pane's two refractions cancel
            PendingRay refracted = childRay(transmittedOrigin, direction, transmitted, media, count, depth + 1u);
            refracted.weight.xyz *= skippedTransmittance(refracted, through);
            storePendingRay(pendingRayIndex(st.pendingRays), refracted);
            st.pendingRays += 1u;
            counters.refractionRays += 1u;
        }
    }
    PendingRay next = matched ? childRay(transmittedOrigin, d, tinted ? w * tint : w, media, count, depth)
                              : childRay(offsetRayOrigin(p, facing), reflectDirection(d, n), mirror ? w * m.specular.xyz : w * r,
                                         st.ray.media, mediaCount(st.ray), depth + 1u);
    // An index-matched continuation is the same ray going on at its own depth, not a new branch:
    // neither max_depth nor min_weight stops it (as on the CPU).
    if (matched || admitChild(rayDepth(next), next.weight.xyz)) {
        if (!matched) counters.reflectionRays += 1u;
        next.weight.xyz *= skippedTransmittance(next, matched ? through : p);
        st.ray = next;
        beginRay();
    } else {
        st.phase = kPhaseNextRay;
    }
}

#endif
